// DESIGN.md §4.2: per S1 element, the graph is a plane graph whose regions are positively
// oriented triangles (intervals for d = 1) tiling the part of the element that lies in D.

#include "check_context.hpp"

namespace plmap::detail {

namespace {

struct GraphSegment {
  double xmin, xmax, ymin, ymax;
  Index a, b;
};

/// One side of a region: the nodes it joins (sorted; d = 1: a single node and -1), the region
/// and the corner opposite the side, and whether the region runs along it from `low` to `high`.
struct RegionSide {
  Index low, high;
  Index region;
  int opposite_corner;
  bool low_to_high;
  friend bool operator<(const RegionSide& x, const RegionSide& y) {
    return std::tie(x.low, x.high, x.region) < std::tie(y.low, y.high, y.region);
  }
};

template <int d>
double local_measure(const MapData<d>& m, const std::array<Index, d + 1>& c) {
  if constexpr (d == 1) {
    return m.node_position[c[1]](0) - m.node_position[c[0]](0);
  } else {
    const Eigen::Vector2d u = m.node_position[c[1]] - m.node_position[c[0]];
    const Eigen::Vector2d v = m.node_position[c[2]] - m.node_position[c[0]];
    return 0.5 * (u.x() * v.y() - u.y() * v.x());
  }
}

bool has_neighbor(const std::span<const Index> nb, Index q) {
  return std::find(nb.begin(), nb.end(), q) != nb.end();
}

}  // namespace

namespace {

/// Scratch space, reused from one element to the next.
struct PlaneGraphScratch {
  std::vector<GraphSegment> segments;
  std::vector<Box2> boxes;
  OverlapGrid grid;
  std::vector<RegionSide> sides;  ///< of the element's regions, sorted
  std::vector<Index> sorted_nodes;
};

/// No two graph edges of element t cross.
template <int d>
void check_no_crossing_edges(const MapContext<d>& ctx, Index t, PlaneGraphScratch& scratch, ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  std::vector<GraphSegment>& segments = scratch.segments;
  std::vector<Box2>& boxes = scratch.boxes;
  OverlapGrid& grid = scratch.grid;
  segments.clear();
  for (Index n = ctx.nodes_begin(t); n < ctx.nodes_end(t); ++n)
    for (Index q : map.neighbors(n)) {
      if (q <= n) continue;
      const auto& p = m.node_position[n];
      const auto& r = m.node_position[q];
      if constexpr (d == 1)
        segments.push_back({std::min(p(0), r(0)), std::max(p(0), r(0)), 0, 0, n, q});
      else
        segments.push_back({std::min(p.x(), r.x()), std::max(p.x(), r.x()), std::min(p.y(), r.y()),
                            std::max(p.y(), r.y()), n, q});
    }
  auto report_crossing = [&](const GraphSegment& a, const GraphSegment& s) {
    sink.add("edge_crossing", {t, s.a}, [&] {
      return fmt::format("graph edges {}-{} and {}-{} of element {} cross ({} to {} and {} to {})",
                         a.a, a.b, s.a, s.b, t, fmt_point<d>(m.node_position[a.a]),
                         fmt_point<d>(m.node_position[a.b]), fmt_point<d>(m.node_position[s.a]),
                         fmt_point<d>(m.node_position[s.b]));
    });
  };
  if constexpr (d == 1) {
    // Intervals sorted by their left end: each must start after the furthest right end so far.
    std::sort(segments.begin(), segments.end(),
              [](const GraphSegment& x, const GraphSegment& y) { return x.xmin < y.xmin; });
    std::size_t furthest = 0;
    for (std::size_t i = 1; i < segments.size(); ++i) {
      const GraphSegment& a = segments[furthest];
      const GraphSegment& s = segments[i];
      if (!(a.a == s.a && a.b == s.b) && s.xmin < a.xmax) report_crossing(a, s);
      if (s.xmax > a.xmax) furthest = i;
    }
  } else {
    boxes.clear();
    for (const GraphSegment& s : segments) boxes.push_back({s.xmin, s.xmax, s.ymin, s.ymax});
    grid.for_each_pair(boxes, [&](std::size_t i, std::size_t j) {
      const GraphSegment& a = segments[i];
      const GraphSegment& s = segments[j];
      if (a.a == s.a && a.b == s.b) return;  // repeated entry, reported by "structure"
      // Edges sharing a node can only overlap if collinear: one exact test settles most pairs.
      const Index shared = (a.a == s.a || a.a == s.b) ? a.a : (a.b == s.a || a.b == s.b) ? a.b : invalid_index;
      if (shared != invalid_index) {
        const Index other_a = a.a == shared ? a.b : a.a, other_s = s.a == shared ? s.b : s.a;
        if (orient2d(m.node_position[shared], m.node_position[other_a], m.node_position[other_s]) != 0)
          return;
      }
      if (segments_cross_properly(m.node_position[a.a], m.node_position[a.b],
                                  m.node_position[s.a], m.node_position[s.b]))
        report_crossing(a, s);
    });
  }
}

/// The regions of element t are positively oriented, their sides are graph edges, and the
/// neighbours they name match their sides; lists the sides (sorted) in scratch.sides and returns
/// the regions' measure in local coordinates.
template <int d>
double check_regions(const MapContext<d>& ctx, Index t, PlaneGraphScratch& scratch, ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  std::vector<RegionSide>& sides = scratch.sides;
  sides.clear();
  double covered = 0.0;
  for (Index r = ctx.regions_begin(t); r < ctx.regions_end(t); ++r) {
    const auto& c = m.region_corners[r];
    bool positive;
    if constexpr (d == 1)
      positive = m.node_position[c[0]](0) < m.node_position[c[1]](0);
    else
      positive = orient2d(m.node_position[c[0]], m.node_position[c[1]], m.node_position[c[2]]) > 0;
    if (!positive)
      sink.add("region_orientation", {t, invalid_index, r}, [&] {
        std::string pts;
        for (Index q : c) pts += fmt::format(" {}{}", q, fmt_point<d>(m.node_position[q]));
        return fmt::format("region {} of element {} is not positively oriented: corners{}", r, t,
                           pts);
      });
    covered += std::abs(local_measure<d>(m, c));
    for (int i = 0; i <= d; ++i) {
      Index a, b;
      if constexpr (d == 1) {
        a = c[1 - i];
        b = invalid_index;
      } else {
        a = c[(i + 1) % 3];
        b = c[(i + 2) % 3];
        if (!has_neighbor(map.neighbors(a), b))
          sink.add("region_side_not_graph_edge", {t, a, r}, [&] {
            return fmt::format("side {}-{} of region {} is not a graph edge", a, b, r);
          });
      }
      if constexpr (d == 1) {
        sides.push_back({a, invalid_index, r, i, i == 1});
      } else {
        sides.push_back({std::min(a, b), std::max(a, b), r, i, a < b});
      }
    }
    if constexpr (d == 1) {
      if (!has_neighbor(map.neighbors(c[0]), c[1]))
        sink.add("region_side_not_graph_edge", {t, c[0], r}, [&] {
          return fmt::format("region {} joins nodes {} and {}, which are not a graph edge", r,
                             c[0], c[1]);
        });
    }
  }
  std::sort(sides.begin(), sides.end());
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].low == sides[i].low && sides[j].high == sides[i].high) ++j;
    const RegionSide& x = sides[i];
    const auto neighbor_of = [&](const RegionSide& s) {
      return m.region_neighbors[s.region][s.opposite_corner];
    };
    if (j - i == 1) {
      if (neighbor_of(x) != invalid_index)
        sink.add("region_adjacency", {t, x.low, x.region}, [&] {
          return fmt::format("region {} names region {} across its side opposite corner {}, but "
                             "no other region has that side",
                             x.region, neighbor_of(x), x.opposite_corner);
        });
    } else if (j - i == 2) {
      const RegionSide& y = sides[i + 1];
      if (neighbor_of(x) != y.region || neighbor_of(y) != x.region)
        sink.add("region_adjacency", {t, x.low, x.region}, [&] {
          return fmt::format("regions {} and {} share a side but name {} and {} across it",
                             x.region, y.region, neighbor_of(x), neighbor_of(y));
        });
      if (x.low_to_high == y.low_to_high)
        sink.add("region_overlap", {t, x.low, x.region}, [&] {
          return fmt::format("regions {} and {} lie on the same side of their common side", x.region,
                             y.region);
        });
    } else {
      sink.add("region_adjacency", {t, x.low, x.region}, [&] {
        return fmt::format("{} regions of element {} share one side (nodes {} {})", j - i, t,
                           x.low, x.high);
      });
    }
    i = j;
  }
  return covered;
}

