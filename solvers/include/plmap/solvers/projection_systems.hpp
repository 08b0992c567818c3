#pragma once
/// \file
/// The two nonlinear systems of normal projection (paper section 3.2).
///
/// The direction field nu is given at the corners of an S1 element and interpolated linearly.
///
/// VertexProjectionSystem<d> (paper eq. 3): which point p of an S1 element is projected along
/// nu onto a given point q (an S2 vertex)?
///     F(xi, mu) = p(xi) + mu nu(xi) - q = 0,
///     p(xi) = c_0 + sum_i xi_i (c_{i+1} - c_0),   nu(xi) = n_0 + sum_i xi_i (n_{i+1} - n_0),
/// with plmap's local coordinates xi (types.hpp); unknowns x = (xi_0, ..., xi_{d-1}, mu).
///
/// EdgeCrossingSystem (paper eq. 4, d = 2): where does the projection of an S2 edge
/// (q_0, q_1) cross an S1 edge (p_0, p_1)?
///     F(lambda, mu, eta) = p(lambda) + mu nu(lambda) - q(eta) = 0,
///     p(lambda) = p_0 + lambda (p_1 - p_0),  nu(lambda) = n_0 + lambda (n_1 - n_0),
///     q(eta) = q_0 + eta (q_1 - q_0);   unknowns x = (lambda, mu, eta).
///
/// Both are bilinear; for a constant direction field they are linear and one Newton step from
/// any start solves them. Jacobians are analytic.

#include <plmap/core/types.hpp>
#include <plmap/solvers/nonlinear_system.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>

namespace plmap {

template <int d>
  requires SurfaceDimension<d>
struct VertexProjectionSystem {
  static constexpr int size = d + 1;
  using Vector = Eigen::Matrix<double, d + 1, 1>;
  using Jacobian = Eigen::Matrix<double, d + 1, d + 1>;

  std::array<WorldPoint<d>, d + 1> corners;     ///< c_0..c_d of the S1 element
  std::array<WorldPoint<d>, d + 1> directions;  ///< n_0..n_d at those corners
  WorldPoint<d> target;                          ///< q

  Vector residual(const Vector& x) const {
    WorldPoint<d> r = corners[0] - target + x(d) * directions[0];
    for (int i = 0; i < d; ++i)
      r += x(i) * ((corners[i + 1] - corners[0]) + x(d) * (directions[i + 1] - directions[0]));
    return r;
  }

  Jacobian jacobian(const Vector& x) const {
    Jacobian j;
    WorldPoint<d> nu = directions[0];
    for (int i = 0; i < d; ++i) {
      j.col(i) = (corners[i + 1] - corners[0]) + x(d) * (directions[i + 1] - directions[0]);
      nu += x(i) * (directions[i + 1] - directions[0]);
    }
    j.col(d) = nu;
    return j;
  }

  /// Longest edge of the element: the scale of the residual.
  double scale() const {
    double h = 0.0;
    for (int i = 0; i <= d; ++i)
      for (int k = i + 1; k <= d; ++k) h = std::max(h, (corners[i] - corners[k]).norm());
    return h;
  }

  /// Start value: the solution of the system with nu frozen at the element's centroid (exact
  /// for constant direction fields). Falls back to the centroid and mu = 0 if that is singular.
  Vector initial_guess() const {
    Jacobian a;
    WorldPoint<d> nu = directions[0];
    for (int i = 0; i < d; ++i) nu += directions[i + 1];
    nu /= d + 1;
    for (int i = 0; i < d; ++i) a.col(i) = corners[i + 1] - corners[0];
    a.col(d) = nu;
    const Eigen::PartialPivLU<Jacobian> lu(a);
    Vector x = lu.solve(target - corners[0]);
    if (!x.allFinite() || std::abs(a.determinant()) <= 1e-14 * std::pow(scale(), d) * nu.norm()) {
      x.setConstant(1.0 / (d + 1));
      x(d) = 0.0;
    }
    return x;
  }

  WorldPoint<d> point(const Vector& x) const {
    WorldPoint<d> p = corners[0];
    for (int i = 0; i < d; ++i) p += x(i) * (corners[i + 1] - corners[0]);
    return p;
  }
};

struct EdgeCrossingSystem {
  static constexpr int size = 3;
  using Vector = Eigen::Vector3d;
  using Jacobian = Eigen::Matrix3d;

  std::array<Eigen::Vector3d, 2> edge;        ///< p_0, p_1 (S1 edge)
  std::array<Eigen::Vector3d, 2> directions;  ///< n_0, n_1 at p_0, p_1
  std::array<Eigen::Vector3d, 2> target;      ///< q_0, q_1 (S2 edge)

  Vector residual(const Vector& x) const {
    return edge[0] + x(0) * (edge[1] - edge[0]) +
           x(1) * (directions[0] + x(0) * (directions[1] - directions[0])) - target[0] -
           x(2) * (target[1] - target[0]);
  }

  Jacobian jacobian(const Vector& x) const {
    Jacobian j;
    j.col(0) = (edge[1] - edge[0]) + x(1) * (directions[1] - directions[0]);
    j.col(1) = directions[0] + x(0) * (directions[1] - directions[0]);
    j.col(2) = target[0] - target[1];
    return j;
  }

  double scale() const { return std::max((edge[1] - edge[0]).norm(), (target[1] - target[0]).norm()); }

  /// Start value: the solution with nu frozen at the edge midpoint; (1/2, 0, 1/2) if singular.
  Vector initial_guess() const {
    Jacobian a;
    a.col(0) = edge[1] - edge[0];
    a.col(1) = 0.5 * (directions[0] + directions[1]);
    a.col(2) = target[0] - target[1];
    const Eigen::PartialPivLU<Jacobian> lu(a);
    Vector x = lu.solve(target[0] - edge[0]);
    const double s = scale();
    if (!x.allFinite() || std::abs(a.determinant()) <= 1e-14 * s * s * a.col(1).norm())
      x = Vector(0.5, 0.0, 0.5);
    return x;
  }
};

}  // namespace plmap
