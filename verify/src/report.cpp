#include <plmap/verify/report.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace plmap {

bool VerificationReport::ok() const {
  return std::all_of(checks.begin(), checks.end(), [](const CheckResult& c) { return c.ok(); });
}

std::size_t VerificationReport::violation_count() const {
  std::size_t n = 0;
  for (const auto& c : checks) n += c.violation_count;
  return n;
}

std::size_t VerificationReport::violation_count(std::string_view check) const {
  const CheckResult* c = find(check);
  return c ? c->violation_count : 0;
}

std::size_t VerificationReport::violation_count(std::string_view check, std::string_view rule) const {
  const CheckResult* c = find(check);
  if (!c) return 0;
  const auto it = c->rule_counts.find(std::string(rule));
  return it == c->rule_counts.end() ? 0 : it->second;
}

const CheckResult* VerificationReport::find(std::string_view check) const {
  const auto it = std::find_if(checks.begin(), checks.end(),
                               [&](const CheckResult& c) { return c.name == check; });
  return it == checks.end() ? nullptr : &*it;
}

void VerificationReport::merge(VerificationReport other) {
  for (auto& c : other.checks) {
    auto it = std::find_if(checks.begin(), checks.end(),
                           [&](const CheckResult& x) { return x.name == c.name; });
    if (it == checks.end()) {
      checks.push_back(std::move(c));
      continue;
    }
    // The same check twice (e.g. the index part of "structure" from two single checks): keep
    // the larger result rather than double-counting.
    if (c.violation_count > it->violation_count || (it->skipped && !c.skipped)) *it = std::move(c);
  }
  if (other.quality) quality = std::move(other.quality);
}

std::string summary(const VerificationReport& report, std::size_t violations_per_check) {
  std::string out = fmt::format("map verification: {} ({} violations)\n",
                                report.ok() ? "OK" : "FAILED", report.violation_count());
  for (const auto& c : report.checks) {
    if (c.skipped) {
      out += fmt::format("  {:<18} {}\n", c.name, c.skipped_reason);
      continue;
    }
    if (c.violation_count == 0) {
      out += fmt::format("  {:<18} ok\n", c.name);
      continue;
    }
    std::string rules;
    for (const auto& [rule, n] : c.rule_counts) rules += fmt::format(" {}={}", rule, n);
    out += fmt::format("  {:<18} {} violations:{}\n", c.name, c.violation_count, rules);
    for (std::size_t i = 0; i < std::min(violations_per_check, c.violations.size()); ++i)
      out += fmt::format("    [{}] {}\n", c.violations[i].rule, c.violations[i].message);
  }
  if (report.quality) {
    const QualityReport& q = *report.quality;
    out += fmt::format("  quality: kappa max {:.4g} (region {}), mean {:.4g}", q.kappa_max,
                       q.kappa_max_region, q.kappa_mean);
    for (std::size_t i = 0; i < q.quantiles.size(); ++i)
      out += fmt::format(", p{:g} {:.4g}", 100 * q.quantile_levels[i], q.quantiles[i]);
    out += fmt::format("; stretch [{:.4g}, {:.4g}]; {} degenerate of {} regions\n", q.stretch_min,
                       q.stretch_max, q.degenerate_count, q.region_count);
  }
  return out;
}

}  // namespace plmap