/// Whether D covers all of element t: every corner has a node and the element's boundary is
/// covered by region sides (d = 2: and no hole of S2 nor island of D lies inside; d = 1: the nodes
/// in order are joined by graph edges), so that the regions must fill the element.
template <int d>
bool fully_covered(const MapContext<d>& ctx, Index t, PlaneGraphScratch& scratch) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  const std::vector<RegionSide>& sides = scratch.sides;
  std::vector<Index>& sorted_nodes = scratch.sorted_nodes;
  bool full = true;
  std::array<bool, d + 1> corner_present{};
  for (Index n = ctx.nodes_begin(t); n < ctx.nodes_end(t); ++n)
    if (is_at_corner(m.node_type[n])) corner_present[m.node_location[n]] = true;
  for (bool p : corner_present) full = full && p;
  if (full) {
    if constexpr (d == 2) {
      auto is_side = [&](Index a, Index b) {
        const RegionSide key{std::min(a, b), std::max(a, b), std::numeric_limits<Index>::min(), 0, false};
        const auto it = std::lower_bound(sides.begin(), sides.end(), key);
        return it != sides.end() && it->low == key.low && it->high == key.high;
      };
      for (int k = 0; k < 3 && full; ++k) {
        const auto list = map.edge_nodes(t, k);
        for (std::size_t i = 1; i < list.size() && full; ++i) full = is_side(list[i - 1], list[i]);
      }
      // ... and no hole of S2 inside: a region side with no region beyond it, away from the
      // element boundary, is the rim of such a hole when its image lies on a boundary edge of
      // S2 (a missing region, in contrast, leaves sides on interior S2 edges or closure edges);
      // nor an island where D ends on its rim (a side between two rim nodes: a normal
      // projection whose S2 leaves the band of admissible distances inside the element).
      auto on_boundary = [&](Index a, Index b) {
        for (int k = 0; k < 3; ++k) {
          const auto list = map.edge_nodes(t, k);
          if (std::find(list.begin(), list.end(), a) != list.end() &&
              std::find(list.begin(), list.end(), b) != list.end())
            return true;
        }
        return false;
      };
      auto on_rim = [&](Index a, Index b) {
        auto rim = [&](Index n) {
          return m.node_type[n] == NodeType::rim_on_edge || m.node_type[n] == NodeType::rim_inside;
        };
        return rim(a) && rim(b);
      };
      auto image_on_target_boundary = [&](const RegionSide& side) {
        const Index r = side.region, t2 = m.region_target[r];
        const auto& c = m.region_corners[r];
        const LocalPoint<2> ya = apply<2>(m.region_map[r], m.node_position[c[(side.opposite_corner + 1) % 3]]);
        const LocalPoint<2> yb = apply<2>(m.region_map[r], m.node_position[c[(side.opposite_corner + 2) % 3]]);
        const double tol = ctx.options.local_tolerance;
        // local edge k of the S2 element: corners k, k + 1; there the barycentric coordinate of
        // corner k + 2 vanishes (edge 0: y = 0, edge 1: 1 - x - y = 0, edge 2: x = 0)
        auto zero = [&](int k, const LocalPoint<2>& y) {
          const double b = k == 0 ? y.y() : (k == 1 ? 1.0 - y.x() - y.y() : y.x());
          return std::abs(b) <= tol;
        };
        for (int k = 0; k < 3; ++k)
          if (zero(k, ya) && zero(k, yb)) return ctx.s2.edge_elements(ctx.s2.element_edge(t2, k)).size() == 1;
        return false;
      };
      for (std::size_t i = 0; i < sides.size() && full; ++i) {
        const bool single = (i == 0 || sides[i - 1].low != sides[i].low || sides[i - 1].high != sides[i].high) &&
                            (i + 1 == sides.size() || sides[i + 1].low != sides[i].low ||
                             sides[i + 1].high != sides[i].high);
        if (single && !on_boundary(sides[i].low, sides[i].high) &&
            (image_on_target_boundary(sides[i]) || on_rim(sides[i].low, sides[i].high)))
          full = false;
      }
    } else {
      sorted_nodes.clear();
      for (Index n = ctx.nodes_begin(t); n < ctx.nodes_end(t); ++n) sorted_nodes.push_back(n);
      std::sort(sorted_nodes.begin(), sorted_nodes.end(), [&](Index a, Index b) {
        return m.node_position[a](0) < m.node_position[b](0);
      });
      for (std::size_t i = 1; i < sorted_nodes.size() && full; ++i)
        full = has_neighbor(map.neighbors(sorted_nodes[i - 1]), sorted_nodes[i]);
    }
  }
  return full;
}

}  // namespace

