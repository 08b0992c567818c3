// Normal projection on copies numbered along a space-filling curve (spatial_renumbering.hpp):
// the copies, and the translation of the finished map and report back to the caller's numbers.

#include "spatial_renumbering.hpp"

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/node_type.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/spatial_order.hpp>
#include <plmap/core/surface_renumbering.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

namespace plmap::projection {

namespace {

template <int d>
WorldPoint<d> centroid(const Surface<d>& s, Index t) {
  WorldPoint<d> c = WorldPoint<d>::Zero();
  for (int k = 0; k <= d; ++k) c += s.corner(t, k);
  return c / double(d + 1);
}

/// The inverse of a permutation given as "new -> old".
std::vector<Index> inverse_of(const std::vector<Index>& original) {
  std::vector<Index> inverse(original.size());
  for (std::size_t i = 0; i < original.size(); ++i) inverse[static_cast<std::size_t>(original[i])] = static_cast<Index>(i);
  return inverse;
}

// ---- S1: per-element arrays regrouped into the caller's element order -------------------------

/// Where each S1 element's nodes and regions (and the entries of per-node lists) go: for the
/// caller's element t, the copy's element internal[t], whose items [old[i], old[i+1]) move to
/// [moved[t], moved[t+1]).
struct Ranges {
  std::vector<Index> old, moved;
  Index shift(Index t, Index i) const { return moved[static_cast<std::size_t>(t)] - old[static_cast<std::size_t>(i)]; }
};

/// `old` are the copy's per-element begins (size |T| + 1).
Ranges regrouped_ranges(std::vector<Index> old, const std::vector<Index>& internal) {
  Ranges r;
  r.moved.resize(old.size());
  r.moved[0] = 0;
  for (std::size_t t = 0; t + 1 < old.size(); ++t) {
    const auto i = static_cast<std::size_t>(internal[t]);
    r.moved[t + 1] = r.moved[t] + (old[i + 1] - old[i]);
  }
  r.old = std::move(old);
  return r;
}

/// `in` regrouped by `ranges` (caller's element t takes the items of internal[t]), each item
/// passed through adjust(item, caller's element, copy's element) — the numbers an item holds
/// refer to its own element's nodes or regions. Written front to back into room marked for huge
/// pages, without zeroing it first: the gather is a pass over the whole map, and fresh pages and
/// a second write were most of its cost.
template <class T, class Adjust>
std::vector<T> regrouped(const std::vector<T>& in, const Ranges& ranges, const std::vector<Index>& internal,
                         Adjust&& adjust) {
  std::vector<T> out;
  reserve_for_writing(out, in.size());
  for (std::size_t t = 0; t < internal.size(); ++t) {
    const Index i = internal[t];
    const auto from = static_cast<std::size_t>(ranges.old[static_cast<std::size_t>(i)]);
    const auto to = static_cast<std::size_t>(ranges.old[static_cast<std::size_t>(i) + 1]);
    for (std::size_t k = from; k < to; ++k) out.push_back(adjust(in[k], static_cast<Index>(t), i));
  }
  return out;
}

/// The same without adjusting: each element's stretch copied in one piece.
template <class T>
std::vector<T> regrouped(const std::vector<T>& in, const Ranges& ranges, const std::vector<Index>& internal) {
  std::vector<T> out;
  reserve_for_writing(out, in.size());
  for (const Index i : internal) {
    const auto from = static_cast<std::ptrdiff_t>(ranges.old[static_cast<std::size_t>(i)]);
    const auto to = static_cast<std::ptrdiff_t>(ranges.old[static_cast<std::size_t>(i) + 1]);
    out.insert(out.end(), in.begin() + from, in.begin() + to);
  }
  return out;
}

Index shifted(Index n, Index shift) { return n == invalid_index ? n : n + shift; }

/// Per-item begins (size items + 1) of a list per node or per element side, regrouped: the
/// lists keep their lengths, in the new order of their owners.
std::vector<Index> regrouped_begins(const std::vector<Index>& begin, const Ranges& owners,
                                    const std::vector<Index>& internal) {
  std::vector<Index> out;
  reserve_for_writing(out, begin.size());
  out.push_back(0);
  for (const Index i : internal)
    for (Index k = owners.old[static_cast<std::size_t>(i)]; k < owners.old[static_cast<std::size_t>(i) + 1]; ++k)
      out.push_back(out.back() + (begin[static_cast<std::size_t>(k) + 1] - begin[static_cast<std::size_t>(k)]));
  return out;
}

/// Where the entries of lists whose owners (nodes, element sides) are grouped per element go:
/// each element's entries stay together, in the element order of `internal`.
Ranges entry_ranges(const std::vector<Index>& begin, const Ranges& owners, const std::vector<Index>& internal) {
  std::vector<Index> per_element(owners.old.size());
  for (std::size_t i = 0; i < owners.old.size(); ++i)
    per_element[i] = begin[static_cast<std::size_t>(owners.old[i])];
  return regrouped_ranges(std::move(per_element), internal);
}

/// The stored graph of a triangle map (StoredGraph: its elements' arrays one element after the
/// other, in increasing element order) with its elements renumbered into the caller's order and
/// their node and region numbers shifted as `nodes` and `regions` moved them: each element's
/// stretch of every array is found, then the stretches are written out in the caller's order.
void regroup_stored_graph(StoredGraph& graph, const Ranges& nodes, const Ranges& regions,
                          const std::vector<Index>& internal) {
  const auto node_shift = [&](Index t, Index i) { return nodes.shift(t, i); };
  const auto region_shift = [&](Index t, Index i) { return regions.shift(t, i); };
  struct Stretch {
    Index element, caller, node, neighbor, side, edge_node, region;
  };
  std::vector<Stretch> stretches;
  stretches.reserve(graph.element.size());
  Index node = 0, neighbor = 0, edge_node = 0, region = 0;
  for (std::size_t j = 0; j < graph.element.size(); ++j) {
    const Index i = graph.element[j];
    const auto ii = static_cast<std::size_t>(i);
    stretches.push_back({i, invalid_index, node, neighbor, static_cast<Index>(3 * j), edge_node, region});
    for (Index n = nodes.old[ii]; n < nodes.old[ii + 1]; ++n, ++node) neighbor += graph.neighbor_count[static_cast<std::size_t>(node)];
    for (int k = 0; k < 3; ++k) edge_node += graph.edge_node_count[3 * j + static_cast<std::size_t>(k)];
    region += regions.old[ii + 1] - regions.old[ii];
  }
  const std::vector<Index> caller = inverse_of(internal);
  for (Stretch& s : stretches) s.caller = caller[static_cast<std::size_t>(s.element)];
  std::sort(stretches.begin(), stretches.end(), [](const Stretch& a, const Stretch& b) { return a.caller < b.caller; });

  StoredGraph out;
  out.element.reserve(graph.element.size());
  out.neighbor_count.reserve(graph.neighbor_count.size());
  out.neighbor.reserve(graph.neighbor.size());
  out.neighbor_edge_kind.reserve(graph.neighbor_edge_kind.size());
  out.edge_node_count.reserve(graph.edge_node_count.size());
  out.edge_node.reserve(graph.edge_node.size());
  out.region_neighbors.reserve(graph.region_neighbors.size());
  for (const Stretch& s : stretches) {
    const auto ii = static_cast<std::size_t>(s.element);
    const Index node_count = nodes.old[ii + 1] - nodes.old[ii], region_count = regions.old[ii + 1] - regions.old[ii];
    const Index shift_nodes = node_shift(s.caller, s.element), shift_regions = region_shift(s.caller, s.element);
    out.element.push_back(s.caller);
    Index neighbors = 0;
    for (Index n = 0; n < node_count; ++n) {
      const Index c = graph.neighbor_count[static_cast<std::size_t>(s.node + n)];
      out.neighbor_count.push_back(c);
      neighbors += c;
    }
    for (Index k = 0; k < neighbors; ++k) {
      out.neighbor.push_back(shifted(graph.neighbor[static_cast<std::size_t>(s.neighbor + k)], shift_nodes));
      out.neighbor_edge_kind.push_back(graph.neighbor_edge_kind[static_cast<std::size_t>(s.neighbor + k)]);
    }
    Index on_edges = 0;
    for (int k = 0; k < 3; ++k) {
      const Index c = graph.edge_node_count[static_cast<std::size_t>(s.side + k)];
      out.edge_node_count.push_back(c);
      on_edges += c;
    }
    for (Index k = 0; k < on_edges; ++k)
      out.edge_node.push_back(shifted(graph.edge_node[static_cast<std::size_t>(s.edge_node + k)], shift_nodes));
    for (Index r = 0; r < region_count; ++r) {
      std::array<Index, 3> across = graph.region_neighbors[static_cast<std::size_t>(s.region + r)];
      for (Index& q : across) q = shifted(q, shift_regions);
      out.region_neighbors.push_back(across);
    }
  }
  graph = std::move(out);
}

/// The map's arrays with S1's elements back in the caller's order (`internal`: caller's element
/// -> the copy's). Graph arrays that are empty (the stored form of a triangle map) stay empty.
template <int d>
void regroup_domain_elements(MapData<d>& m, StoredGraph* graph, const std::vector<Index>& internal) {
  const Ranges nodes = regrouped_ranges(m.node_begin, internal);
  const Ranges regions = regrouped_ranges(m.region_begin, internal);
  const auto node_shift = [&](Index t, Index i) { return nodes.shift(t, i); };
  const auto region_shift = [&](Index t, Index i) { return regions.shift(t, i); };

  const auto shift_nodes = [&](Index n, Index t, Index i) { return shifted(n, node_shift(t, i)); };
  if (!m.neighbor_begin.empty()) {
    const Ranges entries = entry_ranges(m.neighbor_begin, nodes, internal);
    m.neighbor = regrouped(m.neighbor, entries, internal, shift_nodes);
    m.neighbor_edge_kind = regrouped(m.neighbor_edge_kind, entries, internal);
    m.neighbor_begin = regrouped_begins(m.neighbor_begin, nodes, internal);
  }
  if constexpr (d == 2) {
    if (!m.edge_node_begin.empty()) {
      Ranges sides;  // three per element
      sides.old.resize(internal.size() + 1);
      for (std::size_t i = 0; i < sides.old.size(); ++i) sides.old[i] = static_cast<Index>(3 * i);
      sides.moved = sides.old;
      m.edge_node = regrouped(m.edge_node, entry_ranges(m.edge_node_begin, sides, internal), internal, shift_nodes);
      m.edge_node_begin = regrouped_begins(m.edge_node_begin, sides, internal);
    }
  }
  m.node_position = regrouped(m.node_position, nodes, internal);
  m.node_type = regrouped(m.node_type, nodes, internal);
  m.node_location = regrouped(m.node_location, nodes, internal);
  m.node_image_element = regrouped(m.node_image_element, nodes, internal);
  m.node_image_local = regrouped(m.node_image_local, nodes, internal);
  m.node_target = regrouped(m.node_target, nodes, internal);

  m.region_corners = regrouped(m.region_corners, regions, internal, [&](std::array<Index, d + 1> c, Index t, Index i) {
    for (Index& n : c) n = shifted(n, node_shift(t, i));
    return c;
  });
  if (!m.region_neighbors.empty())
    m.region_neighbors =
        regrouped(m.region_neighbors, regions, internal, [&](std::array<Index, d + 1> c, Index t, Index i) {
          for (Index& r : c) r = shifted(r, region_shift(t, i));
          return c;
        });
  m.region_target = regrouped(m.region_target, regions, internal);
  m.region_map = regrouped(m.region_map, regions, internal);

  std::vector<Index> start(m.start_region.size());
  for (std::size_t t = 0; t < internal.size(); ++t)
    start[t] = shifted(m.start_region[static_cast<std::size_t>(internal[t])], region_shift(static_cast<Index>(t), internal[t]));
  m.start_region = std::move(start);
  m.node_begin = nodes.moved;
  m.region_begin = regions.moved;
  if (graph != nullptr && !graph->element.empty()) regroup_stored_graph(*graph, nodes, regions, internal);
}

// ---- S2: elements, vertices and edges renamed ------------------------------------------------

/// For each edge of the copy, the caller's edge and whether it runs the other way (edges run
/// from their smaller-numbered vertex, and the renumbering may swap which one that is). For
/// d = 1 the edges are the elements, with their corners in the caller's order.
struct EdgeRenaming {
  std::vector<Index> original;
  std::vector<std::uint8_t> reversed;  // bytes, not bits: written by several threads
};

template <int d>
EdgeRenaming edge_renaming(const RenumberedSurface<d>& s2, const Surface<d>& original, unsigned threads) {
  EdgeRenaming r;
  if constexpr (d == 1) {
    r.original = s2.original_element;
    r.reversed.assign(r.original.size(), 0);
  } else {
    // every element keeps its corners in their order, so local edge k of an element of the copy
    // is local edge k of the caller's element: each edge is found through its first element
    const Surface<2>& copy = *s2.surface;
    r.original.resize(static_cast<std::size_t>(copy.edge_count()));
    r.reversed.resize(r.original.size());
    parallel_ranges(r.original.size(), threads, [&](std::size_t begin, std::size_t end) {
      for (auto e = static_cast<Index>(begin); e < static_cast<Index>(end); ++e) {
        const EdgeIncidence& first = copy.edge_elements(e).front();
        const Index oe = original.element_edge(s2.original_element[static_cast<std::size_t>(first.element)], first.local_edge);
        r.original[static_cast<std::size_t>(e)] = oe;
        r.reversed[static_cast<std::size_t>(e)] =
            s2.original_vertex[static_cast<std::size_t>(copy.edge_vertices(e)[0])] != original.edge_vertices(oe)[0];
      }
    });
  }
  return r;
}

Index renamed(Index x, const std::vector<Index>& original) {
  return x >= 0 && static_cast<std::size_t>(x) < original.size() ? original[static_cast<std::size_t>(x)] : x;
}

/// Every item renamed on its own, so on all threads.
template <int d>
void rename_target_numbers(MapData<d>& m, const RenumberedSurface<d>& s2, const EdgeRenaming& edges, unsigned threads) {
  parallel_ranges(m.node_target.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t n = begin; n < end; ++n) {
      m.node_image_element[n] = renamed(m.node_image_element[n], s2.original_element);
      const NodeType type = m.node_type[n];
      Index& g = m.node_target[n];
      if (is_target_vertex_preimage(type))
        g = renamed(g, s2.original_vertex);
      else if (type != NodeType::ghost)  // intersection and rim nodes: an S2 edge, or invalid
        g = renamed(g, edges.original);
    }
  });
  parallel_ranges(m.region_target.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) m.region_target[r] = renamed(m.region_target[r], s2.original_element);
  });
}

