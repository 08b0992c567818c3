// finalize(), phase 2: closure (finalize_closure.hpp).

#include "finalize_closure.hpp"
#include "orientation_through_map.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/element_transfer.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/predicates.hpp>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace plmap::detail {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using FaceBaseInfo = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBaseInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Constraints may pass through vertices (we detect and reject that ourselves) but never need a
// constructed intersection point: crossing graph edges raise an exception.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    Kernel, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

const std::array<LocalPoint<2>, 3> reference_corners = {reference_corner<2>(0), reference_corner<2>(1),
                                                        reference_corner<2>(2)};

std::uint64_t segment_key(int a, int b, bool graph) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 33) |
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::max(a, b))) << 1) |
         static_cast<std::uint64_t>(graph);
}

}  // namespace

struct DelaunayFallback {
  Cdt cdt;
};

ClosureWorkspace::ClosureWorkspace() : delaunay(std::make_unique<DelaunayFallback>()) {}
ClosureWorkspace::~ClosureWorkspace() = default;
ClosureWorkspace::ClosureWorkspace(ClosureWorkspace&&) noexcept = default;
ClosureWorkspace& ClosureWorkspace::operator=(ClosureWorkspace&&) noexcept = default;

// Edges 0 (y = 0) and 2 (x = 0) are exact anyway; on edge 1 (x + y = 1) the second coordinate is
// 1 - first, which is exact when first >= 1/2.
LocalPoint<2> on_local_edge(int k, double s) {
  if (k == 0) return LocalPoint<2>(s, 0.0);
  if (k == 2) return LocalPoint<2>(0.0, 1.0 - s);
  if (s >= 0.5) return LocalPoint<2>(1.0 - s, s);
  const double x = 1.0 - s;
  return LocalPoint<2>(x, 1.0 - x);
}

LocalPoint<2> node_local(const BuilderContents<2>& in, Index node, Index t) {
  const auto& p = in.nodes[node].place;
  if (p.kind == PlaceKind::vertex) return reference_corners[in.s1.local_corner(t, p.index)];
  if (p.kind == PlaceKind::element) return p.local();
  for (int k = 0; k < 3; ++k)
    if (in.s1.element_edge(t, k) == p.index)
      return on_local_edge(k, in.s1.local_edge_is_forward(t, k) ? p.t() : 1.0 - p.t());
  return LocalPoint<2>::Zero();
}

namespace {

/// The element's slots: present corners, then edge nodes along edges 0, 1, 2, then interior
/// nodes; and the slots along each local edge. Returns the slot of each corner, or -1.
std::array<int, 3> place_slots(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                               ClosureWorkspace& w) {
  auto& et = w.et;
  if (w.slot_of_node.size() != in.nodes.size()) assign_on_huge_pages(w.slot_of_node, in.nodes.size(), -1);
  for (Index n : et.slots) w.slot_of_node[n] = -1;  // the previous element's
  et.clear();
  std::array<int, 3> corner_slot{-1, -1, -1};
  for (int k = 0; k < 3; ++k) {
    const Index n = in.node_at_domain_vertex[in.s1.element(t)[k]];
    if (n != invalid_index) {
      ++et.corner_count;
      corner_slot[k] = static_cast<int>(et.slots.size());
      et.slots.push_back(n);
      et.positions.push_back(reference_corners[k]);
      et.location.push_back(static_cast<std::int8_t>(k));
    }
  }
  auto& edge_inner = w.edge_inner;
  for (int k = 0; k < 3; ++k) {
    edge_inner[k].clear();
    const auto& list = where.edge_nodes[in.s1.element_edge(t, k)];
    const bool forward = in.s1.local_edge_is_forward(t, k);
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Index n = forward ? list[i] : list[list.size() - 1 - i];
      edge_inner[k].push_back(static_cast<int>(et.slots.size()));
      et.slots.push_back(n);
      const double edge_t = in.nodes[n].place.t();
      et.positions.push_back(on_local_edge(k, forward ? edge_t : 1.0 - edge_t));
      et.location.push_back(static_cast<std::int8_t>(k));
    }
  }
  for (Index n : where.interior_nodes[t]) {
    et.slots.push_back(n);
    et.positions.push_back(in.nodes[n].place.local());
    et.location.push_back(-1);
  }
  const int ns = static_cast<int>(et.slots.size());
  for (int i = 0; i < ns; ++i) w.slot_of_node[et.slots[i]] = i;
  for (int k = 0; k < 3; ++k) {
    auto& es = et.edge_slots;
    et.edge_slots_begin[k] = static_cast<int>(es.size());
    if (corner_slot[k] >= 0) es.push_back(corner_slot[k]);
    es.insert(es.end(), edge_inner[k].begin(), edge_inner[k].end());
    if (corner_slot[(k + 1) % 3] >= 0) es.push_back(corner_slot[(k + 1) % 3]);
  }
  et.edge_slots_begin[3] = static_cast<int>(et.edge_slots.size());
  return corner_slot;
}

