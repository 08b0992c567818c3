#pragma once
// Hand-made maps for the verify tests. `assemble` turns a short description (per S1 element: its
// nodes and its regions) of a map whose image coincides with the domain in world space into the
// complete MapData, so that tests state only what matters and corrupt one thing at a time.

#include <plmap/core/pl_map.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <vector>

namespace plmap::test {

template <int d>
struct NodeSpec {
  LocalPoint<d> local;
  NodeType type;
  int location;
  Index target;
};

template <int d>
struct ElementSpec {
  std::vector<NodeSpec<d>> nodes;
  std::vector<std::array<int, d + 1>> regions;  // indices into nodes, positively oriented
};

template <int d>
std::shared_ptr<const Surface<d>> make_surface(std::vector<WorldPoint<d>> v,
                                               std::vector<ElementCorners<d>> e) {
  return std::make_shared<const Surface<d>>(std::move(v), std::move(e));
}

/// Local coordinates of world point x on element t (least squares; exact for points of t).
template <int d>
LocalPoint<d> local_of(const Surface<d>& s, Index t, const WorldPoint<d>& x) {
  Eigen::Matrix<double, d + 1, d> a;
  for (int i = 0; i < d; ++i) a.col(i) = s.corner(t, i + 1) - s.corner(t, 0);
  return (a.transpose() * a).inverse() * a.transpose() * (x - s.corner(t, 0));
}

template <int d>
bool contains(const Surface<d>& s, Index t, const WorldPoint<d>& x) {
  const LocalPoint<d> xi = local_of(s, t, x);
  return barycentric_from_local<d>(xi).minCoeff() >= -1e-12 &&
         (s.world_position(t, xi) - x).norm() <= 1e-12 * s.max_edge_length();
}

template <int d>
Index element_containing(const Surface<d>& s, const std::vector<WorldPoint<d>>& points) {
  for (Index t = 0; t < s.element_count(); ++t)
    if (std::all_of(points.begin(), points.end(), [&](const auto& x) { return contains(s, t, x); }))
      return t;
  throw std::logic_error("assemble: no S2 element contains the points");
}

template <int d>
bool on_common_target_edge(const Surface<d>& s2, const WorldPoint<d>& a, const WorldPoint<d>& b) {
  if constexpr (d == 1) {
    return true;  // on a curve every graph edge is (part of) an S2 segment's preimage
  } else {
    auto on = [&](Index e, const WorldPoint<2>& x) {
      const auto v = s2.edge_vertices(e);
      const WorldPoint<2> p = s2.vertex(v[0]), q = s2.vertex(v[1]);
      const double s = std::clamp((x - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
      return (p + s * (q - p) - x).norm() <= 1e-12 * s2.max_edge_length();
    };
    for (Index e = 0; e < s2.edge_count(); ++e)
      if (on(e, a) && on(e, b)) return true;
    return false;
  }
}

/// Rebuilds the neighbour CSR after `lists[n]` (neighbours and kinds) changed.
template <int d>
void set_neighbor_lists(MapData<d>& m,
                        const std::vector<std::vector<std::pair<Index, GraphEdgeKind>>>& lists) {
  m.neighbor_begin.assign(1, 0);
  m.neighbor.clear();
  m.neighbor_edge_kind.clear();
  for (const auto& list : lists) {
    for (auto [q, kind] : list) {
      m.neighbor.push_back(q);
      m.neighbor_edge_kind.push_back(kind);
    }
    m.neighbor_begin.push_back(static_cast<Index>(m.neighbor.size()));
  }
}

template <int d>
std::vector<std::vector<std::pair<Index, GraphEdgeKind>>> neighbor_lists(const MapData<d>& m) {
  std::vector<std::vector<std::pair<Index, GraphEdgeKind>>> lists(m.node_type.size());
  for (std::size_t n = 0; n < lists.size(); ++n)
    for (Index k = m.neighbor_begin[n]; k < m.neighbor_begin[n + 1]; ++k)
      lists[n].push_back({m.neighbor[k], m.neighbor_edge_kind[k]});
  return lists;
}

/// Sorts every neighbour list counter-clockwise (d = 1: by position).
template <int d>
void sort_neighbor_lists(MapData<d>& m) {
  auto lists = neighbor_lists(m);
  for (std::size_t n = 0; n < lists.size(); ++n) {
    const LocalPoint<d> c = m.node_position[n];
    std::sort(lists[n].begin(), lists[n].end(), [&](const auto& a, const auto& b) {
      if constexpr (d == 1) {
        return m.node_position[a.first](0) < m.node_position[b.first](0);
      } else {
        const Eigen::Vector2d u = m.node_position[a.first] - c, v = m.node_position[b.first] - c;
        auto angle = [](const Eigen::Vector2d& w) {
          const double x = std::atan2(w.y(), w.x());
          return x < 0 ? x + 2 * M_PI : x;
        };
        return angle(u) < angle(v);
      }
    });
  }
  set_neighbor_lists(m, lists);
}

template <int d>
MapData<d> assemble(const Surface<d>& s1, const Surface<d>& s2, const std::vector<ElementSpec<d>>& spec) {
  MapData<d> m;
  const Index nt = s1.element_count();
  if (static_cast<Index>(spec.size()) != nt) throw std::logic_error("assemble: one spec per element");
  m.node_begin.push_back(0);
  m.region_begin.push_back(0);
  std::vector<std::vector<std::pair<Index, GraphEdgeKind>>> lists;
  for (Index t = 0; t < nt; ++t) {
    const Index base = m.node_begin.back();
    for (const auto& ns : spec[t].nodes) {
      m.node_position.push_back(ns.local);
      m.node_type.push_back(ns.type);
      m.node_location.push_back(static_cast<std::int8_t>(ns.location));
      m.node_target.push_back(ns.target);
      const WorldPoint<d> x = s1.world_position(t, ns.local);
      const Index t2 = element_containing(s2, {x});
      m.node_image_element.push_back(t2);
      m.node_image_local.push_back(local_of(s2, t2, x));
      lists.emplace_back();
    }
    m.node_begin.push_back(static_cast<Index>(m.node_position.size()));
    auto link = [&](Index a, Index b) {
      for (const auto& [q, k] : lists[a])
        if (q == b) return;
      const auto kind = on_common_target_edge(s2, s1.world_position(t, m.node_position[a]),
                                              s1.world_position(t, m.node_position[b]))
                            ? GraphEdgeKind::target_edge
                            : GraphEdgeKind::closure;
      lists[a].push_back({b, kind});
      lists[b].push_back({a, kind});
    };
    for (const auto& rs : spec[t].regions) {
      std::array<Index, d + 1> c;
      std::vector<WorldPoint<d>> world;
      for (int i = 0; i <= d; ++i) {
        c[i] = base + rs[i];
        world.push_back(s1.world_position(t, m.node_position[c[i]]));
      }
      for (int i = 0; i <= d; ++i)
        for (int j = i + 1; j <= d; ++j) link(c[i], c[j]);
      const Index t2 = element_containing(s2, world);
      // Affine map local(T1) -> local(T2) through the corner correspondences.
      Eigen::Matrix<double, d, d> p, q;
      for (int i = 0; i < d; ++i) {
        p.col(i) = m.node_position[c[i + 1]] - m.node_position[c[0]];
        q.col(i) = local_of(s2, t2, world[i + 1]) - local_of(s2, t2, world[0]);
      }
      AffineMap<d> map;
      map.template leftCols<d>() = q * p.inverse();
      map.col(d) = local_of(s2, t2, world[0]) - map.template leftCols<d>() * m.node_position[c[0]];
      m.region_corners.push_back(c);
      m.region_target.push_back(t2);
      m.region_map.push_back(map);
      m.region_neighbors.push_back({});
    }
    m.region_begin.push_back(static_cast<Index>(m.region_corners.size()));
    m.start_region.push_back(m.region_begin[t] < m.region_begin[t + 1] ? m.region_begin[t] : invalid_index);
    // Region neighbours by matching sides.
    for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r)
      for (int i = 0; i <= d; ++i) {
        m.region_neighbors[r][i] = invalid_index;
        std::vector<Index> side;
        for (int j = 0; j <= d; ++j)
          if (j != i) side.push_back(m.region_corners[r][j]);
        std::sort(side.begin(), side.end());
        for (Index o = m.region_begin[t]; o < m.region_begin[t + 1]; ++o) {
          if (o == r) continue;
          int shared = 0;
          for (Index x : side)
            shared += std::count(m.region_corners[o].begin(), m.region_corners[o].end(), x) > 0;
          if (shared == d) m.region_neighbors[r][i] = o;
        }
      }
    if constexpr (d == 2) {
      for (int k = 0; k < 3; ++k) {
        std::vector<Index> on;
        for (Index n = base; n < m.node_begin.back(); ++n) {
          const NodeType ty = m.node_type[n];
          const int loc = m.node_location[n];
          if ((is_at_corner(ty) && (loc == k || loc == (k + 1) % 3)) || (is_on_edge(ty) && loc == k))
            on.push_back(n);
        }
        std::sort(on.begin(), on.end(), [&](Index a, Index b) {
          return barycentric_from_local<2>(m.node_position[a])((k + 1) % 3) <
                 barycentric_from_local<2>(m.node_position[b])((k + 1) % 3);
        });
        if (m.edge_node_begin.empty()) m.edge_node_begin.push_back(0);
        m.edge_node.insert(m.edge_node.end(), on.begin(), on.end());
        m.edge_node_begin.push_back(static_cast<Index>(m.edge_node.size()));
      }
    }
  }
  set_neighbor_lists(m, lists);
  sort_neighbor_lists(m);
  m.orientation = 1;
  return m;
}

template <int d>
LocalPoint<d> lp(double x, double y = 0.0) {
  LocalPoint<d> p;
  p(0) = x;
  if constexpr (d == 2) p(1) = y;
  return p;
}

/// A map that shares the surfaces of `base` with modified arrays.
template <int d>
PlMap<d> modified(const PlMap<d>& base, const std::function<void(MapData<d>&)>& change) {
  MapData<d> m = base.data();
  change(m);
  return PlMap<d>(base.domain_ptr(), base.target_ptr(), std::move(m));
}

/// The node of element t with the given S2 target (first match).
template <int d>
Index node_with_target(const PlMap<d>& map, Index t, Index target, NodeType type) {
  for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n)
    if (map.data().node_target[n] == target && map.data().node_type[n] == type) return n;
  throw std::logic_error("node_with_target: not found");
}


// ---- fixtures ------------------------------------------------------------------------------

inline WorldPoint<2> w2(double x, double y) { return WorldPoint<2>(x, y, 0.0); }
inline WorldPoint<1> w1(double x, double y = 0.0) { return WorldPoint<1>(x, y); }

/// The unit square as two triangles (0,1,2) and (0,2,3), scaled by `scale`; diagonal 0-2 shared.
inline std::shared_ptr<const Surface<2>> square(double scale = 1.0) {
  return make_surface<2>({w2(0, 0) * scale, w2(1, 0) * scale, w2(1, 1) * scale, w2(0, 1) * scale},
                         {{0, 1, 2}, {0, 2, 3}});
}

/// Identity map of the two-triangle square.
inline PlMap<2> identity_square(double scale = 1.0) {
  auto s = square(scale);
  std::vector<ElementSpec<2>> spec(2);
  for (Index t = 0; t < 2; ++t) {
    for (int k = 0; k < 3; ++k)
      spec[t].nodes.push_back({reference_corner<2>(k), NodeType::corner, k, s->element(t)[k]});
    spec[t].regions = {{0, 1, 2}};
  }
  return PlMap<2>(s, s, assemble<2>(*s, *s, spec));
}

/// S1: the square; S2: the square as a fan of four triangles around its centre, which lies on
/// the shared diagonal of S1 (a touching node with copies in both elements).
inline PlMap<2> centre_fan(double scale = 1.0) {
  auto s1 = square(scale);
  auto s2 = make_surface<2>({w2(0, 0) * scale, w2(1, 0) * scale, w2(1, 1) * scale, w2(0, 1) * scale,
                             w2(0.5, 0.5) * scale},
                            {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  std::vector<ElementSpec<2>> spec(2);
  for (Index t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k)
      spec[t].nodes.push_back({reference_corner<2>(k), NodeType::corner, k, s1->element(t)[k]});
  spec[0].nodes.push_back({lp<2>(0.0, 0.5), NodeType::touching, 2, 4});
  spec[0].regions = {{0, 1, 3}, {1, 2, 3}};
  spec[1].nodes.push_back({lp<2>(0.5, 0.0), NodeType::touching, 0, 4});
  spec[1].regions = {{0, 3, 2}, {3, 1, 2}};
  return PlMap<2>(s1, s2, assemble<2>(*s1, *s2, spec));
}

/// S1: the unit right triangle; S2: its 1-to-4 midpoint refinement. Touching nodes have four
/// neighbours.
inline PlMap<2> midpoint_refinement() {
  auto s1 = make_surface<2>({w2(0, 0), w2(1, 0), w2(0, 1)}, {{0, 1, 2}});
  auto s2 = make_surface<2>({w2(0, 0), w2(1, 0), w2(0, 1), w2(0.5, 0), w2(0.5, 0.5), w2(0, 0.5)},
                            {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}});
  std::vector<ElementSpec<2>> spec(1);
  for (int k = 0; k < 3; ++k) spec[0].nodes.push_back({reference_corner<2>(k), NodeType::corner, k, k});
  spec[0].nodes.push_back({lp<2>(0.5, 0.0), NodeType::touching, 0, 3});
  spec[0].nodes.push_back({lp<2>(0.5, 0.5), NodeType::touching, 1, 4});
  spec[0].nodes.push_back({lp<2>(0.0, 0.5), NodeType::touching, 2, 5});
  spec[0].regions = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
  return PlMap<2>(s1, s2, assemble<2>(*s1, *s2, spec));
}

/// S1: the square split along 0-2; S2: the square split along 1-3. The S2 diagonal crosses the
/// S1 diagonal at the centre: an intersection node with a copy in both elements.
inline PlMap<2> crossed_diagonals() {
  auto s1 = square();
  auto s2 = make_surface<2>({w2(0, 0), w2(1, 0), w2(1, 1), w2(0, 1)}, {{0, 1, 3}, {1, 2, 3}});
  const Index diagonal = s2->find_edge(1, 3);
  std::vector<ElementSpec<2>> spec(2);
  for (Index t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k)
      spec[t].nodes.push_back({reference_corner<2>(k), NodeType::corner, k, s1->element(t)[k]});
  spec[0].nodes.push_back({lp<2>(0.0, 0.5), NodeType::intersection, 2, diagonal});
  spec[0].regions = {{0, 1, 3}, {1, 2, 3}};
  spec[1].nodes.push_back({lp<2>(0.5, 0.0), NodeType::intersection, 0, diagonal});
  spec[1].regions = {{0, 3, 2}, {3, 1, 2}};
  return PlMap<2>(s1, s2, assemble<2>(*s1, *s2, spec));
}

/// d = 1: S1 two unit segments, S2 the same line refined at the midpoints.
inline PlMap<1> curve_refinement() {
  auto s1 = make_surface<1>({w1(0), w1(1), w1(2)}, {{0, 1}, {1, 2}});
  auto s2 = make_surface<1>({w1(0), w1(0.5), w1(1), w1(1.5), w1(2)}, {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  std::vector<ElementSpec<1>> spec(2);
  for (Index t = 0; t < 2; ++t) {
    spec[t].nodes = {{lp<1>(0), NodeType::corner, 0, 2 * t},
                     {lp<1>(0.5), NodeType::interior, -1, 2 * t + 1},
                     {lp<1>(1), NodeType::corner, 1, 2 * t + 2}};
    spec[t].regions = {{0, 1}, {1, 2}};
  }
  return PlMap<1>(s1, s2, assemble<1>(*s1, *s2, spec));
}

/// d = 1 with ghost nodes: the S1 vertex at x = 1 maps inside the S2 segment [0.5, 2].
inline PlMap<1> curve_with_ghost() {
  auto s1 = make_surface<1>({w1(0), w1(1), w1(2)}, {{0, 1}, {1, 2}});
  auto s2 = make_surface<1>({w1(0), w1(0.5), w1(2)}, {{0, 1}, {1, 2}});
  std::vector<ElementSpec<1>> spec(2);
  spec[0].nodes = {{lp<1>(0), NodeType::corner, 0, 0},
                   {lp<1>(0.5), NodeType::interior, -1, 1},
                   {lp<1>(1), NodeType::ghost, 1, invalid_index}};
  spec[0].regions = {{0, 1}, {1, 2}};
  spec[1].nodes = {{lp<1>(0), NodeType::ghost, 0, invalid_index}, {lp<1>(1), NodeType::corner, 1, 2}};
  spec[1].regions = {{0, 1}};
  return PlMap<1>(s1, s2, assemble<1>(*s1, *s2, spec));
}

}  // namespace plmap::test
