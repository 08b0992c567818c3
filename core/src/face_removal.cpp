// remove_faces (face_removal.hpp): the map on a smaller domain.

#include <plmap/core/errors.hpp>
#include <plmap/core/face_removal.hpp>
#include <plmap/core/freed_heap.hpp>
#include <plmap/core/huge_page_allocator.hpp>

#include "face_removal_rules.hpp"
#include "face_removal_stored_form.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace plmap {

namespace {

/// Entry of neighbour b in node a's list (an index into MapData::neighbor), or invalid_index.
template <int d>
Index neighbor_entry(const MapData<d>& m, Index a, Index b) {
  for (Index i = m.neighbor_begin[a]; i < m.neighbor_begin[a + 1]; ++i)
    if (m.neighbor[i] == b) return i;
  return invalid_index;
}

/// Marks what goes with the named regions in `removed` (face_removal_rules.hpp: their faces, or
/// with RemovalExtent::named_regions their parts that reach the element's boundary; where a face
/// lies strictly inside its element, all regions of that element). Curves: the named regions.
template <int d>
void mark_removed(const PlMap<d>& map, std::span<const Index> regions, detail::RemovalExtent extent,
                  std::vector<char>& removed, FaceRemovalReport& report) {
  const MapData<d>& m = map.data();
  if constexpr (d == 1) {
    for (Index r : regions)
      if (!removed[r]) {
        removed[r] = 1;
        ++report.removed_faces;
      }
  } else {
    std::vector<char> named;
    if (extent == detail::RemovalExtent::named_regions) {
      named.assign(removed.size(), 0);
      for (Index r : regions) named[static_cast<std::size_t>(r)] = 1;
    }
    std::vector<Index> stack, part;
    for (Index r0 : regions) {
      if (removed[r0]) continue;
      const Index t = map.node_element(m.region_corners[r0][0]);
      detail::remove_for_named_region(
          m, r0, map.regions_begin(t), map.regions_end(t), extent, removed, stack, part, report,
          [&](Index r) { return named[static_cast<std::size_t>(r)] != 0; },
          [&](Index a, Index b) {
            const Index entry = neighbor_entry(m, a, b);
            return entry != invalid_index && m.neighbor_edge_kind[entry] == GraphEdgeKind::closure;
          },
          [&](Index r, int i) { return m.region_neighbors[r][i]; });
    }
  }
}

/// The entries (indices into MapData::neighbor) that leave with the removed regions: closure
/// edges (d = 1: the graph edge of a region) on a side of a removed region that no kept region of
/// the same element has. Found per element from its own regions, so the cost follows what is
/// removed, not the size of the map.
template <int d>
std::vector<Index> entries_leaving(const MapData<d>& m, Index element_count, const std::vector<char>& removed) {
  std::vector<Index> leaving;
  for (Index t = 0; t < element_count; ++t) {
    const Index begin = m.region_begin[t], end = m.region_begin[t + 1];
    for (Index r = begin; r < end; ++r) {
      if (!removed[r]) continue;
      const auto& c = m.region_corners[r];
      for (int i = 0; i <= d; ++i) {
        const Index a = c[i], b = c[(i + 1) % (d + 1)];
        if (!detail::side_leaves(m, begin, end, removed, a, b)) continue;
        for (const Index e : {neighbor_entry(m, a, b), neighbor_entry(m, b, a)})
          if (e != invalid_index && (d == 1 || m.neighbor_edge_kind[e] == GraphEdgeKind::closure)) leaving.push_back(e);
      }
    }
  }
  std::sort(leaving.begin(), leaving.end());
  leaving.erase(std::unique(leaving.begin(), leaving.end()), leaving.end());
  return leaving;
}

}  // namespace

namespace detail {

template <int d>
Index compact_regions(MapData<d>& m, Index element_count, const std::vector<char>& removed,
                      std::vector<Index>& renumbered) {
  const auto nr = static_cast<Index>(m.region_corners.size());
  const bool with_neighbors = !m.region_neighbors.empty();
  assign_on_huge_pages(renumbered, static_cast<std::size_t>(nr), invalid_index);  // pages backed in one call
  Index kept = 0, old_begin = 0;
  for (Index t = 0; t < element_count; ++t) {
    const Index old_end = m.region_begin[t + 1];
    for (Index r = old_begin; r < old_end; ++r)
      if (!removed[r]) renumbered[r] = kept++;
    m.region_begin[t + 1] = kept;
    old_begin = old_end;
  }
  for (Index r = 0; r < nr; ++r) {
    const Index to = renumbered[r];
    if (to == invalid_index) continue;
    if (with_neighbors) {
      std::array<Index, d + 1> across = m.region_neighbors[r];
      for (Index& g : across) g = g == invalid_index ? invalid_index : renumbered[g];
      m.region_neighbors[to] = across;
    }
    m.region_corners[to] = m.region_corners[r];
    m.region_target[to] = m.region_target[r];
    m.region_map[to] = m.region_map[r];
  }
  m.region_corners.resize(kept);
  if (with_neighbors) m.region_neighbors.resize(kept);
  m.region_target.resize(kept);
  m.region_map.resize(kept);
  // A walk starts from the old start region if it is kept, else from any region of the element.
  for (Index t = 0; t < element_count; ++t) {
    const Index s = m.start_region[t];
    if (s != invalid_index && !removed[s])
      m.start_region[t] = renumbered[s];
    else
      m.start_region[t] = m.region_begin[t] < m.region_begin[t + 1] ? m.region_begin[t] : invalid_index;
  }
  return kept;
}

template Index compact_regions<1>(MapData<1>&, Index, const std::vector<char>&, std::vector<Index>&);
template Index compact_regions<2>(MapData<2>&, Index, const std::vector<char>&, std::vector<Index>&);

}  // namespace detail

