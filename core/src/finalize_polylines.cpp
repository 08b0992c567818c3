// finalize() for curves (d = 1): on each S1 segment the nodes sorted along it, and a region
// between two consecutive nodes wherever the preimage of an S2 segment joins them. The phases of
// the triangle case are short here: bucketing, then two passes over the elements. The first
// (counting) sorts each element's nodes, checks its pieces and counts its nodes and regions; the
// second (writing) sorts them again and writes them straight into the map's arrays, in element
// order. Sorting a handful of nodes twice costs less than keeping every element's sorted nodes
// and pending regions between the passes: those arrays (1M circles: 3.3M nodes, 2.3M regions,
// 90 MB) were grown push by push, copied on every doubling, and held at finalize's memory peak.

#include "finalize_buckets.hpp"
#include "finalize_phases.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/huge_page_allocator.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <span>

namespace plmap::detail {

namespace {

/// Sorts a short range by insertion, a long one with std::sort. For up to 16 items this is
/// exactly what std::sort does (libstdc++ sorts such ranges by a stable insertion sort), without
/// its calls; an element has a handful of items.
template <class T, class Less>
void sort_small(std::span<T> items, Less less) {
  if (items.size() > 16) {
    std::sort(items.begin(), items.end(), less);
    return;
  }
  for (std::size_t i = 1; i < items.size(); ++i) {
    T item = items[i];
    std::size_t j = i;
    for (; j > 0 && less(item, items[j - 1]); --j) items[j] = items[j - 1];
    items[j] = item;
  }
}

/// A node on an S1 segment, at local position s.
struct Slot {
  Index node;
  double s;
};

/// A piece between slots a and a + 1 = b that maps into S2 segment `target`.
struct PendingRegion {
  Index a, b, target;
  int sign;  // orientation of the image: +1 if it runs along the S2 segment, -1 against, 0 degenerate
};

/// One element's nodes sorted along it, and a lookup of a node's slot: in place when there are
/// few, by binary search in a sorted table when there are many (stress tests). Both passes use
/// one per element in turn; its buffers are reused.
class ElementSlots {
 public:
  /// Collects and sorts element t's nodes. Throws BuilderError if two lie at the same point.
  void collect(const BuilderContents<1>& in, const NodesAndSegmentsByPlace<1>& where, Index t) {
    slots_.clear();
    const auto& c = in.s1.element(t);
    if (Index n = in.node_at_domain_vertex[c[0]]; n != invalid_index) slots_.push_back({n, 0.0});
    for (Index n : where.interior_nodes[t]) slots_.push_back({n, in.nodes[n].place.coords(0)});
    if (Index n = in.node_at_domain_vertex[c[1]]; n != invalid_index) slots_.push_back({n, 1.0});
    sort_small(std::span<Slot>(slots_), [](const Slot& x, const Slot& y) { return x.s < y.s; });
    for (std::size_t i = 1; i < slots_.size(); ++i)
      if (slots_[i].s == slots_[i - 1].s) throw BuilderError(fmt::format("two nodes at the same point of S1 element {}", t));
    many_ = slots_.size() > 16;
    if (!many_) return;
    index_.resize(slots_.size());
    for (std::size_t i = 0; i < slots_.size(); ++i) index_[i] = {slots_[i].node, static_cast<int>(i)};
    std::sort(index_.begin(), index_.end());
  }

  std::span<const Slot> slots() const { return slots_; }

  /// The slot of node `node`, or -1.
  int operator()(Index node) const {
    if (!many_) {
      for (std::size_t i = 0; i < slots_.size(); ++i)
        if (slots_[i].node == node) return static_cast<int>(i);
      return -1;
    }
    const auto it = std::lower_bound(index_.begin(), index_.end(), std::make_pair(node, -1));
    return it != index_.end() && it->first == node ? it->second : -1;
  }

