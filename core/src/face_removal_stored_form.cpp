// remove_faces on a triangle map's stored form (face_removal_stored_form.hpp).

#include "face_removal_stored_form.hpp"

#include "face_removal_rules.hpp"
#include "element_graph.hpp"
#include "map_graph_derivation.hpp"
#include "stored_graph_offsets.hpp"

#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <utility>

namespace plmap::detail {

namespace {

/// The elements that lose regions, each with its named regions in the order they were named
/// (the order decides which named region counts as the face's).
struct NamedByElement {
  std::vector<Index> element;  // increasing
  std::vector<std::vector<Index>> regions;
};

NamedByElement group_by_element(const MapData<2>& m, std::span<const Index> regions) {
  std::vector<std::pair<Index, Index>> keyed;  // (element, region), in the order named
  keyed.reserve(regions.size());
  for (Index r : regions) {
    const auto at = std::upper_bound(m.region_begin.begin(), m.region_begin.end(), r) - m.region_begin.begin() - 1;
    keyed.emplace_back(static_cast<Index>(at), r);
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  NamedByElement out;
  for (const auto& [t, r] : keyed) {
    if (out.element.empty() || out.element.back() != t) {
      out.element.push_back(t);
      out.regions.emplace_back();
    }
    out.regions.back().push_back(r);
  }
  return out;
}

/// Marks what goes with element t's named regions in `removed` (face_removal_rules.hpp: the
/// faces of the named regions, or with RemovalExtent::named_regions their parts that reach the
/// element's boundary; a face strictly inside the element takes all of its regions).
void mark_removed_in_element(const MapData<2>& m, const ElementGraph& g, const std::vector<Index>& named,
                             RemovalExtent extent, std::vector<char>& removed, FaceRemovalReport& report) {
  const Index t = g.element, nb = m.node_begin[t], rb = m.region_begin[t], re = m.region_begin[t + 1];
  const std::vector<Index> begin = list_begins(g);
  std::vector<Index> stack, part;
  for (Index r0 : named) {
    if (removed[static_cast<std::size_t>(r0)]) continue;
    remove_for_named_region(
        m, r0, rb, re, extent, removed, stack, part, report,
        [&](Index r) { return std::find(named.begin(), named.end(), r) != named.end(); },
        [&](Index a, Index b) {
          const Index entry = g.entry(begin, a - nb, b);
          return entry != invalid_index && g.kind[static_cast<std::size_t>(entry)] == GraphEdgeKind::closure;
        },
        [&](Index r, int i) { return g.region_neighbors[static_cast<std::size_t>(r - rb)][i]; });
  }
}

/// Takes out of g's neighbour lists the closure edges on a side of a removed region that no kept
/// region of the element has.
void drop_leaving_entries(const MapData<2>& m, const std::vector<char>& removed, ElementGraph& g) {
  const Index t = g.element, nb = m.node_begin[t], rb = m.region_begin[t], re = m.region_begin[t + 1];
  const std::vector<Index> begin = list_begins(g);
  std::vector<char> leaves(g.neighbor.size(), 0);
  bool any = false;
  for (Index r = rb; r < re; ++r) {
    if (!removed[static_cast<std::size_t>(r)]) continue;
    const auto& c = m.region_corners[r];
    for (int i = 0; i < 3; ++i) {
      const Index a = c[i], b = c[(i + 1) % 3];
      if (!side_leaves(m, rb, re, removed, a, b)) continue;
      for (const Index e : {g.entry(begin, a - nb, b), g.entry(begin, b - nb, a)})
        if (e != invalid_index && g.kind[static_cast<std::size_t>(e)] == GraphEdgeKind::closure) {
          leaves[static_cast<std::size_t>(e)] = 1;
          any = true;
        }
    }
  }
  if (!any) return;
  std::size_t written = 0;
  for (std::size_t n = 0; n < g.neighbor_count.size(); ++n) {
    Index kept = 0;
    for (auto i = static_cast<std::size_t>(begin[n]); i < static_cast<std::size_t>(begin[n + 1]); ++i) {
      if (leaves[i]) continue;
      g.neighbor[written] = g.neighbor[i];
      g.kind[written] = g.kind[i];
      ++written;
      ++kept;
    }
    g.neighbor_count[n] = kept;
  }
  g.neighbor.resize(written);
  g.kind.resize(written);
}

/// g's region neighbours after the compaction: the kept regions' rows (the removed ones' are
/// dropped when `old_rb` names where the element's regions began), indices renumbered, a removed
/// neighbour becoming invalid_index.
void renumber_regions(const std::vector<char>& removed, const std::vector<Index>& renumbered, Index old_rb,
                      ElementGraph& g) {
  std::size_t written = 0;
  for (std::size_t i = 0; i < g.region_neighbors.size(); ++i) {
    if (removed[static_cast<std::size_t>(old_rb) + i]) continue;
    std::array<Index, 3> across = g.region_neighbors[i];
    for (Index& q : across) q = q == invalid_index ? invalid_index : renumbered[static_cast<std::size_t>(q)];
    g.region_neighbors[written++] = across;
  }
  g.region_neighbors.resize(written);
}

}  // namespace

std::optional<PlMap<2>> remove_faces_in_stored_form(PlMap<2>& map, std::span<const Index> regions,
                                                    RemovalExtent extent, FaceRemovalReport& report,
                                                    unsigned threads) {
  const MapData<2>& stored = map.stored();
  const StoredGraph& stored_graph = map.stored_graph();
  const Surface<2>& target = map.target();
  const Index nt = map.domain().element_count();
  const NamedByElement named = group_by_element(stored, regions);
  const StoredGraphOffsets offsets(stored, stored_graph);
  // Four pieces per thread, for balance: the derivations differ in cost with the elements' sizes.
  const std::size_t piece_count = 4 * resolve_thread_count(threads);
  auto piece_size = [&](std::size_t n) { return std::max<std::size_t>(1, (n + piece_count - 1) / piece_count); };

  // The graphs of the elements that lose regions, before anything changes (a damaged element
  // leaves the map to the full-array path).
  std::vector<ElementGraph> changed(named.element.size());
  std::atomic<bool> underived{false};
  parallel_for_pieces_of_size(changed.size(), piece_size(changed.size()), threads, [&](std::size_t, std::size_t begin, std::size_t end) {
    GraphDerivationScratch scratch;
    for (std::size_t i = begin; i < end && !underived.load(std::memory_order_relaxed); ++i) {
      const Index t = named.element[i];
      const auto kept = std::lower_bound(stored_graph.element.begin(), stored_graph.element.end(), t);
      if (kept != stored_graph.element.end() && *kept == t) {
        changed[i] = stored_element_graph(stored_graph, offsets, static_cast<std::size_t>(kept - stored_graph.element.begin()));
      } else if (std::optional<ElementGraph> g = derived_element_graph(stored, target, t, scratch)) {
        changed[i] = std::move(*g);
      } else {
        underived.store(true, std::memory_order_relaxed);
      }
    }
  });
  if (underived.load()) return std::nullopt;

  std::vector<char> removed(static_cast<std::size_t>(map.region_count()), 0);
  for (std::size_t i = 0; i < changed.size(); ++i) {
    mark_removed_in_element(stored, changed[i], named.regions[i], extent, removed, report);
    drop_leaving_entries(stored, removed, changed[i]);
  }
  std::vector<Index> old_region_begin;
  old_region_begin.reserve(named.element.size());
  for (Index t : named.element) old_region_begin.push_back(stored.region_begin[t]);

  std::shared_ptr<const Surface<2>> domain = map.domain_ptr(), target_ptr = map.target_ptr();
  // (two named references, not a structured binding: the lambda below captures m, which clang
  // before C++20's capture rule for bindings refuses)
  std::pair<MapData<2>, StoredGraph> released = std::move(map).release_stored_form();
  const MapData<2>& m = released.first;
  const StoredGraph& old_graph = released.second;
  std::vector<Index> renumbered;
  report.removed_regions = static_cast<Index>(removed.size()) - compact_regions(released.first, nt, removed, renumbered);

  // The new stored graph, in element order: the changed elements and the elements that stored
  // their graph before, each kept where the derivation from its (remaining) regions differs, as
  // the constructor from full arrays would decide. The candidates are listed in element order,
  // decided in pieces on all threads, and the pieces' graphs joined in order.
  struct Candidate {
    bool changed;       // changed[index], or element `index` of the old stored graph
    std::size_t index;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(changed.size() + old_graph.element.size());
  for (std::size_t c = 0, s = 0; c < changed.size() || s < old_graph.element.size();) {
    const Index tc = c < changed.size() ? changed[c].element : nt;
    const Index ts = s < old_graph.element.size() ? old_graph.element[s] : nt;
    if (tc <= ts) {
      candidates.push_back({true, c++});
      if (ts == tc) ++s;  // its stored graph was the one changed
    } else {
      candidates.push_back({false, s++});
    }
  }
  const std::size_t size = piece_size(candidates.size());
  std::vector<StoredGraph> kept((candidates.size() + size - 1) / size);
  parallel_for_pieces_of_size(candidates.size(), size, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    GraphDerivationScratch scratch;
    for (std::size_t i = begin; i < end; ++i) {
      ElementGraph g;
      if (candidates[i].changed) {
        g = std::move(changed[candidates[i].index]);
        renumber_regions(removed, renumbered, old_region_begin[candidates[i].index], g);
      } else {
        // no region of it goes, so only the region numbers shift, and with them the derivation's:
        // where the old graph was known to be needed, it still is
        g = stored_element_graph(old_graph, offsets, candidates[i].index);
        for (auto& across : g.region_neighbors)
          for (Index& q : across) q = q == invalid_index ? invalid_index : renumbered[static_cast<std::size_t>(q)];
        if (old_graph.known_minimal) {
          append(g, kept[k]);
          continue;
        }
      }
      const std::optional<ElementGraph> derived = derived_element_graph(m, *target_ptr, g.element, scratch);
      if (!derived || *derived != g) append(g, kept[k]);
    }
  });
  StoredGraph graph = join_in_order(kept);
  graph.known_minimal = true;  // every graph kept was derived and compared, now or before
  return PlMap<2>(std::move(domain), std::move(target_ptr), std::move(released.first), std::move(graph));
}

}  // namespace plmap::detail