template <int d>
void translate_report(ProjectionReport<d>& report, const RenumberedSurface<d>& s1, const EdgeRenaming* edges) {
  for (EdgeNotInserted<d>& f : report.edges_not_inserted) {
    if (s1.renumbered()) f.domain_element = renamed(f.domain_element, s1.original_element);
    if (edges != nullptr && f.target_edge >= 0) {
      if (edges->reversed[static_cast<std::size_t>(f.target_edge)]) f.target_parameter = 1.0 - f.target_parameter;
      f.target_edge = edges->original[static_cast<std::size_t>(f.target_edge)];
    }
  }
}

}  // namespace

template <int d>
double consecutive_element_spacing(const Surface<d>& s) {
  const Index n = s.element_count();
  if (n < 2) return 0.0;
  const double size = std::pow(s.measure() / n, 1.0 / d);
  if (!(size > 0.0)) return 0.0;
  constexpr Index samples = 8192;
  const Index pairs = n - 1, step = std::max<Index>(1, pairs / samples);
  std::vector<double> gap;
  gap.reserve(static_cast<std::size_t>(std::min(pairs, samples + 1)));
  for (Index t = 0; t < pairs; t += step) gap.push_back((centroid(s, t + 1) - centroid(s, t)).norm());
  const auto middle = gap.begin() + static_cast<std::ptrdiff_t>(gap.size() / 2);
  std::nth_element(gap.begin(), middle, gap.end());
  return *middle / size;
}

