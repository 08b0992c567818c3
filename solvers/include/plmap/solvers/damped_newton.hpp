#pragma once
/// \file
/// DampedNewtonSolver: a hand-written damped Newton method for SmallNonlinearSystem, a model of
/// ProjectionSolver.
///
/// Each step solves J dx = -F with a partially pivoted LU of the fixed-size Jacobian and then
/// backtracks (halving the step) until the residual norm decreases by the Armijo factor. All
/// vectors are fixed-size Eigen types: no allocation. Converged means
/// |F(x)| <= relative_tolerance * system.scale(). A singular Jacobian, a step that cannot reduce
/// the residual, or the iteration limit end the solve with converged = false.

#include <plmap/solvers/nonlinear_system.hpp>
#include <plmap/solvers/small_lu.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace plmap {

struct DampedNewtonOptions {
  /// Stop when |F(x)| <= relative_tolerance * scale (scale: the element diameter).
  double relative_tolerance = 1e-12;
  int max_iterations = 30;
  /// Give up when backtracking has halved the step below this fraction.
  double min_damping = 1.0 / 1024.0;
};

struct DampedNewtonSolver {
  DampedNewtonOptions options;

  /// J dx = -F by partially pivoted LU; for the projection's 2x2 and 3x3 systems the hand-written
  /// copy of Eigen's algorithm (small_lu.hpp), same bits at a fraction of the cost.
  template <SmallNonlinearSystem System>
  static typename System::Vector newton_step(const typename System::Jacobian& j,
                                             const typename System::Vector& minus_f) {
    if constexpr (System::size == 2 || System::size == 3)
      return solve_with_partial_pivoting<System::size>(j, minus_f);
    else
      return Eigen::PartialPivLU<typename System::Jacobian>(j).solve(minus_f);
  }

  template <SmallNonlinearSystem System>
  SolveResult<System::size> solve(const System& system, const typename System::Vector& initial) const {
    using Vector = typename System::Vector;
    SolveResult<System::size> out;
    const double scale = system.scale() > 0.0 ? system.scale() : 1.0;
    const double tolerance = options.relative_tolerance * scale;
    Vector x = initial;
    Vector r = system.residual(x);
    double norm = r.norm();
    int it = 0;
    for (; it < options.max_iterations && norm > tolerance; ++it) {
      const Vector dx = newton_step<System>(system.jacobian(x), -r);
      if (!dx.allFinite()) break;  // singular Jacobian
      double damping = 1.0;
      bool accepted = false;
      while (damping >= options.min_damping) {
        const Vector trial = x + damping * dx;
        const Vector trial_r = system.residual(trial);
        const double trial_norm = trial_r.norm();
        if (trial_norm <= (1.0 - 1e-4 * damping) * norm) {
          x = trial;
          r = trial_r;
          norm = trial_norm;
          accepted = true;
          break;
        }
        damping *= 0.5;
      }
      if (!accepted) {
        ++it;
        break;
      }
    }
    out.x = x;
    out.iterations = it;
    out.relative_residual = norm / scale;
    out.converged = std::isfinite(norm) && norm <= tolerance;
    return out;
  }
};

}  // namespace plmap
