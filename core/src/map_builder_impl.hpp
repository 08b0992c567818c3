// The builder's collection state, MapBuilder<d>::Impl: the nodes and edge-preimage segments
// entered so far, and the rules that check each entry and place it on S1. Private to core: the
// public entry points (map_builder.cpp) forward to it, and finalize() hands what it holds to the
// finalize phases (finalize_phases.hpp).
//
// Every node is entered once, at its place on S1: an S1 vertex, a point of an S1 edge (parameter
// along the edge from its smaller-index vertex) or a point inside an S1 element. Its image is kept
// as a "support": the S2 vertices with non-zero barycentric weight. Supports make the question
// "which S2 elements contain this image?" exact and cheap, and they let an image be re-expressed
// on any of those elements without rounding.
#pragma once

#include "builder_nodes.hpp"

#include <plmap/core/element_transfer.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/snapping.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <memory>
#include <vector>

namespace plmap {

template <int d>
  requires SurfaceDimension<d>
struct MapBuilder<d>::Impl {
  // The builder's own vocabulary (builder_nodes.hpp), named here as in the rest of the unit.
  template <int k>
  using BuilderNode = detail::BuilderNode<k>;
  template <int k>
  using Place = detail::Place<k>;
  template <int k>
  using Support = detail::Support<k>;
  using BuilderNodeKind = detail::BuilderNodeKind;
  using PlaceKind = detail::PlaceKind;
  using Segment = detail::Segment;
  std::shared_ptr<const Surface<d>> s1, s2;
  BuilderOptions options;
  detail::BuilderNodes<d> nodes;
  std::vector<Index> preimage_of_target_vertex;  // per S2 vertex
  std::vector<Index> node_at_domain_vertex;      // per S1 vertex
  detail::BuilderSegments<d> segments;
  // per S2 edge (d = 2) or S2 element (d = 1): not inserted, inserted whole, or in pieces
  std::vector<char> edge_inserted;
  static constexpr char edge_complete = detail::edge_complete, edge_partial = detail::edge_partial,
                        edge_outside_domain = detail::edge_outside_domain;
  // the nodes' and segments' room (reserve_expected_sizes) backed ahead of the appends
  PagesBackedAhead nodes_backing, segments_backing;

  Impl(std::shared_ptr<const Surface<d>> domain, std::shared_ptr<const Surface<d>> target,
       BuilderOptions opt)
      : s1(std::move(domain)), s2(std::move(target)), options(opt) {
    if (!s1 || !s2) throw BuilderError("MapBuilder needs two surfaces");
    if (!(options.snap_tolerance >= 0.0 && options.snap_tolerance < 0.1))
      throw BuilderError(fmt::format("snap_tolerance {} is outside [0, 0.1)", options.snap_tolerance));
    if (options.orientation < -1 || options.orientation > 1)
      throw BuilderError("orientation must be -1, 0 (automatic) or +1");
    // a segment keeps its S1 element or edge in 31 bits (detail::Segment)
    if (std::max(s1->element_count(), s1->edge_count()) >= Index{1} << 30)
      throw BuilderError(fmt::format("S1 has {} elements and {} edges; the builder takes fewer than 2^30",
                                     s1->element_count(), s1->edge_count()));
    // per vertex and per edge of surfaces with millions of them: on huge pages
    // (first touched on all threads: parallel_first_touch.hpp)
    assign_on_huge_pages(preimage_of_target_vertex, static_cast<std::size_t>(s2->vertex_count()), invalid_index,
                         options.threads);
    assign_on_huge_pages(node_at_domain_vertex, static_cast<std::size_t>(s1->vertex_count()), invalid_index,
                         options.threads);
    assign_on_huge_pages(edge_inserted, static_cast<std::size_t>(s2->edge_count()), char{0}, options.threads);
    reserve_expected_sizes();
  }