template <int d>
RenumberedSurface<d> spatially_renumbered(const Surface<d>& s, unsigned threads) {
  const Index ne = s.element_count(), nv = s.vertex_count();
  RenumberedSurface<d> out;
  out.original_element = morton_order_of<d>(
      static_cast<std::size_t>(ne), [&](std::size_t t) { return centroid(s, static_cast<Index>(t)); },
      s.bounding_box_min(), s.bounding_box_max(), threads);
  // vertices in the order the elements first use them: one pass in the new element order, on
  // one thread (about 2 ms of the armadillo's S2, a few per cent of the renumbering)
  out.original_vertex.reserve(static_cast<std::size_t>(nv));
  std::vector<bool> numbered(static_cast<std::size_t>(nv), false);
  for (const Index t : out.original_element)
    for (const Index v : s.element(t))
      if (!numbered[static_cast<std::size_t>(v)]) {
        numbered[static_cast<std::size_t>(v)] = true;
        out.original_vertex.push_back(v);
      }
  for (Index v = 0; v < nv; ++v)
    if (!numbered[static_cast<std::size_t>(v)]) out.original_vertex.push_back(v);
  // renamed from s's own arrays on all threads, not validated and derived again by the
  // constructor, yet the same surface (core/surface_renumbering.hpp)
  out.surface = std::make_shared<const Surface<d>>(renumbered_surface(s, out.original_element, out.original_vertex, threads));
  return out;
}

