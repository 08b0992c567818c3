// finalize() for curves (d = 1): on each S1 segment the nodes sorted along it, and a region
// between two consecutive nodes wherever the preimage of an S2 segment joins them. The phases of
// the triangle case are short here: bucketing, then per element its slots and pending regions
// (the closure of a polyline is the polyline), and their assembly into the flat arrays.

#include "finalize_buckets.hpp"
#include "finalize_phases.hpp"
#include "map_arrays.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/errors.hpp>

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

/// Per element, its slots and pending regions, flat (element t owns [begin[t], begin[t + 1])).
struct SlotsAndRegions {
  std::vector<Slot> slots;
  std::vector<PendingRegion> regions;
  std::vector<std::size_t> slots_begin, regions_begin;
  int votes = 0;  // regions along their S2 segment minus regions against it

  std::span<const Slot> slots_of(Index t) const {
    return {slots.data() + slots_begin[t], slots.data() + slots_begin[t + 1]};
  }
  std::span<PendingRegion> regions_of(Index t) {
    return {regions.data() + regions_begin[t], regions.data() + regions_begin[t + 1]};
  }
};

/// Looks up an element's slot by node: in place when there are few, by binary search in a
/// sorted table when there are many (stress tests).
class SlotLookup {
 public:
  void reset(std::span<const Slot> slots) {
    slots_ = slots;
    many_ = slots.size() > 16;
    if (!many_) return;
    index_.resize(slots.size());
    for (std::size_t i = 0; i < slots.size(); ++i) index_[i] = {slots[i].node, static_cast<int>(i)};
    std::sort(index_.begin(), index_.end());
  }
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
  std::span<const Slot> slots_;
  bool many_ = false;
  std::vector<std::pair<Index, int>> index_;
};

using Conflicts = std::vector<std::pair<Index, Index>>;  // (S2 segment, S1 element)

/// Appends element t's slots (sorted along it) and pending regions. A segment's preimage that
/// passes over another node (a fold of the projection) is an error, or, with
/// drop_conflicting_edges and within `may_drop` rounds, a conflict to drop.
void collect_element(const BuilderContents<1>& in, const NodesAndSegmentsByPlace<1>& where, Index t,
                     bool may_drop, SlotsAndRegions& out, SlotLookup& lookup, Conflicts& conflicts) {
  const std::size_t first_slot = out.slots.size();
  const auto& c = in.s1.element(t);
  if (Index n = in.node_at_domain_vertex[c[0]]; n != invalid_index) out.slots.push_back({n, 0.0});
  for (Index n : where.interior_nodes[t]) out.slots.push_back({n, in.nodes[n].place.coords(0)});
  if (Index n = in.node_at_domain_vertex[c[1]]; n != invalid_index) out.slots.push_back({n, 1.0});
  const std::span<Slot> slots(out.slots.data() + first_slot, out.slots.size() - first_slot);
  sort_small(slots, [](const Slot& x, const Slot& y) { return x.s < y.s; });
  for (std::size_t i = 1; i < slots.size(); ++i)
    if (slots[i].s == slots[i - 1].s) throw BuilderError(fmt::format("two nodes at the same point of S1 element {}", t));
  lookup.reset(slots);
  for (Index sidx : where.element_segments[t]) {
    const auto& seg = in.segments[sidx];
    int i = lookup(seg.a), j = lookup(seg.b);
    if (i > j) std::swap(i, j);
    // both ends must map into the S2 segment, and no other node may lie between them
    const bool images_on_segment = i >= 0 &&
                                   support_in_element<1>(in.s2, in.nodes[slots[i].node].image, seg.target_edge) &&
                                   support_in_element<1>(in.s2, in.nodes[slots[j].node].image, seg.target_edge);
    if (i < 0 || j != i + 1 || !images_on_segment) {
      if (in.options.drop_conflicting_edges && i >= 0 && may_drop) {
        conflicts.emplace_back(seg.target_edge, t);
        continue;
      }
      throw BuilderError(fmt::format(
          "the preimage of S2 segment {} passes over another node on S1 element {}, or joins "
          "nodes whose images are not on that segment",
          seg.target_edge, t));
    }
    const double ya = support_local<1>(in.s2, in.nodes[slots[i].node].image, seg.target_edge)(0);
    const double yb = support_local<1>(in.s2, in.nodes[slots[j].node].image, seg.target_edge)(0);
    const int sign = (yb > ya) - (yb < ya);
    out.votes += yb > ya ? 1 : -1;
    out.regions.push_back({i, j, seg.target_edge, sign});
  }
}

