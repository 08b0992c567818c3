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
#include <plmap/solvers/small_lu.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

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
    Vector x = solve_with_partial_pivoting<d + 1>(a, target - corners[0]);
    if (!x.allFinite() || std::abs(a.determinant()) <= 1e-14 * integer_power(scale(), d) * nu.norm()) {
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

  /// Start value. Eq. (4) reduces to a quadratic in lambda: eliminating eta (cross with
  /// g = q_1 - q_0) leaves A + lambda B + mu (C + lambda D) = 0 for vectors normal to g, so
  /// A + lambda B and C + lambda D are parallel, a quadratic condition on lambda. With a curved
  /// direction field both roots can be real, and an iterative solver started elsewhere may
  /// reach the one far outside the S1 edge while the crossing lies on it. So the start is the
  /// root on the S1 edge and the S2 edge (the one with the smaller |mu| if both are), from which
  /// every solver converges to the same crossing; without such a root, the solution with nu
  /// frozen at the edge midpoint (exact for constant fields), or (1/2, 0, 1/2) if singular.
  Vector initial_guess() const {
    if (const auto root = root_on_the_edges()) return *root;
    return frozen_midpoint_guess();
  }

  /// The closed-form solution of the reduced quadratic with lambda and eta within [0, 1]
  /// (slack 1e-6), if there is one.
  std::optional<Vector> root_on_the_edges() const {
    const Eigen::Vector3d e = edge[1] - edge[0], f = directions[1] - directions[0];
    const Eigen::Vector3d g = target[1] - target[0], w = edge[0] - target[0];
    const double gg = g.squaredNorm();
    if (!(gg > 0.0)) return std::nullopt;
    const Eigen::Vector3d a = w.cross(g), b = e.cross(g), c = directions[0].cross(g), dv = f.cross(g);
    // ((a + l b) x (c + l dv)) . g = k0 + k1 l + k2 l^2
    const double k0 = a.cross(c).dot(g), k1 = (a.cross(dv) + b.cross(c)).dot(g), k2 = b.cross(dv).dot(g);
    std::array<double, 2> lambdas{};
    int count = 0;
    const double size = std::max({std::abs(k0), std::abs(k1), std::abs(k2)});
    if (!(size > 0.0) || !std::isfinite(size)) return std::nullopt;
    if (std::abs(k2) <= 1e-12 * size) {
      if (std::abs(k1) > 1e-12 * size) lambdas[count++] = -k0 / k1;
    } else {
      const double disc = k1 * k1 - 4.0 * k2 * k0;
      if (disc < 0.0) return std::nullopt;
      const double q = -0.5 * (k1 + std::copysign(std::sqrt(disc), k1));  // no cancellation
      lambdas[count++] = q / k2;
      if (q != 0.0) lambdas[count++] = k0 / q;
    }
    std::optional<Vector> best;
    const double slack = 1e-6;
    for (int i = 0; i < count; ++i) {
      const double l = lambdas[i];
      if (!(l >= -slack && l <= 1.0 + slack)) continue;
      const Eigen::Vector3d along = c + l * dv, offset = a + l * b;
      const double nn = along.squaredNorm();
      if (!(nn > 0.0)) continue;
      const double mu = -offset.dot(along) / nn;
      const double eta = (w + l * e + mu * (directions[0] + l * f)).dot(g) / gg;
      if (!(eta >= -slack && eta <= 1.0 + slack)) continue;
      if (!best || std::abs(mu) < std::abs((*best)(1))) best = Vector(l, mu, eta);
    }
    return best;
  }

  /// True if no point that a solver accepts as a solution, |F(x)| <= relative_tolerance *
  /// scale(), has lambda within [-lambda_slack, 1 + lambda_slack]: the projection of the S2
  /// edge's line provably misses the S1 edge, and solving would only produce a point that the
  /// caller rejects. About half of the systems a walk across S1 poses are of this kind.
  ///
  /// Why it is conclusive: eq. (4) has a solution with parameter lambda iff p(lambda) - q_0,
  /// nu(lambda) and g = q_1 - q_0 are linearly dependent, i.e. iff the quadratic
  ///     P(lambda) = det[w + lambda e, n_0 + lambda f, g]   (w = p_0 - q_0, e, f as above)
  /// vanishes. A point x accepted with residual r = F(x) solves the system exactly with q_0
  /// moved by r, so |P(lambda)| = |det[r, nu(lambda), g]| <= |r| |nu(lambda)| |g| there. If
  /// |P| exceeds that bound (plus the rounding of P and of the residual) on the whole interval,
  /// no accepted point lies in it. P is a quadratic, so its smallest absolute value on an
  /// interval where it keeps its sign is at an end or at its vertex. The margins make the test
  /// inconclusive (false) near tangential and degenerate configurations: those are solved.
  bool misses_the_edge(double relative_tolerance, double lambda_slack) const {
    const Eigen::Vector3d e = edge[1] - edge[0], f = directions[1] - directions[0];
    const Eigen::Vector3d g = target[1] - target[0], w = edge[0] - target[0];
    const Eigen::Vector3d u = directions[0].cross(g), v = f.cross(g);
    const double k0 = w.dot(u), k1 = e.dot(u) + w.dot(v), k2 = e.dot(v);
    if (!std::isfinite(k0 + k1 + k2)) return false;
    auto p = [&](double lambda) { return (k2 * lambda + k1) * lambda + k0; };
    const double lo = -lambda_slack, hi = 1.0 + lambda_slack;
    const double at_lo = p(lo), at_hi = p(hi);
    if ((at_lo > 0.0) != (at_hi > 0.0)) return false;  // a root in between: the common case of a crossing
    double smallest = std::min(std::abs(at_lo), std::abs(at_hi));
    if (k2 != 0.0) {
      const double vertex = -k1 / (2.0 * k2);
      if (vertex > lo && vertex < hi) {
        const double at_vertex = p(vertex);
        if ((at_vertex > 0.0) != (at_lo > 0.0)) return false;
        smallest = std::min(smallest, std::abs(at_vertex));
      }
    }
    // The bound, with 1-norms (>= Euclidean norms) because they are cheap. The residual a solver
    // computes is rounded in absolute coordinates: the bound covers what that rounding can hide.
    auto norm1 = [](const Eigen::Vector3d& x) { return std::abs(x(0)) + std::abs(x(1)) + std::abs(x(2)); };
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const double e_len = norm1(e), g_len = norm1(g), w_len = norm1(w), f_len = norm1(f);
    const double n_len = std::max(norm1(directions[0]), norm1(directions[1])) + f_len * lambda_slack;
    const double coordinates = norm1(edge[0]) + norm1(target[0]) + w_len + e_len + g_len;
    const double residual = relative_tolerance * std::max(e_len, g_len) + 16.0 * eps * coordinates;
    // rounding of the coefficients and of the evaluation of P for |lambda| <= 1 + slack
    const double rounding = 32.0 * eps * (w_len + e_len) * (norm1(directions[0]) + f_len) * g_len;
    return smallest > 2.0 * (residual * n_len * g_len + rounding);
  }

  /// The solution with nu frozen at the edge midpoint (exact for constant direction fields);
  /// (1/2, 0, 1/2) if that is singular.
  Vector frozen_midpoint_guess() const {
    Jacobian a;
    a.col(0) = edge[1] - edge[0];
    a.col(1) = 0.5 * (directions[0] + directions[1]);
    a.col(2) = target[0] - target[1];
    Vector x = solve_with_partial_pivoting<3>(a, target[0] - edge[0]);
    const double s = scale();
    if (!x.allFinite() || std::abs(a.determinant()) <= 1e-14 * s * s * a.col(1).norm())
      x = Vector(0.5, 0.0, 0.5);
    return x;
  }
};

}  // namespace plmap