template <int d>
RenumberingChoice renumbering_choice(const Surface<d>& s2, bool s1_is_s2, SpatialRenumbering rule) {
  switch (rule) {
    case SpatialRenumbering::always: return {true, true};
    case SpatialRenumbering::target: return {s1_is_s2, true};
    case SpatialRenumbering::never: return {false, false};
    case SpatialRenumbering::automatic:
      if (s1_is_s2) return {false, false};
      return {false, consecutive_element_spacing(s2) > poor_order_spacing};
  }
  return {false, false};
}

template <int d>
RenumberedSurface<d> renumbered_or_kept(const std::shared_ptr<const Surface<d>>& s, bool renumber, unsigned threads) {
  if (!renumber || s->element_count() == 0) return RenumberedSurface<d>{s, {}, {}};
  return spatially_renumbered(*s, threads);
}

template <int d>
ProjectionOptions options_for_renumbered(ProjectionOptions options, const RenumberedSurface<d>& s1) {
  if (!s1.renumbered() || options.directions.empty()) return options;
  // a wrong count is the projection's error to report, with its own message
  if (options.directions.size() != s1.original_vertex.size() * (d + 1)) return options;
  std::vector<double> directions(options.directions.size());
  for (std::size_t v = 0; v < s1.original_vertex.size(); ++v)
    for (int k = 0; k <= d; ++k)
      directions[v * (d + 1) + static_cast<std::size_t>(k)] =
          options.directions[static_cast<std::size_t>(s1.original_vertex[v]) * (d + 1) + static_cast<std::size_t>(k)];
  options.directions = std::move(directions);
  return options;
}

