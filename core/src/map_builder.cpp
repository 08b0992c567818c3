// The map factory (paper section 3.1): collects nodes and edge preimages on S1, then finalize()
// turns them into the compact PlMap.
//
// Internally every node is entered once, at its place on S1: an S1 vertex, a point of an S1 edge
// (parameter along the edge from its smaller-index vertex) or a point inside an S1 element. Its
// image is kept as a "support": the S2 vertices with non-zero barycentric weight. Supports make
// the question "which S2 elements contain this image?" exact and cheap, and they let an image be
// re-expressed on any of those elements without rounding.

#include "element_closure.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/element_transfer.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/predicates.hpp>
#include <plmap/core/snapping.hpp>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <thread>

namespace plmap {

namespace {

enum class PlaceKind : std::uint8_t { vertex, edge, element };

/// A point of S1: a vertex, a point on an edge (d = 2; parameter from the smaller-index vertex),
/// or a point inside an element. The builder holds one per node (millions), so the parameter
/// and the local coordinates share storage, unaligned: a node takes 80 bytes instead of 96.
template <int d>
struct Place {
  using Coordinates = Eigen::Matrix<double, d, 1, Eigen::DontAlign>;
  Coordinates coords = Coordinates::Zero();  // kind == element: local; kind == edge: (t, 0)
  Index index = invalid_index;
  PlaceKind kind = PlaceKind::vertex;

  double t() const { return coords(0); }          // kind == edge
  LocalPoint<d> local() const { return coords; }  // kind == element
};

/// Image of a node on S2 as the S2 vertices carrying its barycentric weight.
template <int d>
struct Support {
  std::array<double, d + 1> weight{};
  std::array<Index, d + 1> vertex{};
  Index element = invalid_index;  // an S2 element containing the image (for the stored form)
  std::uint8_t count = 0;
};

enum class BuilderNodeKind : std::uint8_t { vertex_preimage, ghost, intersection };

template <int d>
struct BuilderNode {
  Place<d> place;
  Support<d> image;
  Index target;  // S2 vertex / S2 edge / invalid
  BuilderNodeKind kind;
};
static_assert(sizeof(BuilderNode<2>) <= 80 && sizeof(BuilderNode<1>) <= 64, "builder nodes are kept compact");

/// A straight piece of an S2 edge's preimage between two nodes: inside element `where`, or (d = 2)
/// along S1 edge `where`.
struct Segment {
  Index a, b;
  Index target_edge;
  bool along_edge;
  Index where;
};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using FaceBaseInfo = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBaseInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Constraints may pass through vertices (we detect and reject that ourselves) but never need a
// constructed intersection point: crossing graph edges raise an exception.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    Kernel, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

/// Sorts a short range by insertion, a long one with std::sort. For up to 16 items this is
/// exactly what std::sort does (libstdc++ sorts such ranges by a stable insertion sort), without
/// its calls; the d = 1 finalize sorts a handful of items per element.
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

/// Items grouped by a key in [0, groups) as CSR arrays: two allocations for all groups, where a
/// vector per group would cost one per S1 element or edge (millions on large maps).
class Buckets {
 public:
  /// key_of(i) is the group of item i in [0, items), or -1 to leave the item out. Items keep
  /// their order within a group.
  template <class KeyOf>
  void build(Index groups, Index items, KeyOf&& key_of) {
    begin_.assign(static_cast<std::size_t>(groups) + 1, 0);
    for (Index i = 0; i < items; ++i)
      if (const Index g = key_of(i); g >= 0) ++begin_[static_cast<std::size_t>(g) + 1];
    std::partial_sum(begin_.begin(), begin_.end(), begin_.begin());
    items_.resize(static_cast<std::size_t>(begin_.back()));
    std::vector<Index> cursor(begin_.begin(), begin_.end() - 1);
    for (Index i = 0; i < items; ++i)
      if (const Index g = key_of(i); g >= 0) items_[static_cast<std::size_t>(cursor[static_cast<std::size_t>(g)]++)] = i;
  }
  Index group_count() const { return static_cast<Index>(begin_.size()) - 1; }
  std::span<const Index> operator[](Index g) const { return {items_.data() + begin_[g], items_.data() + begin_[g + 1]}; }
  std::span<Index> group(Index g) { return {items_.data() + begin_[g], items_.data() + begin_[g + 1]}; }
  /// Gives the memory back (the buckets are empty afterwards).
  void release() {
    std::vector<Index>().swap(begin_);
    std::vector<Index>().swap(items_);
  }

 private:
  std::vector<Index> begin_, items_;
};

/// Per S1 element, the outcome of the triangulation step, which finalize() assembles into the
/// flat arrays right away (one per thread, reused from element to element).
struct ElementTriangulation {
  std::vector<Index> slots;               // builder node of each slot (node order of the element)
  std::vector<LocalPoint<2>> positions;   // of the slots, then of the virtual corners
  std::vector<std::int8_t> location;      // of the slots: corner, local edge, or -1 (inside)
  // The closure itself (triangles, neighbours, faces; triangles touching a virtual corner lie
  // outside D) and the rings stay in the workspace that computed them; per face of the graph:
  struct Component {
    Index target = invalid_index;
    int sign = 0;
    bool outside = false;  // touches a virtual corner
  };
  std::vector<Component> components;
  // Per closure triangle of a face with a target: its corners' images on the target element
  // (computed when the target is chosen, used again for the region's affine map).
  std::vector<std::array<LocalPoint<2>, 3>> corner_images;
  // Per closure triangle of a face with a target: the affine map through those images (computed
  // when the face's triangles are judged, used again as the region's map).
  std::vector<AffineMap<2>> corner_maps;
  std::vector<int> edge_slots;                // along local edges 0, 1, 2, corners included
  std::array<int, 4> edge_slots_begin{};
  int corner_count = 0;                       // slots at corners of the element
  int centroid_triangle = -1;                 // a closure triangle inside D, or -1

  /// Empties it for the next element, keeping the buffers.
  void clear() {
    slots.clear();
    positions.clear();
    location.clear();
    components.clear();
    edge_slots.clear();
    edge_slots_begin = {};
    corner_count = 0;
    centroid_triangle = -1;
  }
};

}  // namespace

template <int d>
  requires SurfaceDimension<d>
struct MapBuilder<d>::Impl {
  std::shared_ptr<const Surface<d>> s1, s2;
  BuilderOptions options;
  std::vector<BuilderNode<d>> nodes;
  std::vector<Index> preimage_of_target_vertex;  // per S2 vertex
  std::vector<Index> node_at_domain_vertex;      // per S1 vertex
  std::vector<Segment> segments;
  // per S2 edge (d = 2) or S2 element (d = 1): not inserted, inserted whole, or in pieces
  std::vector<char> edge_inserted;
  static constexpr char edge_complete = 1, edge_partial = 2, edge_outside_domain = 3;

  Impl(std::shared_ptr<const Surface<d>> domain, std::shared_ptr<const Surface<d>> target,
       BuilderOptions opt)
      : s1(std::move(domain)), s2(std::move(target)), options(opt) {
    if (!s1 || !s2) throw BuilderError("MapBuilder needs two surfaces");
    if (!(options.snap_tolerance >= 0.0 && options.snap_tolerance < 0.1))
      throw BuilderError(fmt::format("snap_tolerance {} is outside [0, 0.1)", options.snap_tolerance));
    if (options.orientation < -1 || options.orientation > 1)
      throw BuilderError("orientation must be -1, 0 (automatic) or +1");
    preimage_of_target_vertex.assign(s2->vertex_count(), invalid_index);
    node_at_domain_vertex.assign(s1->vertex_count(), invalid_index);
    edge_inserted.assign(s2->edge_count(), 0);
  }

  double tol() const { return options.snap_tolerance; }

  // ---- argument checks ----------------------------------------------------------------------
  void check_s1_element(Index t) const {
    if (t < 0 || t >= s1->element_count())
      throw BuilderError(fmt::format("S1 element {} does not exist (S1 has {} elements)", t,
                                     s1->element_count()));
  }
  void check_s2_element(Index t) const {
    if (t < 0 || t >= s2->element_count())
      throw BuilderError(fmt::format("S2 element {} does not exist (S2 has {} elements)", t,
                                     s2->element_count()));
  }
  void check_s1_vertex(Index v) const {
    if (v < 0 || v >= s1->vertex_count())
      throw BuilderError(fmt::format("S1 vertex {} does not exist (S1 has {} vertices)", v,
                                     s1->vertex_count()));
  }
  /// A node at an S1 vertex lives on the vertex's elements; an isolated vertex has none.
  void check_s1_vertex_with_elements(Index v) const {
    check_s1_vertex(v);
    if (s1->vertex_elements(v).empty())
      throw BuilderError(fmt::format("S1 vertex {} is isolated (no S1 element uses it): it is not part of S1, "
                                     "so no node can lie on it",
                                     v));
  }
  void check_s2_vertex(Index v) const {
    if (v < 0 || v >= s2->vertex_count())
      throw BuilderError(fmt::format("S2 vertex {} does not exist (S2 has {} vertices)", v,
                                     s2->vertex_count()));
  }
  void check_s2_edge(Index e) const {
    if (e < 0 || e >= s2->edge_count())
      throw BuilderError(fmt::format("S2 edge {} does not exist (S2 has {} edges)", e, s2->edge_count()));
  }

  /// Barycentric coordinates of a local point, validated and with the snapping rule applied:
  /// weights within the tolerance of 0 become 0 (and the rest is renormalised).
  Barycentric<d> snapped_barycentric(const LocalPoint<d>& xi, const char* what, Index element) const {
    if (!xi.allFinite())
      throw BuilderError(fmt::format("{} on element {}: local coordinates are not finite", what, element));
    const Barycentric<d> b = barycentric_from_local<d>(xi);
    for (int k = 0; k <= d; ++k)
      if (b(k) < -tol())
        throw BuilderError(fmt::format("{}: local coordinates ({}) lie outside element {}", what,
                                       fmt::join(xi.data(), xi.data() + d, ", "), element));
    return snap_barycentric<d>(b, tol());
  }

