// DESIGN.md §4.3: the preimage of an S2 edge meets each S1 element in at most one segment. Each
// graph edge marked as target_edge is labelled with its S2 edge (d = 1: S2 segment), derived
// from its endpoints, and per element the graph edges of one label must form a single chain.

#include "check_context.hpp"

#include <numeric>

namespace plmap::detail {

namespace {

/// What a node pins down on S2's edge graph: an S2 vertex, a point inside an S2 edge, or
/// nothing (a ghost whose image lies inside an S2 element).
struct Anchor {
  enum Kind { none, vertex, edge } kind = none;
  Index id = invalid_index;
};

template <int d>
Anchor anchor_of(const MapContext<d>& ctx, Index n) {
  const auto& m = ctx.data;
  const NodeType type = m.node_type[n];
  if (is_target_vertex_preimage(type)) return {Anchor::vertex, m.node_target[n]};
  if (type == NodeType::intersection) return {Anchor::edge, m.node_target[n]};
  // A ghost: where does its image lie on the S2 element that holds it?
  const SurfacePoint<d> img = m.node_image(n);
  const Barycentric<d> b = barycentric_from_local<d>(img.local);
  const double tol = ctx.options.local_tolerance;
  int zeros = 0, zero_index = -1, nonzero_index = -1;
  for (int i = 0; i <= d; ++i) {
    if (std::abs(b(i)) <= tol) {
      ++zeros;
      zero_index = i;
    } else {
      nonzero_index = i;
    }
  }
  if (zeros == d) return {Anchor::vertex, ctx.s2.element(img.element)[nonzero_index]};
  if constexpr (d == 2) {
    if (zeros == 1) return {Anchor::edge, ctx.s2.element_edge(img.element, (zero_index + 1) % 3)};
    return {};
  } else {
    (void)zero_index;
    return {Anchor::edge, img.element};  // inside an S2 segment, which is d = 1's "edge"
  }
}

template <int d>
bool edge_has_vertex(const Surface<d>& s2, Index e, Index v) {
  if constexpr (d == 2) {
    const auto ends = s2.edge_vertices(e);
    return ends[0] == v || ends[1] == v;
  } else {
    const auto& c = s2.element(e);
    return c[0] == v || c[1] == v;
  }
}

template <int d>
Index edge_joining(const Surface<d>& s2, Index v, Index w) {
  if (v == w) return invalid_index;
  if constexpr (d == 2) {
    return s2.find_edge(v, w);
  } else {
    for (Index e : s2.vertex_elements(v))
      if (s2.local_corner(e, w) >= 0) return e;
    return invalid_index;
  }
}

template <int d>
Index label_of(const Surface<d>& s2, const Anchor& a, const Anchor& b) {
  if (a.kind == Anchor::none || b.kind == Anchor::none) return invalid_index;
  if (a.kind == Anchor::vertex && b.kind == Anchor::vertex) return edge_joining<d>(s2, a.id, b.id);
  if (a.kind == Anchor::edge && b.kind == Anchor::edge) return a.id == b.id ? a.id : invalid_index;
  const Anchor& v = a.kind == Anchor::vertex ? a : b;
  const Anchor& e = a.kind == Anchor::vertex ? b : a;
  return edge_has_vertex<d>(s2, e.id, v.id) ? e.id : invalid_index;
}

struct LabelledEdge {
  Index label, a, b;
  friend bool operator<(const LabelledEdge& x, const LabelledEdge& y) {
    return std::tie(x.label, x.a, x.b) < std::tie(y.label, y.a, y.b);
  }
};

}  // namespace

template <int d>
void run_minimal_embedding(const MapContext<d>& ctx, ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  std::vector<LabelledEdge> edges;
  std::vector<Index> nodes, parent, degree;
  for (Index t = 0; t < ctx.element_count(); ++t) {
    edges.clear();
    for (Index n = ctx.nodes_begin(t); n < ctx.nodes_end(t); ++n) {
      const auto nb = map.neighbors(n);
      for (std::size_t i = 0; i < nb.size(); ++i) {
        const Index q = nb[i];
        if (q <= n || m.neighbor_edge_kind[m.neighbor_begin[n] + i] != GraphEdgeKind::target_edge)
          continue;
        const Index label = label_of<d>(ctx.s2, anchor_of(ctx, n), anchor_of(ctx, q));
        if (label == invalid_index) {
          sink.add("unlabelled_target_edge", {t, n}, [&] {
            return fmt::format("graph edge {}-{} of element {} is marked as an S2 edge preimage, "
                               "but its endpoints ({} with target {}, {} with target {}) lie on no "
                               "common S2 {}",
                               n, q, t, to_string(m.node_type[n]), m.node_target[n],
                               to_string(m.node_type[q]), m.node_target[q],
                               d == 2 ? "edge" : "segment");
          });
          continue;
        }
        edges.push_back({label, n, q});
      }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j].label == edges[i].label) ++j;
      // The graph edges [i, j) carry one label: they must form one simple path.
      nodes.clear();
      for (std::size_t k = i; k < j; ++k) {
        nodes.push_back(edges[k].a);
        nodes.push_back(edges[k].b);
      }
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      parent.resize(nodes.size());
      std::iota(parent.begin(), parent.end(), Index{0});
      degree.assign(nodes.size(), 0);
      const auto find = [&](Index x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
      };
      std::size_t components = nodes.size();
      int max_degree = 0;
      for (std::size_t k = i; k < j; ++k) {
        const auto ia = static_cast<Index>(std::lower_bound(nodes.begin(), nodes.end(), edges[k].a) - nodes.begin());
        const auto ib = static_cast<Index>(std::lower_bound(nodes.begin(), nodes.end(), edges[k].b) - nodes.begin());
        max_degree = std::max<int>({max_degree, ++degree[ia], ++degree[ib]});
        const Index ra = find(ia), rb = find(ib);
        if (ra != rb) {
          parent[ra] = rb;
          --components;
        }
      }
      const std::size_t count = j - i;
      const bool chain = components == 1 && max_degree <= 2 && count + 1 == nodes.size();
      if (!chain)
        sink.add("not_minimal", {t, edges[i].a}, [&] {
          return fmt::format("the preimage of S2 {} {} meets element {} in {} graph edges forming "
                             "{} pieces (max degree {}), not one segment",
                             d == 2 ? "edge" : "segment", edges[i].label, t, count, components,
                             max_degree);
        });
      // An S2 edge's interior holds no S2 vertex, so a vertex preimage can only end the chain.
      if (chain)
        for (std::size_t k = 0; k < nodes.size(); ++k)
          if (degree[k] == 2 && is_target_vertex_preimage(m.node_type[nodes[k]]))
            sink.add("not_minimal", {t, nodes[k]}, [&] {
              return fmt::format("the preimage of S2 {} {} passes through node {}, the preimage of "
                                 "S2 vertex {}",
                                 d == 2 ? "edge" : "segment", edges[i].label, nodes[k],
                                 m.node_target[nodes[k]]);
            });
      i = j;
    }
  }
}

template void run_minimal_embedding(const MapContext<1>&, ViolationSink&);
template void run_minimal_embedding(const MapContext<2>&, ViolationSink&);

}  // namespace plmap::detail
