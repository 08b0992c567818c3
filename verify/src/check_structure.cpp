// DESIGN.md §4.1: indices, neighbour lists, node types, edge arrays, copies on shared edges and
// corners.

#include "check_context.hpp"

namespace plmap::detail {

namespace {

constexpr std::string_view rule_index_range = "index_range";

bool valid_type(NodeType t) { return static_cast<unsigned>(t) < static_cast<unsigned>(node_type_count); }

/// Cyclic order around `center`: the half-plane test uses exact signs of differences of doubles
/// (a correctly rounded subtraction keeps the sign), the comparison inside a half-plane the exact
/// orient2d, so the order is decided without rounding errors.
int half_plane(const Eigen::Vector2d& center, const Eigen::Vector2d& p) {
  const double dy = p.y() - center.y(), dx = p.x() - center.x();
  return (dy > 0 || (dy == 0 && dx > 0)) ? 0 : 1;
}

bool angle_less(const Eigen::Vector2d& center, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const int ha = half_plane(center, a), hb = half_plane(center, b);
  if (ha != hb) return ha < hb;
  return orient2d(center, a, b) > 0;
}

}  // namespace

template <int d>
bool check_indices(const MapContext<d>& ctx, ViolationSink& sink) {
  const auto& m = ctx.data;
  const std::size_t before = sink.count();
  const Index nt = ctx.element_count();
  const Index nv2 = ctx.s2.vertex_count();
  const Index ne2 = ctx.s2.edge_count();
  const Index nn = static_cast<Index>(m.node_type.size());
  for (Index n = 0; n < nn; ++n) {
    const Index t = ctx.node_element[n];
    const NodeType type = m.node_type[n];
    const int loc = m.node_location[n];
    auto bad = [&](auto&& make) { sink.add(rule_index_range, {t, n}, make); };
    if (!valid_type(type)) {
      bad([&] { return fmt::format("node {} has invalid type {}", n, static_cast<int>(type)); });
      continue;
    }
    if (d == 1 && (is_on_edge(type) || is_on_rim(type)))
      bad([&] { return fmt::format("node {} of a curve map has type {}", n, to_string(type)); });
    const bool loc_ok = is_at_corner(type) ? (loc >= 0 && loc <= d)
                        : is_on_edge(type) ? (loc >= 0 && loc <= 2)
                                           : loc == -1;
    if (!loc_ok)
      bad([&] {
        return fmt::format("node {} ({}) has location {}", n, to_string(type), loc);
      });
    const Index target = m.node_target[n];
    const bool target_ok = is_target_vertex_preimage(type) ? (target >= 0 && target < nv2)
                           : type == NodeType::intersection ? (target >= 0 && target < ne2)
                           : is_on_rim(type)                ? (target == invalid_index || (target >= 0 && target < ne2))
                                                            : target == invalid_index;
    if (!target_ok)
      bad([&] {
        return fmt::format("node {} ({}) has node_target {} (S2 has {} vertices, {} edges)", n,
                           to_string(type), target, nv2, ne2);
      });
    if (!m.node_position[n].allFinite() || !m.node_image_local[n].allFinite())
      bad([&] { return fmt::format("node {} has a non-finite position or image", n); });
    if (m.node_image_element[n] < 0 || m.node_image_element[n] >= ctx.s2.element_count())
      bad([&] { return fmt::format("node {} has image element {}", n, m.node_image_element[n]); });
    for (Index k = m.neighbor_begin[n]; k < m.neighbor_begin[n + 1]; ++k) {
      const Index q = m.neighbor[k];
      if (q < 0 || q >= nn || q == n || ctx.node_element[q] != t)
        bad([&] {
          return fmt::format("node {} of element {} lists neighbour {}, which is not another node "
                             "of the same element",
                             n, t, q);
        });
    }
  }
  for (Index t = 0; t < nt; ++t) {
    if constexpr (d == 2) {
      for (int k = 0; k < 3; ++k)
        for (Index i = m.edge_node_begin[3 * t + k]; i < m.edge_node_begin[3 * t + k + 1]; ++i) {
          const Index q = m.edge_node[i];
          if (q < 0 || q >= nn || ctx.node_element[q] != t)
            sink.add(rule_index_range, {t, q}, [&] {
              return fmt::format("edge array {} of element {} lists node {} of another element",
                                 k, t, q);
            });
        }
    }
    for (Index r = ctx.regions_begin(t); r < ctx.regions_end(t); ++r) {
      for (Index c : m.region_corners[r])
        if (c < 0 || c >= nn || ctx.node_element[c] != t)
          sink.add(rule_index_range, {t, c, r}, [&] {
            return fmt::format("region {} of element {} has corner {} of another element", r, t, c);
          });
      for (Index q : m.region_neighbors[r])
        if (q != invalid_index && (q < ctx.regions_begin(t) || q >= ctx.regions_end(t)))
          sink.add(rule_index_range, {t, invalid_index, r}, [&] {
            return fmt::format("region {} of element {} has neighbour region {} of another element",
                               r, t, q);
          });
    }
  }
  return sink.count() == before;
}

namespace {

/// Neighbour lists: symmetric (with the same edge kind at both ends), no repeats, and in cyclic
/// (d = 1: increasing) order.
template <int d>
void check_neighbor_lists(const MapContext<d>& ctx, ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  const Index nn = static_cast<Index>(m.node_type.size());
  for (Index n = 0; n < nn; ++n) {
    const auto nb = map.neighbors(n);
    const Index t = ctx.node_element[n];
    for (std::size_t i = 0; i < nb.size(); ++i) {
      const Index q = nb[i];
      if (std::find(nb.begin() + i + 1, nb.end(), q) != nb.end())
        sink.add("neighbor_repeated", {t, n}, [&] {
          return fmt::format("node {} lists neighbour {} more than once", n, q);
        });
      const auto back = map.neighbors(q);
      const auto it = std::find(back.begin(), back.end(), n);
      if (it == back.end()) {
        sink.add("neighbor_symmetry", {t, n}, [&] {
          return fmt::format("node {} lists {} as neighbour, but node {} does not list {}", n, q,
                             q, n);
        });
      } else {
        const auto kind_here = m.neighbor_edge_kind[m.neighbor_begin[n] + i];
        const auto kind_there = m.neighbor_edge_kind[m.neighbor_begin[q] + (it - back.begin())];
        if (kind_here != kind_there)
          sink.add("neighbor_symmetry", {t, n}, [&] {
            return fmt::format("graph edge {}-{} has kind {} at {} but {} at {}", n, q,
                               static_cast<int>(kind_here), n, static_cast<int>(kind_there), q);
          });
      }
    }
    if constexpr (d == 1) {
      for (std::size_t i = 1; i < nb.size(); ++i)
        if (!(m.node_position[nb[i - 1]](0) < m.node_position[nb[i]](0)))
          sink.add("ccw_order", {t, n}, [&] {
            return fmt::format("neighbours of node {} are not by increasing position: {} at {} "
                               "before {} at {}",
                               n, nb[i - 1], m.node_position[nb[i - 1]](0), nb[i],
                               m.node_position[nb[i]](0));
          });
    } else {
      if (nb.size() < 2) continue;
      const Eigen::Vector2d c = m.node_position[n];
      int descents = 0;
      bool coincident = false;
      for (std::size_t i = 0; i < nb.size(); ++i) {
        const Eigen::Vector2d a = m.node_position[nb[i]];
        const Eigen::Vector2d b = m.node_position[nb[(i + 1) % nb.size()]];
        if (a == c) coincident = true;
        if (!angle_less(c, a, b)) ++descents;
      }
      if (coincident || descents != 1)
        sink.add("ccw_order", {t, n}, [&] {
          std::string list;
          for (Index q : nb) list += fmt::format(" {}", q);
          return coincident
                     ? fmt::format("node {} has a neighbour at its own position (neighbours:{})",
                                   n, list)
                     : fmt::format("neighbours of node {} are not in counter-clockwise order "
                                   "(neighbours:{}; {} wrap-arounds instead of 1)",
                                   n, list, descents);
        });
    }
  }
}

/// Node types agree with the positions, and an element has at most one node per corner; returns
/// the corner nodes, (d + 1) per element (invalid_index where there is none).
template <int d>
std::vector<Index> check_node_places(const MapContext<d>& ctx, ViolationSink& sink) {
  const auto& m = ctx.data;
  const Index nt = ctx.element_count();
  const Index nn = static_cast<Index>(m.node_type.size());
  const double snap = ctx.options.snap_tolerance;
  std::vector<Index> corner_node(static_cast<std::size_t>(nt) * (d + 1), invalid_index);
  for (Index n = 0; n < nn; ++n) {
    const Index t = ctx.node_element[n];
    const NodeType type = m.node_type[n];
    const int loc = m.node_location[n];
    const LocalPlace place = classify_local<d>(m.node_position[n], snap);
    bool agrees = false;
    if (is_at_corner(type)) agrees = place.kind == LocalPlace::corner && place.index == loc;
    else if (is_on_edge(type)) agrees = place.kind == LocalPlace::edge && place.index == loc;
    else agrees = place.kind == LocalPlace::interior;
    if (!agrees)
      sink.add("node_position", {t, n}, [&] {
        static constexpr const char* names[] = {"a corner", "an edge", "the interior", "outside"};
        return fmt::format("node {} of element {} is {} with location {}, but its position {} "
                           "lies {} {}(snap tolerance {:g})",
                           n, t, to_string(type), loc, fmt_point<d>(m.node_position[n]),
                           place.kind == LocalPlace::outside ? "outside the element" : "on",
                           place.kind == LocalPlace::outside ? "" : fmt::format("{} {} ",
                               names[place.kind], place.index),
                           snap);
      });
    if (is_at_corner(type)) {
      Index& slot = corner_node[static_cast<std::size_t>(t) * (d + 1) + loc];
      if (slot != invalid_index)
        sink.add("duplicate_corner_node", {t, n}, [&] {
          return fmt::format("element {} has two nodes at corner {}: {} and {}", t, loc, slot, n);
        });
      else
        slot = n;
    }
  }
  return corner_node;
}

/// The edge arrays (d = 2): each lists the nodes on its edge, ordered from corner k to corner
/// k + 1, from the one corner node to the other; each node appears as often as its type says.
void check_edge_arrays(const MapContext<2>& ctx, const std::vector<Index>& corner_node, ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  const Index nt = ctx.element_count();
  const Index nn = static_cast<Index>(m.node_type.size());
  std::vector<int> occurrences(nn, 0);
  for (Index t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto list = map.edge_nodes(t, k);
      double previous = -std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < list.size(); ++i) {
        const Index n = list[i];
        ++occurrences[n];
        const NodeType type = m.node_type[n];
        const int loc = m.node_location[n];
        const bool belongs = is_at_corner(type) ? (loc == k || loc == (k + 1) % 3)
                                                : (is_on_edge(type) && loc == k);
        if (!belongs)
          sink.add("edge_array", {t, n}, [&] {
            return fmt::format("edge array {} of element {} lists node {} ({}, location {}), "
                               "which is not on that edge",
                               k, t, n, to_string(type), loc);
          });
        const double s = edge_parameter(m.node_position[n], k);
        if (!(s > previous))
          sink.add("edge_array", {t, n}, [&] {
            return fmt::format("edge array {} of element {} is not ordered from corner {} to "
                               "corner {}: node {} at parameter {:.17g} follows parameter {:.17g}",
                               k, t, k, (k + 1) % 3, n, s, previous);
          });
        previous = s;
      }
      const Index first = corner_node[3 * static_cast<std::size_t>(t) + k];
      const Index last = corner_node[3 * static_cast<std::size_t>(t) + (k + 1) % 3];
      if (first != invalid_index && (list.empty() || list.front() != first))
        sink.add("edge_array", {t, first}, [&] {
          return fmt::format("edge array {} of element {} does not start at the node {} of "
                             "corner {}",
                             k, t, first, k);
        });
      if (last != invalid_index && (list.empty() || list.back() != last))
        sink.add("edge_array", {t, last}, [&] {
          return fmt::format("edge array {} of element {} does not end at the node {} of "
                             "corner {}",
                             k, t, last, (k + 1) % 3);
        });
    }
  }
  for (Index n = 0; n < nn; ++n) {
    const NodeType type = m.node_type[n];
    const int expected = is_at_corner(type) ? 2 : is_on_edge(type) ? 1 : 0;
    if (occurrences[n] != expected)
      sink.add("edge_array", {ctx.node_element[n], n}, [&] {
        return fmt::format("node {} ({}) appears {} times in the edge arrays of element {}, "
                           "expected {}",
                           n, to_string(type), occurrences[n], ctx.node_element[n], expected);
      });
  }
}

