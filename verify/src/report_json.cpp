#include <plmap/verify/report_json.hpp>

#include <cmath>

namespace plmap {

namespace {

/// JSON has no infinity; a degenerate region's kappa is written as null.
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json index_or_null(Index i) { return i == invalid_index ? nlohmann::json(nullptr) : nlohmann::json(i); }

}  // namespace

nlohmann::json to_json(const QualityReport& q) {
  nlohmann::json j;
  j["region_count"] = q.region_count;
  j["degenerate_count"] = q.degenerate_count;
  j["kappa_max"] = number(q.kappa_max);
  j["kappa_max_region"] = index_or_null(q.kappa_max_region);
  j["kappa_mean"] = number(q.kappa_mean);
  nlohmann::json quantiles = nlohmann::json::array();
  for (std::size_t i = 0; i < q.quantiles.size(); ++i)
    quantiles.push_back({{"level", q.quantile_levels[i]}, {"kappa", number(q.quantiles[i])}});
  j["quantiles"] = quantiles;
  j["log10_kappa_histogram"] = {{"bin_width", q.histogram_bin_width}, {"counts", q.histogram}};
  j["stretch_min"] = number(q.stretch_min);
  j["stretch_max"] = number(q.stretch_max);
  return j;
}

nlohmann::json to_json(const VerificationReport& report) {
  nlohmann::json j;
  j["ok"] = report.ok();
  j["violation_count"] = report.violation_count();
  nlohmann::json checks = nlohmann::json::object();
  for (const CheckResult& c : report.checks) {
    nlohmann::json cj;
    cj["skipped"] = c.skipped;
    if (c.skipped) cj["skipped_reason"] = c.skipped_reason;
    cj["violation_count"] = c.violation_count;
    cj["rules"] = c.rule_counts;
    nlohmann::json list = nlohmann::json::array();
    for (const Violation& v : c.violations)
      list.push_back({{"check", v.check},
                      {"rule", v.rule},
                      {"element", index_or_null(v.element)},
                      {"node", index_or_null(v.node)},
                      {"region", index_or_null(v.region)},
                      {"target_element", index_or_null(v.target_element)},
                      {"message", v.message}});
    cj["violations"] = list;
    checks[c.name] = cj;
  }
  j["checks"] = checks;
  if (report.quality) j["quality"] = to_json(*report.quality);
  return j;
}

}  // namespace plmap