  /// The nodes and segments grow to millions of entries one at a time (the projection); grown by
  /// doubling, every entry is copied about once more and every new block is first touched (page
  /// faults), which was a fifth of the projection's insertion time on the 1M circles. So room is
  /// taken once for what a map between the two surfaces usually holds. Nodes: one per S2 vertex
  /// and per S1 vertex, plus one per crossing of an S2 edge with the inside of an S1 edge (d = 2).
  /// Segments: one per S2 edge, plus one per node an edge passes. Two networks of edges over the
  /// same area cross about sqrt(|E1| |E2|) times a constant of the meshes' shapes (4.3 on the
  /// jittered planes, 5.8 on the spheres); 8 covers both. Room never written costs address space
  /// only (its pages are never touched); a map that needs more grows the arrays as before.
  void reserve_expected_sizes() {
    std::size_t crossings = 0;
    if constexpr (d == 2)
      crossings = static_cast<std::size_t>(
          8.0 * std::sqrt(static_cast<double>(s1->edge_count()) * static_cast<double>(s2->edge_count())));
    const auto n1v = static_cast<std::size_t>(s1->vertex_count());
    // A system that refuses address space it cannot back (strict or heuristic overcommit with
    // huge inputs) refuses a hint, not the map: the arrays then grow as needed.
    try {
      nodes.reserve(n1v + static_cast<std::size_t>(s2->vertex_count()) + crossings);
      segments.reserve(static_cast<std::size_t>(s2->edge_count()) + n1v + crossings);
    } catch (const std::exception&) {  // std::bad_alloc, or std::length_error beyond max_size()
      detail::BuilderNodes<d>().swap(nodes);
      detail::BuilderSegments<d>().swap(segments);
    }
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
      if (b(k) > 0.0) s.add(k, b(k));
    return s;
  }

  Support<d> vertex_support(Index v) const {
    Support<d> s;
    const auto star = s2->vertex_elements(v);
    if (star.empty())
      throw BuilderError(fmt::format("S2 vertex {} is isolated (no S2 element uses it): it is not part of S2, "
                                     "so it has no preimage",
                                     v));
    s.element = star.front();
    s.add(s2->local_corner(s.element, v), 1.0);
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
    s.add(s2->local_corner(element, u), 1.0 - tau);
    s.add(s2->local_corner(element, v), tau);
    return s;
  }

