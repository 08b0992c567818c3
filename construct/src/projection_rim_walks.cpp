// Normal projection, phase 5: walks from where the rim's tracing crosses S2 edges that no walk
// gave a piece (projection_edge_walks.hpp, plan_rim_walks; docs/projection.md, "Walks from the
// rim").

#include "projection_edge_walker.hpp"

#include <plmap/solvers/solver_kind.hpp>

#include <algorithm>
#include <span>
#include <utility>
#include <vector>

namespace plmap::projection {

namespace {

/// The walks of S2 edge e (no piece yet) from the rim crossings `starts` (by edge parameter)
/// into the band, appended to `buffer` as pieces; returns the plan. A crossing inside the
/// stretch of an earlier start's walk is that walk's other end, and is skipped.
template <class Solver>
PlannedEdge plan_from_rim(const EdgeWalker<2, Solver>& walker, const ProjectionContext<2>& ctx,
                          const ProjectionState<2>& state, Index e, std::span<const RimStart<2>> starts,
                          PlanBuffer<2>& buffer) {
  constexpr int d = 2;
  using Walker = EdgeWalker<2, Solver>;
  PlannedEdge plan;
  plan.pieces_begin = static_cast<std::uint32_t>(buffer.pieces.size());
  plan.failures_begin = static_cast<std::uint32_t>(buffer.failures.size());
  const double piece_slack = ctx.options.search_limits.piece_parameter_slack;
  const auto tv = ctx.target_edge_vertices(e);
  const WorldPoint<2> qa = ctx.s2.vertex(tv[0]), qb = ctx.s2.vertex(tv[1]);
  auto& crossings = buffer.crossings;
  std::vector<std::pair<double, double>> walked;  // stretches of the edge parameter
  for (const RimStart<d>& start : starts) {
    const RimPoint<d>& rim = start.at;
    if (std::any_of(walked.begin(), walked.end(), [&](const auto& stretch) {
          return rim.eta >= stretch.first - piece_slack && rim.eta <= stretch.second + piece_slack;
        }))
      continue;
    const int into_band = ctx.direction_into_band(rim.element, rim.level, rim.local, qa, qb);
    if (into_band == 0) continue;
    const bool forwards = into_band > 0;
    Place<d> inside;
    inside.kind = PlaceKind::element;
    inside.index = rim.element;
    inside.local = rim.local;
    const std::size_t begin = crossings.size();
    const WalkDirection direction = forwards ? WalkDirection::from_first_vertex : WalkDirection::from_second_vertex;
    const std::optional<Place<d>>& far_vertex = state.target_place[forwards ? tv[1] : tv[0]];
    WalkResult<d> w = walker.walk(e, inside, forwards ? rim.eta : 1.0 - rim.eta, far_vertex, direction, buffer);
    // one rim node per S1 element, S2 edge and level: leaving the band the same way in the
    // start's element, the piece ends at its last crossing
    if (w.rim && w.rim->element == rim.element && w.rim->level == rim.level) w.rim.reset();
    const bool reached = w.end == WalkEnd::reached;
    const bool to_rim = w.end == WalkEnd::failed && w.rim.has_value();
    if (!reached && !to_rim && w.crossing_count == 0) {
      crossings.resize(begin);
      continue;
    }
    const double far_eta = reached ? 1.0 : (to_rim ? w.rim->eta : w.eta);  // in the walk's direction
    if (forwards) {
      // kept one after the other: as two arguments of one call, their order (and so the rim
      // points' indices) would be the compiler's choice
      const std::uint32_t start_rim = buffer.keep_rim(rim, false);
      const std::uint32_t end_rim = to_rim ? buffer.keep_rim(*w.rim, false) : PlanBuffer<d>::no_rim;
      Walker::add_piece(buffer, begin, PieceStart::rim_node,
                reached ? PieceEnd::second_vertex : (to_rim ? PieceEnd::rim_node : PieceEnd::last_crossing),
                end_rim, start_rim);
      walked.emplace_back(rim.eta, far_eta);
    } else {
      // measured from the first vertex again, in the edge's direction, ending at the start
      std::reverse(crossings.begin() + static_cast<std::ptrdiff_t>(begin), crossings.end());
      for (std::size_t i = begin; i < crossings.size(); ++i)
        crossings[i].target_parameter = 1.0 - crossings[i].target_parameter;
      const std::uint32_t start_rim = to_rim ? buffer.keep_rim(*w.rim, true) : PlanBuffer<d>::no_rim;
      Walker::add_piece(buffer, begin,
                reached ? PieceStart::first_vertex : (to_rim ? PieceStart::rim_node : PieceStart::first_crossing),
                PieceEnd::rim_node, buffer.keep_rim(rim, false), start_rim);
      walked.emplace_back(1.0 - far_eta, rim.eta);
    }
  }
  plan.pieces_end = static_cast<std::uint32_t>(buffer.pieces.size());
  plan.failures_end = static_cast<std::uint32_t>(buffer.failures.size());
  return plan;
}

}  // namespace

template <int d, class Solver>
void plan_rim_walks(const ProjectionContext<d>& ctx, const ProjectionState<d>& state, const Solver& solver,
                    std::span<const RimStart<d>> starts, PlanBuffer<d>& buffer, std::vector<Index>& edges,
                    std::vector<PlannedEdge>& planned) {
  buffer.clear();
  edges.clear();
  planned.clear();
  if constexpr (d == 2) {
    const EdgeWalker<d, Solver> walker(ctx, state, solver);
    for (std::size_t i = 0; i < starts.size();) {
      std::size_t j = i;
      while (j < starts.size() && starts[j].target_edge == starts[i].target_edge) ++j;
      const Index e = starts[i].target_edge;
      const PlannedEdge plan = plan_from_rim(walker, ctx, state, e, starts.subspan(i, j - i), buffer);
      if (plan.pieces_end > plan.pieces_begin) {
        edges.push_back(e);
        planned.push_back(plan);
      }
      i = j;
    }
  }
}

#define PLMAP_RIM_WALKS(d, Solver)                                                                         \
  template void plan_rim_walks<d, Solver>(const ProjectionContext<d>&, const ProjectionState<d>&, const Solver&, \
                                          std::span<const RimStart<d>>, PlanBuffer<d>&, std::vector<Index>&,      \
                                          std::vector<PlannedEdge>&);
PLMAP_RIM_WALKS(1, DampedNewtonSolver)
PLMAP_RIM_WALKS(2, DampedNewtonSolver)
PLMAP_RIM_WALKS(1, CeresTinySolver)
PLMAP_RIM_WALKS(2, CeresTinySolver)
#undef PLMAP_RIM_WALKS

}  // namespace plmap::projection
