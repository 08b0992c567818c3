// Normal projection, phase 4: the points where S2 edges enter S1 across its boundary
// (projection_edge_walks.hpp, find_boundary_entries); the edge walks start there too.

#include "projection_edge_crossings.hpp"
#include "projection_edge_walks.hpp"

#include <plmap/core/parallel_ranges.hpp>
#include <plmap/solvers/projection_systems.hpp>
#include <plmap/solvers/solver_kind.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace plmap::projection {

template <int d, class Solver>
std::vector<std::vector<BoundaryEntry<d>>> find_boundary_entries(const ProjectionContext<d>& ctx,
                                                                 const ProjectionState<d>& state, const Solver& solver) {
  const EdgeCrossings<d, Solver> crossings(ctx, solver);
  // One list per S2 edge, made only once an entry is found: on a closed S1 there is none, and
  // the million empty lists of the 1M circles cost their page faults and frees for nothing.
  std::vector<std::vector<BoundaryEntry<d>>> entries;
  auto list_of = [&](Index e) -> std::vector<BoundaryEntry<d>>& {
    if (entries.empty()) entries.resize(static_cast<std::size_t>(ctx.s2.edge_count()));
    return entries[static_cast<std::size_t>(e)];
  };
  if constexpr (d == 1) {
    for (Index v = 0; v < ctx.s1.vertex_count(); ++v) {
      if (!ctx.s1.is_boundary_vertex(v) || state.vertex_state[v] != VertexState::ghost || !state.vertex_image[v]) continue;
      const auto& image = *state.vertex_image[v];
      BoundaryEntry<1> entry;
      entry.place.kind = PlaceKind::vertex;
      entry.place.index = v;
      entry.eta = image.local(0);
      entry.crossing = VertexCrossing{v, entry.eta};
      list_of(image.element).push_back(entry);
    }
  } else {
    // The S1 edges are searched in pieces on all threads, each piece listing what it finds in
    // edge order; the lists are then taken in piece order, so the entries, and which of two at
    // the same place is kept, are those of one thread whatever the thread count.
    struct Found {
      Index target_edge;
      BoundaryEntry<2> entry;
    };
    const std::size_t piece_size = 4096;
    const auto s1_edges = static_cast<std::size_t>(ctx.s1.edge_count());
    std::vector<std::vector<Found>> found((s1_edges + piece_size - 1) / piece_size);
    const double piece_slack = ctx.options.search_limits.piece_parameter_slack;
    parallel_for_pieces_of_size(s1_edges, piece_size, ctx.threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
      long long calls = 0, failures = 0;
      std::vector<Index> edges;
      for (auto edge = static_cast<Index>(begin); edge < static_cast<Index>(end); ++edge) {
        if (ctx.s1.edge_elements(edge).size() != 1) continue;
        const auto ev = ctx.s1.edge_vertices(edge);
        const auto& ia = state.vertex_image[ev[0]];
        const auto& ib = state.vertex_image[ev[1]];
        if (!ia && !ib) continue;
        const double length = (ctx.s1.vertex(ev[0]) - ctx.s1.vertex(ev[1])).norm();
        WorldPoint<2> centre;
        double radius;
        if (ia && ib) {
          const WorldPoint<2> a = ctx.s2.world_position(ia->element, ia->local);
          const WorldPoint<2> b = ctx.s2.world_position(ib->element, ib->local);
          centre = 0.5 * (a + b);
          radius = 0.5 * (a - b).norm();
        } else {
          const auto& i = ia ? *ia : *ib;
          centre = ctx.s2.world_position(i.element, i.local);
          radius = 2.0 * length;
        }
        edges.clear();
        for (Index t : ctx.s2_index->within(centre, radius + ctx.s2_index->radius * 1.01 + 1e-9 * length))
          for (int j = 0; j < 3; ++j) edges.push_back(ctx.s2.element_edge(t, j));
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        for (Index e : edges) {
          const auto tv = ctx.s2.edge_vertices(e);
          const CrossingCandidate c = crossings.solve(edge, ctx.s2.vertex(tv[0]), ctx.s2.vertex(tv[1]), calls, failures);
          if (!c.valid || !(c.eta > piece_slack && c.eta < 1.0 - piece_slack)) continue;
          if (!ctx.unfolded_at(ctx.edge_place(edge, c.lambda), c.mu)) continue;
          BoundaryEntry<2> entry;
          entry.place = ctx.edge_place(edge, c.lambda);
          entry.eta = c.eta;
          entry.crossing = EdgeCrossing{edge, c.lambda, c.eta};
          found[k].push_back({e, entry});
        }
      }
      ctx.solver_calls += calls;
      ctx.solver_failures += failures;
    });
    for (const auto& piece : found)
      for (const auto& [e, entry] : piece) {
        auto& list = list_of(e);
        const bool duplicate = std::any_of(list.begin(), list.end(), [&](const BoundaryEntry<2>& x) {
          return x.place == entry.place;
        });
        if (!duplicate) list.push_back(entry);
      }
  }
  for (auto& list : entries)
    std::sort(list.begin(), list.end(), [](const auto& x, const auto& y) { return x.eta < y.eta; });
  return entries;
}

#define PLMAP_BOUNDARY_ENTRIES(d, Solver)                                                \
  template std::vector<std::vector<BoundaryEntry<d>>> find_boundary_entries<d, Solver>( \
      const ProjectionContext<d>&, const ProjectionState<d>&, const Solver&);
PLMAP_BOUNDARY_ENTRIES(1, DampedNewtonSolver)
PLMAP_BOUNDARY_ENTRIES(2, DampedNewtonSolver)
PLMAP_BOUNDARY_ENTRIES(1, CeresTinySolver)
PLMAP_BOUNDARY_ENTRIES(2, CeresTinySolver)
#undef PLMAP_BOUNDARY_ENTRIES

}  // namespace plmap::projection
