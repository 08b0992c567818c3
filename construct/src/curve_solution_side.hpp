#pragma once
// Normal projection of curves (d = 1): where along a segment's line the solutions of the vertex
// system (eq. 3) lie, from a closed form, without solving it. The vertex preimage search uses it
// to leave out the solves whose only outcome would be a step into a segment already solved
// (projection_vertex_preimages.cpp); every walk step of a curve otherwise costs a Newton solve.
//
// On segment c0-c1 with directions n0, n1, the system c(xi) + mu n(xi) = q, c(xi) = c0 + xi e,
// n(xi) = n0 + xi m (e = c1 - c0, m = n1 - n0), has a solution at xi exactly where q - c(xi) is
// parallel to n(xi):
//     f(xi) = cross(q - c0 - xi e, n0 + xi m) = cross(w, n0) + xi (cross(w, m) - cross(e, n0)) - xi^2 cross(e, m)
// with w = q - c0, a quadratic in xi (linear where the directions turn with the segment, as on
// a circle with exact normals: all lines then meet at the centre).

#include <plmap/core/types.hpp>

#include <cmath>

namespace plmap::projection {

/// +1 if every solution of eq. (3) on the segment c0-c1 lies at xi > 1 + margin, -1 if every one
/// lies at xi < -margin, 0 if one may lie in between, or the answer is not clear-cut: no real
/// solution (a solver would fail, which a caller may need to know), two solutions close together
/// (their position is ill-conditioned), or solutions on both sides (the one a solver converges to
/// decides the walk's direction). Solutions more than `far` segment lengths away count as none:
/// no solver started on the segment reaches them (they are where the direction lines turn
/// parallel, e.g. rounding on a circle's exact normals puts one about 1e16 lengths away).
inline int curve_solution_side(const WorldPoint<1>& c0, const WorldPoint<1>& c1, const WorldPoint<1>& n0,
                               const WorldPoint<1>& n1, const WorldPoint<1>& q, double margin) {
  constexpr double far = 1e6;
  auto cross = [](const WorldPoint<1>& u, const WorldPoint<1>& v) { return u.x() * v.y() - u.y() * v.x(); };
  const WorldPoint<1> e = c1 - c0, m = n1 - n0, w = q - c0;
  const double a = -cross(e, m), b = cross(w, m) - cross(e, n0), c = cross(w, n0);
  double roots[2];
  int count = 0;
  if (a == 0.0) {
    if (b == 0.0) return 0;
    roots[count++] = -c / b;
  } else {
    const double discriminant = b * b - 4.0 * a * c;
    // Real and well apart (|r1 - r2| >= 1e-3 |r1 + r2|): else a solver's root may sit anywhere
    // near the double root, or not exist.
    if (!(discriminant > 1e-6 * b * b) || !(discriminant > 0.0)) return 0;
    const double half = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));  // no cancellation
    roots[count++] = half / a;
    roots[count++] = c / half;
  }
  int side = 0;
  for (int i = 0; i < count; ++i) {
    const double r = roots[i];
    if (!(std::abs(r) <= far)) continue;  // far away, infinite or not a number
    const int s = r > 1.0 + margin ? 1 : (r < -margin ? -1 : 0);
    if (s == 0 || (side != 0 && s != side)) return 0;
    side = s;
  }
  return side;
}

}  // namespace plmap::projection