namespace {

/// Drops the given entries (sorted, each once) from m's neighbour lists in place.
template <int d>
void compact_neighbors(MapData<d>& m, const std::vector<Index>& leaving) {
  if (leaving.empty()) return;
  // the lists before the first node that loses an entry stay where they are
  const auto first = static_cast<std::size_t>(
      std::upper_bound(m.neighbor_begin.begin(), m.neighbor_begin.end(), leaving.front()) - m.neighbor_begin.begin() - 1);
  std::size_t written = static_cast<std::size_t>(m.neighbor_begin[first]), next = 0;
  Index old_begin = m.neighbor_begin[first];
  for (std::size_t n = first; n + 1 < m.neighbor_begin.size(); ++n) {
    const Index old_end = m.neighbor_begin[n + 1];
    for (Index i = old_begin; i < old_end; ++i) {
      if (next < leaving.size() && leaving[next] == i) {
        ++next;
        continue;
      }
      m.neighbor[written] = m.neighbor[i];
      m.neighbor_edge_kind[written] = m.neighbor_edge_kind[i];
      ++written;
    }
    m.neighbor_begin[n + 1] = static_cast<Index>(written);
    old_begin = old_end;
  }
  m.neighbor.resize(written);
  m.neighbor_edge_kind.resize(written);
}

}  // namespace

namespace {

template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_from_domain(PlMap<d>&& map, std::span<const Index> regions, detail::RemovalExtent extent,
                            FaceRemovalReport* report, unsigned threads) {
  const Index nr = map.region_count();
  const Index nt = map.domain().element_count();
  for (Index r : regions)
    if (r < 0 || r >= nr)
      throw InvalidMapError(fmt::format("{}: region {} does not exist (the map has {})",
                                        extent == detail::RemovalExtent::whole_faces ? "remove_faces" : "remove_regions", r, nr));

  FaceRemovalReport rep;
  // A triangle map in its stored form is changed element by element where regions go; its
  // graph is neither derived whole nor compared whole again (face_removal_stored_form.hpp).
  if constexpr (d == 2)
    if (std::optional<PlMap<2>> smaller = detail::remove_faces_in_stored_form(map, regions, extent, rep, threads)) {
      if (report) *report = rep;
      // The old stored graph and the removal's working arrays are freed now, into malloc's heap,
      // where they stay resident under whatever the caller allocates next: on the femur pair of
      // the projection peers, whose projection removes twice, they raised the peak from 11.9 to
      // 12.5 MiB, above half of ContactMerge's (docs/benchmarks.md).
      give_freed_heap_back();
      return std::move(*smaller);
    }
  std::vector<char> removed(static_cast<std::size_t>(nr), 0);
  mark_removed(map, regions, extent, removed, rep);
  std::shared_ptr<const Surface<d>> domain = map.domain_ptr(), target = map.target_ptr();
  // The map's arrays are changed in place: nodes, graph edges and edge arrays stay as they are,
  // and only the regions and the entries that leave with them are taken out.
  MapData<d> m = std::move(map).release_data();
  const std::vector<Index> leaving = entries_leaving(m, nt, removed);
  std::vector<Index> renumbered;
  rep.removed_regions = nr - detail::compact_regions(m, nt, removed, renumbered);
  compact_neighbors(m, leaving);
  if (report) *report = rep;
  return PlMap<d>(std::move(domain), std::move(target), std::move(m));
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_faces(PlMap<d>&& map, std::span<const Index> regions, FaceRemovalReport* report, unsigned threads) {
  return remove_from_domain(std::move(map), regions, detail::RemovalExtent::whole_faces, report, threads);
}

template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_regions(PlMap<d>&& map, std::span<const Index> regions, FaceRemovalReport* report, unsigned threads) {
  return remove_from_domain(std::move(map), regions, detail::RemovalExtent::named_regions, report, threads);
}

template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_faces(const PlMap<d>& map, std::span<const Index> regions, FaceRemovalReport* report, unsigned threads) {
  return remove_faces(PlMap<d>(map), regions, report, threads);
}

template PlMap<1> remove_faces<1>(const PlMap<1>&, std::span<const Index>, FaceRemovalReport*, unsigned);
template PlMap<2> remove_faces<2>(const PlMap<2>&, std::span<const Index>, FaceRemovalReport*, unsigned);
template PlMap<1> remove_faces<1>(PlMap<1>&&, std::span<const Index>, FaceRemovalReport*, unsigned);
template PlMap<2> remove_faces<2>(PlMap<2>&&, std::span<const Index>, FaceRemovalReport*, unsigned);
template PlMap<1> remove_regions<1>(PlMap<1>&&, std::span<const Index>, FaceRemovalReport*, unsigned);
template PlMap<2> remove_regions<2>(PlMap<2>&&, std::span<const Index>, FaceRemovalReport*, unsigned);

}  // namespace plmap
