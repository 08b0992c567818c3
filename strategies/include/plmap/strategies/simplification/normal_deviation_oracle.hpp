#pragma once
/// \file
/// Error oracle: How far the new triangles turn away from the old ones: 1 − the smallest cosine between the
/// normal of a new triangle and the normal of a removed one (0 for a flat star, 2 when reversed).

#include <plmap/strategies/simplification/error_oracle.hpp>

namespace plmap {

struct NormalDeviationOracle {
  OracleVerdict evaluate(const RemovalCandidate& candidate) const;
};
static_assert(ErrorOracle<NormalDeviationOracle>);

}  // namespace plmap
