// finalize(), phase 3: assembly (finalize_assembly.hpp).

#include "finalize_assembly.hpp"

#include "finalize_region_maps.hpp"
#include "map_arrays.hpp"
#include "map_graph_derivation.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/huge_page_allocator.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>

namespace plmap::detail {

PartBounds part_bounds(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index begin, Index end) {
  PartBounds b;
  b.elements = static_cast<std::size_t>(end - begin);
  for (Index t = begin; t < end; ++t) {
    std::size_t corners = 0, edge_inner = 0;
    for (int k = 0; k < 3; ++k) {
      if (in.node_at_domain_vertex[in.s1.element(t)[k]] != invalid_index) ++corners;
      edge_inner += where.edge_nodes[in.s1.element_edge(t, k)].size();
    }
    const std::size_t ns = corners + edge_inner + where.interior_nodes[t].size();
    b.nodes += ns;
    b.on_edges += 2 * corners + edge_inner;
    if (ns == 0) continue;
    const std::size_t n = ns + (3 - corners), h = 3 + edge_inner;
    b.triangles += 2 * n - h - 2;
    b.sides += 3 * n - h - 3;
  }
  return b;
}

PartBounds& PartBounds::operator+=(const PartBounds& o) {
  elements += o.elements;
  nodes += o.nodes;
  on_edges += o.on_edges;
  triangles += o.triangles;
  sides += o.sides;
  return *this;
}

void size_part(const PartBounds& own, const PartBounds& room, MapData<2>& part, const AssemblyCursor& at) {
  part = MapData<2>{};
  // room first (address space only: nothing beyond `own` is touched here), then the sizes
  // Each array on transparent huge pages where it spans them (huge_page_allocator.hpp): marked
  // before its first write, so that the assembly's writes fault in 2 MiB pages.
  auto reserved = [](auto& array, std::size_t capacity) {
    array.reserve(capacity);
    advise_huge_pages(array.data(), array.capacity() * sizeof(array[0]));
  };
  // (with BuilderOptions::spare_room, the node and region arrays take room to grow as well)
  const auto spare = [&](std::size_t n) { return with_spare_room(n, at.spare_room); };
  auto sized = [&](auto& array, std::size_t size, std::size_t capacity) {
    reserved(array, std::max(size, capacity));
    back_pages(array.data(), size * sizeof(array[0]));  // written in full next: backed in one call
    array.resize(size);
  };
  sized(part.node_begin, own.elements + 1, room.elements + 1);
  sized(part.region_begin, own.elements + 1, room.elements + 1);
  sized(part.start_region, own.elements, room.elements);
  sized(part.edge_node_begin, 3 * own.elements + 1, 3 * room.elements + 1);
  sized(part.node_position, own.nodes, spare(room.nodes));
  sized(part.node_type, own.nodes, spare(room.nodes));
  sized(part.node_location, own.nodes, spare(room.nodes));
  sized(part.node_image_element, own.nodes, spare(room.nodes));
  sized(part.node_image_local, own.nodes, spare(room.nodes));
  sized(part.node_target, own.nodes, spare(room.nodes));
  // Neighbour entries and regions are bounded, not known: reserved (their slack stays
  // untouched, so it costs no resident memory) and sized as they are written. So are the
  // neighbour ends and the edge nodes: only the elements that keep their graph write them
  // (finalize_assembly.hpp).
  sized(part.neighbor_begin, 1, std::max(own.nodes, room.nodes) + 1);
  reserved(part.edge_node, std::max(own.on_edges, room.on_edges));
  reserved(part.neighbor, 2 * std::max(own.sides, room.sides));
  reserved(part.neighbor_edge_kind, 2 * std::max(own.sides, room.sides));
  reserved(part.region_corners, spare(std::max(own.triangles, room.triangles)));
  reserved(part.region_neighbors, std::max(own.triangles, room.triangles));
  reserved(part.region_target, spare(std::max(own.triangles, room.triangles)));
  if (at.kept_omitted_weights != nullptr)
    at.kept_omitted_weights->clear();
  else
    reserved(part.region_map, spare(std::max(own.triangles, room.triangles)));
}

FinalizeReport::MeasureLeftOut AssemblyCursor::LeftOutTally::measures(double s1_measure) const {
  const double unit = s1_measure * 0x1p-60;
  FinalizeReport::MeasureLeftOut m;
  m.outside = static_cast<double>(outside) * unit;
  m.reversed = static_cast<double>(reversed) * unit;
  m.unmapped = static_cast<double>(unmapped) * unit;
  m.enclosed = static_cast<double>(enclosed) * unit;
  return m;
}

namespace {

/// Neighbour entries and regions are written in place, into arrays reserved by their bounds but
/// sized only a chunk ahead of what is written: sizing them to the bound would first-touch the
/// slack (66 MiB more peak on the L7 spheres), appending costs a push_back per value. (A bound
/// that is ever short grows the array instead.)
template <class Array>
void make_room(Array& array, std::size_t needed) {
  if (array.size() >= needed) return;
  const std::size_t size = std::max(needed, std::min(array.capacity(), array.size() + std::size_t{4096}));
  // the new stretch's pages backed in one call, not faulted in one by one (back_pages)
  if (size <= array.capacity()) back_pages(array.data() + array.size(), (size - array.size()) * sizeof(array[0]));
  array.resize(size);
}

NodeType node_type_of(const BuilderNode<2>& bn) {
  if (bn.place.kind == PlaceKind::vertex) return bn.kind == BuilderNodeKind::ghost ? NodeType::ghost : NodeType::corner;
  if (bn.kind == BuilderNodeKind::rim) return bn.place.kind == PlaceKind::edge ? NodeType::rim_on_edge : NodeType::rim_inside;
  if (bn.place.kind == PlaceKind::edge)
    return bn.kind == BuilderNodeKind::intersection ? NodeType::intersection : NodeType::touching;
  return NodeType::interior;
}

/// The S2 element of closure triangle f's region: its face's, or, in an unmapped face, its own
/// (ElementTriangulation::split_target).
Index target_of(const ElementTriangulation& et, const ElementClosure& closure, int f) {
  const Index t2 = et.components[closure.face[f]].target;
  return t2 != invalid_index || et.split_target.empty() ? t2 : et.split_target[f];
}

/// Whether the side of closure triangle f opposite its corner i maps onto a boundary edge of S2
/// (f a region's triangle: its corner images are on its face's target). Within the tolerance
/// verify judges this with (VerifyOptions::local_tolerance).
bool side_on_target_boundary(const Surface<2>& s2, const ClosureWorkspace& w, int f, int i) {
  constexpr double tolerance = 1e-9;
  const Index t2 = target_of(w.et, w.closure, f);
  const auto& image = w.et.corner_images[f];
  const LocalPoint<2>& ya = image[(i + 1) % 3];
  const LocalPoint<2>& yb = image[(i + 2) % 3];
  // local edge k of the S2 element joins corners k and k + 1: the weight of corner k + 2 vanishes
  auto weight_opposite = [](int k, const LocalPoint<2>& y) {
    return k == 0 ? y.y() : (k == 1 ? 1.0 - y.x() - y.y() : y.x());
  };
  for (int k = 0; k < 3; ++k)
    if (std::abs(weight_opposite(k, ya)) <= tolerance && std::abs(weight_opposite(k, yb)) <= tolerance)
      return s2.edge_elements(s2.element_edge(t2, k)).size() == 1;
  return false;
}

/// Whether the side of closure triangle f opposite its corner i joins two rim nodes. Asked of a
/// side between a region and a triangle left out, which belong to different faces: the side is
/// then a constraint of the closure, and between rim nodes a rim edge (MapBuilder::add_rim_edge,
/// a constraint but no graph edge), where D ends inside the element because S2 leaves the
/// admissible band of distances there (normal projection).
bool side_on_rim(const BuilderContents<2>& in, const ClosureWorkspace& w, int f, int i) {
  const auto& corners = w.closure.triangles[f];
  const auto slots = static_cast<int>(w.et.slots.size());
  for (const int k : {(i + 1) % 3, (i + 2) % 3}) {
    const int v = corners[k];
    if (v >= slots || in.nodes[w.et.slots[v]].kind != BuilderNodeKind::rim) return false;
  }
  return true;
}

/// Whether the faces left out of D lie strictly inside an element whose boundary the regions
/// cover in full (every closure triangle on the element boundary is a region): verify expects
/// such an element to be covered entirely (the region_tiling invariant, face_removal.hpp), unless
/// a hole of S2 explains the gap (a region side with no region across that maps onto a boundary
/// edge of S2), or the rim of D does (a region side with no region across that is a rim edge:
/// an island of S1 whose rays meet S2 only beyond the distance limit, or behind S1). A reversed
/// or unmapped face surrounded by regions (a missing S2 edge preimage between S2 vertices inside
/// the element) would break it.
bool encloses_a_hole(const BuilderContents<2>& in, const ClosureWorkspace& w, const AssemblyCursor& at) {
  const auto& closure = w.closure;
  const int nf = static_cast<int>(closure.triangles.size());
  for (int f = 0; f < nf; ++f)
    if (at.triangle_region[f] == invalid_index)
      for (int i = 0; i < 3; ++i)
        if (closure.neighbors[f][i] < 0) return false;  // the gap reaches the element boundary
  for (int f = 0; f < nf; ++f) {
    if (at.triangle_region[f] == invalid_index) continue;
    for (int i = 0; i < 3; ++i) {
      const int g = closure.neighbors[f][i];
      if (g >= 0 && at.triangle_region[g] == invalid_index &&
          (side_on_target_boundary(in.s2, w, f, i) || side_on_rim(in, w, f, i)))
        return false;
    }
  }
  return true;
}

/// Numbers the element's regions: triangles of faces inside D with a target element and the
/// map's orientation. Returns how many there are: none if the faces left out would be a hole
/// strictly inside the element (encloses_a_hole); then the element leaves D whole, as
/// remove_faces takes an element whose removed face lies strictly inside it.
Index number_regions(const BuilderContents<2>& in, const ClosureWorkspace& w, int orientation, AssemblyCursor& at) {
  const ElementTriangulation& et = w.et;
  const auto rbase = static_cast<Index>(at.regions);
  const int nf = static_cast<int>(w.closure.triangles.size());
  at.triangle_region.assign(nf, invalid_index);
  // A closure triangle's S1 measure, in the tally's units: the reference triangle's measure is
  // 1/2, so a triangle whose local corners span |cross| covers |cross| times the element's.
  const double element_units = in.s1.element_measure(et.element) / in.s1.measure() * 0x1p60;
  if (nf == 0) at.left_out.outside += std::llround(element_units);  // nothing of the map on the element
  auto measure_of = [&](int f) {
    const auto& tr = w.closure.triangles[f];
    const LocalPoint<2> u = et.positions[tr[1]] - et.positions[tr[0]], v = et.positions[tr[2]] - et.positions[tr[0]];
    return std::llround(std::abs(u(0) * v(1) - u(1) * v(0)) * element_units);
  };
  for (const auto& comp : et.components) {
    if (comp.target != invalid_index && comp.sign != orientation) ++at.reversed_faces;
    if (!comp.outside && comp.target == invalid_index) ++at.unmapped_faces;
  }
  // The triangles of unmapped faces that map into an S2 element of their own with the map's
  // orientation are regions too (split_unmapped_face), unless keeping them would leave a hole
  // strictly inside the element that keeping none of them does not.
  auto number = [&](bool split) {
    Index nr = 0;
    at.split_kept = false;
    for (int f = 0; f < nf; ++f) {
      const auto& comp = et.components[w.closure.face[f]];
      at.triangle_region[f] = invalid_index;
      if (comp.target == invalid_index) {  // unmapped, or outside (no target either)
        if (!split || et.split_target.empty() || et.split_target[f] == invalid_index || et.split_sign[f] != orientation)
          continue;
        at.split_kept = true;
      } else if (comp.sign != orientation) {
        continue;
      }
      at.triangle_region[f] = rbase + nr++;
    }
    return nr;
  };
  Index nr = number(true);
  bool enclosed = nr > 0 && nr < nf && encloses_a_hole(in, w, at);
  if (enclosed && at.split_kept) {
    nr = number(false);
    enclosed = nr > 0 && nr < nf && encloses_a_hole(in, w, at);
  }
  for (int f = 0; f < nf; ++f) {
    const auto& comp = et.components[w.closure.face[f]];
    if (at.triangle_region[f] != invalid_index) {
      if (enclosed) at.left_out.enclosed += measure_of(f);
    } else if (comp.outside) {
      at.left_out.outside += measure_of(f);
    } else if (comp.target == invalid_index) {
      at.left_out.unmapped += measure_of(f);
    } else {
      at.left_out.reversed += measure_of(f);
    }
  }
  if (enclosed) {
    at.triangle_region.assign(nf, invalid_index);
    at.split_kept = false;
    return 0;
  }
  return nr;
}

/// The element's nodes with their neighbours: graph edges, and closure edges that border a
/// region (virtual corners are not nodes). An element its regions tile gets no neighbour
/// entries: PlMap derives them from the regions (hand_over_stored_form), and an element with
/// entries is one that stores its graph.
void write_nodes(const BuilderContents<2>& in, const ClosureWorkspace& w, bool tiled, MapData<2>& part,
                 AssemblyCursor& at) {
  const ElementTriangulation& et = w.et;
  const auto base = static_cast<Index>(at.nodes);
  const int ns = static_cast<int>(et.slots.size());
  auto is_region = [&](int f) { return f >= 0 && at.triangle_region[f] != invalid_index; };
  make_room(part.neighbor_begin, at.graph_nodes + 1 + static_cast<std::size_t>(ns));  // kept if entries are written
  for (int i = 0; i < ns; ++i) {
    const auto& bn = in.nodes[et.slots[i]];
    const std::size_t n = at.nodes + static_cast<std::size_t>(i);
    part.node_position[n] = et.positions[i];
    part.node_type[n] = node_type_of(bn);
    part.node_location[n] = et.location[i];
    part.node_image_element[n] = bn.image.element;
    part.node_image_local[n] = support_local<2>(in.s2, bn.image, bn.image.element);
    part.node_target[n] = bn.kind == BuilderNodeKind::ghost ? invalid_index : bn.target;
    if (at.kept_omitted_weights != nullptr)
      if (const std::optional<double> w = omitted_weight_to_keep(bn.image, part.node_image_local[n]))
        at.kept_omitted_weights->push_back({static_cast<Index>(n), *w});
    if (!tiled) visit_ring(w.closure, i, w.ring_start[i], [&](const RingEntry& entry) {
      if (entry.vertex >= ns || (!entry.graph && !is_region(entry.before) && !is_region(entry.after))) return;
      part.neighbor[at.entries] = base + entry.vertex;
      part.neighbor_edge_kind[at.entries++] = entry.graph ? GraphEdgeKind::target_edge : GraphEdgeKind::closure;
    });
    part.neighbor_begin[at.graph_nodes + static_cast<std::size_t>(i) + 1] = static_cast<Index>(at.entries);
  }
  at.nodes += static_cast<std::size_t>(ns);
  part.node_begin[at.elements + 1] = static_cast<Index>(at.nodes);
  make_room(part.edge_node, at.edge_nodes + et.edge_slots.size());
  for (int k = 0; k < 3; ++k) {
    for (int q = et.edge_slots_begin[k]; q < et.edge_slots_begin[k + 1]; ++q)
      part.edge_node[at.edge_nodes++] = base + et.edge_slots[q];
    part.edge_node_begin[3 * at.elements + static_cast<std::size_t>(k) + 1] = static_cast<Index>(at.edge_nodes);
  }
}

/// Whether every side at a ghost node of the element just written (nodes [nb, ne), their
/// neighbour ends from `first_end` on, regions [rb, re) of the part) has the kind the derivation
/// gives it (map_graph_derivation.hpp): the regions' S2 elements differ across it, or, with no
/// region across, its nodes lie on one S2 edge.
bool ghost_sides_derive_as_written(const Surface<2>& s2, const MapData<2>& part, Index nb, Index ne,
                                   std::size_t first_end, std::size_t rb, std::size_t re) {
  for (Index n = nb; n < ne; ++n) {
    if (part.node_type[n] != NodeType::ghost) continue;
    const std::size_t end = first_end + static_cast<std::size_t>(n - nb);  // n's neighbour ends
    for (Index j = part.neighbor_begin[end]; j < part.neighbor_begin[end + 1]; ++j) {
      const Index y = part.neighbor[j];
      Index sides[2] = {invalid_index, invalid_index};
      int count = 0;
      for (std::size_t r = rb; r < re && count < 3; ++r) {
        const auto& c = part.region_corners[r];
        const bool has_n = c[0] == n || c[1] == n || c[2] == n, has_y = c[0] == y || c[1] == y || c[2] == y;
        if (has_n && has_y) {
          if (count < 2) sides[count] = static_cast<Index>(r);
          ++count;
        }
      }
      if (count == 0 || count > 2) return false;
      const bool target_edge = count == 2 ? part.region_target[sides[0]] != part.region_target[sides[1]]
                                          : on_common_target_edge(part, s2, part.region_target[sides[0]], n, y);
      if (target_edge != (part.neighbor_edge_kind[j] == GraphEdgeKind::target_edge)) return false;
    }
  }
  return true;
}

/// The element's regions, and the region a point-location walk starts from.
void write_regions(const ClosureWorkspace& w, Index base, Index region_count, MapData<2>& part, AssemblyCursor& at) {
  const ElementTriangulation& et = w.et;
  const ElementClosure& closure = w.closure;
  const auto rbase = static_cast<Index>(at.regions);
  const int nf = static_cast<int>(closure.triangles.size());
  for (int f = 0; f < nf; ++f) {
    if (at.triangle_region[f] == invalid_index) continue;
    const auto& tr = closure.triangles[f];
    auto& corners = part.region_corners[at.regions];
    auto& neighbors = part.region_neighbors[at.graph_regions++];  // kept only with neighbour entries
    for (int i = 0; i < 3; ++i) {
      corners[i] = base + tr[i];
      const int g = closure.neighbors[f][i];
      neighbors[i] = g >= 0 ? at.triangle_region[g] : invalid_index;
    }
    part.region_target[at.regions] = target_of(et, closure, f);
    if (const auto& comp = et.components[closure.face[f]]; comp.target == invalid_index) {
      at.split_targets.push_back(part.region_target[at.regions]);
      if (comp.outside) at.outside_split_regions.push_back(static_cast<Index>(at.regions));
    }
    // judged with the face (a region's face has sign != 0); or written after the builder is freed
    if (at.kept_omitted_weights == nullptr) part.region_map[at.regions] = et.corner_maps[f];
    ++at.regions;
  }
  part.region_begin[at.elements + 1] = static_cast<Index>(at.regions);
  if (region_count > 0) {
    const int ct = et.centroid_triangle;
    part.start_region[at.elements] = (ct >= 0 && at.triangle_region[ct] != invalid_index) ? at.triangle_region[ct] : rbase;
  } else {
    part.start_region[at.elements] = invalid_index;
  }
}

}  // namespace

void keep_or_drop_graph_of_element(std::size_t nodes, std::size_t first_entry, std::size_t first_edge_node,
                                   std::size_t first_graph_region, MapData<2>& part, AssemblyCursor& at) {
  if (at.entries != first_entry) {
    at.graph_nodes += nodes;
    at.graph_elements.push_back(static_cast<Index>(at.elements));
    return;
  }
  at.edge_nodes = first_edge_node;
  at.graph_regions = first_graph_region;
  for (std::size_t k = 1; k <= 3; ++k) part.edge_node_begin[3 * at.elements + k] = static_cast<Index>(first_edge_node);
}

void assemble_element(const BuilderContents<2>& in, const ClosureWorkspace& w, int orientation, MapData<2>& part,
                      AssemblyCursor& at) {
  const ElementTriangulation& et = w.et;
  const int ns = static_cast<int>(et.slots.size());
  const auto nf = w.closure.triangles.size();
  // the element's shares of the bounds size_part reserved: 2 entries per closure side, and
  // 3n - h - 3 sides for n vertices, h on the boundary (3 corners and the edge nodes)
  const std::size_t n = et.positions.size();
  const std::size_t h = 3 + et.edge_slots.size() - static_cast<std::size_t>(2 * et.corner_count);
  const std::size_t max_entries = ns > 0 ? 2 * (3 * n - h - 3) : 0;
  make_room(part.neighbor, at.entries + max_entries);
  make_room(part.neighbor_edge_kind, at.entries + max_entries);
  make_room(part.region_corners, at.regions + nf);
  make_room(part.region_neighbors, at.graph_regions + nf);
  make_room(part.region_target, at.regions + nf);
  if (at.kept_omitted_weights == nullptr) make_room(part.region_map, at.regions + nf);
  const Index region_count = number_regions(in, w, orientation, at);
  const auto base = static_cast<Index>(at.nodes);
  // Tiled: every face of the closure is a region, so the graph follows from the regions. At a
  // ghost node the derived kind of a side with no region across rests on an exactly zero weight
  // of the ghost's image, which the rounding of the input's scale can decide either way: such an
  // element is written with its neighbour entries and keeps them if the derivation would differ.
  const bool tiled = nf > 0 && static_cast<std::size_t>(region_count) == nf;
  // An element with a rim node keeps its graph: D ends on it, so its regions do not tile it
  // anyway, and the derivation knows no rim edges.
  bool has_ghost = false, has_rim = false;
  for (const Index slot : et.slots) {
    has_ghost = has_ghost || in.nodes[slot].kind == BuilderNodeKind::ghost;
    has_rim = has_rim || in.nodes[slot].kind == BuilderNodeKind::rim;
  }
  const std::size_t first_entry = at.entries, first_edge_node = at.edge_nodes, first_graph_region = at.graph_regions;
  // Split triangles (number_regions) keep the graph too: the derivation would read their sides
  // between regions of different S2 elements as graph edges, which no walk inserted.
  write_nodes(in, w, tiled && !has_ghost && !has_rim && !at.split_kept, part, at);
  write_regions(w, base, region_count, part, at);
  if (tiled && has_ghost && !has_rim && !at.split_kept &&
      ghost_sides_derive_as_written(in.s2, part, base, static_cast<Index>(at.nodes), at.graph_nodes,
                                    at.regions - static_cast<std::size_t>(region_count), at.regions))
    at.entries = first_entry;  // the derivation gives these entries back: drop them
  keep_or_drop_graph_of_element(static_cast<std::size_t>(ns), first_entry, first_edge_node, first_graph_region, part, at);
  ++at.elements;
}

void trim_part(const AssemblyCursor& at, MapData<2>& part) {
  // the element and node arrays too: a part whose tail another thread took was sized for more
  // elements than it closed (finalize_triangles.cpp, ClosingPass)
  part.node_begin.resize(at.elements + 1);
  part.region_begin.resize(at.elements + 1);
  part.start_region.resize(at.elements);
  part.edge_node_begin.resize(3 * at.elements + 1);
  part.node_position.resize(at.nodes);
  part.node_type.resize(at.nodes);
  part.node_location.resize(at.nodes);
  part.node_image_element.resize(at.nodes);
  part.node_image_local.resize(at.nodes);
  part.node_target.resize(at.nodes);
  part.neighbor_begin.resize(at.graph_nodes + 1);
  part.neighbor.resize(at.entries);
  part.neighbor_edge_kind.resize(at.entries);
  part.edge_node.resize(at.edge_nodes);
  part.region_corners.resize(at.regions);
  part.region_neighbors.resize(at.graph_regions);
  part.region_target.resize(at.regions);
  if (at.kept_omitted_weights == nullptr) part.region_map.resize(at.regions);
}

StoredGraph hand_over_stored_form(AssembledMap& assembled) {
  MapData<2>& m = assembled.map;
  StoredGraph g;
  std::size_t graph_region = 0;  // m's region neighbours are those of the elements kept here, in order
  std::size_t end = 0;           // m's neighbour ends are those of their nodes, in order
  for (const Index element : assembled.graph_elements) {
    const auto t = static_cast<std::size_t>(element);
    const Index nb = m.node_begin[t], ne = m.node_begin[t + 1];
    const std::size_t first_end = end;
    g.element.push_back(element);
    for (Index n = nb; n < ne; ++n, ++end) g.neighbor_count.push_back(m.neighbor_begin[end + 1] - m.neighbor_begin[end]);
    g.neighbor.insert(g.neighbor.end(), m.neighbor.begin() + m.neighbor_begin[first_end], m.neighbor.begin() + m.neighbor_begin[end]);
    g.neighbor_edge_kind.insert(g.neighbor_edge_kind.end(), m.neighbor_edge_kind.begin() + m.neighbor_begin[first_end],
                                m.neighbor_edge_kind.begin() + m.neighbor_begin[end]);
    for (std::size_t k = 3 * t; k < 3 * t + 3; ++k) g.edge_node_count.push_back(m.edge_node_begin[k + 1] - m.edge_node_begin[k]);
    g.edge_node.insert(g.edge_node.end(), m.edge_node.begin() + m.edge_node_begin[3 * t],
                       m.edge_node.begin() + m.edge_node_begin[3 * t + 3]);
    const auto regions = static_cast<std::size_t>(m.region_begin[t + 1] - m.region_begin[t]);
    g.region_neighbors.insert(g.region_neighbors.end(), m.region_neighbors.begin() + static_cast<std::ptrdiff_t>(graph_region),
                              m.region_neighbors.begin() + static_cast<std::ptrdiff_t>(graph_region + regions));
    graph_region += regions;
  }
  if (graph_region != m.region_neighbors.size() || end + 1 != m.neighbor_begin.size())
    throw BuilderError("internal: the assembled map has region neighbours or neighbour ends of elements that store no graph");
  std::vector<Index>().swap(assembled.graph_elements);
  auto release = [](auto& v) { std::decay_t<decltype(v)>().swap(v); };
  release(m.neighbor_begin);
  release(m.neighbor);
  release(m.neighbor_edge_kind);
  release(m.edge_node_begin);
  release(m.edge_node);
  release(m.region_neighbors);
  return g;
}

}  // namespace plmap::detail