/// The vertices of the closure: the slots, then one "virtual" vertex per missing corner (faces
/// touching a virtual vertex lie outside D). Returns the vertex at each corner.
std::array<int, 3> add_virtual_corners(ElementTriangulation& et, const std::array<int, 3>& corner_slot) {
  std::array<int, 3> corner_vertex{};
  for (int k = 0; k < 3; ++k) {
    if (corner_slot[k] >= 0) {
      corner_vertex[k] = corner_slot[k];
    } else {
      corner_vertex[k] = static_cast<int>(et.positions.size());
      et.positions.push_back(reference_corners[k]);
    }
  }
  return corner_vertex;
}

/// The constraints into w.segments (each edge once, sorted): the element boundary between
/// consecutive points, and the graph edges. Returns the boundary's first piece from corner 0.
std::array<int, 2> collect_constraints(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where,
                                       Index t, const std::array<int, 3>& corner_vertex, ClosureWorkspace& w) {
  auto& keys = w.segment_keys;
  keys.clear();
  std::array<int, 2> boundary_start{};
  for (int k = 0; k < 3; ++k) {
    int previous = corner_vertex[k];
    auto add_piece = [&](int next) {
      if (k == 0 && previous == corner_vertex[0]) boundary_start = {previous, next};
      keys.push_back(segment_key(previous, next, false));
      previous = next;
    };
    for (int i : w.edge_inner[k]) add_piece(i);
    add_piece(corner_vertex[(k + 1) % 3]);
  }
  auto add_graph = [&](Index sidx) {
    const auto& seg = in.segments[sidx];
    const int a = w.slot_of_node[seg.a], b = w.slot_of_node[seg.b];
    if (a < 0 || b < 0)
      throw BuilderError(fmt::format(
          "internal: a piece of the preimage of S2 edge {} lacks an endpoint on S1 element {}", seg.target_edge, t));
    if (a == b)
      throw BuilderError(fmt::format(
          "a graph edge on S1 element {} passes through another node (or its endpoints coincide)", t));
    // A rim edge is a constraint like the element boundary, not a graph edge: it is no S2 edge's
    // preimage, and its sides are closure edges.
    keys.push_back(segment_key(a, b, seg.target_edge != invalid_index));
  };
  for (Index sidx : where.element_segments[t]) add_graph(sidx);
  for (int k = 0; k < 3; ++k)
    for (Index sidx : where.edge_segments[in.s1.element_edge(t, k)]) add_graph(sidx);
  std::sort(keys.begin(), keys.end());
  // each edge once: a boundary piece that is also a graph edge is a graph edge
  w.segments.clear();
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const auto a = static_cast<int>(keys[i] >> 33), b = static_cast<int>((keys[i] >> 1) & 0xffffffffu);
    const bool graph = (keys[i] & 1u) != 0;
    if (!w.segments.empty() && w.segments.back().a == a && w.segments.back().b == b)
      w.segments.back().graph = w.segments.back().graph || graph;
    else
      w.segments.push_back({a, b, graph});
  }
  return boundary_start;
}

