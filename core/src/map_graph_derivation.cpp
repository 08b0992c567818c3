#include "map_graph_derivation.hpp"

#include <algorithm>
#include <array>

namespace plmap::detail {

namespace {

bool in_range(Index i, Index begin, Index end) { return i >= begin && i < end; }

/// The S2 vertex a node maps to (one entry), or the S2 edge it maps into (two entries, smaller
/// first), or nothing: vertex nodes give their vertex, intersection nodes their edge, ghost
/// and rim nodes the edge their image lies on when one barycentric weight is exactly zero (the
/// snapping rule makes it so). Indices out of range (a corrupt file) give nothing: the element then keeps
/// its stored graph.
struct Carrier {
  int size = 0;
  std::array<Index, 2> vertex{invalid_index, invalid_index};
};

Carrier carrier_of(const MapData<2>& m, const Surface<2>& target, Index n) {
  Carrier c;
  const NodeType type = m.node_type[n];
  const Index g = m.node_target[n];
  if (type == NodeType::intersection) {
    if (!in_range(g, 0, target.edge_count())) return c;
    c.size = 2;
    c.vertex = target.edge_vertices(g);
  } else if (type == NodeType::ghost || is_on_rim(type)) {
    const SurfacePoint<2> image = m.node_image(n);
    if (!in_range(image.element, 0, target.element_count())) return c;
    const std::array<double, 3> weight{1.0 - image.local(0) - image.local(1), image.local(0), image.local(1)};
    const auto& corners = target.element(image.element);
    int zero = -1;
    for (int j = 0; j < 3; ++j)
      if (weight[static_cast<std::size_t>(j)] == 0.0) {
        if (zero >= 0) return c;  // on a vertex: not a ghost node's image
        zero = j;
      }
    if (zero < 0) return c;
    const Index a = corners[static_cast<std::size_t>((zero + 1) % 3)], b = corners[static_cast<std::size_t>((zero + 2) % 3)];
    c.size = 2;
    c.vertex = {std::min(a, b), std::max(a, b)};
  } else {
    if (!in_range(g, 0, target.vertex_count())) return c;
    c.size = 1;
    c.vertex[0] = g;
  }
  return c;
}


}  // namespace

bool on_common_target_edge(const MapData<2>& m, const Surface<2>& target, Index t2, Index x, Index y) {
  const Carrier cx = carrier_of(m, target, x), cy = carrier_of(m, target, y);
  if (cx.size == 0 || cy.size == 0) return false;
  if (cx.size == 2 && cy.size == 2) return cx.vertex == cy.vertex;
  if (cx.size == 2 || cy.size == 2) {
    const Carrier& edge = cx.size == 2 ? cx : cy;
    const Index vertex = cx.size == 2 ? cy.vertex[0] : cx.vertex[0];
    return vertex == edge.vertex[0] || vertex == edge.vertex[1];
  }
  return cx.vertex[0] != cy.vertex[0] && target.local_corner(t2, cx.vertex[0]) >= 0 &&
         target.local_corner(t2, cy.vertex[0]) >= 0;
}

bool derive_region_neighbors(const MapData<2>& m, Index t, std::span<std::array<Index, 3>> out,
                             GraphDerivationScratch& scratch) {
  const Index nb = m.node_begin[t], ne = m.node_begin[t + 1];
  const Index rb = m.region_begin[t], re = m.region_begin[t + 1];
  auto& sides = scratch.sides;
  sides.clear();
  for (Index r = rb; r < re; ++r) {
    const auto& c = m.region_corners[r];
    for (int i = 0; i < 3; ++i) {
      if (!in_range(c[i], nb, ne)) return false;
      const auto a = static_cast<std::uint64_t>(c[(i + 1) % 3] - nb);
      const auto b = static_cast<std::uint64_t>(c[(i + 2) % 3] - nb);
      sides.push_back({a < b ? (a << 32 | b) : (b << 32 | a), static_cast<std::uint32_t>(3 * (r - rb) + i)});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const auto& p, const auto& q) {
    return p.key != q.key ? p.key < q.key : p.region_side < q.region_side;
  });
  auto forward = [&](std::uint32_t rs) {  // the side runs from the smaller to the larger node
    const auto& c = m.region_corners[rb + static_cast<Index>(rs / 3)];
    const int i = static_cast<int>(rs % 3);
    return c[(i + 1) % 3] < c[(i + 2) % 3];
  };
  for (std::size_t s = 0; s < sides.size();) {
    std::size_t e = s + 1;
    while (e < sides.size() && sides[e].key == sides[s].key) ++e;
    const std::uint32_t p = sides[s].region_side;
    if (e - s == 1) {
      out[p / 3][p % 3] = invalid_index;
    } else {
      const std::uint32_t q = sides[s + 1].region_side;
      // a side shared by more than two regions, or twice in the same direction (overlapping
      // regions), does not come from a plane triangulation
      if (e - s > 2 || forward(p) == forward(q)) return false;
      out[p / 3][p % 3] = rb + static_cast<Index>(q / 3);
      out[q / 3][q % 3] = rb + static_cast<Index>(p / 3);
    }
    s = e;
  }
  return true;
}

bool derive_neighbor_lists(const MapData<2>& m, const Surface<2>& target, Index t,
                           std::span<const std::array<Index, 3>> region_neighbors,
                           std::vector<Index>& count, std::vector<Index>& neighbor,
                           std::vector<GraphEdgeKind>& kind, GraphDerivationScratch& scratch) {
  const Index nb = m.node_begin[t], ne = m.node_begin[t + 1];
  const Index rb = m.region_begin[t], re = m.region_begin[t + 1];
  const auto nodes = static_cast<std::size_t>(ne - nb);
  auto& begin = scratch.incidence_begin;
  auto& incidence = scratch.incidence;
  begin.assign(nodes + 1, 0);
  for (Index r = rb; r < re; ++r)
    for (Index c : m.region_corners[r]) {
      if (!in_range(c, nb, ne)) return false;
      ++begin[static_cast<std::size_t>(c - nb) + 1];
    }
  for (std::size_t v = 0; v < nodes; ++v) begin[v + 1] += begin[v];
  incidence.resize(static_cast<std::size_t>(begin[nodes]));
  {
    std::vector<Index>& fill = scratch.incidence_fill;
    fill.assign(begin.begin(), begin.end() - 1);
    for (Index r = rb; r < re; ++r)
      for (int i = 0; i < 3; ++i)
        incidence[static_cast<std::size_t>(fill[static_cast<std::size_t>(m.region_corners[r][i] - nb)]++)] =
            3 * (r - rb) + i;
  }
  auto across = [&](Index r, int side) { return region_neighbors[static_cast<std::size_t>(r - rb)][side]; };
  auto side_kind = [&](Index r, int side, Index x, Index y) {
    const Index q = across(r, side);
    const bool target_edge = q != invalid_index ? m.region_target[q] != m.region_target[r]
                                                : on_common_target_edge(m, target, m.region_target[r], x, y);
    return target_edge ? GraphEdgeKind::target_edge : GraphEdgeKind::closure;
  };
  for (std::size_t lv = 0; lv < nodes; ++lv) {
    const Index v = nb + static_cast<Index>(lv);
    const Index ib = begin[lv], ie = begin[lv + 1];
    if (ib == ie) {
      count.push_back(0);
      continue;
    }
    // Around v in region (v, a, b) a comes before b counter-clockwise: the next region shares
    // side v-b (opposite a), the previous one side v-a (opposite b).
    Index start = invalid_index;
    for (Index k = ib; k < ie; ++k) {
      const Index r = rb + incidence[k] / 3;
      const int i = incidence[k] % 3;
      if (across(r, (i + 2) % 3) == invalid_index) {
        if (start != invalid_index) return false;  // two fans: not a closed ring or one sector
        start = k;
      }
    }
    if (start == invalid_index) {  // interior: start at the smallest neighbour
      start = ib;
      for (Index k = ib + 1; k < ie; ++k) {
        auto a_of = [&](Index q) { return m.region_corners[rb + incidence[q] / 3][(incidence[q] % 3 + 1) % 3]; };
        if (a_of(k) < a_of(start)) start = k;
      }
    }
    Index r = rb + incidence[start] / 3;
    int i = incidence[start] % 3;
    const Index first = r;
    const std::size_t entries = neighbor.size();
    auto emit = [&](Index x, GraphEdgeKind k) {
      neighbor.push_back(x);
      kind.push_back(k);
    };
    emit(m.region_corners[r][(i + 1) % 3], side_kind(r, (i + 2) % 3, v, m.region_corners[r][(i + 1) % 3]));
    Index visited = 1;
    for (;;) {
      const Index next = across(r, (i + 1) % 3);
      if (next == invalid_index) {
        emit(m.region_corners[r][(i + 2) % 3], side_kind(r, (i + 1) % 3, v, m.region_corners[r][(i + 2) % 3]));
        break;
      }
      if (next == first) break;
      if (++visited > ie - ib) return false;
      r = next;
      const auto& c = m.region_corners[r];
      i = c[0] == v ? 0 : (c[1] == v ? 1 : (c[2] == v ? 2 : -1));
      if (i < 0) return false;
      emit(c[(i + 1) % 3], side_kind(r, (i + 2) % 3, v, c[(i + 1) % 3]));
    }
    if (visited != ie - ib) return false;  // regions at v that the ring did not reach
    count.push_back(static_cast<Index>(neighbor.size() - entries));
  }
  return true;
}

void derive_edge_nodes(const MapData<2>& m, Index t, std::vector<Index>& count, std::vector<Index>& edge_node) {
  const Index nb = m.node_begin[t], ne = m.node_begin[t + 1];
  for (int k = 0; k < 3; ++k) {
    const std::size_t first = edge_node.size();
    for (Index n = nb; n < ne; ++n) {
      const NodeType type = m.node_type[n];
      const int at = m.node_location[n];
      const bool on_corner = is_at_corner(type);
      const bool on_edge = is_on_edge(type);
      if ((on_corner && (at == k || at == (k + 1) % 3)) || (on_edge && at == k)) edge_node.push_back(n);
    }
    // along local edge k: corner 0 (0,0) -> 1 (1,0) by x, 1 -> 2 (0,1) by y, 2 -> 0 by -y
    auto along = [&](Index n) {
      const auto& p = m.node_position[n];
      return k == 0 ? p(0) : (k == 1 ? p(1) : -p(1));
    };
    std::sort(edge_node.begin() + static_cast<std::ptrdiff_t>(first), edge_node.end(), [&](Index a, Index b) {
      const double sa = along(a), sb = along(b);
      return sa != sb ? sa < sb : a < b;
    });
    count.push_back(static_cast<Index>(edge_node.size() - first));
  }
}

}  // namespace plmap::detail
