// κ_Ξ's distribution as JSON (kappa_json.hpp).

#include "kappa_json.hpp"

#include <fmt/format.h>

namespace plmap::cli {

KappaSummary kappa_summary(const QualityReport& q) {
  return {q.kappa_max, q.kappa_mean, q.quantile_levels, q.quantiles, q.histogram_bin_width, q.histogram, q.degenerate_count};
}

Json kappa_json(const KappaSummary& k) {
  Json j;
  j["kappa_max"] = k.max;
  j["kappa_mean"] = k.mean;
  Json quantiles = Json::object();
  for (std::size_t i = 0; i < k.quantile_levels.size() && i < k.quantiles.size(); ++i) {
    // {:g} keeps 99.9 apart from 100 (levels 0.999 and 1)
    quantiles[fmt::format("p{:g}", k.quantile_levels[i] * 100.0)] = k.quantiles[i];
    if (k.quantile_levels[i] == 0.99) j["kappa_p99"] = k.quantiles[i];
  }
  j["kappa_quantiles"] = quantiles;
  j["log10_kappa_histogram"] = {{"bin_width", k.histogram_bin_width}, {"counts", k.histogram}};
  j["degenerate_regions"] = k.degenerate_regions;
  return j;
}

}  // namespace plmap::cli
