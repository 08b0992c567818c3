#pragma once
/// \file
/// Error oracle: Triangle quality (paper 3.3.1): the largest aspect ratio (1 = equilateral) among the new
/// triangles minus the largest among the removed ones, so steps that remove slivers and create
/// well-shaped triangles come first.

#include <plmap/strategies/simplification/error_oracle.hpp>

namespace plmap {

struct AspectRatioOracle {
  OracleVerdict evaluate(const RemovalCandidate& candidate) const;
};
static_assert(ErrorOracle<AspectRatioOracle>);

}  // namespace plmap
