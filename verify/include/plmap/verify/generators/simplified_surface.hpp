#pragma once
/// \file
/// Coarse versions of real meshes, for maps "of the femur kind" in experiments and tests: a
/// triangle surface simplified by CGAL's edge collapse (Surface_mesh_simplification, default
/// cost and placement). The same input and face count give the same result.

#include <plmap/core/surface.hpp>

#include <cstddef>
#include <functional>

namespace plmap::generators {

/// `surface` simplified to about `faces` triangles. The surface must be an oriented 2-manifold
/// (possibly with boundary) that CGAL's Surface_mesh accepts; throws plmap::Error otherwise.
Surface<2> simplify_by_edge_collapse(const Surface<2>& surface, std::size_t faces);

/// Called right before and right after CGAL's collapse, so that a benchmark can time the
/// simplification without the conversions from and to Surface<2> (experiments/peers' CGAL floor).
struct EdgeCollapseHooks {
  std::function<void()> before_collapse, after_collapse;
};
Surface<2> simplify_by_edge_collapse(const Surface<2>& surface, std::size_t faces, const EdgeCollapseHooks& hooks);

}  // namespace plmap::generators
