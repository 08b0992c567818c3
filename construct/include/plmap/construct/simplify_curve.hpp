#pragma once
/// \file
/// simplify_curve(): paper 3.3.1 for d = 1. A fine polyline S2 (open, closed, or several curves
/// meeting at junctions) becomes a coarse polyline S1 with the parametrization Ξ: S1 → S2.
/// S1 starts as S2 and loses vertices one at a time, cheapest first: removing a vertex merges
/// its two segments into one, and every S2 vertex of the merged segment becomes a node on it,
/// placed by arc length along S2 (the polar map of a 1-d star is this trivial flattening).
/// Feature corners are never removed: endpoints of open curves, junctions (not on exactly two
/// segments), vertices where the two segments run against each other, and vertices where the
/// curve turns by more than `feature_angle_degrees`.
///
///   SimplifyOptions options;                 // the same options as for surfaces
///   options.target_elements = 20;
///   options.oracles.add("hausdorff", 1.0).add("long-edge", 0.1);
///   CurveSimplifyResult r = simplify_curve(fine, options);   // r.map: PlMap<1>, S1 → S2
///
/// Oracles for curves: `hausdorff` (largest distance between a node of the merged segment and
/// its image, over the mean S2 segment length) and `long-edge` (squared merged length over the
/// squared mean segment length); the other names throw plmap::Error. The flattening and hole
/// triangulation options do not apply to curves.

#include <plmap/construct/simplify.hpp>
#include <plmap/core/pl_map.hpp>

#include <memory>

namespace plmap {

struct CurveSimplifyResult {
  PlMap<1> map;
  /// The fields that apply to curves: elements are segments, feature_corners the vertices never
  /// removed, hausdorff_error over all nodes; removed_along_lines stays 0.
  SimplifyReport report;
};

/// Throws plmap::Error for options that cannot be met (a target not below the curve's size,
/// neither target nor error bound, an oracle that does not apply to curves).
CurveSimplifyResult simplify_curve(std::shared_ptr<const Surface<1>> fine, SimplifyOptions options = {});

}  // namespace plmap
