// plmap's simplification (construct/simplify.hpp) and smoothing (construct/smooth.hpp) as one
// tool of the simplification benchmark.

#include "simplification_tools.hpp"

#include <plmap/construct/refine_through_map.hpp>
#include <plmap/construct/simplify.hpp>
#include <plmap/construct/smooth.hpp>
#include <plmap/verify/quality.hpp>

#include <chrono>
#include <exception>

namespace plmap::peers {

namespace {

std::vector<double> region_kappas(const PlMap<2>& map) {
  std::vector<double> k(static_cast<std::size_t>(map.region_count()));
  for (Index r = 0; r < map.region_count(); ++r) k[static_cast<std::size_t>(r)] = region_conditioning(map, r).kappa;
  return k;
}

/// The modified Hausdorff distance of a map: the largest distance between a node on S1 and its
/// image on S2 (the distance is convex on every region, so its maximum is at a node).
double node_hausdorff(const PlMap<2>& map) {
  double h = 0.0;
  for (Index n = 0; n < map.node_count(); ++n)
    h = std::max(h, (map.node_domain_world(n) - map.node_target_world(n)).norm());
  return h;
}

}  // namespace

SimplificationOutcome simplify_with_plmap(const SimplificationRequest& request, Measurement& clock) {
  SimplificationOutcome out;
  SimplifyOptions options;
  options.target_elements = request.target_elements;
  options.feature_angle_degrees = request.feature_angle_degrees;
  for (const auto& spec : request.oracles) options.oracles.add_spec(spec);
  options.ranking = request.ranking;
  options.cut = request.cut;
  SmoothOptions smoothing;
  smoothing.sweeps = std::max(1, request.smooth_sweeps);
  smoothing.weights = request.smoothing_weights;
  smoothing.quadrilaterals = request.smooth_quadrilaterals;
  try {
    clock.start();
    auto t0 = std::chrono::steady_clock::now();
    const double c0 = process_cpu_seconds();
    SimplifyResult simplified = simplify(request.fine, options);
    auto t1 = std::chrono::steady_clock::now();
    const double c1 = process_cpu_seconds();
    PlMap<2> map = std::move(simplified.map);
    std::optional<PlMap<2>> smoothed;
    Index quadrilaterals_smoothed = 0;
    if (request.smooth_sweeps > 0) {
      SmoothResult result = smooth(map, smoothing);
      for (const auto& sweep : result.report.sweeps) quadrilaterals_smoothed += sweep.quadrilaterals_smoothed;
      smoothed = std::move(result.map);
    }
    auto t2 = std::chrono::steady_clock::now();
    const double c2 = process_cpu_seconds();
    clock.stop();
    out.cpu_simplify = c1 - c0;
    out.cpu_smooth = c2 - c1;
    out.seconds_simplify = std::chrono::duration<double>(t1 - t0).count();
    out.seconds_smooth = std::chrono::duration<double>(t2 - t1).count();
    const PlMap<2>& final_map = smoothed ? *smoothed : map;
    const double diagonal = bounding_box_diagonal(*request.fine);
    const auto& r = simplified.report;
    nlohmann::json f;
    f["elements"] = map.domain().element_count();
    f["vertices"] = map.domain().vertex_count();
    f["nodes"] = map.node_count();
    f["regions"] = map.region_count();
    f["ranking"] = r.ranking;
    f["smooth_quadrilaterals"] = request.smooth_quadrilaterals;
    f["quadrilaterals_smoothed"] = quadrilaterals_smoothed;
    f["ranking_plans"] = r.ranking_plans;
    f["cut"] = r.cut;
    f["cut_fell_back"] = r.cut_fell_back;
    f["full_plans"] = r.full_plans;
    f["hausdorff_before_smoothing"] = node_hausdorff(map) / diagonal;
    f["hausdorff"] = node_hausdorff(final_map) / diagonal;
    f["kappa_before"] = kappa_summary(region_kappas(map));
    f["kappa_after"] = kappa_summary(region_kappas(final_map));
    f["coarse_aspect"] = aspect_ratio_json(map.domain());
    if (request.refine_levels > 0) {
      const RefineResult refined = refine_through_map(final_map, {.levels = request.refine_levels});
      f["refined_aspect"] = aspect_ratio_json(refined.surface);
      f["refined_distance"] = refined.report.distance_max_relative;
    }
    f["details"] = {{"oracles", r.oracles},
                    {"feature_edges", r.feature_edges},
                    {"skipped_vertices", r.skipped_vertices},
                    {"target_reached", r.target_reached},
                    {"seconds_by_phase",
                     {{"simplify", r.seconds_simplify}, {"finalize", r.seconds_finalize}, {"total", r.seconds_total}}}};
    out.figures = std::move(f);
    out.ok = true;
  } catch (const std::exception& e) {
    clock.stop();
    out.error = e.what();
  }
  return out;
}

}  // namespace plmap::peers
