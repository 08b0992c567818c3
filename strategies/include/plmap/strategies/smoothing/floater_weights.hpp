#pragma once
/// \file
/// Floater's shape-preserving weights (1997), the paper's choice (3.3.2). The S2 star is laid out
/// in the plane by Floater's geodesic polar map: spoke lengths are kept and the angles at the
/// centre scaled by 2π / (their sum). For each neighbour j, the centre lies in one triangle
/// (p_j, p_r, p_{r+1}) of the flattened ring; its barycentric coordinates there are a set of
/// weights that reproduce the centre. The weights are their mean over all j. If the star is
/// planar, an affine image of it is reproduced exactly (linear precision).

#include <plmap/strategies/smoothing/smoothing_weights.hpp>

namespace plmap {

struct FloaterWeights {
  std::optional<std::vector<double>> weights(const Eigen::Vector3d& center, std::span<const Eigen::Vector3d> ring) const;
};
static_assert(SmoothingWeights<FloaterWeights>);

}  // namespace plmap
