#pragma once
// The rule of remove_faces (core/face_removal.hpp), evaluated by brute force over a whole map,
// and a check of remove_faces(PlMap&&) against it: a neighbour entry stays exactly when it is a
// graph edge (d = 2) or a side of a kept region, and the kept regions are the others, in order,
// with their neighbours renumbered. Used by tests/core and tests/construct (projected maps have
// closure edges everywhere; the subdivision maps of the core tests mostly graph edges).

#include <plmap/core/face_removal.hpp>
#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>

#include <set>
#include <utility>
#include <vector>

namespace plmap::test {


/// The neighbour entries (a, b) the rule keeps in `map` when the regions flagged in `removed`
/// go: graph edges of d = 2, and every side of a kept region at both ends.
template <int d>
std::set<std::pair<Index, Index>> entries_the_rule_keeps(const PlMap<d>& map, const std::vector<char>& removed) {
  const MapData<d>& m = map.data();
  std::set<std::pair<Index, Index>> present, kept;
  for (Index n = 0; n < map.node_count(); ++n)
    for (Index i = m.neighbor_begin[n]; i < m.neighbor_begin[n + 1]; ++i) {
      present.insert({n, m.neighbor[i]});
      if (d == 2 && m.neighbor_edge_kind[i] == GraphEdgeKind::target_edge) kept.insert({n, m.neighbor[i]});
    }
  for (Index r = 0; r < map.region_count(); ++r) {
    if (removed[r]) continue;
    const auto& c = m.region_corners[r];
    for (int i = 0; i <= d; ++i)
      for (const auto& entry : {std::pair{c[i], c[(i + 1) % (d + 1)]}, std::pair{c[(i + 1) % (d + 1)], c[i]}})
        if (present.count(entry)) kept.insert(entry);
  }
  return kept;
}

template <int d>
std::set<std::pair<Index, Index>> entries_of(const PlMap<d>& map) {
  std::set<std::pair<Index, Index>> out;
  for (Index n = 0; n < map.node_count(); ++n)
    for (Index b : map.neighbors(n)) out.insert({n, b});
  return out;
}

/// How the tests remove regions: remove_faces (whole faces) or remove_regions (named parts).
enum class Removal { faces, regions };

/// Removes `named` in place (remove_faces or remove_regions) and compares with the rule; returns
/// the smaller map, and in `removed_out` (if given) which of map's regions went.
template <int d>
PlMap<d> expect_rule_holds(const PlMap<d>& map, const std::vector<Index>& named, Removal removal = Removal::faces,
                           std::vector<char>* removed_out = nullptr) {
  // which regions go: the report of removed regions fixes the count, the in-place result's
  // region targets and corners fix which (the kept ones stay in order)
  PlMap<d> copy = map;
  PlMap<d> copy_for_threads = map;  // removed on three threads below (d = 2)
  FaceRemovalReport report;
  PlMap<d> smaller = removal == Removal::faces ? remove_faces(std::move(copy), std::span<const Index>(named), &report)
                                               : remove_regions(std::move(copy), std::span<const Index>(named), &report);
  EXPECT_EQ(smaller.region_count(), map.region_count() - report.removed_regions);
  std::vector<char> removed(static_cast<std::size_t>(map.region_count()), 1);
  const MapData<d>& m = map.data();
  const MapData<d>& s = smaller.data();
  std::vector<Index> renumbered(static_cast<std::size_t>(map.region_count()), invalid_index);
  Index next = 0;
  for (Index r = 0; r < map.region_count() && next < smaller.region_count(); ++r)
    if (m.region_corners[r] == s.region_corners[next] && m.region_target[r] == s.region_target[next]) {
      removed[r] = 0;
      renumbered[r] = next++;
    }
  EXPECT_EQ(next, smaller.region_count()) << "the kept regions are not the map's, in order";
  for (Index r : named) EXPECT_TRUE(removed[r]) << "named region " << r << " is still there";
  for (Index r = 0; r < map.region_count(); ++r) {
    if (removed[r]) continue;
    for (int i = 0; i <= d; ++i) {
      const Index g = m.region_neighbors[r][i];
      const Index expected = g == invalid_index || removed[g] ? invalid_index : renumbered[g];
      EXPECT_EQ(s.region_neighbors[renumbered[r]][i], expected) << "region " << r << " side " << i;
    }
  }
  EXPECT_EQ(entries_of(smaller), entries_the_rule_keeps(map, removed));
  EXPECT_EQ(s.node_position.size(), m.node_position.size());
  EXPECT_EQ(s.edge_node, m.edge_node);
  EXPECT_TRUE(verify(smaller).ok());
  if constexpr (d == 2) {
    // A triangle map loses its faces in its stored form: it must store the graph of exactly the
    // elements whose regions do not give it back, as the constructor from full arrays decides.
    const PlMap<2> from_full(smaller.domain_ptr(), smaller.target_ptr(), MapData<2>(s));
    EXPECT_EQ(smaller.stored_graph(), from_full.stored_graph());
    EXPECT_EQ(smaller.elements_with_stored_graph(), from_full.elements_with_stored_graph());
    // Decided in pieces on several threads, the same map: the pieces' graphs joined in order.
    const PlMap<2> on_threads = removal == Removal::faces
                                    ? remove_faces(std::move(copy_for_threads), std::span<const Index>(named), nullptr, 3)
                                    : remove_regions(std::move(copy_for_threads), std::span<const Index>(named), nullptr, 3);
    EXPECT_EQ(on_threads.stored_graph(), smaller.stored_graph());
    EXPECT_EQ(on_threads.data(), s);
  }
  if (removed_out) *removed_out = removed;
  return smaller;
}


}  // namespace plmap::test
