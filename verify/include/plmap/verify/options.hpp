#pragma once
/// \file
/// VerifyOptions: the tolerances and switches of the invariant checks (DESIGN.md §4).
///
/// Every tolerance is relative to the scale of the input, so the same surfaces scaled by 1e-6 or
/// 1e6 give the same verdict: local coordinates are already scale-free (the reference element
/// has unit legs), and world-space comparisons are multiplied by the surface's
/// max_edge_length().

#include <cstddef>
#include <limits>

namespace plmap {

struct VerifyOptions {
  /// A local position within this distance (in barycentric coordinates) of a corner or an edge
  /// counts as lying on it. Same default as BuilderOptions::snap_tolerance, because the builder
  /// snapped everything closer than that.
  double snap_tolerance = 1e-10;
  /// Tolerance for comparing local coordinates that were computed, not snapped: positions of
  /// copies on a shared edge, "point inside a region" (barycentric >= -tol).
  double local_tolerance = 1e-9;
  /// World-space comparisons (an image of a node computed two ways, the two sides of a shared
  /// edge) accept a distance of world_tolerance * max_edge_length() of the surface concerned.
  double world_tolerance = 1e-8;
  /// Relative tolerance for sums of measures (region areas against the element area, image
  /// areas against the S2 element area) and for pairwise overlap areas.
  double measure_tolerance = 1e-8;
  /// Continuity: sample points per piece between consecutive nodes of a shared edge.
  int continuity_samples_per_piece = 2;
  /// Coverage: additionally require that the map is a parametrization, i.e. the regions cover
  /// all of S1 and their images all of S2.
  bool expect_parametrization = false;
  /// Quality: a region whose condition number exceeds this is reported as a violation of the
  /// "quality" check (infinity: only report the distribution).
  double max_condition = std::numeric_limits<double>::infinity();
  /// Compute the quality distribution in verify() (it is cheap, but optional).
  bool compute_quality = true;
  /// Violations stored in full per rule; further ones are only counted, so a badly broken map
  /// with 10^6 regions still gives a report of bounded size.
  std::size_t max_reported_per_rule = 20;
};

}  // namespace plmap