 private:
  std::vector<Slot> slots_;
  bool many_ = false;
  std::vector<std::pair<Index, int>> index_;
};

/// Segment `sidx` of element t as a pending region between its slots (a < b), if both ends are
/// slots of the element.
struct PieceOnElement {
  bool ends_found = false;
  PendingRegion region{};
};

PieceOnElement piece_on_element(const BuilderContents<1>& in, const ElementSlots& slots, Index sidx) {
  const auto& seg = in.segments[sidx];
  int i = slots(seg.a), j = slots(seg.b);
  if (i > j) std::swap(i, j);
  PieceOnElement piece;
  piece.ends_found = i >= 0;
  piece.region = {i, j, seg.target_edge, 0};
  return piece;
}

/// The orientation of a piece's image along its S2 segment (PendingRegion::sign).
int image_sign(const BuilderContents<1>& in, const ElementSlots& slots, const PendingRegion& r) {
  const std::span<const Slot> sl = slots.slots();
  const double ya = support_local<1>(in.s2, in.nodes[sl[r.a].node].image, r.target)(0);
  const double yb = support_local<1>(in.s2, in.nodes[sl[r.b].node].image, r.target)(0);
  return (yb > ya) - (yb < ya);
}

using Conflicts = std::vector<std::pair<Index, Index>>;  // (S2 segment, S1 element)

/// What the counting pass finds: per element its node count and its regions of either image
/// orientation, and the votes for the map's orientation.
struct ElementCounts {
  std::vector<Index> nodes, along, against;  // per element
  int votes = 0;  // regions along their S2 segment minus regions against it (or degenerate)
};

/// Counts element t's nodes and regions. A segment's preimage that passes over another node (a
/// fold of the projection) is an error, or, with drop_conflicting_edges and within `may_drop`
/// rounds, a conflict to drop.
void count_element(const BuilderContents<1>& in, const NodesAndSegmentsByPlace<1>& where, Index t, bool may_drop,
                   ElementSlots& slots, ElementCounts& counts, Conflicts& conflicts) {
  slots.collect(in, where, t);
  const std::span<const Slot> sl = slots.slots();
  Index along = 0, against = 0;
  for (Index sidx : where.element_segments[t]) {
    const PieceOnElement piece = piece_on_element(in, slots, sidx);
    const PendingRegion& r = piece.region;
    // both ends must map into the S2 segment, and no other node may lie between them
    const bool images_on_segment = piece.ends_found &&
                                   support_in_element<1>(in.s2, in.nodes[sl[r.a].node].image, r.target) &&
                                   support_in_element<1>(in.s2, in.nodes[sl[r.b].node].image, r.target);
    if (!piece.ends_found || r.b != r.a + 1 || !images_on_segment) {
      if (in.options.drop_conflicting_edges && piece.ends_found && may_drop) {
        conflicts.emplace_back(r.target, t);
        continue;
      }
      throw BuilderError(fmt::format(
          "the preimage of S2 segment {} passes over another node on S1 element {}, or joins "
          "nodes whose images are not on that segment",
          r.target, t));
    }
    const int sign = image_sign(in, slots, r);
    counts.votes += sign > 0 ? 1 : -1;
    along += sign > 0 ? 1 : 0;
    against += sign < 0 ? 1 : 0;
  }
  counts.nodes[t] = static_cast<Index>(sl.size());
  counts.along[t] = along;
  counts.against[t] = against;
}

/// Counts every element; S2 segments in conflict are dropped and the elements counted again (up
/// to 16 rounds).
ElementCounts count_elements(const BuilderContents<1>& in, NodesAndSegmentsByPlace<1>& where, DroppedEdges& dropped,
                             ElementSlots& slots) {
  const Index n1 = in.s1.element_count();
  ElementCounts counts;
  counts.nodes.resize(static_cast<std::size_t>(n1));
  counts.along.resize(static_cast<std::size_t>(n1));
  counts.against.resize(static_cast<std::size_t>(n1));
  for (int round = 0;; ++round) {
    Conflicts conflicts;
    counts.votes = 0;
    for (Index t = 0; t < n1; ++t) count_element(in, where, t, round < 16, slots, counts, conflicts);
    if (conflicts.empty()) return counts;
    for (const auto& [e, t] : conflicts) dropped.drop(e, t);
    where.build(in, dropped);
  }
}

/// Writes element t's nodes and its regions with the map's orientation at the ends of the map's
/// arrays (sized by the counting pass, so nothing is copied on the way).
void write_element(const BuilderContents<1>& in, const NodesAndSegmentsByPlace<1>& where, Index t,
                   ElementSlots& slots, std::vector<PendingRegion>& regs, MapData<1>& m, FinalizeReport* report) {
  slots.collect(in, where, t);
  const std::span<const Slot> sl = slots.slots();
  // As for triangle surfaces, only pieces mapped with the map's orientation are regions: a
  // piece against it (or onto a single point) is where the projection folds.
  regs.clear();
  Index reversed = 0;
  for (Index sidx : where.element_segments[t]) {
    PendingRegion r = piece_on_element(in, slots, sidx).region;
    r.sign = image_sign(in, slots, r);
    if (r.sign == m.orientation)
      regs.push_back(r);
    else
      ++reversed;
  }
  if (report) report->reversed_faces += reversed;
  sort_small(std::span<PendingRegion>(regs), [](const auto& x, const auto& y) { return x.a < y.a; });
  const auto base = static_cast<Index>(m.node_position.size());
  // Every region joins consecutive slots (b = a + 1), so sorted by a they are sorted by b:
  // one cursor finds the region ending at a slot, one the region starting there.
  std::size_t ending = 0, starting = 0;
  for (std::size_t i = 0; i < sl.size(); ++i) {
    const auto& bn = in.nodes[sl[i].node];
    m.node_position.push_back(LocalPoint<1>::Constant(sl[i].s));
    const bool at_corner = bn.place.kind == PlaceKind::vertex;
    m.node_type.push_back(bn.kind == BuilderNodeKind::ghost ? NodeType::ghost
                          : at_corner                       ? NodeType::corner
                                                            : NodeType::interior);
    m.node_location.push_back(at_corner ? static_cast<std::int8_t>(sl[i].s == 0.0 ? 0 : 1) : std::int8_t{-1});
    m.node_image_element.push_back(bn.image.element);
    m.node_image_local.push_back(support_local<1>(in.s2, bn.image, bn.image.element));
    m.node_target.push_back(bn.kind == BuilderNodeKind::vertex_preimage ? bn.target : invalid_index);
    const auto slot = static_cast<Index>(i);
    while (ending < regs.size() && regs[ending].b < slot) ++ending;
    if (ending < regs.size() && regs[ending].b == slot) {
      m.neighbor.push_back(base + slot - 1);
      m.neighbor_edge_kind.push_back(GraphEdgeKind::target_edge);
    }
    while (starting < regs.size() && regs[starting].a < slot) ++starting;
    if (starting < regs.size() && regs[starting].a == slot) {
      m.neighbor.push_back(base + slot + 1);
      m.neighbor_edge_kind.push_back(GraphEdgeKind::target_edge);
    }
    m.neighbor_begin.push_back(static_cast<Index>(m.neighbor.size()));
  }
  m.node_begin.push_back(static_cast<Index>(m.node_position.size()));
  const auto rbase = static_cast<Index>(m.region_target.size());
  Index start = invalid_index;
  for (std::size_t k = 0; k < regs.size(); ++k) {
    const auto& r = regs[k];
    const Index r_id = rbase + static_cast<Index>(k);
    m.region_corners.push_back({base + r.a, base + r.b});
    // neighbour opposite corner 0 lies beyond corner 1 (the next region), and vice versa
    const Index next = (k + 1 < regs.size() && regs[k + 1].a == r.b) ? r_id + 1 : invalid_index;
    const Index prev = (k > 0 && regs[k - 1].b == r.a) ? r_id - 1 : invalid_index;
    m.region_neighbors.push_back({next, prev});
    m.region_target.push_back(r.target);
    std::array<LocalPoint<1>, 2> from, to;
    from[0](0) = sl[r.a].s;
    from[1](0) = sl[r.b].s;
    to[0] = support_local<1>(in.s2, in.nodes[sl[r.a].node].image, r.target);
    to[1] = support_local<1>(in.s2, in.nodes[sl[r.b].node].image, r.target);
    m.region_map.push_back(affine_through<1>(from, to));
    if (start == invalid_index || (sl[r.a].s <= 0.5 && sl[r.b].s >= 0.5)) start = r_id;
  }
  m.start_region.push_back(start);
  m.region_begin.push_back(static_cast<Index>(m.region_target.size()));
}

/// Reserves exactly what the counted elements fill: the arrays are then written front to back,
/// each entry once (no zero-fill before, no copy on growth).
void reserve_map_arrays(const ElementCounts& counts, MapData<1>& m) {
  std::size_t nodes = 0, regions = 0;
  const std::vector<Index>& kept = m.orientation > 0 ? counts.along : counts.against;
  for (std::size_t t = 0; t < counts.nodes.size(); ++t) {
    nodes += static_cast<std::size_t>(counts.nodes[t]);
    regions += static_cast<std::size_t>(kept[t]);
  }
  const std::size_t elements = counts.nodes.size();
  // on transparent huge pages (huge_page_allocator.hpp): every array is first written here,
  // front to back, and with 4 KiB pages that was a page fault per 4 KiB (1M circles: 200 MB);
  // those filled exactly are backed now, in one call each (the neighbour lists only reserved)
  reserve_for_writing(m.node_begin, elements + 1);
  reserve_for_writing(m.region_begin, elements + 1);
  reserve_for_writing(m.start_region, elements);
  reserve_for_writing(m.node_position, nodes);
  reserve_for_writing(m.node_type, nodes);
  reserve_for_writing(m.node_location, nodes);
  reserve_for_writing(m.node_image_element, nodes);
  reserve_for_writing(m.node_image_local, nodes);
  reserve_for_writing(m.node_target, nodes);
  reserve_for_writing(m.neighbor_begin, nodes + 1);
  // two entries per region, fewer where two regions join the same slots
  reserve_on_huge_pages(m.neighbor, 2 * regions);
  reserve_on_huge_pages(m.neighbor_edge_kind, 2 * regions);
  reserve_for_writing(m.region_corners, regions);
  reserve_for_writing(m.region_neighbors, regions);
  reserve_for_writing(m.region_target, regions);
  reserve_for_writing(m.region_map, regions);
}

}  // namespace

MapData<1> finalize_polylines(BuilderContents<1>& in, FinalizeReport* report) {
  const Index n1 = in.s1.element_count();
  DroppedEdges dropped(in.edge_inserted, report);
  NodesAndSegmentsByPlace<1> where;
  where.build(in, dropped);
  if (report) *report = FinalizeReport{};
  ElementSlots slots;
  ElementCounts counts = count_elements(in, where, dropped, slots);

  MapData<1> m;
  m.orientation = in.options.orientation != 0 ? in.options.orientation : (counts.votes >= 0 ? 1 : -1);
  reserve_map_arrays(counts, m);
  counts = ElementCounts{};  // the map's arrays are sized: what is left of the count goes
  m.node_begin.push_back(0);
  m.region_begin.push_back(0);
  m.neighbor_begin.push_back(0);
  std::vector<PendingRegion> regs;
  for (Index t = 0; t < n1; ++t) write_element(in, where, t, slots, regs, m, report);
  // every element is written: what the builder collected goes before the map is handed on
  where.release();
  BuilderSegments<1>().swap(in.segments);
  BuilderNodes<1>().swap(in.nodes);
  return m;
}

}  // namespace plmap::detail