  /// Place on S1 of a point given on an element, after snapping.
  Place<d> place_of(const SurfacePoint<d>& p, const char* what) const {
    check_s1_element(p.element);
    const Barycentric<d> b = snapped_barycentric(p.local, what, p.element);
    int nonzero = 0;
    std::array<int, d + 1> which{};
    for (int k = 0; k <= d; ++k)
      if (b(k) > 0.0) which[nonzero++] = k;
    const auto& corners = s1->element(p.element);
    Place<d> place;
    if (nonzero == 1) {
      place.kind = PlaceKind::vertex;
      place.index = corners[which[0]];
    } else if (d == 2 && nonzero == 2) {
      if constexpr (d == 2) {
        const Index u = corners[which[0]], v = corners[which[1]];
        place.kind = PlaceKind::edge;
        place.index = s1->find_edge(u, v);
        // parameter from the smaller-index vertex
        place.coords(0) = u < v ? b(which[1]) : b(which[0]);
      }
    } else {
      place.kind = PlaceKind::element;
      place.index = p.element;
      place.coords = local_from_barycentric<d>(b);
    }
    return place;
  }

  /// Image support of a point given on S2, after snapping.
  Support<d> support_of(const SurfacePoint<d>& p, const char* what) const {
    check_s2_element(p.element);
    if (!p.local.allFinite())
      throw BuilderError(fmt::format("{}: image coordinates on S2 element {} are not finite", what, p.element));
    Barycentric<d> b = barycentric_from_local<d>(p.local);
    for (int k = 0; k <= d; ++k)
      if (b(k) < -tol())
        throw BuilderError(fmt::format("{}: image coordinates lie outside S2 element {}", what, p.element));
    b = snap_barycentric<d>(b, tol());
    Support<d> s;
    s.element = p.element;
    for (int k = 0; k <= d; ++k)
      if (b(k) > 0.0) {
        s.vertex[s.count] = s2->element(p.element)[k];
        s.weight[s.count] = b(k);
        ++s.count;
      }
    return s;
  }

  Support<d> vertex_support(Index v) const {
    Support<d> s;
    s.count = 1;
    s.vertex[0] = v;
    s.weight[0] = 1.0;
    const auto star = s2->vertex_elements(v);
    if (star.empty())
      throw BuilderError(fmt::format("S2 vertex {} is isolated (no S2 element uses it): it is not part of S2, "
                                     "so it has no preimage",
                                     v));
    s.element = star.front();
    return s;
  }

  /// Support of the point at parameter tau along the S2 edge (d = 2: edge index, tau from its
  /// smaller vertex) or S2 segment (d = 1: element index, tau = local coordinate).
  Support<d> edge_support(Index e, double tau) const {
    Index u, v, element;
    if constexpr (d == 2) {
      const auto ev = s2->edge_vertices(e);
      u = ev[0];
      v = ev[1];
      element = s2->edge_elements(e).front().element;
    } else {
      u = s2->element(e)[0];
      v = s2->element(e)[1];
      element = e;
    }
    Support<d> s;
    s.element = element;
    s.count = 2;
    s.vertex[0] = u;
    s.weight[0] = 1.0 - tau;
    s.vertex[1] = v;
    s.weight[1] = tau;
    return s;
  }

  // ---- node entry -----------------------------------------------------------------------------
  Index new_node(const Place<d>& place, BuilderNodeKind kind, Index target, const Support<d>& image) {
    const auto id = static_cast<Index>(nodes.size());
    nodes.push_back({place, image, target, kind});
    if (place.kind == PlaceKind::vertex) node_at_domain_vertex[place.index] = id;
    if (kind == BuilderNodeKind::vertex_preimage) preimage_of_target_vertex[target] = id;
    return id;
  }

  Index add_vertex_preimage(Index target_vertex, const Place<d>& place) {
    check_s2_vertex(target_vertex);
    if (preimage_of_target_vertex[target_vertex] != invalid_index)
      throw BuilderError(fmt::format("S2 vertex {} already has a preimage (node {})", target_vertex,
                                     preimage_of_target_vertex[target_vertex]));
    if (place.kind == PlaceKind::vertex && node_at_domain_vertex[place.index] != invalid_index)
      throw BuilderError(fmt::format(
          "S1 vertex {} already carries a node; cannot also be the preimage of S2 vertex {}",
          place.index, target_vertex));
    return new_node(place, BuilderNodeKind::vertex_preimage, target_vertex,
                    vertex_support(target_vertex));
  }

  Index add_ghost_node(Index domain_vertex, const Support<d>& image) {
    check_s1_vertex_with_elements(domain_vertex);
    if (image.count == 1) {
      // The image is an S2 vertex: this is a corner node, not a ghost.
      const Index tv = image.vertex[0];
      const Index existing = preimage_of_target_vertex[tv];
      if (existing != invalid_index) {
        const auto& n = nodes[existing];
        if (n.place.kind == PlaceKind::vertex && n.place.index == domain_vertex) return existing;
        throw BuilderError(fmt::format(
            "ghost node at S1 vertex {} maps onto S2 vertex {}, which already has a preimage",
            domain_vertex, tv));
      }
      Place<d> place;
      place.kind = PlaceKind::vertex;
      place.index = domain_vertex;
      return add_vertex_preimage(tv, place);
    }
    if (node_at_domain_vertex[domain_vertex] != invalid_index)
      throw BuilderError(fmt::format("S1 vertex {} already carries a node", domain_vertex));
    Place<d> place;
    place.kind = PlaceKind::vertex;
    place.index = domain_vertex;
    return new_node(place, BuilderNodeKind::ghost, invalid_index, image);
  }

  // ---- geometry of places ----------------------------------------------------------------------
  WorldPoint<d> world_of(const Place<d>& p) const {
    switch (p.kind) {
      case PlaceKind::vertex: return s1->vertex(p.index);
      case PlaceKind::edge:
        if constexpr (d == 2) {
          const auto ev = s1->edge_vertices(p.index);
          return (1.0 - p.t()) * s1->vertex(ev[0]) + p.t() * s1->vertex(ev[1]);
        }
        break;
      case PlaceKind::element: return s1->world_position(p.index, p.local());
    }
    return WorldPoint<d>::Zero();
  }

  static bool same_place(const Place<d>& a, const Place<d>& b) {
    return a.kind == b.kind && a.index == b.index && a.coords == b.coords;
  }

  /// S1 elements containing a place, in increasing order, as a view into the surface's
  /// adjacency (no allocation: every piece of every inserted edge asks it twice).
  class ElementsOf {
   public:
    ElementsOf(const Surface<d>& s1, const Place<d>& p) {
      switch (p.kind) {
        case PlaceKind::vertex: {
          const auto star = s1.vertex_elements(p.index);
          elements_ = star.data();
          size_ = star.size();
          break;
        }
        case PlaceKind::edge:
          if constexpr (d == 2) {
            const auto incidences = s1.edge_elements(p.index);
            incidences_ = incidences.data();
            size_ = incidences.size();
          }
          break;
        case PlaceKind::element:
          single_ = p.index;
          elements_ = &single_;
          size_ = 1;
          break;
      }
    }
    std::size_t size() const { return size_; }
    Index operator[](std::size_t i) const { return incidences_ ? incidences_[i].element : elements_[i]; }

   private:
    const Index* elements_ = nullptr;
    const EdgeIncidence* incidences_ = nullptr;
    std::size_t size_ = 0;
    Index single_ = invalid_index;
  };

  /// Where the straight segment between two places lies: along an S1 edge, or in one element.
  Segment locate_segment(Index a, Index b, Index target_edge) const {
    const Place<d>& pa = nodes[a].place;
    const Place<d>& pb = nodes[b].place;
    if constexpr (d == 2) {
      // along an S1 edge?
      auto edge_through = [&](const Place<d>& p, const Place<d>& q) -> Index {
        if (p.kind == PlaceKind::edge && q.kind == PlaceKind::edge)
          return p.index == q.index ? p.index : invalid_index;
        if (p.kind == PlaceKind::vertex && q.kind == PlaceKind::vertex) return s1->find_edge(p.index, q.index);
        if (p.kind == PlaceKind::vertex && q.kind == PlaceKind::edge) {
          const auto ev = s1->edge_vertices(q.index);
          return (ev[0] == p.index || ev[1] == p.index) ? q.index : invalid_index;
        }
        return invalid_index;
      };
      Index along = edge_through(pa, pb);
      if (along == invalid_index) along = edge_through(pb, pa);
      if (along != invalid_index) return {a, b, target_edge, true, along};
    }
    // the elements both places lie in (both lists sorted): the first two found
    const ElementsOf ea(*s1, pa), eb(*s1, pb);
    std::array<Index, 2> common{};
    int found = 0;
    for (std::size_t i = 0, j = 0; i < ea.size() && j < eb.size() && found < 2;) {
      if (ea[i] < eb[j]) {
        ++i;
      } else if (eb[j] < ea[i]) {
        ++j;
      } else {
        common[found++] = ea[i];
        ++i;
        ++j;
      }
    }
    if (found == 0)
      throw BuilderError(fmt::format(
          "the preimage of S2 {} {} jumps between points that share no S1 element "
          "(missing or misordered crossings?)",
          d == 2 ? "edge" : "segment", target_edge));
    if (found > 1)
      throw BuilderError(fmt::format(
          "the preimage of S2 {} {} has a piece whose S1 element is ambiguous (elements {} and {})",
          d == 2 ? "edge" : "segment", target_edge, common[0], common[1]));
    return {a, b, target_edge, false, common[0]};
  }

  // ---- edge entry -----------------------------------------------------------------------------
  struct CrossingPlace {
    Place<d> place;
    double target_parameter;
  };

  /// Inserts the preimage of S2 edge `target_edge` = (u, v), or a piece of it: the chain starts
  /// at the preimage of u (from_u) or at the first crossing, and ends at the preimage of v (to_v)
  /// or at the last crossing.
  // Buffers of insert_edge_preimage, reused from edge to edge: insertion is sequential, and
  // millions of S2 edges would otherwise cost a handful of allocations each.
  std::vector<CrossingPlace> places_scratch, cs_scratch;
  std::vector<double> arc_scratch;
  std::vector<WorldPoint<d>> points_scratch;
  std::vector<Index> chain_scratch;

