// Normal projection, phase 4: edge walks (projection_edge_walks.hpp), planned block by block
// with the walker of projection_edge_walker.hpp.

#include "projection_edge_walker.hpp"

#include <plmap/solvers/solver_kind.hpp>

namespace plmap::projection {

template <int d, class Solver>
void plan_edge_block(const ProjectionContext<d>& ctx, const ProjectionState<d>& state, const Solver& solver,
                     Index block, Index block_end, unsigned slot, PlanBuffer<d>& buffer,
                     std::vector<PlannedEdge>& planned) {
  const EdgeWalker<d, Solver> walker(ctx, state, solver);
  buffer.clear();
  planned.resize(static_cast<std::size_t>(block_end - block));
  for (Index e = block; e < block_end; ++e) planned[e - block] = walker.plan_edge(e, slot, buffer);
}

#define PLMAP_EDGE_WALKS(d, Solver)                                                                          \
  template void plan_edge_block<d, Solver>(const ProjectionContext<d>&, const ProjectionState<d>&, const Solver&, \
                                           Index, Index, unsigned, PlanBuffer<d>&, std::vector<PlannedEdge>&);
PLMAP_EDGE_WALKS(1, DampedNewtonSolver)
PLMAP_EDGE_WALKS(2, DampedNewtonSolver)
PLMAP_EDGE_WALKS(1, CeresTinySolver)
PLMAP_EDGE_WALKS(2, CeresTinySolver)
#undef PLMAP_EDGE_WALKS

}  // namespace plmap::projection
