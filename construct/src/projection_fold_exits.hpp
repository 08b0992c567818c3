#pragma once
// Normal projection, phase 4: the search after a walk's stop for where its S2 edge's preimage
// comes out again (fold_reentry.hpp says why; the walker, projection_edge_walker.hpp, restarts
// there). d = 2. Internal to construct/.

#include "fold_reentry.hpp"
#include "projection_context.hpp"
#include "projection_edge_crossings.hpp"
#include "seen_indices.hpp"
#include "segment_reach.hpp"
#include "walk_acceptance.hpp"

#include <plmap/solvers/projection_systems.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace plmap::projection {

/// Where a walk's S2 edge, from qa to qb (in the walk's direction), comes out of the fold at
/// which the walk stopped (at `stop`, edge parameter stop_eta): the nearest unfolded crossing in
/// (stop_eta, before), inside an S1 edge, as the walks solve it; its parameters are measured
/// from qa. Searched in the S1 elements within search_limits.fold_exit_reach rings around the
/// stop (see below).
struct FoldExit {
  Place<2> place;
  CrossingCandidate crossing;
};
template <class Solver>
std::optional<FoldExit> find_fold_exit(const ProjectionContext<2>& ctx, const EdgeCrossings<2, Solver>& crossings,
                                       const WorldPoint<2>& qa, const WorldPoint<2>& qb, const Place<2>& stop,
                                       double stop_eta, double before, long long& calls, long long& failures) {
  const auto& limits = ctx.options.search_limits;
  std::vector<Index> ring, next_ring, ring_edges, at_exit;
  SeenIndices seen_elements, seen_edges;
  std::vector<FoldExitCandidate> exits;
  // the rest of the edge, where an exit may lie (nearest_fold_exit keeps none elsewhere)
  const SegmentReach<2> rest(ctx, qa + stop_eta * (qb - qa), qa + before * (qb - qa));
  auto solve = [&](Index edge) -> std::optional<FoldExitCandidate> {
    // the closed-form root of eq. (4)'s quadratic, without the solver: dozens of S1 edges
    // are tried per search, and only the one chosen is solved (below)
    const auto ev = ctx.s1.edge_vertices(edge);
    const WorldPoint<2>& p0 = ctx.s1.vertex(ev[0]);
    const WorldPoint<2>& p1 = ctx.s1.vertex(ev[1]);
    if (rest.out_of_reach(0.5 * (p0 + p1), 0.5 * (p1 - p0).norm())) return std::nullopt;
    EdgeCrossingSystem sys;
    sys.edge = {p0, p1};
    sys.directions = {ctx.vertex_directions[ev[0]], ctx.vertex_directions[ev[1]]};
    sys.target = {qa, qb};
    const auto root = sys.root_on_the_edges();
    if (!root || !ctx.distance_ok((*root)(1), sys.scale())) return std::nullopt;
    return FoldExitCandidate{edge, std::clamp((*root)(0), 0.0, 1.0), (*root)(2), (*root)(1)};
  };
  auto accept = [&](const FoldExitCandidate& c) {
    // inside the S1 edge (an S1 vertex is a ghost node's or vertex preimage's place), and
    // unfolded in an element at it, as the walks judge a crossing
    const Place<2> at = ctx.edge_place(c.domain_edge, c.lambda);
    if (at.kind != PlaceKind::edge) return false;
    ctx.elements_of(at, at_exit);
    return unfolded_in_some_element(at_exit, [&](Index t) { return ctx.unfolded_in_at(t, at, c.mu); });
  };
  // A fold band is a few elements wide: the exit is looked for ring by ring around the stop
  // (ring 0: the elements at it; ring r + 1: the elements sharing a vertex with ring r, not seen
  // yet; one element size per ring), up to fold_exit_reach rings, and the first ring whose S1
  // edges give an exit ends the search. A crossing in a nearer ring is, but for a preimage that
  // doubles back, also the nearer one along the S2 edge, and most stops have their exit in the
  // first two rings: far fewer edges are solved than by a search of every element within the
  // reach.
  std::vector<Index> candidates;
  ctx.elements_of(stop, candidates);
  take_unseen_into(candidates, seen_elements, ring);
  const int rings = static_cast<int>(std::ceil(limits.fold_exit_reach));
  std::optional<FoldExitCandidate> exit;
  for (int r = 0; r <= rings && !ring.empty(); ++r) {
    candidates.clear();
    for (Index t : ring)
      for (int k = 0; k < 3; ++k) candidates.push_back(ctx.s1.element_edge(t, k));
    take_unseen_into(candidates, seen_edges, ring_edges);
    exit = nearest_fold_exit(stop_eta, before, limits.edge_parameter_slack, ring_edges, exits, solve, accept);
    if (exit || r == rings) break;
    candidates.clear();
    for (Index t : ring)
      for (Index v : ctx.s1.element(t))
        for (Index n : ctx.s1.vertex_elements(v)) candidates.push_back(n);
    take_unseen_into(candidates, seen_elements, next_ring);
    std::swap(ring, next_ring);
  }
  if (!exit) return std::nullopt;
  // the chosen crossing as the walks solve it
  const CrossingCandidate c = crossings.solve(exit->domain_edge, qa, qb, calls, failures);
  const double slack = limits.edge_parameter_slack;
  if (!c.valid || !(c.eta > stop_eta + slack) || !(c.eta < before - slack)) return std::nullopt;
  const Place<2> at = ctx.edge_place(exit->domain_edge, c.lambda);
  if (at.kind != PlaceKind::edge) return std::nullopt;
  return FoldExit{at, c};
}


}  // namespace plmap::projection