  void insert_edge_preimage(Index target_edge, Index u, Index v, const std::vector<CrossingPlace>& crossings,
                            bool from_u = true, bool to_v = true) {
    const char* noun = d == 2 ? "edge" : "segment";
    const bool piece = !from_u || !to_v;
    if (edge_inserted[target_edge] == edge_outside_domain)
      throw BuilderError(fmt::format("S2 {} {} was declared outside the domain", noun, target_edge));
    if (edge_inserted[target_edge] == edge_complete || (edge_inserted[target_edge] && !piece))
      throw BuilderError(fmt::format("the preimage of S2 {} {} was already inserted", noun, target_edge));
    const Index a = from_u ? preimage_of_target_vertex[u] : invalid_index;
    const Index b = to_v ? preimage_of_target_vertex[v] : invalid_index;
    if ((from_u && a == invalid_index) || (to_v && b == invalid_index))
      throw BuilderError(fmt::format("cannot insert S2 {} {}: S2 vertex {} has no preimage yet", noun,
                                     target_edge, from_u && a == invalid_index ? u : v));
    // Drop repeated consecutive places (a crossing through a vertex given as two edge ends).
    auto& cs = cs_scratch;
    cs.clear();
    for (const auto& c : crossings) {
      if (!cs.empty() && same_place(cs.back().place, c.place)) continue;
      cs.push_back(c);
    }
    if (static_cast<int>(cs.size()) + from_u + to_v < 2)
      throw BuilderError(fmt::format("a piece of the preimage of S2 {} {} needs two distinct points",
                                     noun, target_edge));
    // Arc-length image parameters for crossings of complete edges that have none given.
    auto& arc = arc_scratch;
    arc.assign(cs.size() + 2, 0.0);
    if (!piece) {
      auto& pts = points_scratch;
      pts.clear();
      pts.push_back(world_of(nodes[a].place));
      for (const auto& c : cs) pts.push_back(world_of(c.place));
      pts.push_back(world_of(nodes[b].place));
      for (std::size_t i = 1; i < pts.size(); ++i) arc[i] = arc[i - 1] + (pts[i] - pts[i - 1]).norm();
      if (!cs.empty() && !(arc.back() > 0.0))
        throw BuilderError(fmt::format("the preimage of S2 {} {} has zero length", noun, target_edge));
    }

    auto& chain = chain_scratch;
    chain.clear();
    if (from_u) chain.push_back(a);
    for (std::size_t i = 0; i < cs.size(); ++i) {
      double tau = cs[i].target_parameter;
      if (std::isnan(tau)) {
        if (piece)
          throw BuilderError(fmt::format(
              "crossing {} of a piece of S2 {} {} needs its image parameter", i, noun, target_edge));
        tau = arc[i + 1] / arc.back();
      }
      if (!(tau > 0.0 && tau < 1.0))
        throw BuilderError(fmt::format(
            "crossing {} of S2 {} {}: image parameter {} is not strictly between its end vertices", i,
            noun, target_edge, tau));
      const Place<d>& p = cs[i].place;
      Index node;
      if (p.kind == PlaceKind::vertex) {
        node = node_at_domain_vertex[p.index];
        if (node == invalid_index) {
          node = new_node(p, BuilderNodeKind::ghost, invalid_index, edge_support(target_edge, tau));
        } else if (nodes[node].kind != BuilderNodeKind::ghost) {
          throw BuilderError(fmt::format(
              "the preimage of S2 {} {} passes through S1 vertex {}, which is the preimage of S2 "
              "vertex {}",
              noun, target_edge, p.index, nodes[node].target));
        }
      } else {
        node = new_node(p, BuilderNodeKind::intersection, target_edge, edge_support(target_edge, tau));
      }
      chain.push_back(node);
    }
    if (to_v) chain.push_back(b);
    for (std::size_t i = 0; i + 1 < chain.size(); ++i)
      segments.push_back(locate_segment(chain[i], chain[i + 1], target_edge));
    edge_inserted[target_edge] = piece ? edge_partial : edge_complete;
  }
};

// ==== public interface ============================================================================

template <int d>
  requires SurfaceDimension<d>
MapBuilder<d>::MapBuilder(std::shared_ptr<const Surface<d>> domain,
                          std::shared_ptr<const Surface<d>> target, BuilderOptions options)
    : impl_(std::make_unique<Impl>(std::move(domain), std::move(target), options)) {}

template <int d>
  requires SurfaceDimension<d>
MapBuilder<d>::~MapBuilder() = default;
template <int d>
  requires SurfaceDimension<d>
MapBuilder<d>::MapBuilder(MapBuilder&&) noexcept = default;
template <int d>
  requires SurfaceDimension<d>
MapBuilder<d>& MapBuilder<d>::operator=(MapBuilder&&) noexcept = default;

template <int d>
  requires SurfaceDimension<d>
const Surface<d>& MapBuilder<d>::domain() const {
  return *impl_->s1;
}
template <int d>
  requires SurfaceDimension<d>
const Surface<d>& MapBuilder<d>::target() const {
  return *impl_->s2;
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_vertex_preimage(Index target_vertex,
                                                                    const SurfacePoint<d>& at) {
  return impl_->add_vertex_preimage(target_vertex, impl_->place_of(at, "vertex preimage"));
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_vertex_preimage_at_vertex(Index target_vertex,
                                                                              Index domain_vertex) {
  impl_->check_s1_vertex_with_elements(domain_vertex);
  Place<d> p;
  p.kind = PlaceKind::vertex;
  p.index = domain_vertex;
  return impl_->add_vertex_preimage(target_vertex, p);
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_vertex_preimage_on_edge(Index target_vertex,
                                                                            Index domain_edge, double t)
  requires(d == 2)
{
  // Clang 14 compiles members whose constraints fail when `template class MapBuilder<1>;`
  // instantiates the class (fixed in clang 15); the `if constexpr` keeps such bodies
  // compiling there (scripts/fuzz builds with Debian's clang). Same below.
  if constexpr (d == 2) {
    if (domain_edge < 0 || domain_edge >= impl_->s1->edge_count())
      throw BuilderError(fmt::format("S1 edge {} does not exist", domain_edge));
    if (!(t >= -impl_->tol() && t <= 1.0 + impl_->tol()))
      throw BuilderError(fmt::format("parameter {} on S1 edge {} is outside [0, 1]", t, domain_edge));
    Place<d> p;
    const auto ev = impl_->s1->edge_vertices(domain_edge);
    if (const EdgeSnap snap = snap_edge_parameter(t, impl_->tol()); snap != EdgeSnap::inside) {
      p.kind = PlaceKind::vertex;
      p.index = ev[snap == EdgeSnap::first_vertex ? 0 : 1];
    } else {
      p.kind = PlaceKind::edge;
      p.index = domain_edge;
      p.coords(0) = t;
    }
    return impl_->add_vertex_preimage(target_vertex, p);
  }
  __builtin_unreachable();  // d == 1 never calls it (the constraint)
}

template <int d>
  requires SurfaceDimension<d>
typename MapBuilder<d>::NodeHandle MapBuilder<d>::add_ghost_node(Index domain_vertex,
                                                               const SurfacePoint<d>& image) {
  return impl_->add_ghost_node(domain_vertex, impl_->support_of(image, "ghost node image"));
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge(Index target_edge)
  requires(d == 2)
{
  if constexpr (d == 2) {
    add_edge(target_edge, std::span<const EdgeCrossing>{});
  }
}

namespace {

/// The crossings as places on S1, written into the builder's reused buffer.
template <int d, class Impl>
const std::vector<typename Impl::CrossingPlace>& crossing_places(Impl& im, Index target_edge,
                                                                 std::span<const EdgeCrossing> crossings) {
  auto& places = im.places_scratch;
  places.clear();
  for (std::size_t i = 0; i < crossings.size(); ++i) {
    const auto& c = crossings[i];
    if (c.domain_edge < 0 || c.domain_edge >= im.s1->edge_count())
      throw BuilderError(fmt::format("crossing {} of S2 edge {}: S1 edge {} does not exist", i,
                                     target_edge, c.domain_edge));
    if (!(c.domain_parameter >= -im.tol() && c.domain_parameter <= 1.0 + im.tol()))
      throw BuilderError(fmt::format("crossing {} of S2 edge {}: parameter {} is outside [0, 1]", i,
                                     target_edge, c.domain_parameter));
    Place<d> p;
    const auto ev = im.s1->edge_vertices(c.domain_edge);
    if (const EdgeSnap snap = snap_edge_parameter(c.domain_parameter, im.tol()); snap != EdgeSnap::inside) {
      p.kind = PlaceKind::vertex;
      p.index = ev[snap == EdgeSnap::first_vertex ? 0 : 1];
    } else {
      p.kind = PlaceKind::edge;
      p.index = c.domain_edge;
      p.coords(0) = c.domain_parameter;
    }
    places.push_back({p, c.target_parameter});
  }
  return places;
}

template <int d, class Impl>
const std::vector<typename Impl::CrossingPlace>& crossing_places(Impl& im,
                                                                 std::span<const VertexCrossing> crossings) {
  auto& places = im.places_scratch;
  places.clear();
  for (const auto& c : crossings) {
    im.check_s1_vertex(c.domain_vertex);
    Place<d> p;
    p.kind = PlaceKind::vertex;
    p.index = c.domain_vertex;
    places.push_back({p, c.target_parameter});
  }
  return places;
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge(Index target_edge, std::span<const EdgeCrossing> crossings)
  requires(d == 2)
{
  if constexpr (d == 2) {
    add_edge_piece(target_edge, crossings, PieceStart::first_vertex, PieceEnd::second_vertex);
  }
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge_piece(Index target_edge, std::span<const EdgeCrossing> crossings, PieceStart start,
                                   PieceEnd end)
  requires(d == 2)
{
  if constexpr (d == 2) {
    auto& im = *impl_;
    im.check_s2_edge(target_edge);
    const auto ev = im.s2->edge_vertices(target_edge);
    im.insert_edge_preimage(target_edge, ev[0], ev[1], crossing_places<d>(im, target_edge, crossings),
                            start == PieceStart::first_vertex, end == PieceEnd::second_vertex);
  }
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge(Index target_element, std::span<const VertexCrossing> crossings)
  requires(d == 1)
{
  if constexpr (d == 1) {
    add_edge_piece(target_element, crossings, PieceStart::first_vertex, PieceEnd::second_vertex);
  }
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge_piece(Index target_element, std::span<const VertexCrossing> crossings,
                                   PieceStart start, PieceEnd end)
  requires(d == 1)
{
  if constexpr (d == 1) {
    auto& im = *impl_;
    im.check_s2_element(target_element);
    const auto& c = im.s2->element(target_element);
    im.insert_edge_preimage(target_element, c[0], c[1], crossing_places<d>(im, crossings),
                            start == PieceStart::first_vertex, end == PieceEnd::second_vertex);
  }
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_target_element(Index target_element) {
  impl_->check_s2_element(target_element);
  if constexpr (d == 2) {
    for (int k = 0; k < 3; ++k) {
      const Index e = impl_->s2->element_edge(target_element, k);
      if (!impl_->edge_inserted[e]) add_edge(e);
    }
  } else {
    if (!impl_->edge_inserted[target_element]) add_edge(target_element);
  }
}

template <int d>
  requires SurfaceDimension<d>
std::optional<typename MapBuilder<d>::NodeHandle> MapBuilder<d>::vertex_preimage(Index target_vertex) const {
  impl_->check_s2_vertex(target_vertex);
  const Index n = impl_->preimage_of_target_vertex[target_vertex];
  if (n == invalid_index) return std::nullopt;
  return n;
}

template <int d>
  requires SurfaceDimension<d>
bool MapBuilder<d>::has_edge(Index target_edge) const {
  if (target_edge < 0 || target_edge >= static_cast<Index>(impl_->edge_inserted.size()))
    throw BuilderError(fmt::format("S2 edge {} does not exist", target_edge));
  const char state = impl_->edge_inserted[target_edge];
  return state == Impl::edge_complete || state == Impl::edge_partial;
}

template <int d>
  requires SurfaceDimension<d>
void MapBuilder<d>::add_edge_outside_domain(Index target_edge) {
  if (target_edge < 0 || target_edge >= static_cast<Index>(impl_->edge_inserted.size()))
    throw BuilderError(fmt::format("S2 edge {} does not exist", target_edge));
  if (impl_->edge_inserted[target_edge] == Impl::edge_complete ||
      impl_->edge_inserted[target_edge] == Impl::edge_partial)
    throw BuilderError(fmt::format("S2 edge {} has a preimage; it cannot lie outside the domain", target_edge));
  impl_->edge_inserted[target_edge] = Impl::edge_outside_domain;
}

// ==== finalize ====================================================================================

namespace {

template <int d>
bool support_in_element(const Surface<d>& s2, const Support<d>& s, Index t) {
  for (int i = 0; i < s.count; ++i)
    if (s2.local_corner(t, s.vertex[i]) < 0) return false;
  return true;
}

[[noreturn, gnu::cold]] void throw_not_in_element(Index t, Index vertex) {
  throw BuilderError(fmt::format("internal: an image is re-expressed on S2 element {}, which does not "
                                 "contain its S2 vertex {}",
                                 t, vertex));
}

/// Local coordinates of a support on an S2 element that contains it (exact transfer): the
/// weights of the element's corners 1 .. d, copied. Called for every node and region corner.
template <int d>
LocalPoint<d> support_local(const Surface<d>& s2, const Support<d>& s, Index t) {
  const auto& corners = s2.element(t);
  LocalPoint<d> y = LocalPoint<d>::Zero();
  for (int i = 0; i < s.count; ++i) {
    const Index v = s.vertex[i];
    if (v == corners[0]) continue;
    int k = 1;
    while (k <= d && corners[k] != v) ++k;
    if (k > d) throw_not_in_element(t, v);
    y(k - 1) = s.weight[i];
  }
  return y;
}

/// Joins the parts assembled per block of elements (each numbered from 0) into one map: arrays
/// are concatenated and node, region and entry indices shifted by the sizes of the parts before.
/// One array at a time, with the parts' copies of it released as soon as it is joined: the
/// parts and the map are then never held whole at once (with two blocks the peak of the 200k
/// plane pair was the map twice over).
template <class RunBlocks>
void concatenate_parts(std::vector<MapData<2>>& parts, Index elements, MapData<2>& m,
                       RunBlocks&& run_blocks) {
  const std::size_t np = parts.size();
  if (np == 1) {  // one block: already numbered globally, and no second copy of the map
    if (parts[0].start_region.size() != static_cast<std::size_t>(elements))
      throw BuilderError("internal: the assembled block does not cover every element");
    const int orientation = m.orientation;
    m = std::move(parts[0]);
    m.orientation = orientation;
    return;
  }
  // offsets[k]: where part k starts in the joined arrays, by what the arrays count
  using Offsets = std::vector<std::size_t>;
  Offsets node0(np + 1, 0), region0(np + 1, 0), entry0(np + 1, 0), edge0(np + 1, 0), element0(np + 1, 0);
  for (std::size_t k = 0; k < np; ++k) {
    node0[k + 1] = node0[k] + parts[k].node_type.size();
    region0[k + 1] = region0[k] + parts[k].region_target.size();
    entry0[k + 1] = entry0[k] + parts[k].neighbor.size();
    edge0[k + 1] = edge0[k] + parts[k].edge_node.size();
    element0[k + 1] = element0[k] + parts[k].start_region.size();
  }
  if (element0[np] != static_cast<std::size_t>(elements))
    throw BuilderError("internal: the assembled blocks do not cover every element");
  Offsets edge_begin0(np + 1, 0);  // edge_node_begin has three entries per element
  for (std::size_t k = 0; k <= np; ++k) edge_begin0[k] = 3 * element0[k];

  // Joins array `field` of the parts at `at` (each part's values passed through shift(k, value)),
  // then releases the parts' copies.
  auto join = [&](auto field, const Offsets& at, auto shift) {
    auto& out = m.*field;
    out.resize(at[np]);
    run_blocks([&](unsigned k) {
      auto& in = parts[k].*field;
      for (std::size_t i = 0; i < in.size(); ++i) out[at[k] + i] = shift(k, in[i]);
      std::remove_reference_t<decltype(in)>().swap(in);
    });
  };
  // The same for a CSR begin array: a leading 0, then each part's ends shifted by the values of
  // the parts before.
  auto join_begins = [&](std::vector<Index> MapData<2>::*field, const Offsets& at, const Offsets& values) {
    auto& out = m.*field;
    out.assign(at[np] + 1, 0);
    run_blocks([&](unsigned k) {
      auto& in = parts[k].*field;
      for (std::size_t i = 0; i + 1 < in.size(); ++i)
        out[at[k] + i + 1] = in[i + 1] + static_cast<Index>(values[k]);
      std::vector<Index>().swap(in);
    });
  };
  const auto same = [](unsigned, const auto& value) { return value; };
  const auto node_index = [&](unsigned k, Index n) { return n + static_cast<Index>(node0[k]); };
  const auto region_index = [&](unsigned k, Index r) {
    return r == invalid_index ? invalid_index : r + static_cast<Index>(region0[k]);
  };
  join(&MapData<2>::node_position, node0, same);
  join(&MapData<2>::node_type, node0, same);
  join(&MapData<2>::node_location, node0, same);
  join(&MapData<2>::node_image, node0, same);
  join(&MapData<2>::node_target, node0, same);
  join_begins(&MapData<2>::neighbor_begin, node0, entry0);
  join(&MapData<2>::neighbor, entry0, node_index);
  join(&MapData<2>::neighbor_edge_kind, entry0, same);
  join_begins(&MapData<2>::edge_node_begin, edge_begin0, edge0);
  join(&MapData<2>::edge_node, edge0, node_index);
  join(&MapData<2>::region_corners, region0, [&](unsigned k, std::array<Index, 3> c) {
    for (Index& n : c) n = node_index(k, n);
    return c;
  });
  join(&MapData<2>::region_neighbors, region0, [&](unsigned k, std::array<Index, 3> c) {
    for (Index& r : c) r = region_index(k, r);
    return c;
  });
  join(&MapData<2>::region_target, region0, same);
  join(&MapData<2>::region_map, region0, same);
  join_begins(&MapData<2>::node_begin, element0, node0);
  join_begins(&MapData<2>::region_begin, element0, region0);
  join(&MapData<2>::start_region, element0, region_index);
}

/// Sizes the per-node arrays of a map (or of a part of one) for `nodes` nodes.
template <int d>
void size_node_arrays(MapData<d>& m, std::size_t nodes) {
  m.node_position.resize(nodes);
  m.node_type.resize(nodes);
  m.node_location.resize(nodes);
  m.node_image.resize(nodes);
  m.node_target.resize(nodes);
  m.neighbor_begin.resize(nodes + 1);
}

/// Gives back the slack of arrays that were reserved by an upper bound, so the map holds about
/// what it needs; slack under 1/16 of an array is kept, as copying the array to save it would
/// cost more time (and first-touched memory) than the slack is worth.
template <int d>
void shrink_to_fit(MapData<d>& m) {
  auto shrink = [](auto&... v) {
    ((v.capacity() - v.size() > v.size() / 16 ? v.shrink_to_fit() : void()), ...);
  };
  shrink(m.node_begin, m.node_position, m.node_type, m.node_location, m.node_image, m.node_target,
         m.neighbor_begin, m.neighbor, m.neighbor_edge_kind, m.edge_node_begin, m.edge_node,
         m.region_begin, m.region_corners, m.region_neighbors, m.region_target, m.region_map,
         m.start_region);
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
PlMap<d> MapBuilder<d>::finalize(FinalizeReport* report) && {
  auto impl = std::move(impl_);
  auto& im = *impl;
  const Surface<d>& s1 = *im.s1;
  const Surface<d>& s2 = *im.s2;
  const Index n1 = s1.element_count();

  // Bucket nodes and segments by where they live. S2 edges dropped because their preimages
  // conflict with others (BuilderOptions::drop_conflicting_edges) leave out their segments and
  // the intersection nodes they created.
  std::vector<char> dropped(im.edge_inserted.size(), 0);
  Buckets interior_nodes, edge_nodes, element_segments, edge_segments;
  auto bucket = [&] {
    const Index n1e = d == 2 ? s1.edge_count() : 0;
    const Index nn = static_cast<Index>(im.nodes.size()), ns = static_cast<Index>(im.segments.size());
    auto live = [&](Index n) {
      const auto& node = im.nodes[n];
      return !(d == 2 && node.kind == BuilderNodeKind::intersection && dropped[node.target]);
    };
    interior_nodes.build(n1, nn, [&](Index n) {
      return live(n) && im.nodes[n].place.kind == PlaceKind::element ? im.nodes[n].place.index : -1;
    });
    edge_nodes.build(n1e, nn, [&](Index n) {
      return live(n) && im.nodes[n].place.kind == PlaceKind::edge ? im.nodes[n].place.index : -1;
    });
    for (Index e = 0; e < n1e; ++e) {
      const auto list = edge_nodes.group(e);
      std::sort(list.begin(), list.end(),
                [&](Index a, Index b) { return im.nodes[a].place.t() < im.nodes[b].place.t(); });
      for (std::size_t i = 1; i < list.size(); ++i)
        if (im.nodes[list[i]].place.t() == im.nodes[list[i - 1]].place.t())
          throw BuilderError(fmt::format("two nodes at the same point of S1 edge {}",
                                         im.nodes[list[i]].place.index));
    }
    edge_segments.build(n1e, ns, [&](Index s) {
      const auto& seg = im.segments[s];
      return !dropped[seg.target_edge] && seg.along_edge ? seg.where : -1;
    });
    element_segments.build(n1, ns, [&](Index s) {
      const auto& seg = im.segments[s];
      return !dropped[seg.target_edge] && !seg.along_edge ? seg.where : -1;
    });
  };
  bucket();
  if (report) *report = FinalizeReport{};

  MapData<d> m;
  m.node_begin.assign(n1 + 1, 0);
  m.region_begin.assign(n1 + 1, 0);
  m.start_region.assign(n1, invalid_index);
  m.neighbor_begin.push_back(0);

  if constexpr (d == 1) {
    // ---- polylines: nodes sorted along each segment; regions between nodes joined by an edge --
    struct Slot {
      Index node;
      double s;
    };
    int votes = 0;
    struct PendingRegion {
      Index a, b, target;
      int sign;  // orientation of the image: +1 if it runs along the S2 segment, -1 against, 0 degenerate
    };
    // Per element, its slots and pending regions, flat (element t owns [begin[t], begin[t + 1])).
    std::vector<PendingRegion> all_regions;
    std::vector<Slot> all_slots;
    std::vector<std::size_t> regions_begin(static_cast<std::size_t>(n1) + 1, 0), slots_begin(static_cast<std::size_t>(n1) + 1, 0);
    std::vector<std::pair<Index, int>> slot_index;
    // A segment's preimage that passes over another node (a fold of the projection) is an error,
    // or, with drop_conflicting_edges, that S2 segment is left out and the elements redone.
    for (int round = 0;; ++round) {
      std::vector<std::pair<Index, Index>> conflicts;  // (S2 segment, S1 element)
      votes = 0;
      all_regions.clear();
      all_slots.clear();
      for (Index t = 0; t < n1; ++t) {
        // the element's slots go straight to the end of all_slots
        const std::size_t first_slot = all_slots.size();
        const auto& c = s1.element(t);
        if (Index n = im.node_at_domain_vertex[c[0]]; n != invalid_index) all_slots.push_back({n, 0.0});
        for (Index n : interior_nodes[t]) all_slots.push_back({n, im.nodes[n].place.coords(0)});
        if (Index n = im.node_at_domain_vertex[c[1]]; n != invalid_index) all_slots.push_back({n, 1.0});
        const std::span<Slot> slots(all_slots.data() + first_slot, all_slots.size() - first_slot);
        sort_small(slots, [](const Slot& x, const Slot& y) { return x.s < y.s; });
        for (std::size_t i = 1; i < slots.size(); ++i)
          if (slots[i].s == slots[i - 1].s)
            throw BuilderError(fmt::format("two nodes at the same point of S1 element {}", t));
        // Few nodes per segment, except in stress tests: searched in place, or by binary search
        // in a sorted table when there are many.
        const bool many = slots.size() > 16;
        if (many) {
          slot_index.resize(slots.size());
          for (std::size_t i = 0; i < slots.size(); ++i) slot_index[i] = {slots[i].node, static_cast<int>(i)};
          std::sort(slot_index.begin(), slot_index.end());
        }
        auto slot_of = [&](Index node) {
          if (!many) {
            for (std::size_t i = 0; i < slots.size(); ++i)
              if (slots[i].node == node) return static_cast<int>(i);
            return -1;
          }
          const auto it = std::lower_bound(slot_index.begin(), slot_index.end(), std::make_pair(node, -1));
          return it != slot_index.end() && it->first == node ? it->second : -1;
        };
        for (Index sidx : element_segments[t]) {
          const auto& seg = im.segments[sidx];
          int i = slot_of(seg.a), j = slot_of(seg.b);
          if (i > j) std::swap(i, j);
          // both ends must map into the S2 segment, and no other node may lie between them
          const bool images_on_segment =
              i >= 0 && support_in_element<1>(s2, im.nodes[slots[i].node].image, seg.target_edge) &&
              support_in_element<1>(s2, im.nodes[slots[j].node].image, seg.target_edge);
          if (i < 0 || j != i + 1 || !images_on_segment) {
            if (im.options.drop_conflicting_edges && i >= 0 && round < 16) {
              conflicts.emplace_back(seg.target_edge, t);
              continue;
            }
            throw BuilderError(fmt::format(
                "the preimage of S2 segment {} passes over another node on S1 element {}, or joins "
                "nodes whose images are not on that segment",
                seg.target_edge, t));
          }
          const auto& na = im.nodes[slots[i].node].image;
          const auto& nb = im.nodes[slots[j].node].image;
          const double ya = support_local<1>(s2, na, seg.target_edge)(0);
          const double yb = support_local<1>(s2, nb, seg.target_edge)(0);
          const int sign = (yb > ya) - (yb < ya);
          votes += yb > ya ? 1 : -1;
          all_regions.push_back({i, j, seg.target_edge, sign});
        }
        regions_begin[t + 1] = all_regions.size();
        slots_begin[t + 1] = all_slots.size();
      }
      if (conflicts.empty()) break;
      for (const auto& [e, t] : conflicts) {
        if (dropped[e]) continue;
        dropped[e] = 1;
        im.edge_inserted[e] = 0;
        if (report) {
          report->dropped_edges.push_back(e);
          report->dropped_edge_element.push_back(t);
        }
      }
      bucket();
    }
    m.orientation = im.options.orientation != 0 ? im.options.orientation : (votes >= 0 ? 1 : -1);
    // From here on only the slots, the pending regions and the nodes are read. The segments and
    // the buckets go before the map's arrays are sized, which is where finalize's memory peaks
    // (1M circles: 510 -> 449 MiB above the inputs).
    std::vector<Segment>().swap(im.segments);
    for (Buckets* b : {&interior_nodes, &edge_nodes, &element_segments, &edge_segments}) b->release();
    std::vector<std::pair<Index, int>>().swap(slot_index);
    // Sizes are known now (nodes; regions and neighbour entries once the orientation has
    // filtered the regions): the arrays are sized once and written in place.
    std::size_t kept = 0;
    for (const auto& r : all_regions) kept += r.sign == m.orientation ? 1 : 0;
    const std::size_t node_count = all_slots.size();
    size_node_arrays(m, node_count);
    m.neighbor.resize(2 * kept);
    m.neighbor_edge_kind.resize(2 * kept);
    m.region_corners.resize(kept);
    m.region_neighbors.resize(kept);
    m.region_target.resize(kept);
    m.region_map.resize(kept);
    std::size_t entry = 0, region = 0;
    for (Index t = 0; t < n1; ++t) {
      const std::span<const Slot> sl(all_slots.data() + slots_begin[t], all_slots.data() + slots_begin[t + 1]);
      std::span<PendingRegion> regs(all_regions.data() + regions_begin[t], all_regions.data() + regions_begin[t + 1]);
      // As for triangle surfaces, only pieces mapped with the map's orientation are regions: a
      // piece against it (or onto a single point) is where the projection folds.
      const auto kept_end = std::remove_if(regs.begin(), regs.end(), [&](const PendingRegion& r) { return r.sign != m.orientation; });
      if (report) report->reversed_faces += static_cast<Index>(regs.end() - kept_end);
      regs = regs.first(static_cast<std::size_t>(kept_end - regs.begin()));
      sort_small(regs, [](const auto& x, const auto& y) { return x.a < y.a; });
      const auto base = static_cast<Index>(slots_begin[t]);
      // Every region joins consecutive slots (b = a + 1), so sorted by a they are sorted by b:
      // one cursor finds the region ending at a slot, one the region starting there.
      std::size_t ending = 0, starting = 0;
      for (std::size_t i = 0; i < sl.size(); ++i) {
        const auto& bn = im.nodes[sl[i].node];
        const std::size_t n = slots_begin[t] + i;
        m.node_position[n](0) = sl[i].s;
        const bool at_corner = bn.place.kind == PlaceKind::vertex;
        m.node_type[n] = bn.kind == BuilderNodeKind::ghost ? NodeType::ghost
                         : at_corner                       ? NodeType::corner
                                                           : NodeType::interior;
        m.node_location[n] = at_corner ? static_cast<std::int8_t>(sl[i].s == 0.0 ? 0 : 1) : std::int8_t{-1};
        m.node_image[n] = {bn.image.element, support_local<1>(s2, bn.image, bn.image.element)};
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
      m.node_begin[t + 1] = static_cast<Index>(slots_begin[t + 1]);
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
        to[0] = support_local<1>(s2, im.nodes[sl[r.a].node].image, r.target);
        to[1] = support_local<1>(s2, im.nodes[sl[r.b].node].image, r.target);
        m.region_map[region] = affine_through<1>(from, to);
        if (m.start_region[t] == invalid_index || (sl[r.a].s <= 0.5 && sl[r.b].s >= 0.5))
          m.start_region[t] = r_id;
      }
      m.region_begin[t + 1] = static_cast<Index>(region);
    }
    m.neighbor.resize(entry);  // a slot between two regions was counted by both
    m.neighbor_edge_kind.resize(entry);
  } else {
    // ---- triangle surfaces: a constrained triangulation per S1 element ------------------------
    const std::array<LocalPoint<2>, 3> ref = {reference_corner<2>(0), reference_corner<2>(1),
                                              reference_corner<2>(2)};
    // Local position of a point at parameter s along local edge k (from corner k). Points must lie
    // exactly on their edge line, or exact predicates would see them a rounding step off it.
    // Edges 0 (y = 0) and 2 (x = 0) are exact anyway; on edge 1 (x + y = 1) the second
    // coordinate is 1 - first, which is exact when first >= 1/2.
    auto on_local_edge = [](int k, double s) -> LocalPoint<2> {
      if (k == 0) return LocalPoint<2>(s, 0.0);
      if (k == 2) return LocalPoint<2>(0.0, 1.0 - s);
      if (s >= 0.5) return LocalPoint<2>(1.0 - s, s);
      const double x = 1.0 - s;
      return LocalPoint<2>(x, 1.0 - x);
    };
    auto node_local = [&](Index node, Index t) -> LocalPoint<2> {
      const auto& p = im.nodes[node].place;
      if (p.kind == PlaceKind::vertex) return ref[s1.local_corner(t, p.index)];
      if (p.kind == PlaceKind::element) return p.local();
      for (int k = 0; k < 3; ++k)
        if (s1.element_edge(t, k) == p.index)
          return on_local_edge(k, s1.local_edge_is_forward(t, k) ? p.t() : 1.0 - p.t());
      return LocalPoint<2>::Zero();
    };

    // Per element: the plane graph (slots, then virtual corners for corners outside D; the
    // element boundary split at its nodes, and the graph edges), closed into triangles by the
    // face-based fast path or, where it declines, a constrained Delaunay triangulation.
    struct Workspace {
      ElementTriangulation et;  // the element being closed, assembled right after
      Cdt cdt;
      detail::ElementClosure closure;
      detail::ClosureScratch scratch;
      std::vector<detail::ClosureSegment> segments;
      // Constraints as (a, b, graph) packed into one integer each, a < b: sorting integers is
      // cheaper than comparing pairs, and the order is the order of (a, b).
      std::vector<std::uint64_t> segment_keys;
      std::vector<int> ring_start;  // per vertex, see detail::ring_starts
      // Slot of each builder node on the element being closed, -1 elsewhere: the graph edges
      // name builder nodes, and elements may carry thousands of them. Entries of the previous
      // element are reset when the next one starts (also after an exception).
      std::vector<int> slot_of_node;
      // per-element scratch, kept to avoid allocating for every element
      std::array<std::vector<int>, 3> edge_inner;
      std::vector<int> face_order, face_begin, comp_nodes, vertex_stamp;
      std::vector<LocalPoint<2>> on_candidate;  // per vertex: its image on a candidate S2 element
      long long votes = 0;
    };
    auto segment_key = [](int a, int b, bool graph) {
      return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 33) |
             (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::max(a, b))) << 1) |
             static_cast<std::uint64_t>(graph);
    };

    // The general path: a constrained Delaunay triangulation of the same graph. Also the place
    // where invalid input (crossing edges, a node on another edge) is diagnosed.
    auto close_by_cdt = [&](Index t, Workspace& w, int vertex_count) {
      const auto& points = w.et.positions;
      Cdt& cdt = w.cdt;
      cdt.clear();
      std::vector<Cdt::Vertex_handle> vh(vertex_count);
      for (int i = 0; i < vertex_count; ++i) {
        const auto before = cdt.number_of_vertices();
        vh[i] = cdt.insert(Kernel::Point_2(points[i](0), points[i](1)));
        if (cdt.number_of_vertices() == before)
          throw BuilderError(fmt::format("two nodes coincide on S1 element {} at local ({}, {})", t,
                                         points[i](0), points[i](1)));
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
    };

    auto close_element = [&](Index t, Workspace& w) {
      auto& et = w.et;
      if (w.slot_of_node.size() != im.nodes.size()) w.slot_of_node.assign(im.nodes.size(), -1);
      for (Index n : et.slots) w.slot_of_node[n] = -1;  // the previous element's
      et.clear();
      // slots: present corners, then edge nodes along edges 0, 1, 2, then interior nodes
      std::array<int, 3> corner_slot{-1, -1, -1};
      for (int k = 0; k < 3; ++k) {
        const Index n = im.node_at_domain_vertex[s1.element(t)[k]];
        if (n != invalid_index) {
          ++et.corner_count;
          corner_slot[k] = static_cast<int>(et.slots.size());
          et.slots.push_back(n);
          et.positions.push_back(ref[k]);
          et.location.push_back(static_cast<std::int8_t>(k));
        }
      }
      auto& edge_inner = w.edge_inner;
      for (int k = 0; k < 3; ++k) {
        edge_inner[k].clear();
        const auto& list = edge_nodes[s1.element_edge(t, k)];
        const bool fwd = s1.local_edge_is_forward(t, k);
        for (std::size_t i = 0; i < list.size(); ++i) {
          const Index n = fwd ? list[i] : list[list.size() - 1 - i];
          edge_inner[k].push_back(static_cast<int>(et.slots.size()));
          et.slots.push_back(n);
          const double edge_t = im.nodes[n].place.t();
          et.positions.push_back(on_local_edge(k, fwd ? edge_t : 1.0 - edge_t));
          et.location.push_back(static_cast<std::int8_t>(k));
        }
      }
      for (Index n : interior_nodes[t]) {
        et.slots.push_back(n);
        et.positions.push_back(im.nodes[n].place.local());
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
      if (ns == 0) {  // nothing of the map on this element
        w.closure.clear();
        return;
      }

      // Vertices: the slots, then one "virtual" vertex per missing corner; faces touching a
      // virtual vertex lie outside D.
      std::array<int, 3> corner_vertex{};
      for (int k = 0; k < 3; ++k) {
        if (corner_slot[k] >= 0) {
          corner_vertex[k] = corner_slot[k];
        } else {
          corner_vertex[k] = static_cast<int>(et.positions.size());
          et.positions.push_back(ref[k]);
        }
      }
      const int vertex_count = static_cast<int>(et.positions.size());

      // constraints: the element boundary between consecutive points, and the graph edges
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
        for (int i : edge_inner[k]) add_piece(i);
        add_piece(corner_vertex[(k + 1) % 3]);
      }
      auto add_graph = [&](Index sidx) {
        const auto& seg = im.segments[sidx];
        const int a = w.slot_of_node[seg.a], b = w.slot_of_node[seg.b];
        if (a < 0 || b < 0)
          throw BuilderError(fmt::format(
              "internal: a piece of the preimage of S2 edge {} lacks an endpoint on S1 element {}",
              seg.target_edge, t));
        if (a == b)
          throw BuilderError(fmt::format(
              "a graph edge on S1 element {} passes through another node (or its endpoints coincide)", t));
        keys.push_back(segment_key(a, b, true));
      };
      for (Index sidx : element_segments[t]) add_graph(sidx);
      for (int k = 0; k < 3; ++k)
        for (Index sidx : edge_segments[s1.element_edge(t, k)]) add_graph(sidx);
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

      if (!detail::close_by_faces(et.positions, w.segments, boundary_start, w.closure, w.scratch))
        close_by_cdt(t, w, vertex_count);
      const auto& closure = w.closure;
      const int nf = static_cast<int>(closure.triangles.size());
      const int ncomp = closure.face_count;

      // Classify the faces: touching a virtual corner → outside D; else the S2 element all its
      // nodes map into, and the sign of its image there.
      et.components.assign(ncomp, {});
      et.corner_images.resize(nf);
      et.corner_maps.resize(nf);
      auto& face_begin = w.face_begin;  // triangles grouped by face (counting sort)
      auto& face_order = w.face_order;
      face_begin.assign(ncomp + 1, 0);
      for (int f = 0; f < nf; ++f) {
        ++face_begin[closure.face[f] + 1];
        const auto& tr = closure.triangles[f];
        if (tr[0] >= ns || tr[1] >= ns || tr[2] >= ns) et.components[closure.face[f]].outside = true;
      }
      for (int c = 0; c < ncomp; ++c) face_begin[c + 1] += face_begin[c];
      face_order.resize(nf);
      {
        auto& cursor = w.comp_nodes;
        cursor.assign(face_begin.begin(), face_begin.end() - 1);
        for (int f = 0; f < nf; ++f) face_order[cursor[closure.face[f]]++] = f;
      }
      auto& comp_nodes = w.comp_nodes;
      auto& stamp = w.vertex_stamp;
      stamp.assign(vertex_count, -1);
      w.on_candidate.resize(vertex_count);
      auto& y = w.on_candidate;
      for (int c = 0; c < ncomp; ++c) {
        auto& comp = et.components[c];
        if (comp.outside) continue;
        // The face's nodes, and the S2 vertices carrying their images: an S2 element containing
        // every image has them all as corners.
        comp_nodes.clear();
        std::array<Index, 3> support_union{};
        int union_size = 0;
        for (int q = face_begin[c]; q < face_begin[c + 1]; ++q)
          for (int i = 0; i < 3; ++i) {
            const int v = closure.triangles[face_order[q]][i];
            if (stamp[v] == c) continue;
            stamp[v] = c;
            comp_nodes.push_back(v);
            const Support<2>& support = im.nodes[et.slots[v]].image;
            for (int j = 0; j < support.count; ++j) {
              const Index x = support.vertex[j];
              int u = 0;
              while (u < union_size && u < 3 && support_union[u] != x) ++u;
              if (u == union_size) {
                if (union_size < 3) support_union[u] = x;
                ++union_size;  // more than 3: no S2 element contains them all
              }
            }
          }
        // The candidates are the S2 elements containing all the images, tried in the order of the
        // star of one support vertex; of those with every edge inserted, the one where the face's
        // image has the largest area wins (ties: the first).
        auto try_candidate = [&](Index cand, double& best_area) {
          for (int k = 0; k < 3; ++k)
            if (!im.edge_inserted[s2.element_edge(cand, k)]) return;
          for (int i : comp_nodes) y[i] = support_local<2>(s2, im.nodes[et.slots[i]].image, cand);
          double area = 0.0;
          for (int q = face_begin[c]; q < face_begin[c + 1]; ++q) {
            const auto& tr = closure.triangles[face_order[q]];
            const LocalPoint<2> u = y[tr[1]] - y[tr[0]], v = y[tr[2]] - y[tr[0]];
            area += u(0) * v(1) - u(1) * v(0);
          }
          if (std::abs(area) > std::abs(best_area)) {
            best_area = area;
            comp.target = cand;
            for (int q = face_begin[c]; q < face_begin[c + 1]; ++q) {
              const auto& tr = closure.triangles[face_order[q]];
              et.corner_images[face_order[q]] = {y[tr[0]], y[tr[1]], y[tr[2]]};
            }
          }
        };
        double best_area = 0.0;
        if (union_size == 3) {
          // Three S2 vertices: only the S2 element with exactly these corners (elements are
          // distinct vertex sets) can contain every image.
          for (Index cand : s2.vertex_elements(support_union[0]))
            if (s2.local_corner(cand, support_union[1]) >= 0 && s2.local_corner(cand, support_union[2]) >= 0) {
              try_candidate(cand, best_area);
              break;
            }
        } else if (union_size < 3) {
          // All images on one S2 edge or vertex: every element around it contains them. The
          // search starts from a node with the most support vertices, the first such slot.
          int best = comp_nodes[0];
          for (int i : comp_nodes) {
            const int count = im.nodes[et.slots[i]].image.count, best_count = im.nodes[et.slots[best]].image.count;
            if (count > best_count || (count == best_count && i < best)) best = i;
          }
          const Support<2>& best_support = im.nodes[et.slots[best]].image;
          for (Index cand : s2.vertex_elements(best_support.vertex[0])) {
            bool all = true;
            for (int i : comp_nodes) all = all && support_in_element<2>(s2, im.nodes[et.slots[i]].image, cand);
            if (all) try_candidate(cand, best_area);
          }
        }
        if (comp.target != invalid_index) {
          comp.sign = best_area > 0 ? 1 : -1;
          // Every triangle of the face must map with the face's orientation. Where the images
          // do not follow one affine map (a discontinuous projection direction field), three
          // nodes of a face can map onto one S2 edge, or a triangle can fold back, although the
          // face as a whole keeps its orientation: such a face is left out of D like a reversed
          // one (FinalizeReport::reversed_faces), instead of giving a region that verify rejects.
          // The corners are judged both as given and as the region's affine map reproduces them
          // (what verify sees): a nearly flat image may become exactly flat through the map.
          for (int q = face_begin[c]; q < face_begin[c + 1] && comp.sign != 0; ++q) {
            const auto& tr = closure.triangles[face_order[q]];
            const auto& image = et.corner_images[face_order[q]];
            const std::array<LocalPoint<2>, 3> from{et.positions[tr[0]], et.positions[tr[1]], et.positions[tr[2]]};
            const AffineMap<2>& map = et.corner_maps[face_order[q]] = affine_through<2>(from, image);
            if (orient2d(image[0], image[1], image[2]) != comp.sign ||
                orient2d(apply<2>(map, from[0]), apply<2>(map, from[1]), apply<2>(map, from[2])) != comp.sign)
              comp.sign = 0;
          }
          w.votes += comp.sign * static_cast<long long>(face_begin[c + 1] - face_begin[c]);
        }
      }
      // the walk starts from the triangle at the element's centroid (the first inside D)
      const LocalPoint<2> centroid(1.0 / 3.0, 1.0 / 3.0);
      const auto& points = et.positions;
      for (int f = 0; f < nf && et.centroid_triangle < 0; ++f) {
        const auto& tr = closure.triangles[f];
        if (!et.components[closure.face[f]].outside && orient2d(points[tr[0]], points[tr[1]], centroid) >= 0 &&
            orient2d(points[tr[1]], points[tr[2]], centroid) >= 0 &&
            orient2d(points[tr[2]], points[tr[0]], centroid) >= 0)
          et.centroid_triangle = f;
      }
      // where each node's ring of neighbours starts (they are circulated at assembly)
      detail::ring_starts(closure, vertex_count, w.ring_start);
    };

    // Elements are independent: close them on all threads. Errors are reported for the
    // smallest element that has one, whatever the thread count.
    const unsigned threads = std::max(1u, std::min<unsigned>(im.options.threads == 0
                                                                 ? std::max(1u, std::thread::hardware_concurrency())
                                                                 : im.options.threads,
                                                             static_cast<unsigned>(std::max<Index>(1, n1 / 64))));
    // Runs f(k) for the blocks k = 0 .. threads - 1, on that many threads.
    auto run_blocks = [threads](auto&& f) {
      if (threads == 1) {
        f(0u);
        return;
      }
      std::vector<std::jthread> pool;
      for (unsigned k = 0; k < threads; ++k) pool.emplace_back([&f, k] { f(k); });
    };
    // The S2 edges whose pieces on element t cross another piece or pass through a node.
    auto conflicting_edges = [&](Index t) {
      std::vector<Index> pieces(element_segments[t].begin(), element_segments[t].end());
      for (int k = 0; k < 3; ++k) {
        const auto& along = edge_segments[s1.element_edge(t, k)];
        pieces.insert(pieces.end(), along.begin(), along.end());
      }
      std::vector<Index> nodes(interior_nodes[t].begin(), interior_nodes[t].end());
      for (int k = 0; k < 3; ++k) {
        const auto& on_edge = edge_nodes[s1.element_edge(t, k)];
        nodes.insert(nodes.end(), on_edge.begin(), on_edge.end());
        const Index corner = im.node_at_domain_vertex[s1.element(t)[k]];
        if (corner != invalid_index) nodes.push_back(corner);
      }
      std::vector<Index> edges;
      for (std::size_t i = 0; i < pieces.size(); ++i) {
        const auto& si = im.segments[pieces[i]];
        const LocalPoint<2> p = node_local(si.a, t), q = node_local(si.b, t);
        for (std::size_t j = i + 1; j < pieces.size(); ++j) {
          const auto& sj = im.segments[pieces[j]];
          if (segments_cross_properly(p, q, node_local(sj.a, t), node_local(sj.b, t))) {
            edges.push_back(si.target_edge);
            edges.push_back(sj.target_edge);
          }
        }
        for (Index n : nodes) {
          if (n == si.a || n == si.b) continue;
          const LocalPoint<2> x = node_local(n, t);
          if (orient2d(p, q, x) == 0 && x.x() >= std::min(p.x(), q.x()) && x.x() <= std::max(p.x(), q.x()) &&
              x.y() >= std::min(p.y(), q.y()) && x.y() <= std::max(p.y(), q.y()))
            edges.push_back(si.target_edge);
        }
      }
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      return edges;
    };

    // ---- assemble the flat arrays ----------------------------------------------------------------
    // Each element is assembled right after it is closed, into the part of its block of elements
    // (local numbering); the parts are concatenated with their offsets added at the end. Only
    // faces mapped with the map's orientation become regions, and that orientation is voted on
    // by all elements: the pass assembles with a guess (the vote of a sample of elements, or the
    // orientation given in the options) and runs again in the rare case the full vote differs.
    struct AssemblyScratch {
      std::vector<Index> triangle_region;
      Index reversed_faces = 0;  // faces with a target element but the other orientation
      // Where the next element's values go in the block's part, whose arrays are sized up front
      // (see size_part) and written in place.
      std::size_t elements = 0, nodes = 0, entries = 0, edge_nodes = 0, regions = 0;
    };
    auto assemble_element = [&](const Workspace& w, MapData<2>& part, int orientation, AssemblyScratch& sc) {
      const ElementTriangulation& et = w.et;
      const detail::ElementClosure& closure = w.closure;
      const auto base = static_cast<Index>(sc.nodes);
      const auto rbase = static_cast<Index>(sc.regions);
      const int ns = static_cast<int>(et.slots.size());
      const int nf = static_cast<int>(closure.triangles.size());
      // Neighbour entries and regions are written in place too, into arrays reserved by their
      // bounds but sized only a chunk ahead of what is written: sizing them to the bound would
      // first-touch the slack (66 MiB more peak on the L7 spheres), appending costs a push_back
      // per value. (A bound that is ever short grows the array instead.)
      auto room = [](auto& array, std::size_t needed) {
        if (array.size() < needed)
          array.resize(std::max(needed, std::min(array.capacity(), array.size() + std::size_t{4096})));
      };
      // the element's shares of the bounds size_part reserved: 2 entries per closure side, and
      // 3n - h - 3 sides for n vertices, h on the boundary (3 corners and the edge nodes)
      const std::size_t n = et.positions.size();
      const std::size_t h = 3 + et.edge_slots.size() - static_cast<std::size_t>(2 * et.corner_count);
      const std::size_t max_entries = ns > 0 ? 2 * (3 * n - h - 3) : 0;
      room(part.neighbor, sc.entries + max_entries);
      room(part.neighbor_edge_kind, sc.entries + max_entries);
      room(part.region_corners, sc.regions + static_cast<std::size_t>(nf));
      room(part.region_neighbors, sc.regions + static_cast<std::size_t>(nf));
      room(part.region_target, sc.regions + static_cast<std::size_t>(nf));
      room(part.region_map, sc.regions + static_cast<std::size_t>(nf));
      // regions: triangles of faces inside D with a target element and the map's orientation
      sc.triangle_region.assign(nf, invalid_index);
      for (const auto& comp : et.components)
        if (comp.target != invalid_index && comp.sign != orientation) ++sc.reversed_faces;
      Index nr = 0;
      for (int f = 0; f < nf; ++f) {
        const auto& comp = et.components[closure.face[f]];
        if (comp.outside || comp.target == invalid_index || comp.sign != orientation) continue;
        sc.triangle_region[f] = rbase + nr++;
      }
      auto is_region = [&](int f) { return f >= 0 && sc.triangle_region[f] != invalid_index; };
      for (int i = 0; i < ns; ++i) {
        const auto& bn = im.nodes[et.slots[i]];
        const std::size_t n = sc.nodes + static_cast<std::size_t>(i);
        part.node_position[n] = et.positions[i];
        NodeType type = NodeType::interior;
        if (bn.place.kind == PlaceKind::vertex)
          type = bn.kind == BuilderNodeKind::ghost ? NodeType::ghost : NodeType::corner;
        else if (bn.place.kind == PlaceKind::edge)
          type = bn.kind == BuilderNodeKind::intersection ? NodeType::intersection : NodeType::touching;
        part.node_type[n] = type;
        part.node_location[n] = et.location[i];
        part.node_image[n] = {bn.image.element, support_local<2>(s2, bn.image, bn.image.element)};
        part.node_target[n] = bn.kind == BuilderNodeKind::ghost ? invalid_index : bn.target;
        // graph edges, and closure edges that border a region (virtual corners are not nodes)
        detail::visit_ring(closure, i, w.ring_start[i], [&](const detail::RingEntry& entry) {
          if (entry.vertex >= ns || (!entry.graph && !is_region(entry.before) && !is_region(entry.after))) return;
          part.neighbor[sc.entries] = base + entry.vertex;
          part.neighbor_edge_kind[sc.entries++] = entry.graph ? GraphEdgeKind::target_edge : GraphEdgeKind::closure;
        });
        part.neighbor_begin[n + 1] = static_cast<Index>(sc.entries);
      }
      sc.nodes += static_cast<std::size_t>(ns);
      part.node_begin[sc.elements + 1] = static_cast<Index>(sc.nodes);
      for (int k = 0; k < 3; ++k) {
        for (int q = et.edge_slots_begin[k]; q < et.edge_slots_begin[k + 1]; ++q)
          part.edge_node[sc.edge_nodes++] = base + et.edge_slots[q];
        part.edge_node_begin[3 * sc.elements + static_cast<std::size_t>(k) + 1] = static_cast<Index>(sc.edge_nodes);
      }
      for (int f = 0; f < nf; ++f) {
        if (sc.triangle_region[f] == invalid_index) continue;
        const auto& tr = closure.triangles[f];
        const Index target = et.components[closure.face[f]].target;
        auto& corners = part.region_corners[sc.regions];
        auto& neighbors = part.region_neighbors[sc.regions];
        for (int i = 0; i < 3; ++i) {
          const int s = tr[i];
          corners[i] = base + s;
          const int g = closure.neighbors[f][i];
          neighbors[i] = g >= 0 ? sc.triangle_region[g] : invalid_index;
        }
        part.region_target[sc.regions] = target;
        part.region_map[sc.regions] = et.corner_maps[f];  // judged with the face (a region's face has sign != 0)
        ++sc.regions;
      }
      part.region_begin[sc.elements + 1] = static_cast<Index>(sc.regions);
      if (nr > 0) {
        const int ct = et.centroid_triangle;
        part.start_region[sc.elements] =
            (ct >= 0 && sc.triangle_region[ct] != invalid_index) ? sc.triangle_region[ct] : rbase;
      } else {
        part.start_region[sc.elements] = invalid_index;
      }
      ++sc.elements;
    };

    // ---- close and assemble every element -----------------------------------------------------
    // An element whose graph has crossing edges (or an edge through another node) cannot be
    // closed. Unless asked to drop the S2 edges involved, that is an error; otherwise they are
    // dropped everywhere and the elements are closed again (each round removes at least one).
    const bool drop = im.options.drop_conflicting_edges;
    std::vector<Workspace> workspaces;
    std::vector<MapData<2>> parts(threads);
    std::vector<Index> reversed_faces(threads, 0);  // per block, FinalizeReport::reversed_faces
    const Index block = (n1 + static_cast<Index>(threads) - 1) / static_cast<Index>(threads);
    // Closes and assembles every element; returns the elements that could not be closed, in
    // element order (blocks are in element order).
    // A block's arrays are sized before it is assembled: nodes and edge arrays exactly (written
    // in place: a push_back per value costs more than the store), the rest reserved by the size
    // of each element's closure (a triangulation of n points, h of them on the element boundary,
    // has 2n - h - 2 triangles and 3n - h - 3 sides), which is exact unless faces lie outside D.
    // Growing by push_back instead would copy the map several times and first-touch up to twice
    // its memory, and the final shrink_to_fit would copy it again.
    auto size_part = [&](MapData<2>& part, Index begin, Index end) {
      std::size_t nodes = 0, on_edges = 0, triangles = 0, sides = 0;
      for (Index t = begin; t < end; ++t) {
        std::size_t corners = 0, edge_inner = 0;
        for (int k = 0; k < 3; ++k) {
          if (im.node_at_domain_vertex[s1.element(t)[k]] != invalid_index) ++corners;
          edge_inner += edge_nodes[s1.element_edge(t, k)].size();
        }
        const std::size_t ns = corners + edge_inner + interior_nodes[t].size();
        nodes += ns;
        on_edges += 2 * corners + edge_inner;
        if (ns == 0) continue;
        const std::size_t n = ns + (3 - corners), h = 3 + edge_inner;
        triangles += 2 * n - h - 2;
        sides += 3 * n - h - 3;
      }
      const std::size_t elements = static_cast<std::size_t>(end - begin);
      part = MapData<2>{};
      part.node_begin.resize(elements + 1);
      part.region_begin.resize(elements + 1);
      part.start_region.resize(elements);
      part.edge_node_begin.resize(3 * elements + 1);
      size_node_arrays(part, nodes);
      part.edge_node.resize(on_edges);
      // Neighbour entries and regions are bounded, not known: reserved (their slack stays
      // untouched, so it costs no resident memory) and sized as they are written.
      part.neighbor.reserve(2 * sides);
      part.neighbor_edge_kind.reserve(2 * sides);
      part.region_corners.reserve(triangles);
      part.region_neighbors.reserve(triangles);
      part.region_target.reserve(triangles);
      part.region_map.reserve(triangles);
    };
    auto close_and_assemble = [&](int orientation) {
      workspaces.assign(threads, Workspace{});
      std::vector<std::vector<std::pair<Index, std::exception_ptr>>> failures(threads);
      run_blocks([&](unsigned k) {
        const Index begin = std::min<Index>(n1, static_cast<Index>(k) * block);
        const Index end = std::min<Index>(n1, begin + block);
        size_part(parts[k], begin, end);
        AssemblyScratch scratch;
        for (Index t = begin; t < end; ++t) {
          try {
            close_element(t, workspaces[k]);
            // after a failure the part is discarded: only the failures are still collected
            if (failures[k].empty()) assemble_element(workspaces[k], parts[k], orientation, scratch);
          } catch (...) {
            failures[k].emplace_back(t, std::current_exception());
            if (!drop) return;  // finalize throws: the part and its count are not used
          }
        }
        reversed_faces[k] = scratch.reversed_faces;
        // cut the arrays sized ahead back to what was written
        parts[k].neighbor.resize(scratch.entries);
        parts[k].neighbor_edge_kind.resize(scratch.entries);
        parts[k].region_corners.resize(scratch.regions);
        parts[k].region_neighbors.resize(scratch.regions);
        parts[k].region_target.resize(scratch.regions);
        parts[k].region_map.resize(scratch.regions);
      });
      std::vector<std::pair<Index, std::exception_ptr>> failed;
      for (auto& list : failures) failed.insert(failed.end(), list.begin(), list.end());
      return failed;
    };
    // The orientation guess: the vote of up to 64 elements spread over S1.
    auto sampled_orientation = [&] {
      Workspace w;
      const Index stride = std::max<Index>(1, n1 / 64);
      for (Index t = 0; t < n1; t += stride) {
        try {
          close_element(t, w);
        } catch (...) {
          // an element that cannot be closed does not vote; the full pass reports it
        }
      }
      return w.votes >= 0 ? 1 : -1;
    };
    // Minimal embedding (DESIGN §4.3): the preimage of an S2 edge meets an S1 element in at most
    // one connected piece. Where a projection is discontinuous a preimage can enter an element
    // twice; with drop_conflicting_edges such an edge is dropped, like one that crosses another.
    if (drop) {
      bool any = false;
      std::vector<std::pair<Index, std::array<Index, 2>>> pieces;  // (S2 edge, end nodes)
      std::vector<Index> reached;
      for (Index t = 0; t < n1; ++t) {
        pieces.clear();
        for (Index s : element_segments[t]) pieces.push_back({im.segments[s].target_edge, {im.segments[s].a, im.segments[s].b}});
        for (int k = 0; k < 3; ++k)
          for (Index s : edge_segments[s1.element_edge(t, k)])
            pieces.push_back({im.segments[s].target_edge, {im.segments[s].a, im.segments[s].b}});
        if (pieces.size() < 2) continue;
        std::sort(pieces.begin(), pieces.end());
        for (std::size_t i = 0, j = 0; i < pieces.size(); i = j) {
          for (j = i + 1; j < pieces.size() && pieces[j].first == pieces[i].first;) ++j;
          if (j - i < 2 || dropped[pieces[i].first]) continue;
          // grow one piece from the first segment; the edge is split if a segment stays out
          reached.assign(pieces[i].second.begin(), pieces[i].second.end());
          std::vector<char> in(j - i, 0);
          in[0] = 1;
          for (bool grew = true; grew;) {
            grew = false;
            for (std::size_t q = i + 1; q < j; ++q) {
              if (in[q - i]) continue;
              const auto& [a, b] = pieces[q].second;
              if (std::find(reached.begin(), reached.end(), a) == reached.end() &&
                  std::find(reached.begin(), reached.end(), b) == reached.end())
                continue;
              in[q - i] = 1;
              reached.push_back(a);
              reached.push_back(b);
              grew = true;
            }
          }
          if (std::find(in.begin(), in.end(), 0) == in.end()) continue;
          const Index e = pieces[i].first;
          dropped[e] = 1;
          im.edge_inserted[e] = 0;
          any = true;
          if (report) {
            report->dropped_edges.push_back(e);
            report->dropped_edge_element.push_back(t);
          }
        }
      }
      if (any) bucket();
    }
    const int guess = im.options.orientation != 0 ? im.options.orientation : sampled_orientation();
    for (int round = 0;; ++round) {
      const auto failed = close_and_assemble(guess);
      if (failed.empty()) break;
      // failed.front() is the smallest element that failed
      if (!drop || round == 16) std::rethrow_exception(failed.front().second);
      bool any = false;
      for (const auto& [t, error] : failed)
        for (Index e : conflicting_edges(t)) {
          if (dropped[e]) continue;
          dropped[e] = 1;
          im.edge_inserted[e] = 0;
          any = true;
          if (report) {
            report->dropped_edges.push_back(e);
            report->dropped_edge_element.push_back(t);
          }
        }
      if (!any) std::rethrow_exception(failed.front().second);
      bucket();
    }
    long long votes = 0;
    for (const auto& w : workspaces) votes += w.votes;
    m.orientation = im.options.orientation != 0 ? im.options.orientation : (votes >= 0 ? 1 : -1);
    if (m.orientation != guess) {
      const auto failed = close_and_assemble(m.orientation);  // the same graphs: they close again
      if (!failed.empty()) std::rethrow_exception(failed.front().second);
    }
    if (report)
      for (Index r : reversed_faces) report->reversed_faces += r;
    concatenate_parts(parts, n1, m, run_blocks);
  }
  shrink_to_fit(m);
  return PlMap<d>(im.s1, im.s2, std::move(m));
}

template class MapBuilder<1>;
template class MapBuilder<2>;

}  // namespace plmap
