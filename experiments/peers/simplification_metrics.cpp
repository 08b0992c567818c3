// The measuring code shared by the simplification tools (simplification_tools.hpp).

#include "simplification_tools.hpp"

#include <plmap/construct/refine_through_map.hpp>

#include <algorithm>
#include <cmath>

namespace plmap::peers {

nlohmann::json kappa_summary(std::vector<double> kappas) {
  std::size_t degenerate = 0;
  std::vector<double> finite;
  finite.reserve(kappas.size());
  for (const double k : kappas) {
    if (std::isfinite(k)) finite.push_back(k);
    else ++degenerate;
  }
  nlohmann::json j = {{"regions", kappas.size()}, {"degenerate", degenerate}};
  if (finite.empty()) return j;
  std::sort(finite.begin(), finite.end());
  double sum = 0.0;
  for (const double k : finite) sum += k;
  const auto quantile = [&](double level) {
    const auto i = static_cast<std::size_t>(std::ceil(level * double(finite.size()))) - 1;
    return finite[std::min(i, finite.size() - 1)];
  };
  j["max"] = finite.back();
  j["mean"] = sum / double(finite.size());
  j["p50"] = quantile(0.5);
  j["p90"] = quantile(0.9);
  j["p99"] = quantile(0.99);
  return j;
}

nlohmann::json aspect_ratio_json(const Surface<2>& surface) {
  const AspectRatioSummary a = aspect_ratio_summary(surface);
  return {{"min", a.min}, {"mean", a.mean}, {"p50", a.p50}, {"p90", a.p90}, {"p99", a.p99}, {"max", a.max}};
}

double bounding_box_diagonal(const Surface<2>& surface) {
  WorldPoint<2> lo = surface.vertices().front(), hi = lo;
  for (const auto& p : surface.vertices()) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

}  // namespace plmap::peers
