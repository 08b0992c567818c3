#pragma once
/// \file
/// Refinement through a map (the "remesher" of paper section 5, and the use of a
/// parametrization in paper 3.3): S1 is refined uniformly — every triangle split into 4^levels
/// triangles on the lattice of its barycentric coordinates — and every vertex of the refined
/// surface is moved to its image under Ξ. The result approximates S2 with S1's connectivity,
/// refined; its distance to S2 and its triangle quality are reported.
///
///   RefineResult r = refine_through_map(map, {.levels = 3});
///   write_surface("refined.off", r.surface);

#include <plmap/core/progress.hpp>
#include <plmap/core/pl_map.hpp>

#include <vector>

namespace plmap {

struct RefineOptions {
  /// Levels of uniform refinement: each splits every triangle into four (0 keeps S1's
  /// triangles and only moves its vertices to their images).
  int levels = 1;
  /// Phases "refining S1 elements" and "distance to S2", counting elements (S1's, then the
  /// refined surface's), every few thousand and at the end. Optional; a callback that throws
  /// cancels.
  ProgressCallback progress = {};
};

/// Distribution of the aspect ratio (longest edge × perimeter / (4√3 × area), 1 = equilateral)
/// of a surface's triangles.
struct AspectRatioSummary {
  double min = 1.0, mean = 1.0, p50 = 1.0, p90 = 1.0, p99 = 1.0, max = 1.0;
};

struct RefineReport {
  int levels = 0;
  Index vertices = 0, elements = 0;
  /// Distance from the refined surface to S2, sampled at every refined triangle's centroid and
  /// edge midpoints (exact closest points on S2, CGAL AABB tree): largest and mean, and the
  /// largest over S2's bounding-box diagonal. The refined vertices lie on S2 by construction.
  double distance_max = 0.0, distance_mean = 0.0, distance_max_relative = 0.0;
  AspectRatioSummary refined_quality;  ///< of the refined surface
  AspectRatioSummary coarse_quality;   ///< of S1, for comparison
  double seconds = 0.0;
};

struct RefineResult {
  Surface<2> surface;
  RefineReport report;
};

/// Throws plmap::Error if a refined vertex lies outside the map's domain D (the map is not a
/// parametrization) or the levels are outside 0..8.
RefineResult refine_through_map(const PlMap<2>& map, const RefineOptions& options = {});

/// Aspect-ratio distribution of a triangle surface.
AspectRatioSummary aspect_ratio_summary(const Surface<2>& surface);

}  // namespace plmap
