#pragma once
/// \file
/// Maps by normal projection (paper section 3.2): Xi: D ⊂ S1 -> S2 with Xi(p) = p + mu nu(p).
///
///   auto r = plmap::project<2>(s1, s2, {.max_distance = 0.05});
///   r.map (the PlMap), r.report (what was built, what not and why), r.measures.
///
/// See docs/projection.md for the algorithm, the options and the limitations.

#include <plmap/construct/projection_options.hpp>
#include <plmap/construct/projection_result.hpp>

#include <memory>

namespace plmap {

/// Projects S2 onto S1 along the direction field of `options` and returns the map from the
/// covered part D of S1 to S2. Throws plmap::Error on bad options (unknown solver name, wrong
/// number of directions) and BuilderError if the collected graph is inconsistent.
template <int d>
  requires SurfaceDimension<d>
ProjectionResult<d> project(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
                            const ProjectionOptions& options = {});

extern template ProjectionResult<1> project<1>(std::shared_ptr<const Surface<1>>,
                                               std::shared_ptr<const Surface<1>>, const ProjectionOptions&);
extern template ProjectionResult<2> project<2>(std::shared_ptr<const Surface<2>>,
                                               std::shared_ptr<const Surface<2>>, const ProjectionOptions&);

}  // namespace plmap
