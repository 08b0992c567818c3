#pragma once
/// \file
/// Focal points of the projection along a direction field: where it folds.
///
/// On an S1 element the projection sweeps space by F(xi, t) = p(xi) + t nu(xi) (the notation of
/// projection_systems.hpp). Its Jacobian determinant along the ray from p(xi),
///     J(t) = det [ dp/dxi_1 + t dnu/dxi_1, ..., dp/dxi_d + t dnu/dxi_d, nu(xi) ],
/// is a polynomial in t of degree d. Where it vanishes the neighbouring rays meet (a focal point
/// of the field, e.g. under a concave part of S1 whose normals converge), and beyond it the swept
/// sheet is folded back: the points found there are images of a folded projection (paper Fig. 5,
/// right), and regions built on them map with reversed orientation or overlap others on S2.
///
/// A solution (xi, mu) of eq. (3) or (4) is therefore accepted only if the ray from p(xi)
/// reaches distance mu without passing a focal point: J keeps the sign it has at t = 0 on the
/// whole interval between 0 and mu. The test is combinatorial up to a tolerance relative to
/// the scale of J, so it does not depend on the size of the surfaces.

#include <plmap/core/types.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace plmap {

/// Coefficients a_0..a_d of J(t) = sum a_k t^k at local point xi of the element with the given
/// corners and corner directions.
template <int d>
  requires SurfaceDimension<d>
std::array<double, d + 1> ray_jacobian_polynomial(const std::array<WorldPoint<d>, d + 1>& corners,
                                                  const std::array<WorldPoint<d>, d + 1>& directions,
                                                  const LocalPoint<d>& xi) {
  WorldPoint<d> nu = directions[0];
  for (int i = 0; i < d; ++i) nu += xi(i) * (directions[i + 1] - directions[0]);
  if constexpr (d == 1) {
    const Eigen::Vector2d e = corners[1] - corners[0], f = directions[1] - directions[0];
    const auto det2 = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
    return {det2(e, nu), det2(f, nu)};
  } else {
    const Eigen::Vector3d e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
    const Eigen::Vector3d f1 = directions[1] - directions[0], f2 = directions[2] - directions[0];
    // det[a, b, nu] = (a x b) . nu, multilinear in the columns
    return {e1.cross(e2).dot(nu), (f1.cross(e2) + e1.cross(f2)).dot(nu), f1.cross(f2).dot(nu)};
  }
}

/// True if the ray from p(xi) along nu(xi) reaches t = mu without passing a focal point: J(t)
/// has no root strictly between 0 and mu (a sign change, or a double root where J touches
/// zero). Values of J within 1e-9 of its scale (the largest |a_k| |mu|^k) count as zero, so a
/// solution exactly at a focal point, or on an element whose direction field is tangential at
/// p(xi), is accepted; the other checks of the projection deal with those.

template <int d>
  requires SurfaceDimension<d>
bool reaches_without_focal_point(const std::array<WorldPoint<d>, d + 1>& corners,
                                 const std::array<WorldPoint<d>, d + 1>& directions, const LocalPoint<d>& xi,
                                 double mu) {
  if (mu == 0.0 || !std::isfinite(mu)) return true;
  const auto a = ray_jacobian_polynomial<d>(corners, directions, xi);
  double scale = 0.0;
  for (int k = 0; k <= d; ++k) scale = std::max(scale, std::abs(a[k]) * integer_power(std::abs(mu), k));
  if (!(scale > 0.0)) return true;
  const double zero = 1e-9 * scale;
  auto value = [&](double t) {
    double v = 0.0;
    for (int k = d; k >= 0; --k) v = v * t + a[k];
    return v;
  };
  auto sign = [&](double v) { return v > zero ? 1 : (v < -zero ? -1 : 0); };
  const int at_start = sign(value(0.0)), at_end = sign(value(mu));
  if (at_start != 0 && at_end != 0 && at_start != at_end) return false;
  // J is monotone between its critical points: for d = 2 a root inside the interval that the
  // ends do not show is at the vertex of the parabola, where J touches or crosses zero. A
  // double root is a point focus (the rays of a spherical cap meet in its centre): the sheet
  // beyond it is turned by 180 degrees, orientation kept but folded all the same.
  if constexpr (d == 2) {
    if (a[2] != 0.0) {
      const double vertex = -a[1] / (2.0 * a[2]);
      if (vertex > std::min(0.0, mu) && vertex < std::max(0.0, mu)) {
        const int at_vertex = sign(value(vertex));
        const int outer = at_start != 0 ? at_start : at_end;
        if (outer != 0 && at_vertex != outer) return false;
      }
    }
  }
  return true;
}

