#pragma once
// Midpoint refinement of a triangle surface and the map from the coarse surface onto the fine
// one, built with plmap's MapBuilder: the kind of map a downstream code (a multigrid transfer, a
// mesh-adaptation step) would construct and then check with plmap::verify.

#include <plmap/core/pl_map.hpp>
#include <plmap/core/surface.hpp>

#include <memory>

namespace downstream {

/// Every triangle split into four at its edge midpoints. Fine vertex V + e is the midpoint of
/// coarse edge e, where V is the coarse vertex count.
std::shared_ptr<const plmap::Surface<2>> midpoint_refine(const plmap::Surface<2>& coarse);

/// The identity of the geometry seen as a map from `coarse` onto `fine` = midpoint_refine(coarse):
/// coarse vertices map to themselves, fine edge-midpoint vertices have their preimages on the
/// coarse edges, and each coarse triangle carries four regions.
plmap::PlMap<2> refinement_map(std::shared_ptr<const plmap::Surface<2>> coarse,
                               std::shared_ptr<const plmap::Surface<2>> fine);

/// The unit square in the plane z = 0, split along the diagonal from (0,0) to (1,1).
std::shared_ptr<const plmap::Surface<2>> unit_square();
/// The surface of the tetrahedron with corners at the origin and the three unit vectors.
std::shared_ptr<const plmap::Surface<2>> tetrahedron();

}  // namespace downstream