/// Slots and pending regions of every element; S2 segments in conflict are dropped and the
/// elements redone (up to 16 rounds).
SlotsAndRegions collect_slots_and_regions(const BuilderContents<1>& in, NodesAndSegmentsByPlace<1>& where,
                                          DroppedEdges& dropped) {
  const Index n1 = in.s1.element_count();
  SlotsAndRegions out;
  out.slots_begin.assign(static_cast<std::size_t>(n1) + 1, 0);
  out.regions_begin.assign(static_cast<std::size_t>(n1) + 1, 0);
  SlotLookup lookup;
  for (int round = 0;; ++round) {
    Conflicts conflicts;
    out.votes = 0;
    out.slots.clear();
    out.regions.clear();
    for (Index t = 0; t < n1; ++t) {
      collect_element(in, where, t, round < 16, out, lookup, conflicts);
      out.regions_begin[t + 1] = out.regions.size();
      out.slots_begin[t + 1] = out.slots.size();
    }
    if (conflicts.empty()) return out;
    for (const auto& [e, t] : conflicts) dropped.drop(e, t);
    where.build(in, dropped);
  }
}

/// Writes element t's nodes and the regions with the map's orientation into the map's arrays,
/// at `entry` and `region`, which it advances.
void write_element(const BuilderContents<1>& in, Index t, SlotsAndRegions& sr, MapData<1>& m,
                   std::size_t& entry, std::size_t& region, FinalizeReport* report) {
  const std::span<const Slot> sl = sr.slots_of(t);
  std::span<PendingRegion> regs = sr.regions_of(t);
  // As for triangle surfaces, only pieces mapped with the map's orientation are regions: a
  // piece against it (or onto a single point) is where the projection folds.
  const auto kept_end = std::remove_if(regs.begin(), regs.end(), [&](const PendingRegion& r) { return r.sign != m.orientation; });
  if (report) report->reversed_faces += static_cast<Index>(regs.end() - kept_end);
  regs = regs.first(static_cast<std::size_t>(kept_end - regs.begin()));
  sort_small(regs, [](const auto& x, const auto& y) { return x.a < y.a; });
  const std::size_t first_node = sr.slots_begin[t];
  const auto base = static_cast<Index>(first_node);
  // Every region joins consecutive slots (b = a + 1), so sorted by a they are sorted by b:
  // one cursor finds the region ending at a slot, one the region starting there.
  std::size_t ending = 0, starting = 0;
  for (std::size_t i = 0; i < sl.size(); ++i) {
    const auto& bn = in.nodes[sl[i].node];
    const std::size_t n = first_node + i;
    m.node_position[n](0) = sl[i].s;
    const bool at_corner = bn.place.kind == PlaceKind::vertex;
    m.node_type[n] = bn.kind == BuilderNodeKind::ghost ? NodeType::ghost
                     : at_corner                       ? NodeType::corner
                                                       : NodeType::interior;
    m.node_location[n] = at_corner ? static_cast<std::int8_t>(sl[i].s == 0.0 ? 0 : 1) : std::int8_t{-1};
    m.node_image_element[n] = bn.image.element;
    m.node_image_local[n] = support_local<1>(in.s2, bn.image, bn.image.element);
    m.node_target[n] = bn.kind == BuilderNodeKind::vertex_preimage ? bn.target : invalid_index;
    const auto slot = static_cast<Index>(i);
    while (ending < regs.size() && regs[ending].b < slot) ++ending;
    if (ending < regs.size() && regs[ending].b == slot) {
      m.neighbor[entry] = base + slot - 1;
      m.neighbor_edge_kind[entry++] = GraphEdgeKind::target_edge;
    }
    while (starting < regs.size() && regs[starting].a < slot) ++starting;
    if (starting < regs.size() && regs[starting].a == slot) {
      m.neighbor[entry] = base + slot + 1;
      m.neighbor_edge_kind[entry++] = GraphEdgeKind::target_edge;
    }
    m.neighbor_begin[n + 1] = static_cast<Index>(entry);
  }
  m.node_begin[t + 1] = static_cast<Index>(sr.slots_begin[t + 1]);
  const auto rbase = static_cast<Index>(region);
  for (std::size_t k = 0; k < regs.size(); ++k, ++region) {
    const auto& r = regs[k];
    const Index r_id = rbase + static_cast<Index>(k);
    m.region_corners[region] = {base + r.a, base + r.b};
    // neighbour opposite corner 0 lies beyond corner 1 (the next region), and vice versa
    const Index next = (k + 1 < regs.size() && regs[k + 1].a == r.b) ? r_id + 1 : invalid_index;
    const Index prev = (k > 0 && regs[k - 1].b == r.a) ? r_id - 1 : invalid_index;
    m.region_neighbors[region] = {next, prev};
    m.region_target[region] = r.target;
    std::array<LocalPoint<1>, 2> from, to;
    from[0](0) = sl[r.a].s;
    from[1](0) = sl[r.b].s;
    to[0] = support_local<1>(in.s2, in.nodes[sl[r.a].node].image, r.target);
    to[1] = support_local<1>(in.s2, in.nodes[sl[r.b].node].image, r.target);
    m.region_map[region] = affine_through<1>(from, to);
    if (m.start_region[t] == invalid_index || (sl[r.a].s <= 0.5 && sl[r.b].s >= 0.5)) m.start_region[t] = r_id;
  }
  m.region_begin[t + 1] = static_cast<Index>(region);
}

}  // namespace

