#pragma once
/// \file
/// CeresTinySolver: the projection systems answered by ceres::TinySolver (Ceres's
/// Levenberg-Marquardt solver for small dense fixed-size problems), fed with the same analytic
/// Jacobian as DampedNewtonSolver. A model of ProjectionSolver.
///
/// TinySolver minimises |F|^2 / 2; a square system is solved when the minimum is zero. Whatever
/// TinySolver's own stopping reason, converged is decided exactly as for the Newton solver:
/// |F(x)| <= relative_tolerance * system.scale(), so the two strategies are comparable.

#include <plmap/solvers/nonlinear_system.hpp>

#include <ceres/tiny_solver.h>

#include <cmath>

namespace plmap {

struct CeresTinySolverOptions {
  double relative_tolerance = 1e-12;
  int max_iterations = 50;
};

struct CeresTinySolver {
  CeresTinySolverOptions options;

  /// Adapts a SmallNonlinearSystem to TinySolver's Function interface (column-major Jacobian).
  template <SmallNonlinearSystem System>
  struct Function {
    using Scalar = double;
    enum { NUM_RESIDUALS = System::size, NUM_PARAMETERS = System::size };
    const System* system;
    bool operator()(const double* parameters, double* residuals, double* jacobian) const {
      const Eigen::Map<const typename System::Vector> x(parameters);
      Eigen::Map<typename System::Vector> r(residuals);
      r = system->residual(x);
      if (jacobian) {
        Eigen::Map<typename System::Jacobian> j(jacobian);
        j = system->jacobian(x);
      }
      return true;
    }
  };

  template <SmallNonlinearSystem System>
  SolveResult<System::size> solve(const System& system, const typename System::Vector& initial) const {
    SolveResult<System::size> out;
    const double scale = system.scale() > 0.0 ? system.scale() : 1.0;
    const double tolerance = options.relative_tolerance * scale;
    ceres::TinySolver<Function<System>> solver;
    solver.options.max_num_iterations = options.max_iterations;
    // Stop once the residual is within the tolerance; the other criteria are set so that they
    // do not stop the iteration before that on well-posed systems (all are absolute in Ceres).
    solver.options.cost_threshold = 0.5 * tolerance * tolerance;
    solver.options.gradient_tolerance = 1e-3 * tolerance * tolerance;
    solver.options.parameter_tolerance = 1e-3 * options.relative_tolerance;
    solver.options.function_tolerance = 1e-6 * tolerance * tolerance;
    typename System::Vector x = initial;
    const Function<System> f{&system};
    const auto& summary = solver.Solve(f, &x);
    const double norm = system.residual(x).norm();
    out.x = x;
    out.iterations = summary.iterations;
    out.relative_residual = norm / scale;
    out.converged = std::isfinite(norm) && norm <= tolerance;
    return out;
  }
};

}  // namespace plmap