/// Two copies of a node on a shared S1 vertex or edge (`where_kind` `where`): the same type and
/// target, and images within the world tolerance.
template <int d>
void compare_copies(const MapContext<d>& ctx, Index a, Index b, Index tb, const char* where_kind, Index where,
                    ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  const double world_tol = ctx.world_tolerance_s2;
  if (m.node_type[a] != m.node_type[b] || m.node_target[a] != m.node_target[b]) {
    sink.add("copies_agree", {tb, b}, [&] {
      return fmt::format("copies {} and {} on S1 {} {} differ: {} with target {} vs {} with "
                         "target {}",
                         a, b, where_kind, where, to_string(m.node_type[a]), m.node_target[a],
                         to_string(m.node_type[b]), m.node_target[b]);
    });
    return;
  }
  const double dist = (map.node_target_world(a) - map.node_target_world(b)).norm();
  if (!(dist <= world_tol))
    sink.add("copies_agree", {tb, b}, [&] {
      return fmt::format("copies {} and {} on S1 {} {} have images {:.3g} apart (tolerance "
                         "{:.3g})",
                         a, b, where_kind, where, dist, world_tol);
    });
}

/// The copies of a corner node on every element around a shared S1 vertex agree.
template <int d>
void check_copies_on_vertices(const MapContext<d>& ctx, const std::vector<Index>& corner_node, ViolationSink& sink) {
  for (Index v = 0; v < ctx.s1.vertex_count(); ++v) {
    const auto elements = ctx.s1.vertex_elements(v);
    if (elements.size() < 2) continue;
    const Index t0 = elements[0];
    const Index ref = corner_node[static_cast<std::size_t>(t0) * (d + 1) + ctx.s1.local_corner(t0, v)];
    for (std::size_t i = 1; i < elements.size(); ++i) {
      const Index t = elements[i];
      const Index n = corner_node[static_cast<std::size_t>(t) * (d + 1) + ctx.s1.local_corner(t, v)];
      if ((ref == invalid_index) != (n == invalid_index)) {
        sink.add("copies_agree", {t, n}, [&] {
          return fmt::format("S1 vertex {}: element {} has {} node there, element {} has {}", v,
                             t0, ref == invalid_index ? "no" : "a", t,
                             n == invalid_index ? "none" : "one");
        });
        continue;
      }
      if (ref != invalid_index) compare_copies(ctx, ref, n, t, "vertex", v, sink);
    }
  }
}