template <int d>
void run_plane_graph(const MapContext<d>& ctx, ViolationSink& sink) {
  const Index nt = ctx.element_count();
  const double element_measure = d == 1 ? 1.0 : 0.5;  // of the reference element
  const double measure_tol = ctx.options.measure_tolerance * element_measure;
  PlaneGraphScratch scratch;
  for (Index t = 0; t < nt; ++t) {
    check_no_crossing_edges(ctx, t, scratch, sink);
    const double covered = check_regions(ctx, t, scratch, sink);
    // the regions tile T ∩ D: they do not overlap, and fill a fully covered element
    if (covered > element_measure + measure_tol)
      sink.add("region_tiling", {t}, [&] {
        return fmt::format("regions of element {} cover {:.17g} of the reference element's {:g}: "
                           "they overlap",
                           t, covered, element_measure);
      });
    const bool full = fully_covered(ctx, t, scratch);
    if (full && std::abs(covered - element_measure) > measure_tol)
      sink.add("region_tiling", {t}, [&] {
        return fmt::format("element {} is fully covered (all corners and boundary present) but its "
                           "regions sum to {:.17g} instead of {:g}",
                           t, covered, element_measure);
      });
  }
}

template void run_plane_graph(const MapContext<1>&, ViolationSink&);
template void run_plane_graph(const MapContext<2>&, ViolationSink&);

}  // namespace plmap::detail
