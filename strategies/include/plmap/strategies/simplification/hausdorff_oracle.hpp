#pragma once
/// \file
/// Error oracle: The modified Hausdorff distance of paper 3.3.1: the largest distance between a node of the star
/// (relocated vertex preimage or new crossing) on the new S1 triangles and its image on S2,
/// divided by the length scale.

#include <plmap/strategies/simplification/error_oracle.hpp>

namespace plmap {

struct HausdorffOracle {
  OracleVerdict evaluate(const RemovalCandidate& candidate) const;
};
static_assert(ErrorOracle<HausdorffOracle>);

}  // namespace plmap