/// The copies of the nodes on a shared S1 edge (d = 2) agree: as many on each side, at the same
/// parameters along the edge.
void check_copies_on_edges(const MapContext<2>& ctx, ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  std::vector<Index> reference, other;
  auto canonical = [&](const EdgeIncidence& inc, std::vector<Index>& out) {
    const auto list = map.edge_nodes(inc.element, inc.local_edge);
    out.assign(list.begin(), list.end());
    if (!ctx.s1.local_edge_is_forward(inc.element, inc.local_edge))
      std::reverse(out.begin(), out.end());
  };
  for (Index e = 0; e < ctx.s1.edge_count(); ++e) {
    const auto inc = ctx.s1.edge_elements(e);
    if (inc.size() < 2) continue;
    canonical(inc[0], reference);
    for (std::size_t j = 1; j < inc.size(); ++j) {
      canonical(inc[j], other);
      const Index t = inc[j].element;
      if (other.size() != reference.size()) {
        sink.add("copies_agree", {t}, [&] {
          return fmt::format("S1 edge {}: element {} has {} nodes on it, element {} has {}", e,
                             inc[0].element, reference.size(), t, other.size());
        });
        continue;
      }
      for (std::size_t i = 0; i < other.size(); ++i) {
        const Index a = reference[i], b = other[i];
        if (is_at_corner(m.node_type[a]) && is_at_corner(m.node_type[b])) continue;  // compared per vertex
        const double sa = global_edge_parameter(ctx.s1, inc[0].element, inc[0].local_edge,
                                                m.node_position[a]);
        const double sb = global_edge_parameter(ctx.s1, t, inc[j].local_edge, m.node_position[b]);
        if (!(std::abs(sa - sb) <= ctx.options.local_tolerance))
          sink.add("copies_agree", {t, b}, [&] {
            return fmt::format("copies {} and {} on S1 edge {} sit at parameters {:.17g} and "
                               "{:.17g}",
                               a, b, e, sa, sb);
          });
        compare_copies(ctx, a, b, t, "edge", e, sink);
      }
    }
  }
}

}  // namespace

template <int d>
void run_structure(const MapContext<d>& ctx, ViolationSink& sink) {
  check_neighbor_lists(ctx, sink);
  const std::vector<Index> corner_node = check_node_places(ctx, sink);
  if constexpr (d == 2) check_edge_arrays(ctx, corner_node, sink);
  check_copies_on_vertices(ctx, corner_node, sink);
  if constexpr (d == 2) check_copies_on_edges(ctx, sink);
}

template bool check_indices(const MapContext<1>&, ViolationSink&);
template bool check_indices(const MapContext<2>&, ViolationSink&);
template void run_structure(const MapContext<1>&, ViolationSink&);
template void run_structure(const MapContext<2>&, ViolationSink&);

}  // namespace plmap::detail