/// A distance up to which no ray of the element meets a focal point: reaches_without_focal_point
/// is true for every local point of the element (barycentric weights down to -1e-9, the slack
/// of the projection's inside tests) and every |mu| <= the returned value. 0 where the
/// directions are nearly tangential to the element or point to both of its sides.
///
/// The projection asks the focal test for almost every solution it accepts, and on the usual
/// element the answer is obviously yes: J(t) = a_0 + a_1 t (+ a_2 t^2) with |a_0| bounded below
/// and |a_1|, |a_2| bounded above over the element (J is linear in nu, and nu(xi) is a convex
/// combination of the corner directions). Where |a_1| |mu| + |a_2| mu^2 <= |a_0| / 2, J keeps
/// the sign of a_0 with a margin far above the test's zero threshold and its rounding, so the
/// test would accept: this distance, computed once per element, answers it without the
/// polynomial.
template <int d>
  requires SurfaceDimension<d>
double focal_free_distance(const std::array<WorldPoint<d>, d + 1>& corners,
                           const std::array<WorldPoint<d>, d + 1>& directions) {
  double longest_direction = 0.0;
  for (int k = 0; k <= d; ++k) longest_direction = std::max(longest_direction, directions[k].norm());
  longest_direction *= 1.0 + 1e-6;  // nu at local points barely outside the element
  // J's coefficients are a_k = N_k . nu(xi) for vectors N_k of the element (d = 1: a_k =
  // det[E_k, nu] with E_0 = the edge, E_1 = the difference of the directions).
  double a0_smallest = std::numeric_limits<double>::infinity(), a0_largest = 0.0;
  int sign = 0;
  double n0_length, a1_largest, a2_largest = 0.0;
  auto take_a0 = [&](double a0) {
    const int s = a0 > 0.0 ? 1 : (a0 < 0.0 ? -1 : 0);
    if (sign == 0) sign = s;
    if (s == 0 || s != sign) sign = 2;  // mixed or zero: no bound
    a0_smallest = std::min(a0_smallest, std::abs(a0));
    a0_largest = std::max(a0_largest, std::abs(a0));
  };
  if constexpr (d == 1) {
    const Eigen::Vector2d e = corners[1] - corners[0], f = directions[1] - directions[0];
    for (int k = 0; k <= 1; ++k) take_a0(e.x() * directions[k].y() - e.y() * directions[k].x());
    n0_length = e.norm();
    a1_largest = f.norm() * longest_direction;
  } else {
    const Eigen::Vector3d e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
    const Eigen::Vector3d f1 = directions[1] - directions[0], f2 = directions[2] - directions[0];
    const Eigen::Vector3d n0 = e1.cross(e2);
    for (int k = 0; k <= 2; ++k) take_a0(n0.dot(directions[k]));
    n0_length = n0.norm();
    a1_largest = (f1.cross(e2) + e1.cross(f2)).norm() * longest_direction;
    a2_largest = f1.cross(f2).norm() * longest_direction;
  }
  // The margin: a_0 far from zero relative to its scale, so that nu slightly outside the
  // element and the rounding of a_0 cannot change its sign or come near the zero threshold.
  if (sign == 2 || !(a0_smallest > 1e-6 * n0_length * longest_direction) || !std::isfinite(a0_largest)) return 0.0;
  const double budget = 0.5 * a0_smallest;  // |a_1| m + |a_2| m^2 <= budget
  double m;
  if (a2_largest > 0.0)
    m = 2.0 * budget / (a1_largest + std::sqrt(a1_largest * a1_largest + 4.0 * a2_largest * budget));
  else if (a1_largest > 0.0)
    m = budget / a1_largest;
  else
    return std::numeric_limits<double>::infinity();
  return std::isfinite(m) ? 0.99 * m : 0.0;
}

}  // namespace plmap
