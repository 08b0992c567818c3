#pragma once
// Normal projection, vertex preimages: how near to an S2 vertex q a preimage on a given S1 element
// can lie at best. The seed walks of the vertex preimage search (projection_vertex_preimages.cpp)
// keep the admissible solution of least rank; once a preimage of rank r is found, only elements on
// which a solution of rank below r can be accepted matter, and if every such element has already
// been solved, no later walk can change the answer: it stops.
//
// The floor. A walk accepts on element T a solution (xi, mu) of eq. (3) whose residual
// |p(xi) + mu nu(xi) - q| the solver found to be at most eps h (eps: the solver's relative
// tolerance, h: T's longest edge, the solvers' scale), whose barycentric coordinates b are all
// >= -tau (the inside tolerance), and (without allow_negative_distance) whose mu is >= -1e-9 h
// (distance_ok's slack). Then p(xi) lies within 2 d tau h of T (moving b onto the simplex changes
// the coordinates by at most 2 d tau in sum), and |nu(xi)| <= sum |b_k| <= 1 + 2 d tau, the
// directions being unit vectors. So
//     |mu| >= (dist(q, T) - (2 d tau + eps) h - rounding) / (1 + 2 d tau),
// and the rank (|mu|, or max(mu, 0)) is at least that, except that without negative distances a
// solution with mu in [-1e-9 h, 0) has rank 0: where the bound does not exclude such a mu, the
// floor is 0.
//
// The distance to T is itself bounded from below (distance_floor): by the distance to the part of
// T's line (d = 1) or plane (d = 2) on the inner side of every side of T, which contains T, with
// margins for its rounding; a triangle too thin for its plane to be computed accurately by the
// distance to its bounding box.

#include <plmap/core/surface.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace plmap::projection {

/// What a seed walk of the vertex preimage search accepts on an element (see above).
struct PreimageAcceptance {
  /// The solver's relative tolerance (residual / longest edge).
  double solver_tolerance = 1e-12;
  /// Barycentric coordinates down to -inside_tolerance count as inside.
  double inside_tolerance = 1e-9;
  /// Whether mu < 0 is admissible (rank |mu|), else rank max(mu, 0) with mu >= -1e-9 h.
  bool allow_negative_distance = false;
};

/// The longest edge of the simplex with corners c, as the solvers compute their scale.
template <int d>
double longest_edge(const std::array<WorldPoint<d>, d + 1>& c) {
  double h = 0.0;
  for (int i = 0; i <= d; ++i)
    for (int k = i + 1; k <= d; ++k) h = std::max(h, (c[i] - c[k]).norm());
  return h;
}

/// A lower bound of the distance from x to the simplex with corners c (longest edge h), with room
/// for the rounding of its own computation.
template <int d>
double distance_floor(const WorldPoint<d>& x, const std::array<WorldPoint<d>, d + 1>& c, double h) {
  const WorldPoint<d> w = x - c[0];
  double bound = 0.0;
  if constexpr (d == 1) {
    const WorldPoint<1> along = c[1] - c[0];
    const double length = along.norm();
    if (!(length > 0.0)) {
      bound = w.norm();
    } else {
      const double off_line = std::abs(along.x() * w.y() - along.y() * w.x()) / length;
      const double beyond = std::max({0.0, -w.dot(along), (x - c[1]).dot(along)}) / length;
      bound = std::sqrt(off_line * off_line + beyond * beyond);
    }
  } else {
    const WorldPoint<2> u = c[1] - c[0], v = c[2] - c[0];
    const WorldPoint<2> n = u.cross(v);
    const double n2 = n.squaredNorm();
    if (n2 > 1e-6 * u.squaredNorm() * v.squaredNorm()) {
      // the distance to the part of the plane on the inner side of every side line
      const double normal_length = std::sqrt(n2);
      const double off_plane = std::abs(w.dot(n)) / normal_length;
      double beyond = 0.0;
      for (int k = 0; k < 3; ++k) {
        const WorldPoint<2> side = c[(k + 1) % 3] - c[k];
        const double outward = (x - c[k]).dot(side.cross(n));  // |side x n| = |side| |n|
        if (outward > 0.0) beyond = std::max(beyond, outward / (side.norm() * normal_length));
      }
      bound = std::sqrt(off_plane * off_plane + beyond * beyond);
    } else {
      // a sliver's plane is dominated by rounding: its bounding box
      WorldPoint<2> low = c[0].cwiseMin(c[1]).cwiseMin(c[2]), high = c[0].cwiseMax(c[1]).cwiseMax(c[2]);
      bound = (x.cwiseMax(low).cwiseMin(high) - x).norm();
    }
  }
  const double magnitude = x.cwiseAbs().maxCoeff() + c[0].cwiseAbs().maxCoeff();
  return bound * (1.0 - 1e-9) - 1e-9 * (w.norm() + h) - 1e-12 * magnitude;
}

/// The least rank any solution of eq. (3) for target q that a seed walk accepts on the simplex
/// with corners c can have (0 if nothing better is known).
template <int d>
double preimage_rank_floor(const WorldPoint<d>& q, const std::array<WorldPoint<d>, d + 1>& c,
                           const PreimageAcceptance& accept) {
  const double h = longest_edge<d>(c);
  const double tau = accept.inside_tolerance;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  // the residual the solver computes is rounded in absolute coordinates
  const double rounding = 64.0 * eps * (q.cwiseAbs().maxCoeff() + c[0].cwiseAbs().maxCoeff() + h);
  const double off = distance_floor<d>(q, c, h) - (2.0 * d * tau + accept.solver_tolerance) * h - rounding;
  const double mu = off / ((1.0 + 2.0 * d * tau) * (1.0 + 1e-12));
  if (!(mu > 0.0)) return 0.0;
  if (accept.allow_negative_distance) return mu;
  return mu > 1.001e-9 * h ? mu : 0.0;  // else mu in [-1e-9 h, 0) is not excluded: rank 0
}

/// The radius around q beyond which (by box distance) no element of longest edge <= h_max has a
/// rank floor below `rank`.
template <int d>
double rival_search_radius(const WorldPoint<d>& q, double rank, double h_max, double coordinate_magnitude,
                           const PreimageAcceptance& accept) {
  const double tau = accept.inside_tolerance;
  const double mu = std::max(rank, 1.001e-9 * h_max) * (1.0 + 2.0 * d * tau) * (1.0 + 1e-12);
  const double slack = (2.0 * d * tau + accept.solver_tolerance) * h_max +
                       64.0 * std::numeric_limits<double>::epsilon() * (q.cwiseAbs().maxCoeff() + coordinate_magnitude + h_max);
  // distance_floor's own margins, for a distance up to this radius
  return (mu + slack) * (1.0 + 1e-6) + 4e-9 * h_max + 1e-12 * (q.cwiseAbs().maxCoeff() + coordinate_magnitude) +
         1e-300;
}

}  // namespace plmap::projection
