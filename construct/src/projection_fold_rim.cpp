// Normal projection: the rim where the sheets on both sides of a fold meet (projection_fold_rim.hpp).

#include "projection_fold_rim.hpp"

#include "projection_edge_crossings.hpp"

#include <plmap/solvers/solver_kind.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>

namespace plmap::projection {
namespace {

/// A path needs no more S1 elements than a walk across a few: a fold band is a few elements wide.
constexpr int max_steps = 32;

/// The local point on S2 triangle t of the point at parameter eta of its edge e.
LocalPoint<2> on_triangle_edge(const Surface<2>& s2, Index t, Index e, double eta) {
  const auto ev = s2.edge_vertices(e);
  const auto& corners = s2.element(t);
  Barycentric<2> b = Barycentric<2>::Zero();
  for (int k = 0; k < 3; ++k) {
    if (corners[k] == ev[0]) b(k) = 1.0 - eta;
    if (corners[k] == ev[1]) b(k) = eta;
  }
  return local_from_barycentric<2>(b);
}

WorldPoint<2> on_edge(const Surface<2>& s2, Index e, double eta) {
  const auto ev = s2.edge_vertices(e);
  return s2.vertex(ev[0]) + eta * (s2.vertex(ev[1]) - s2.vertex(ev[0]));
}

Index across(const Surface<2>& s1, Index edge, Index t) {
  const auto incidences = s1.edge_elements(edge);
  if (incidences.size() != 2) return invalid_index;  // S1's boundary, or a non-manifold edge
  return incidences[0].element == t ? incidences[1].element : incidences[0].element;
}

/// The preimage of the segment from a's image to b's image across S2 triangle `target`, from a's
/// element to b's: at each step the crossing of the current element's other sides with the
/// smallest segment parameter beyond the last, unfolded on both sides of its S1 edge.
template <class Solver>
std::optional<FoldRimPath> trace(const ProjectionContext<2>& ctx, const EdgeCrossings<2, Solver>& equations,
                                 Index target, const FoldRimNode& a, const FoldRimNode& b, long long& calls,
                                 long long& failures) {
  const WorldPoint<2> qa = on_edge(ctx.s2, a.target_edge, a.eta), qb = on_edge(ctx.s2, b.target_edge, b.eta);
  const LocalPoint<2> la = on_triangle_edge(ctx.s2, target, a.target_edge, a.eta);
  const LocalPoint<2> lb = on_triangle_edge(ctx.s2, target, b.target_edge, b.eta);
  const double slack = ctx.options.search_limits.edge_parameter_slack;
  FoldRimPath path;
  path.target = target;
  path.from = a.node;
  path.to = b.node;
  Index t = a.element, entered = invalid_index;
  double s = 0.0;
  for (int step = 0; step < max_steps; ++step) {
    if (t == b.element) return path;
    double best = std::numeric_limits<double>::infinity();
    CrossingCandidate chosen;
    Index chosen_edge = invalid_index;
    for (int k = 0; k < 3; ++k) {
      const Index edge = ctx.s1.element_edge(t, k);
      if (edge == entered) continue;
      const CrossingCandidate c = equations.solve(edge, qa, qb, calls, failures);
      if (!c.valid || !(c.eta > s + slack) || !(c.eta < 1.0 - slack) || !(c.eta < best)) continue;
      const Place<2> place = ctx.edge_place(edge, c.lambda);
      if (place.kind != PlaceKind::edge || !ctx.unfolded_in_at(t, place, c.mu)) continue;
      best = c.eta;
      chosen = c;
      chosen_edge = edge;
    }
    if (chosen_edge == invalid_index) return std::nullopt;
    const Index next = across(ctx.s1, chosen_edge, t);
    if (next == invalid_index || !ctx.unfolded_in_at(next, ctx.edge_place(chosen_edge, chosen.lambda), chosen.mu))
      return std::nullopt;
    path.crossings.push_back({chosen_edge, chosen.lambda, la + chosen.eta * (lb - la)});
    s = chosen.eta;
    entered = chosen_edge;
    t = next;
  }
  return std::nullopt;
}

}  // namespace

template <class Solver>
std::vector<FoldRimPath> trace_fold_rims(const ProjectionContext<2>& ctx, const Solver& solver,
                                         std::span<const FoldRimNode> nodes) {
  const EdgeCrossings<2, Solver> equations(ctx, solver);
  // the nodes by S2 triangle (each node lies on an edge of one or two triangles)
  struct AtTriangle {
    Index target;
    std::uint32_t node;
  };
  std::vector<AtTriangle> by_triangle;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (const auto& incidence : ctx.s2.edge_elements(nodes[i].target_edge))
      by_triangle.push_back({incidence.element, static_cast<std::uint32_t>(i)});
  std::sort(by_triangle.begin(), by_triangle.end(), [](const AtTriangle& x, const AtTriangle& y) {
    return x.target < y.target || (x.target == y.target && x.node < y.node);
  });
  std::vector<FoldRimPath> paths;
  long long calls = 0, failures = 0;
  for (std::size_t i = 0; i < by_triangle.size();) {
    const Index target = by_triangle[i].target;
    std::size_t j = i;
    while (j < by_triangle.size() && by_triangle[j].target == target) ++j;
    // per edge of the triangle that has nodes: its node on each side (toward its first vertex,
    // toward its second), or none; a triangle with nodes on three edges, or with two nodes on
    // one side of an edge, is left alone
    struct EdgeNodes {
      Index edge = invalid_index;
      std::array<const FoldRimNode*, 2> side{nullptr, nullptr};  // [0]: toward_first
    };
    std::array<EdgeNodes, 2> edges;
    int edge_count = 0;
    bool usable = true;
    for (std::size_t k = i; k < j && usable; ++k) {
      const FoldRimNode& n = nodes[by_triangle[k].node];
      int slot = 0;
      while (slot < edge_count && edges[slot].edge != n.target_edge) ++slot;
      if (slot == edge_count) {
        if (edge_count == 2) {
          usable = false;
          break;
        }
        edges[edge_count++].edge = n.target_edge;
      }
      const FoldRimNode*& place = edges[slot].side[n.toward_first ? 0 : 1];
      if (place) usable = false;
      place = &n;
    }
    i = j;
    if (!usable || edge_count != 2) continue;
    // the corner the two edges share, and on each edge the side toward it
    const auto e0 = ctx.s2.edge_vertices(edges[0].edge), e1 = ctx.s2.edge_vertices(edges[1].edge);
    const Index shared = (e0[0] == e1[0] || e0[0] == e1[1]) ? e0[0] : e0[1];
    const int toward0 = e0[0] == shared ? 0 : 1, toward1 = e1[0] == shared ? 0 : 1;
    const std::array<std::array<const FoldRimNode*, 2>, 2> pairs{{
        {edges[0].side[toward0], edges[1].side[toward1]},          // the sheet holding the shared corner
        {edges[0].side[1 - toward0], edges[1].side[1 - toward1]},  // the sheet holding the rest
    }};
    for (const auto& [a, b] : pairs) {
      if (!a || !b) continue;
      if (auto path = trace(ctx, equations, target, *a, *b, calls, failures)) paths.push_back(std::move(*path));
    }
  }
  ctx.solver_calls += calls;
  ctx.solver_failures += failures;
  return paths;
}

template std::vector<FoldRimPath> trace_fold_rims(const ProjectionContext<2>&, const DampedNewtonSolver&,
                                                  std::span<const FoldRimNode>);
template std::vector<FoldRimPath> trace_fold_rims(const ProjectionContext<2>&, const CeresTinySolver&,
                                                  std::span<const FoldRimNode>);

}  // namespace plmap::projection
