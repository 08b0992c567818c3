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
BoundaryEntries<d> find_boundary_entries(const ProjectionContext<d>& ctx, const ProjectionState<d>& state,
                                         const Solver& solver) {
  const EdgeCrossings<d, Solver> crossings(ctx, solver);
  // (S2 edge, entry) in the order found: by S1 vertex (d = 1) or S1 edge (d = 2)
  struct Found {
    Index target_edge;
    BoundaryEntry<d> entry;
  };
  std::vector<Found> all;
  if constexpr (d == 1) {
    for (Index v = 0; v < ctx.s1.vertex_count(); ++v) {
      if (!ctx.s1.is_boundary_vertex(v) || state.vertex_state[v] != VertexState::ghost || !state.vertex_image[v]) continue;
      const auto& image = *state.vertex_image[v];
      BoundaryEntry<1> entry;
      entry.place.kind = PlaceKind::vertex;
      entry.place.index = v;
      entry.eta = image.local(0);
      entry.crossing = VertexCrossing{v, entry.eta};
      all.push_back({image.element, entry});
    }
  } else {
    // The S1 edges are searched in pieces on all threads, each piece listing what it finds in
    // edge order; the lists are then taken in piece order, so the entries, and which of two at
    // the same place is kept, are those of one thread whatever the thread count.
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
    for (const auto& piece : found) all.insert(all.end(), piece.begin(), piece.end());
  }
  // By S2 edge, each edge's entries in the order found; of two at the same place the first found
  // is kept; then each edge's by the edge parameter (stable: ties keep the order found).
  std::stable_sort(all.begin(), all.end(), [](const Found& a, const Found& b) { return a.target_edge < b.target_edge; });
  BoundaryEntries<d> out;
  for (std::size_t i = 0; i < all.size();) {
    const Index e = all[i].target_edge;
    const std::size_t first = out.entry.size();
    for (; i < all.size() && all[i].target_edge == e; ++i) {
      const auto& place = all[i].entry.place;
      if (std::none_of(out.entry.begin() + static_cast<std::ptrdiff_t>(first), out.entry.end(),
                       [&](const BoundaryEntry<d>& x) { return x.place == place; }))
        out.entry.push_back(all[i].entry);
    }
    std::stable_sort(out.entry.begin() + static_cast<std::ptrdiff_t>(first), out.entry.end(),
                     [](const BoundaryEntry<d>& x, const BoundaryEntry<d>& y) { return x.eta < y.eta; });
    out.edge.resize(out.entry.size(), e);
  }
  return out;
}

#define PLMAP_BOUNDARY_ENTRIES(d, Solver)                                                              \
  template BoundaryEntries<d> find_boundary_entries<d, Solver>(const ProjectionContext<d>&, const ProjectionState<d>&, \
                                                               const Solver&);
PLMAP_BOUNDARY_ENTRIES(1, DampedNewtonSolver)
PLMAP_BOUNDARY_ENTRIES(2, DampedNewtonSolver)
PLMAP_BOUNDARY_ENTRIES(1, CeresTinySolver)
PLMAP_BOUNDARY_ENTRIES(2, CeresTinySolver)
#undef PLMAP_BOUNDARY_ENTRIES

}  // namespace plmap::projection
