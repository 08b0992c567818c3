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

}  // namespace plmap
