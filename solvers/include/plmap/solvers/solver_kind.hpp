#pragma once
/// \file
/// Run-time names of the projection solvers ("newton", "ceres") for configuration files and the
/// command line, and a dispatcher that calls a generic function with the chosen model. Inside
/// algorithms the solver is a template parameter; the name is resolved once, at the API edge.

#include <plmap/solvers/ceres_tiny_solver.hpp>
#include <plmap/solvers/damped_newton.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace plmap {

enum class SolverKind { newton, ceres };

/// "newton" or "ceres".
std::string_view to_string(SolverKind kind);
/// Parses a solver name; throws plmap::Error naming the unknown name and the known ones.
SolverKind solver_kind_from_string(std::string_view name);
/// All registered names, for help texts.
std::vector<std::string> solver_names();

/// Calls f(solver) with the model of `kind`, both configured with `relative_tolerance`.
template <class F>
decltype(auto) with_solver(SolverKind kind, double relative_tolerance, F&& f) {
  if (kind == SolverKind::ceres) {
    CeresTinySolver s;
    s.options.relative_tolerance = relative_tolerance;
    return f(s);
  }
  DampedNewtonSolver s;
  s.options.relative_tolerance = relative_tolerance;
  return f(s);
}

}  // namespace plmap