/// The general path: a constrained Delaunay triangulation of the same graph. Also the place
/// where invalid input (crossing edges, a node on another edge) is diagnosed.
void close_by_cdt(Index t, ClosureWorkspace& w, int vertex_count) {
  const auto& points = w.et.positions;
  Cdt& cdt = w.delaunay->cdt;
  cdt.clear();
  std::vector<Cdt::Vertex_handle> vh(vertex_count);
  for (int i = 0; i < vertex_count; ++i) {
    const auto before = cdt.number_of_vertices();
    vh[i] = cdt.insert(Kernel::Point_2(points[i](0), points[i](1)));
    if (cdt.number_of_vertices() == before)
      throw BuilderError(fmt::format("two nodes coincide on S1 element {} at local ({}, {})", t, points[i](0),
                                     points[i](1)));
    vh[i]->info() = i;
  }
  try {
    for (const auto& seg : w.segments) cdt.insert_constraint(vh[seg.a], vh[seg.b]);
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    throw BuilderError(fmt::format("graph edges cross each other on S1 element {}", t));
  }
  for (const auto& seg : w.segments)
    if (seg.graph && !cdt.is_edge(vh[seg.a], vh[seg.b]))
      throw BuilderError(fmt::format(
          "a graph edge on S1 element {} passes through another node (or its endpoints coincide)", t));
  auto is_graph_edge = [&](int a, int b) {
    return std::binary_search(w.segment_keys.begin(), w.segment_keys.end(), segment_key(a, b, true));
  };
  auto& closure = w.closure;
  closure.clear();
  int nf = 0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) f->info() = nf++;
  std::vector<Cdt::Face_handle> face_of(nf);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) face_of[f->info()] = f;
  closure.triangles.resize(nf);
  closure.neighbors.resize(nf);
  closure.graph_sides.assign(nf, 0);
  closure.face.assign(nf, -1);
  for (int f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i) {
      closure.triangles[f][i] = face_of[f]->vertex(i)->info();
      const auto g = face_of[f]->neighbor(i);
      closure.neighbors[f][i] = cdt.is_infinite(g) ? -1 : g->info();
    }
  for (int f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i)
      if (face_of[f]->is_constrained(i) &&
          is_graph_edge(closure.triangles[f][(i + 1) % 3], closure.triangles[f][(i + 2) % 3]))
        closure.graph_sides[f] = static_cast<std::uint8_t>(closure.graph_sides[f] | (1u << i));
  // faces of the graph: flood fill across unconstrained sides
  std::vector<int> stack;
  for (int f0 = 0; f0 < nf; ++f0) {
    if (closure.face[f0] >= 0) continue;
    const int c = closure.face_count++;
    closure.face[f0] = c;
    stack.push_back(f0);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const int g = closure.neighbors[f][i];
        if (g < 0 || face_of[f]->is_constrained(i) || closure.face[g] >= 0) continue;
        closure.face[g] = c;
        stack.push_back(g);
      }
    }
  }
}

}  // namespace

