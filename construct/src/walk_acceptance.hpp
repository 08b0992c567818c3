#pragma once
// Normal projection: which solutions the phases accept where the direction field folds.
//
// The ray check (verify/ray_check.hpp) judges a point of S1 by the ray from that point in its
// own element: admissible if J, the Jacobian determinant of the element's sweep, keeps its sign
// up to the hit (solvers/focal_points.hpp). The walks judge each crossing the same way, in the
// element they cross. A ghost node sits on an S1 vertex shared by several elements, each with
// its own J: requiring the ray to be unfolded in all of them loses the vertex's image, and with
// it every face around the vertex, in the unfolded elements too, wherever one element at the
// vertex folds. So a ghost ray is accepted if it is unfolded in at least one element at the
// vertex. In the elements where it is folded no walk enters (the walk's own per-element test),
// so their faces at the vertex cannot be closed into regions with a common S2 element and stay
// outside D; the finalizer leaves out faces with reversed orientation and the nearer-sheet
// test overlapping ones, as anywhere else.

#include <plmap/core/types.hpp>

#include <algorithm>
#include <span>

namespace plmap::projection {

/// Whether `unfolded(t)` holds for at least one of the elements at a point.
template <class UnfoldedIn>
bool unfolded_in_some_element(std::span<const Index> elements, UnfoldedIn&& unfolded) {
  return std::any_of(elements.begin(), elements.end(), [&](Index t) { return unfolded(t); });
}

}  // namespace plmap::projection
