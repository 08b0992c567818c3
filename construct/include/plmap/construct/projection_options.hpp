#pragma once
/// \file
/// ProjectionOptions: everything normal projection (project.hpp) can be told, with defaults.

#include <plmap/core/progress.hpp>

#include <limits>
#include <string>
#include <vector>

namespace plmap {

/// Which S2 points may be the image of an S1 point, judged by the S2 vertex normal n2 at the
/// image against the projection direction nu at the preimage (paper section 3.2 compares n2 with
/// w = q - p; w = mu nu, and comparing nu itself keeps the test meaningful for mu = 0 (S1 = S2)
/// and for negative mu (penetrating contact)).
enum class TargetNormalCheck {
  none,     ///< accept any orientation (default)
  facing,   ///< <nu, n2> < 0: the paper's check, for contact pairs whose normals face each other
  aligned,  ///< <nu, n2> > 0: both surfaces oriented the same way (offset or remeshed copies)
};

struct ProjectionOptions {
  /// Projection directions at the S1 vertices, d+1 numbers per vertex (vertex-major); they are
  /// normalised, so the distance mu along them is a length. Empty (default): averaged vertex
  /// normals of S1 (area-weighted for d = 2, length-weighted for d = 1).
  std::vector<double> directions = {};
  /// "newton" (hand-written damped Newton, default) or "ceres" (ceres::TinySolver).
  std::string solver = "newton";
  /// Solvers stop when the residual is below this times the element diameter.
  double solver_tolerance = 1e-12;
  /// Largest admissible |mu| (distance along the unit direction). Infinite by default.
  double max_distance = std::numeric_limits<double>::infinity();
  /// If true, max_distance is a multiple of the diagonal of S1's bounding box; else a length.
  bool max_distance_is_relative = false;
  /// Accept images behind S1 (mu < 0, down to -max_distance), as for slightly penetrating
  /// bodies in contact. The solution with the smallest |mu| wins. Default: only mu >= 0.
  bool allow_negative_distance = false;
  TargetNormalCheck normal_check = TargetNormalCheck::none;
  /// Worker threads for the vertex preimages, ghost nodes and edge walks; 0 = all cores. The
  /// result does not depend on it.
  unsigned threads = 1;
  /// How many nearest S1 (S2) elements seed the search for a vertex preimage (ray hit).
  int search_seeds = 8;
  /// Passed to MapBuilder: the single snapping rule of plmap (local coordinates).
  double snap_tolerance = 1e-10;
  /// Orientation of the map: 0 = automatic (majority), +1 preserving, -1 reversing.
  int orientation = 0;
  /// Where two sheets of S1 project onto the same part of S2 (the projection is not injective
  /// there: a steep hill whose flanks fan out over the plain around it, two bodies one above
  /// the other), keep the nearer sheet: a face whose image overlaps the image of a nearer face
  /// is left out of D (ProjectionReport::occluded_faces), as a vertex preimage keeps the nearest
  /// solution. With false such maps are returned as they are, and fail verify's coverage check.
  bool keep_nearer_sheet = true;
  /// Told the phase ("rays from S1 vertices", "S2 vertex preimages", "S2 edges", "finalize")
  /// at its start and end, and every 4096 edges in "S2 edges"; called from the calling thread
  /// only. Optional; a callback that throws cancels the projection.
  ProgressCallback progress = {};
};

}  // namespace plmap