namespace {

/// Marks the faces touching a virtual corner as outside D, and groups the closure triangles by
/// face (counting sort): face c owns face_order[face_begin[c] .. face_begin[c + 1]).
void group_triangles_by_face(ClosureWorkspace& w, int ns) {
  const auto& closure = w.closure;
  auto& et = w.et;
  const int nf = static_cast<int>(closure.triangles.size());
  const int ncomp = closure.face_count;
  auto& face_begin = w.face_begin;
  auto& face_order = w.face_order;
  face_begin.assign(ncomp + 1, 0);
  for (int f = 0; f < nf; ++f) {
    ++face_begin[closure.face[f] + 1];
    const auto& tr = closure.triangles[f];
    if (tr[0] >= ns || tr[1] >= ns || tr[2] >= ns) et.components[closure.face[f]].outside = true;
  }
  for (int c = 0; c < ncomp; ++c) face_begin[c + 1] += face_begin[c];
  face_order.resize(nf);
  auto& cursor = w.comp_nodes;
  cursor.assign(face_begin.begin(), face_begin.end() - 1);
  for (int f = 0; f < nf; ++f) face_order[cursor[closure.face[f]]++] = f;
}

/// Face c's vertices into w.comp_nodes, and the S2 vertices carrying their images (the first
/// three; the count says how many there are): an S2 element containing every image has them all
/// as corners.
int gather_face_supports(const BuilderContents<2>& in, ClosureWorkspace& w, int c, std::array<Index, 3>& support_union) {
  auto& comp_nodes = w.comp_nodes;
  auto& stamp = w.vertex_stamp;
  comp_nodes.clear();
  int union_size = 0;
  for (int q = w.face_begin[c]; q < w.face_begin[c + 1]; ++q)
    for (int i = 0; i < 3; ++i) {
      const int v = w.closure.triangles[w.face_order[q]][i];
      if (stamp[v] == c) continue;
      stamp[v] = c;
      comp_nodes.push_back(v);
      const Support<2>& support = in.nodes[w.et.slots[v]].image;
      for (int j = 0; j < support.count; ++j) {
        const Index x = support.vertex(in.s2, j);
        int u = 0;
        while (u < union_size && u < 3 && support_union[u] != x) ++u;
        if (u == union_size) {
          if (union_size < 3) support_union[u] = x;
          ++union_size;  // more than 3: no S2 element contains them all
        }
      }
    }
  return union_size;
}

/// The S2 element whose corners are a, b and c (elements are distinct vertex sets), or invalid.
Index element_with_corners(const Surface<2>& s2, Index a, Index b, Index c) {
  for (Index t : s2.vertex_elements(a))
    if (s2.local_corner(t, b) >= 0 && s2.local_corner(t, c) >= 0) return t;
  return invalid_index;
}

/// Chooses face c's S2 element. The candidates are the S2 elements containing all the images,
/// tried in the order of the star of one support vertex; of those with every edge inserted, the
/// one where the face's image has the largest area wins (ties: the first). Returns that signed
/// area (0: no candidate) and records the corner images of the face's triangles.
double choose_face_target(const BuilderContents<2>& in, ClosureWorkspace& w, int c) {
  const Surface<2>& s2 = in.s2;
  auto& et = w.et;
  auto& comp = et.components[c];
  const auto& triangles = w.closure.triangles;
  const int first = w.face_begin[c], last = w.face_begin[c + 1];
  auto& y = w.on_candidate;
  std::array<Index, 3> support_union{};
  const int union_size = gather_face_supports(in, w, c, support_union);
  const auto& comp_nodes = w.comp_nodes;
  double best_area = 0.0;
  auto try_candidate = [&](Index cand) {
    for (int k = 0; k < 3; ++k)
      if (!in.edge_inserted[s2.element_edge(cand, k)]) return;
    for (int i : comp_nodes) y[i] = support_local<2>(s2, in.nodes[et.slots[i]].image, cand);
    double area = 0.0;
    for (int q = first; q < last; ++q) {
      const auto& tr = triangles[w.face_order[q]];
      const LocalPoint<2> u = y[tr[1]] - y[tr[0]], v = y[tr[2]] - y[tr[0]];
      area += u(0) * v(1) - u(1) * v(0);
    }
    if (std::abs(area) > std::abs(best_area)) {
      best_area = area;
      comp.target = cand;
      for (int q = first; q < last; ++q) {
        const auto& tr = triangles[w.face_order[q]];
        et.corner_images[w.face_order[q]] = {y[tr[0]], y[tr[1]], y[tr[2]]};
      }
    }
  };
  if (union_size == 3) {
    // Three S2 vertices: only the S2 element with exactly these corners can contain every image.
    if (const Index cand = element_with_corners(s2, support_union[0], support_union[1], support_union[2]);
        cand != invalid_index)
      try_candidate(cand);
  } else if (union_size < 3) {
    // All images on one S2 edge or vertex: every element around it contains them. The
    // search starts from a node with the most support vertices, the first such slot.
    int best = comp_nodes[0];
    for (int i : comp_nodes) {
      const int count = in.nodes[et.slots[i]].image.count, best_count = in.nodes[et.slots[best]].image.count;
      if (count > best_count || (count == best_count && i < best)) best = i;
    }
    const Support<2>& best_support = in.nodes[et.slots[best]].image;
    for (Index cand : s2.vertex_elements(best_support.vertex(s2, 0))) {
      bool all = true;
      for (int i : comp_nodes) all = all && support_in_element<2>(s2, in.nodes[et.slots[i]].image, cand);
      if (all) try_candidate(cand);
    }
  }
  return best_area;
}

/// The distinct S2 vertices that carry the images of closure triangle tr's corners (slots, not
/// virtual corners): the first three into `vertices`. Returns how many there are, counting
/// stops at 4 (more than 3: no S2 element holds all the images).
int corner_support_vertices(const BuilderContents<2>& in, const ElementTriangulation& et, const std::array<int, 3>& tr,
                            std::array<Index, 3>& vertices) {
  int count = 0;
  for (int v : tr) {
    const Support<2>& support = in.nodes[et.slots[v]].image;
    for (int j = 0; j < support.count; ++j) {
      const Index x = support.vertex(in.s2, j);
      if (std::find(vertices.begin(), vertices.begin() + count, x) != vertices.begin() + count) continue;
      if (count == 3) return 4;
      vertices[count++] = x;
    }
  }
  return count;
}

/// Whether the images of closure triangle tr's corners all lie on one S2 edge (or vertex): their
/// supports span at most two S2 vertices. Xi then collapses the triangle onto a segment, whatever
/// the rounding of the corner images makes orient2d say (on the edge between corners 1 and 2 of
/// the S2 element, the images' coordinates add up to 1 only up to rounding, so the sign went
/// either way: the same face was kept with a region of kappa 1e13 in one frame and dropped as
/// reversed in a rotated one). Virtual corners (S1 corners without a node) never collapse.
[[gnu::noinline]] bool image_collapses(const BuilderContents<2>& in, const ElementTriangulation& et,
                                       const std::array<int, 3>& tr) {
  for (int v : tr)
    if (v >= static_cast<int>(et.slots.size())) return false;
  std::array<Index, 3> vertices{};
  return corner_support_vertices(in, et, tr, vertices) <= 2;  // a third S2 vertex: the images span a triangle
}

/// Whether the corner images a, b, c may be collinear: their cross product is within what the
/// rounding of images on one S2 edge gives (coordinates at most 1, errors of a few ulps, so at
/// most about 1e-16 times the longer side). A filter for image_collapses, which is exact: a
/// triangle whose image collapses always passes it.
bool nearly_flat(const LocalPoint<2>& a, const LocalPoint<2>& b, const LocalPoint<2>& c) {
  const LocalPoint<2> u = b - a, v = c - a;
  const double cross = u(0) * v(1) - u(1) * v(0);
  return std::abs(cross) <= 1e-12 * (std::abs(u(0)) + std::abs(u(1)) + std::abs(v(0)) + std::abs(v(1)));
}

/// Every triangle of face c must map with the face's orientation. Where the images do not follow
/// one affine map (a discontinuous projection direction field), three nodes of a face can map
/// onto one S2 edge, or a triangle can fold back, although the face as a whole keeps its
/// orientation: such a face is left out of D like a reversed one (FinalizeReport::reversed_faces),
/// instead of giving a region that verify rejects. The corners are judged both as given and as
/// the region's affine map reproduces them (what verify sees): a nearly flat image may become
/// exactly flat through the map. A triangle whose three corners map onto one S2 edge is judged
/// combinatorially (image_collapses), not by the rounding of its images, and its face is listed
/// in w.collapsed_faces (rejudge_collapsed_faces may flip the triangle away). Returns the sign
/// given, or 0; computes the triangles' affine maps on the way.
int judge_face_orientation(const BuilderContents<2>& in, ClosureWorkspace& w, int c, int sign) {
  auto& et = w.et;
  for (int q = w.face_begin[c]; q < w.face_begin[c + 1] && sign != 0; ++q) {
    const int f = w.face_order[q];
    const auto& tr = w.closure.triangles[f];
    const auto& image = et.corner_images[f];
    const std::array<LocalPoint<2>, 3> from{et.positions[tr[0]], et.positions[tr[1]], et.positions[tr[2]]};
    if (w.corner_maps_wanted) et.corner_maps[f] = affine_through<2>(from, image);
    if (nearly_flat(image[0], image[1], image[2]) && image_collapses(in, et, tr)) {
      w.collapsed_faces.push_back(c);
      sign = 0;
    } else if (orient2d(image[0], image[1], image[2]) != sign) {
      sign = 0;
    } else if (!orientation_survives_the_map(from, image)) {
      if (!w.corner_maps_wanted) et.corner_maps[f] = affine_through<2>(from, image);
      const AffineMap<2>& map = et.corner_maps[f];
      if (orient2d(apply<2>(map, from[0]), apply<2>(map, from[1]), apply<2>(map, from[2])) != sign) sign = 0;
    }
  }
  return sign;
}

/// For face c, which has a triangle whose image collapses: flips a diagonal of each such triangle
/// (one whose triangle across lies in the same face) where the quadrilateral is convex and
/// neither new triangle collapses. Returns whether any diagonal was flipped; the triangles keep
/// their indices and faces.
bool flip_collapsed_triangles(const BuilderContents<2>& in, ClosureWorkspace& w, int c) {
  auto& closure = w.closure;
  const auto& et = w.et;
  bool flipped = false;
  for (int k = w.face_begin[c]; k < w.face_begin[c + 1]; ++k) {
    const int t = w.face_order[k];
    if (!image_collapses(in, et, closure.triangles[t])) continue;
    for (int i = 0; i < 3; ++i) {
      const int u = closure.neighbors[t][i];
      if (u < 0 || closure.face[u] != c || ((closure.graph_sides[t] >> i) & 1u)) continue;
      // the triangles after the flip: (p, a, q) and (q, b, p), with q the far corner of u
      const auto& tr = closure.triangles[t];
      const int p = tr[i], a = tr[(i + 1) % 3], b = tr[(i + 2) % 3];
      int q = -1;
      for (int j = 0; j < 3; ++j)
        if (closure.neighbors[u][j] == t) q = closure.triangles[u][j];
      if (q < 0 || image_collapses(in, et, {p, a, q}) || image_collapses(in, et, {q, b, p})) continue;
      if (flip_side(et.positions, closure, t, i)) {
        flipped = true;
        break;
      }
    }
  }
  return flipped;
}

/// Classifies the faces: touching a virtual corner -> outside D; else the S2 element all its
/// nodes map into, and the sign of its image there (votes for the map's orientation).
void classify_faces(const BuilderContents<2>& in, ClosureWorkspace& w, int ns, int vertex_count) {
  auto& et = w.et;
  const int nf = static_cast<int>(w.closure.triangles.size());
  const int ncomp = w.closure.face_count;
  et.components.assign(ncomp, {});
  et.corner_images.resize(nf);
  et.corner_maps.resize(nf);
  group_triangles_by_face(w, ns);
  w.collapsed_faces.clear();
  w.vertex_stamp.assign(vertex_count, -1);
  w.on_candidate.resize(vertex_count);
  for (int c = 0; c < ncomp; ++c) {
    auto& comp = et.components[c];
    if (comp.outside) continue;
    const double area = choose_face_target(in, w, c);
    if (comp.target == invalid_index) continue;
    comp.sign = judge_face_orientation(in, w, c, area > 0 ? 1 : -1);
    w.votes += comp.sign * static_cast<long long>(w.face_begin[c + 1] - w.face_begin[c]);
  }
}

/// The faces in w.collapsed_faces have a triangle whose image collapses onto one S2 edge: where
/// flips of such diagonals give triangles that do not, the face is judged again with them (images,
/// maps and votes anew). Rare (the maps of the femur, bones and armadillo pairs do not change),
/// so it runs after classify_faces, out of its loop.
[[gnu::noinline]] void rejudge_collapsed_faces(const BuilderContents<2>& in, ClosureWorkspace& w) {
  // by index up to the faces listed now: judging a face again may list it again
  const std::size_t listed = w.collapsed_faces.size();
  for (std::size_t k = 0; k < listed; ++k) {
    const int c = w.collapsed_faces[k];
    if (!flip_collapsed_triangles(in, w, c)) continue;
    auto& comp = w.et.components[c];
    comp.target = invalid_index;
    for (int q = w.face_begin[c]; q < w.face_begin[c + 1]; ++q)  // gathered again (the same vertices)
      for (int v : w.closure.triangles[w.face_order[q]]) w.vertex_stamp[v] = -1;
    const double area = choose_face_target(in, w, c);
    if (comp.target == invalid_index) continue;
    comp.sign = judge_face_orientation(in, w, c, area > 0 ? 1 : -1);
    w.votes += comp.sign * static_cast<long long>(w.face_begin[c + 1] - w.face_begin[c]);
  }
  w.collapsed_faces.clear();
}

/// The S2 element that closure triangle tr's own three corners map into, with every edge
/// inserted, and the orientation of its image there (split_unmapped_face); nullopt where it has
/// none or the image is degenerate, before or after the affine map.
struct SplitJudgement {
  Index target;
  int sign;
  std::array<LocalPoint<2>, 3> image;
  AffineMap<2> map;
};

std::optional<SplitJudgement> judge_split_triangle(const BuilderContents<2>& in, const ElementTriangulation& et,
                                                   const std::array<int, 3>& tr) {
  const Surface<2>& s2 = in.s2;
  const int ns = static_cast<int>(et.slots.size());
  if (tr[0] >= ns || tr[1] >= ns || tr[2] >= ns) return std::nullopt;
  std::array<Index, 3> vertices{};
  // fewer than three: it collapses onto an S2 edge; more: no one S2 element holds it
  if (corner_support_vertices(in, et, tr, vertices) != 3) return std::nullopt;
  const Index target = element_with_corners(s2, vertices[0], vertices[1], vertices[2]);
  if (target == invalid_index) return std::nullopt;
  for (int k = 0; k < 3; ++k)
    if (!in.edge_inserted[s2.element_edge(target, k)]) return std::nullopt;
  const std::array<LocalPoint<2>, 3> image{support_local<2>(s2, in.nodes[et.slots[tr[0]]].image, target),
                                           support_local<2>(s2, in.nodes[et.slots[tr[1]]].image, target),
                                           support_local<2>(s2, in.nodes[et.slots[tr[2]]].image, target)};
  const std::array<LocalPoint<2>, 3> from{et.positions[tr[0]], et.positions[tr[1]], et.positions[tr[2]]};
  const int sign = orient2d(image[0], image[1], image[2]);
  if (sign == 0 || orient2d(from[0], from[1], from[2]) <= 0) return std::nullopt;  // no affine map
  const AffineMap<2> map = affine_through<2>(from, image);
  if (orient2d(apply<2>(map, from[0]), apply<2>(map, from[1]), apply<2>(map, from[2])) != sign) return std::nullopt;
  return SplitJudgement{target, sign, image, map};
}

/// The local measure (twice the area) of closure triangle tr that a split keeps: all of it if its
/// corners map into one S2 element with the map's orientation, else none.
double kept_by_split(const BuilderContents<2>& in, const ElementTriangulation& et, const std::array<int, 3>& tr,
                     int orientation) {
  const std::optional<SplitJudgement> judged = judge_split_triangle(in, et, tr);
  if (!judged || judged->sign != orientation) return 0.0;
  const LocalPoint<2> u = et.positions[tr[1]] - et.positions[tr[0]], v = et.positions[tr[2]] - et.positions[tr[0]];
  return std::abs(u(0) * v(1) - u(1) * v(0));
}

/// Re-triangulates unmapped face c so that more of it maps into single S2 elements: a diagonal
/// (a side inside the face that is no constraint) is flipped where the two new triangles keep
/// more of the quadrilateral than the two old ones (kept_by_split). The face's nodes stay; only
/// which three of them span a triangle changes, and with it which triangles a split keeps. Each
/// flip raises the kept measure, so the loop ends; it is also bounded by a pass count.
void flip_towards_split(const BuilderContents<2>& in, ClosureWorkspace& w, int c, int orientation) {
  auto& closure = w.closure;
  const auto& et = w.et;
  auto is_constraint = [&](int a, int b) {
    return std::binary_search(w.segment_keys.begin(), w.segment_keys.end(), segment_key(a, b, false)) ||
           std::binary_search(w.segment_keys.begin(), w.segment_keys.end(), segment_key(a, b, true));
  };
  // the kept measure of each triangle of the face as it stands (indexed by closure triangle)
  auto& kept = w.kept_measure;
  if (kept.size() < closure.triangles.size()) kept.resize(closure.triangles.size());
  for (int k = w.face_begin[c]; k < w.face_begin[c + 1]; ++k)
    kept[w.face_order[k]] = kept_by_split(in, et, closure.triangles[w.face_order[k]], orientation);
  const int count = w.face_begin[c + 1] - w.face_begin[c];
  for (int pass = 0; pass < 2 * count + 2; ++pass) {
    bool flipped = false;
    for (int k = w.face_begin[c]; k < w.face_begin[c + 1]; ++k) {
      const int t = w.face_order[k];
      for (int i = 0; i < 3; ++i) {
        const int u = closure.neighbors[t][i];
        if (u < 0 || closure.face[u] != c || ((closure.graph_sides[t] >> i) & 1u)) continue;
        const auto& tr = closure.triangles[t];
        const int p = tr[i], a = tr[(i + 1) % 3], b = tr[(i + 2) % 3];
        if (is_constraint(a, b)) continue;
        int q = -1;
        for (int j = 0; j < 3; ++j)
          if (closure.neighbors[u][j] == t) q = closure.triangles[u][j];
        // only a strictly convex quadrilateral can flip (flip_side): the new triangles are then
        // proper, and only those are judged (a degenerate one has no affine map)
        if (q < 0 || orient2d(et.positions[p], et.positions[a], et.positions[q]) <= 0 ||
            orient2d(et.positions[q], et.positions[b], et.positions[p]) <= 0)
          continue;
        const double before = kept[t] + kept[u];
        const double kept_t = kept_by_split(in, et, {p, a, q}, orientation);
        const double kept_u = kept_by_split(in, et, {q, b, p}, orientation);
        // a margin above rounding: equal measures computed two ways must not flip back and forth
        if (kept_t + kept_u <= before * (1.0 + 1e-9) + 1e-300) continue;
        if (flip_side(et.positions, closure, t, i)) {  // t becomes (p, a, q), u (q, b, p)
          kept[t] = kept_t;
          kept[u] = kept_u;
          flipped = true;
          break;  // t changed: its sides are looked at in the next pass
        }
      }
    }
    if (!flipped) break;
  }
}

/// The triangles of face c, which has no target (its nodes share no S2 element: an S2 edge's
/// preimage that would split it is missing in part): each triangle whose own three corners map
/// into one S2 element gets that element and the sign of its image there, as a face would. The
/// assembly keeps those with the map's orientation as regions of their own; two such triangles of
/// different elements share only corners whose images lie on the S2 edge between them, so the
/// map stays continuous across their common side. Where the map's orientation is known, the
/// face is first re-triangulated to keep more (flip_towards_split).
void split_unmapped_face(const BuilderContents<2>& in, ClosureWorkspace& w, int c, int orientation) {
  auto& et = w.et;
  if (orientation != 0) flip_towards_split(in, w, c, orientation);
  for (int q = w.face_begin[c]; q < w.face_begin[c + 1]; ++q) {
    const int f = w.face_order[q];
    const std::optional<SplitJudgement> judged = judge_split_triangle(in, et, w.closure.triangles[f]);
    if (!judged) continue;
    et.split_target[f] = judged->target;
    et.split_sign[f] = static_cast<signed char>(judged->sign);
    et.corner_images[f] = judged->image;
    et.corner_maps[f] = judged->map;
  }
}

/// Gives the triangles of every face without a target their own S2 elements where they have one
/// (split_unmapped_face). That includes the faces at a corner of the element that has no node
/// (outside D as a whole): the triangles touching the corner have no image, but the others,
/// between nodes the walks did reach, are judged like those of an unmapped face.
void split_unmapped_faces(const BuilderContents<2>& in, ClosureWorkspace& w, int orientation) {
  auto& et = w.et;
  bool any = false;
  for (const auto& comp : et.components) any = any || comp.target == invalid_index;
  if (!any) return;
  const std::size_t nf = w.closure.triangles.size();
  et.split_target.assign(nf, invalid_index);
  et.split_sign.assign(nf, 0);
  for (int c = 0; c < static_cast<int>(et.components.size()); ++c)
    if (et.components[c].target == invalid_index) split_unmapped_face(in, w, c, orientation);
}

/// The closure triangle a point-location walk starts from: the first inside D at the element's
/// centroid, or -1.
int centroid_triangle(const ElementTriangulation& et, const ElementClosure& closure) {
  const LocalPoint<2> centroid(1.0 / 3.0, 1.0 / 3.0);
  const auto& points = et.positions;
  for (int f = 0; f < static_cast<int>(closure.triangles.size()); ++f) {
    const auto& tr = closure.triangles[f];
    if (!et.components[closure.face[f]].outside && orient2d(points[tr[0]], points[tr[1]], centroid) >= 0 &&
        orient2d(points[tr[1]], points[tr[2]], centroid) >= 0 && orient2d(points[tr[2]], points[tr[0]], centroid) >= 0)
      return f;
  }
  return -1;
}

}  // namespace