MapData<1> finalize_polylines(BuilderContents<1>& in, FinalizeReport* report) {
  const Index n1 = in.s1.element_count();
  DroppedEdges dropped(in.edge_inserted, report);
  NodesAndSegmentsByPlace<1> where;
  where.build(in, dropped);
  if (report) *report = FinalizeReport{};
  SlotsAndRegions sr = collect_slots_and_regions(in, where, dropped);

  MapData<1> m;
  m.node_begin.assign(static_cast<std::size_t>(n1) + 1, 0);
  m.region_begin.assign(static_cast<std::size_t>(n1) + 1, 0);
  m.start_region.assign(static_cast<std::size_t>(n1), invalid_index);
  m.neighbor_begin.push_back(0);
  m.orientation = in.options.orientation != 0 ? in.options.orientation : (sr.votes >= 0 ? 1 : -1);
  // From here on only the slots, the pending regions and the nodes are read. The segments and
  // the buckets go before the map's arrays are sized, which is where finalize's memory peaks
  // (1M circles: 510 -> 449 MiB above the inputs).
  BuilderSegments<1>().swap(in.segments);
  where.release();
  // Sizes are known now (nodes; regions and neighbour entries once the orientation has
  // filtered the regions): the arrays are sized once and written in place.
  std::size_t kept = 0;
  for (const auto& r : sr.regions) kept += r.sign == m.orientation ? 1 : 0;
  size_node_arrays(m, sr.slots.size());
  m.neighbor.resize(2 * kept);
  m.neighbor_edge_kind.resize(2 * kept);
  m.region_corners.resize(kept);
  m.region_neighbors.resize(kept);
  m.region_target.resize(kept);
  m.region_map.resize(kept);
  std::size_t entry = 0, region = 0;
  for (Index t = 0; t < n1; ++t) write_element(in, t, sr, m, entry, region, report);
  m.neighbor.resize(entry);  // a slot between two regions was counted by both
  m.neighbor_edge_kind.resize(entry);
  return m;
}

}  // namespace plmap::detail
