#pragma once
/// \file
/// Error oracle: Penalty on long edges, for uniform element size (paper 3.3.1): the squared longest new edge
/// divided by the squared length scale.

#include <plmap/strategies/simplification/error_oracle.hpp>

namespace plmap {

struct LongEdgeOracle {
  OracleVerdict evaluate(const RemovalCandidate& candidate) const;
};
static_assert(ErrorOracle<LongEdgeOracle>);

}  // namespace plmap
