#include <plmap/core/errors.hpp>
#include <plmap/solvers/projection_solver.hpp>
#include <plmap/solvers/solver_kind.hpp>

#include <fmt/format.h>

namespace plmap {

static_assert(ProjectionSolver<DampedNewtonSolver>);
static_assert(ProjectionSolver<CeresTinySolver>);

std::string_view to_string(SolverKind kind) { return kind == SolverKind::ceres ? "ceres" : "newton"; }

SolverKind solver_kind_from_string(std::string_view name) {
  if (name == "newton") return SolverKind::newton;
  if (name == "ceres") return SolverKind::ceres;
  throw Error(fmt::format("unknown projection solver '{}' (known: newton, ceres)", name));
}

std::vector<std::string> solver_names() { return {"newton", "ceres"}; }

}  // namespace plmap