  // ---- node entry -----------------------------------------------------------------------------
  Index new_node(const Place<d>& place, BuilderNodeKind kind, Index target, const Support<d>& image) {
    const auto id = static_cast<Index>(nodes.size());
    nodes_backing.before_append(nodes);
    nodes.emplace_back(place, kind, target, image);
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
      const Index tv = image.vertex(*s2, 0);
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

  // ---- the rim of D inside S1 --------------------------------------------------------------------
  /// S2 edge an image support lies on (two support vertices), or invalid_index (inside an element).
  Index target_edge_of(const Support<d>& image) const {
    if constexpr (d == 2) {
      if (image.count == 2) return s2->find_edge(image.vertex(*s2, 0), image.vertex(*s2, 1));
    }
    return invalid_index;
  }

  Index add_rim_node(const Place<d>& place, const Support<d>& image) {
    if (image.count < 2)
      throw BuilderError(fmt::format("a rim node maps onto S2 vertex {}: enter it as that vertex's preimage",
                                     image.count > 0 ? image.vertex(*s2, 0) : invalid_index));
    if (place.kind == PlaceKind::vertex) {
      const Index existing = node_at_domain_vertex[place.index];
      if (existing == invalid_index) return new_node(place, BuilderNodeKind::ghost, invalid_index, image);
      if (nodes[existing].kind != BuilderNodeKind::ghost)
        throw BuilderError(fmt::format("a rim node at S1 vertex {} meets the preimage of S2 vertex {}", place.index,
                                       nodes[existing].target));
      return existing;  // the rim passes through the ghost node already there
    }
    return new_node(place, BuilderNodeKind::rim, target_edge_of(image), image);
  }

  void check_node_handle(Index n, const char* what) const {
    if (n < 0 || n >= static_cast<Index>(nodes.size()))
      throw BuilderError(fmt::format("{}: node {} does not exist (the builder has {} nodes)", what, n, nodes.size()));
  }

  /// A piece that starts or ends at rim node n: n must be a rim node (or a ghost node the rim
  /// passes) whose image lies on the piece's S2 edge (u, v), strictly between its ends.
  void check_rim_end(Index n, Index target_edge, Index u, Index v) const {
    check_node_handle(n, "the end of a piece");
    const auto& node = nodes[n];
    if (node.kind != BuilderNodeKind::rim && node.kind != BuilderNodeKind::ghost)
      throw BuilderError(fmt::format("a piece of S2 edge {} ends at node {}, which is no rim node", target_edge, n));
    const Support<d>& s = node.image;
    const bool on_edge = s.count == 2 && ((s.vertex(*s2, 0) == u && s.vertex(*s2, 1) == v) ||
                                          (s.vertex(*s2, 0) == v && s.vertex(*s2, 1) == u));
    if (!on_edge)
      throw BuilderError(fmt::format("a piece of S2 edge {} ends at rim node {}, whose image does not lie on that edge",
                                     target_edge, n));
  }

  void add_rim_edge(Index a, Index b) {
    check_node_handle(a, "rim edge");
    check_node_handle(b, "rim edge");
    if (a == b) throw BuilderError(fmt::format("a rim edge needs two distinct nodes (node {} twice)", a));
    try {
      segments_backing.before_append(segments);
      segments.push_back(locate_segment(a, b, invalid_index));
    } catch (const BuilderError&) {
      throw BuilderError(fmt::format("the rim edge between nodes {} and {} does not lie in one S1 element", a, b));
    }
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
                            bool from_u = true, bool to_v = true, Index start_rim = invalid_index,
                            Index end_rim = invalid_index) {
    const char* noun = d == 2 ? "edge" : "segment";
    const bool piece = !from_u || !to_v;
    for (const Index rim : {start_rim, end_rim})
      if (rim != invalid_index) check_rim_end(rim, target_edge, u, v);
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
    if (static_cast<int>(cs.size()) + (from_u || start_rim != invalid_index) + (to_v || end_rim != invalid_index) < 2)
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

    // An S1 vertex the preimage passes must not be a corner node, and a ghost node already there
    // (a ray hit) must map onto this edge: the chain's sides become graph edges labelled with it,
    // and a ghost whose image lies elsewhere (on a coincident copy of the edge in an unstitched
    // S2, or beside it) gives a side with no S2 edge through both ends. Checked before any node
    // is made, so that a refused preimage leaves nothing behind.
    for (const auto& c : cs) {
      if (c.place.kind != PlaceKind::vertex) continue;
      const Index node = node_at_domain_vertex[c.place.index];
      if (node == invalid_index) continue;
      if (nodes[node].kind != BuilderNodeKind::ghost)
        throw BuilderError(fmt::format(
            "the preimage of S2 {} {} passes through S1 vertex {}, which is the preimage of S2 "
            "vertex {}",
            noun, target_edge, c.place.index, nodes[node].target));
      const Support<d>& image = nodes[node].image;
      for (int i = 0; i < image.count; ++i)
        if (const Index x = image.vertex(*s2, i); x != u && x != v)
          throw BuilderError(fmt::format(
              "the preimage of S2 {} {} passes through S1 vertex {}, whose ghost node maps off that {}: "
              "its image has weight on S2 vertex {}",
              noun, target_edge, c.place.index, noun, x));
    }

    auto& chain = chain_scratch;
    chain.clear();
    if (from_u) chain.push_back(a);
    if (start_rim != invalid_index) chain.push_back(start_rim);
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
        if (node == invalid_index)  // (an existing node was checked above)
          node = new_node(p, BuilderNodeKind::ghost, invalid_index, edge_support(target_edge, tau));
      } else {
        node = new_node(p, BuilderNodeKind::intersection, target_edge, edge_support(target_edge, tau));
      }
      chain.push_back(node);
    }
    if (to_v) chain.push_back(b);
    if (end_rim != invalid_index) chain.push_back(end_rim);
    if (chain.size() > 1) segments_backing.before_append(segments, chain.size() - 1);
    for (std::size_t i = 0; i + 1 < chain.size(); ++i)
      segments.push_back(locate_segment(chain[i], chain[i + 1], target_edge));
    edge_inserted[target_edge] = piece ? edge_partial : edge_complete;
  }
};

}  // namespace plmap
