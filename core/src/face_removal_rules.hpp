#pragma once
// What remove_faces (face_removal.hpp) decides per element, shared by its two paths: the one
// on a map's full arrays (face_removal.cpp) and the one on a triangle map's stored form
// (face_removal_stored_form.cpp).

#include <plmap/core/face_removal.hpp>
#include <plmap/core/pl_map.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace plmap::detail {

/// Bit k is set when node n lies on local edge k of its element (edge k joins corners k and
/// k + 1, so corner k lies on edges k and k + 2).
inline std::uint8_t element_edges_through(const MapData<2>& m, Index n) {
  const int k = m.node_location[n];
  if (is_at_corner(m.node_type[n])) return static_cast<std::uint8_t>((1u << k) | (1u << ((k + 2) % 3)));
  if (is_on_edge(m.node_type[n])) return static_cast<std::uint8_t>(1u << k);
  return 0;
}

/// Whether a region with corners c has the side a-b (either direction).
template <std::size_t n>
bool has_side(const std::array<Index, n>& c, Index a, Index b) {
  for (std::size_t i = 0; i < n; ++i) {
    const Index x = c[i], y = c[(i + 1) % n];
    if ((x == a && y == b) || (x == b && y == a)) return true;
  }
  return false;
}

/// Walks a triangle map's face from region r0 across closure edges: `enter(next)` is asked for
/// each region across a closure side and says whether the walk goes on from it (and must not say
/// so twice for one region). `is_closure(a, b)` says whether the graph edge a-b is a closure edge,
/// `across(r, i)` names the region across the side of r opposite corner i (or invalid_index);
/// the two paths of remove_faces read these from different arrays. Returns whether a region
/// walked has a side on its element's boundary. `stack` is scratch space.
template <class IsClosure, class Across, class Enter>
bool walk_face(const MapData<2>& m, Index r0, std::vector<Index>& stack, IsClosure&& is_closure, Across&& across,
               Enter&& enter) {
  stack.assign(1, r0);
  bool reaches_boundary = false;
  while (!stack.empty()) {
    const Index r = stack.back();
    stack.pop_back();
    const auto& c = m.region_corners[r];
    for (int i = 0; i < 3; ++i) {
      const Index a = c[(i + 1) % 3], b = c[(i + 2) % 3];
      if (element_edges_through(m, a) & element_edges_through(m, b)) reaches_boundary = true;
      const Index next = across(r, i);
      if (next != invalid_index && is_closure(a, b) && enter(next)) stack.push_back(next);
    }
  }
  return reaches_boundary;
}

/// Marks in `removed` the face of region r0: r0 and every region reached from it across closure
/// edges (walk_face). Returns whether the face touches its element's boundary; a face strictly
/// inside its element takes all of the element's regions, which the caller clears.
template <class IsClosure, class Across>
bool mark_face(const MapData<2>& m, Index r0, std::vector<char>& removed, std::vector<Index>& stack,
               IsClosure&& is_closure, Across&& across) {
  removed[static_cast<std::size_t>(r0)] = 1;
  return walk_face(m, r0, stack, is_closure, across, [&](Index next) {
    if (removed[static_cast<std::size_t>(next)]) return false;
    removed[static_cast<std::size_t>(next)] = 1;
    return true;
  });
}

/// How much of a face goes with a named region: all of it (remove_faces), or the named regions
/// only where they reach the element's boundary (remove_regions).
enum class RemovalExtent { whole_faces, named_regions };

/// Marks in `removed` the part of named region r0's face that the named regions make: r0 and the
/// named regions reached from it across closure edges, if that part has a side on its element's
/// boundary; returns whether it does (and marks nothing if not). `named(r)` says whether region r
/// was named; `whole` tells whether the part is all of the face. The rest as mark_face; `part`
/// is scratch space.
template <class Named, class IsClosure, class Across>
bool mark_named_part_of_face(const MapData<2>& m, Index r0, std::vector<char>& removed, std::vector<Index>& stack,
                             std::vector<Index>& part, bool& whole, Named&& named, IsClosure&& is_closure,
                             Across&& across) {
  part.assign(1, r0);
  whole = true;
  const bool reaches_boundary = walk_face(m, r0, stack, is_closure, across, [&](Index next) {
    if (!named(next)) {
      whole = false;
      return false;
    }
    if (std::find(part.begin(), part.end(), next) != part.end()) return false;
    part.push_back(next);
    return true;
  });
  if (reaches_boundary)
    for (Index r : part) removed[static_cast<std::size_t>(r)] = 1;
  return reaches_boundary;
}

/// The rule for one named region r0 of a triangle map that is not removed yet, for both paths:
/// with RemovalExtent::named_regions its named part alone if that reaches the element's
/// boundary; else its face, and if the face lies strictly inside its element, every region of
/// the element ([element_begin, element_end)). Counts what it did in `report`.
template <class Named, class IsClosure, class Across>
void remove_for_named_region(const MapData<2>& m, Index r0, Index element_begin, Index element_end,
                             RemovalExtent extent, std::vector<char>& removed, std::vector<Index>& stack,
                             std::vector<Index>& part, FaceRemovalReport& report, Named&& named,
                             IsClosure&& is_closure, Across&& across) {
  ++report.removed_faces;
  bool whole = true;
  if (extent == RemovalExtent::named_regions &&
      mark_named_part_of_face(m, r0, removed, stack, part, whole, named, is_closure, across)) {
    if (!whole) ++report.partial_faces;
    return;
  }
  if (!mark_face(m, r0, removed, stack, is_closure, across)) {
    for (Index r = element_begin; r < element_end; ++r) removed[static_cast<std::size_t>(r)] = 1;
    ++report.cleared_elements;
  }
}

/// Whether the side a-b of a removed region of the element whose regions are [begin, end) leaves
/// with it: no kept region of the element has that side. Its graph edges, if closure edges, go.
template <int d>
bool side_leaves(const MapData<d>& m, Index begin, Index end, const std::vector<char>& removed, Index a, Index b) {
  for (Index other = begin; other < end; ++other)
    if (!removed[static_cast<std::size_t>(other)] && has_side(m.region_corners[other], a, b)) return false;
  return true;
}

}  // namespace plmap::detail