template <int d>
ProjectionResult<d> in_original_numbering(ProjectionResult<d> result, const RenumberedSurface<d>& s1,
                                          const RenumberedSurface<d>& s2,
                                          const std::shared_ptr<const Surface<d>>& original1,
                                          const std::shared_ptr<const Surface<d>>& original2, unsigned threads) {
  if (!s1.renumbered() && !s2.renumbered()) return result;
  std::optional<EdgeRenaming> edges;
  if (s2.renumbered()) edges = edge_renaming(s2, *original2, threads);
  const auto translate = [&](MapData<d>& m, StoredGraph* graph) {
    if (s1.renumbered()) regroup_domain_elements(m, graph, inverse_of(s1.original_element));
    if (s2.renumbered()) rename_target_numbers(m, s2, *edges, threads);
  };
  std::optional<PlMap<d>> map;
  if constexpr (d == 2) {
    auto [stored, graph] = std::move(result.map).release_stored_form();
    translate(stored, &graph);
    map.emplace(original1, original2, std::move(stored), std::move(graph));
  } else {
    MapData<d> data = std::move(result.map).release_data();
    translate(data, nullptr);
    map.emplace(original1, original2, std::move(data));
  }
  translate_report(result.report, s1, edges ? &*edges : nullptr);
  return ProjectionResult<d>{std::move(*map), std::move(result.report), result.measures};
}

#define PLMAP_INSTANTIATE(d)                                                                                          \
  template double consecutive_element_spacing<d>(const Surface<d>&);                                                 \
  template RenumberedSurface<d> spatially_renumbered<d>(const Surface<d>&, unsigned);                                \
  template RenumberingChoice renumbering_choice<d>(const Surface<d>&, bool, SpatialRenumbering); \
  template RenumberedSurface<d> renumbered_or_kept<d>(const std::shared_ptr<const Surface<d>>&, bool, unsigned);   \
  template ProjectionOptions options_for_renumbered<d>(ProjectionOptions, const RenumberedSurface<d>&);              \
  template ProjectionResult<d> in_original_numbering<d>(ProjectionResult<d>, const RenumberedSurface<d>&,           \
                                                        const RenumberedSurface<d>&,                                  \
                                                        const std::shared_ptr<const Surface<d>>&,                    \
                                                        const std::shared_ptr<const Surface<d>>&, unsigned);
PLMAP_INSTANTIATE(1)
PLMAP_INSTANTIATE(2)
#undef PLMAP_INSTANTIATE

}  // namespace plmap::projection