bool close_graph(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                 ClosureWorkspace& w) {
  const std::array<int, 3> corner_slot = place_slots(in, where, t, w);
  w.et.element = t;
  if (w.et.slots.empty()) {  // nothing of the map on this element
    w.closure.clear();
    return false;
  }
  const std::array<int, 3> corner_vertex = add_virtual_corners(w.et, corner_slot);
  const int vertex_count = static_cast<int>(w.et.positions.size());
  const std::array<int, 2> boundary_start = collect_constraints(in, where, t, corner_vertex, w);
  if (!close_by_faces(w.et.positions, w.segments, boundary_start, w.closure, w.scratch))
    close_by_cdt(t, w, vertex_count);
  return true;
}

void close_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                   ClosureWorkspace& w, int orientation) {
  if (!close_graph(in, where, t, w)) return;
  const int ns = static_cast<int>(w.et.slots.size());
  const int vertex_count = static_cast<int>(w.et.positions.size());
  classify_faces(in, w, ns, vertex_count);
  if (!w.collapsed_faces.empty()) rejudge_collapsed_faces(in, w);
  if (in.options.split_unmapped_faces) split_unmapped_faces(in, w, orientation);
  w.et.centroid_triangle = centroid_triangle(w.et, w.closure);
  // where each node's ring of neighbours starts (they are circulated at assembly)
  ring_starts(w.closure, vertex_count, w.ring_start);
}

}  // namespace plmap::detail
