#pragma once
/// \file
/// ProjectionSolver: the strategy concept for solving the projection systems (paper eq. 3, 4).
///
/// A model has a `solve(system, initial_guess)` member template accepting any
/// SmallNonlinearSystem and returning SolveResult<system size>. Models: DampedNewtonSolver
/// (damped_newton.hpp) and CeresTinySolver (ceres_tiny_solver.hpp). Algorithms take the solver as
/// a template parameter (zero cost); solver_kind.hpp maps the run-time names to the models.

#include <plmap/solvers/nonlinear_system.hpp>
#include <plmap/solvers/projection_systems.hpp>

#include <concepts>

namespace plmap {

template <class Solver>
concept ProjectionSolver =
    requires(const Solver& solver, const VertexProjectionSystem<1>& s1,
             const VertexProjectionSystem<2>& s2, const EdgeCrossingSystem& e) {
      { solver.solve(s1, VertexProjectionSystem<1>::Vector{}) } -> std::same_as<SolveResult<2>>;
      { solver.solve(s2, VertexProjectionSystem<2>::Vector{}) } -> std::same_as<SolveResult<3>>;
      { solver.solve(e, EdgeCrossingSystem::Vector{}) } -> std::same_as<SolveResult<3>>;
    };

}  // namespace plmap
