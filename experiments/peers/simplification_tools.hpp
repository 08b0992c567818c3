#pragma once
// The tools compared by bench_simplification_peers (README.md, "Simplification against the
// peers"): plmap (simplify + smooth), PSurface 2.0 (its point removal driven by a vertex heap, then
// its edge relaxation) and, as the floor without a map, CGAL's edge-collapse simplification. Each
// tool gets the fine surface in its own form first (not measured), calls `clock.start()`, runs,
// calls `clock.stop()`, and then measures its result with plmap's own code (quality.hpp's
// condition number, refine_through_map.hpp's aspect ratio), so that the figures compare.

#include "measurement.hpp"

#include <plmap/core/surface.hpp>

#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

namespace plmap::peers {

struct SimplificationRequest {
  std::shared_ptr<const Surface<2>> fine;
  Index target_elements = 500;
  /// plmap's error oracles, "NAME[:WEIGHT]" each.
  std::vector<std::string> oracles = {"hausdorff:1", "aspect-ratio:1"};
  /// plmap's queueing of removal candidates (SimplifyOptions::ranking): "exact" or "estimate".
  std::string ranking = "exact";
  /// plmap's cut of the fine edges (SimplifyOptions::cut): "per-step" or "deferred".
  std::string cut = "per-step";
  /// plmap: dihedral angle above which an edge is a feature line (180: none, as PSurface sees a
  /// mesh without feature-line marks).
  double feature_angle_degrees = 180.0;
  /// PSurface: the QualityRequest's weights of aspect ratio and Hausdorff distance.
  double psurface_aspect_ratio = 0.5, psurface_hausdorff = 0.5;
  /// Smoothing sweeps (plmap: per-element convex-combination sweeps; PSurface: relaxation passes
  /// over all base edges); 0: no smoothing.
  int smooth_sweeps = 1;
  std::string smoothing_weights = "floater";
  /// plmap's smoothing also over edge quadrilaterals (SmoothOptions::quadrilaterals); false:
  /// inside each element only.
  bool smooth_quadrilaterals = true;
  /// Uniform refinement levels of the coarse surface through the map for the refined surface's
  /// quality (0: skip).
  int refine_levels = 2;
};

struct SimplificationOutcome {
  bool ok = false;
  std::string error;
  double seconds_simplify = 0.0, seconds_smooth = 0.0;  ///< wall clock
  double cpu_simplify = 0.0, cpu_smooth = 0.0;          ///< CPU time of the process
  /// Everything else the tool measured (elements, Hausdorff, kappa, aspect ratios, ...).
  nlohmann::json figures = nlohmann::json::object();
};

SimplificationOutcome simplify_with_plmap(const SimplificationRequest& request, Measurement& clock);
SimplificationOutcome simplify_with_cgal(const SimplificationRequest& request, Measurement& clock);
#ifdef PLMAP_PEERS_HAVE_PSURFACE
SimplificationOutcome simplify_with_psurface(const SimplificationRequest& request, Measurement& clock);
#endif

// ---- the shared measuring code ----------------------------------------------------------------

/// Condition numbers of the regions: max, mean, p50, p90, p99 over the finite ones, and the
/// count of degenerate (infinite) ones.
nlohmann::json kappa_summary(std::vector<double> kappas);

/// Aspect-ratio distribution of a triangle surface (plmap::aspect_ratio_summary).
nlohmann::json aspect_ratio_json(const Surface<2>& surface);

/// Length of the bounding-box diagonal of a surface.
double bounding_box_diagonal(const Surface<2>& surface);

}  // namespace plmap::peers
