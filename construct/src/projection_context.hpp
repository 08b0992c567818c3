#pragma once
// Normal projection (project.cpp), what its phases share: the places of S1 that the builder's
// snapping rule distinguishes, the context every phase reads (the surfaces, the options, the
// direction field, the search indexes and the tests on rays), and the state that one phase leaves
// for the next ones. The phases, each in its own unit:
//   1. ghost rays (projection_ghost_rays): the ray from every S1 vertex against S2;
//   2. vertex preimages (projection_vertex_preimages): eq. (3) for every S2 vertex;
//   3. sheet selection (projection_sheet_selection): of the preimages that coincide, and of the
//      sheets of S1 whose images overlap on S2, the nearer one is kept;
//   4. edge walks (projection_edge_walks): the preimages of the S2 edges, walked across S1;
//   5. insertion (projection_insertion): everything entered into the MapBuilder, in index order.

#include "element_box_index.hpp"
#include "element_index.hpp"
#include "walk_acceptance.hpp"

#include <plmap/construct/projection_options.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/snapping.hpp>
#include <plmap/core/surface.hpp>
#include <plmap/solvers/focal_points.hpp>
#include <plmap/solvers/projection_systems.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

namespace plmap::projection {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

enum class PlaceKind : std::uint8_t { vertex, edge, element };

/// A point of S1 after the builder's snapping rule: a vertex, a point of an edge (d = 2, parameter
/// from the smaller-index vertex) or a point inside an element.
template <int d>
struct Place {
  PlaceKind kind = PlaceKind::element;
  Index index = invalid_index;
  double t = 0.0;
  LocalPoint<d> local = LocalPoint<d>::Zero();
  friend bool operator==(const Place&, const Place&) = default;
};

/// What became of an S1 vertex: free, the preimage of an S2 vertex (a corner node), or a ghost
/// node (its ray hit S2 inside an element or on an edge).
enum class VertexState : std::uint8_t { free, corner, ghost };

/// Where the preimage of an S2 edge crosses S1: an S1 edge (d = 2) or an S1 vertex (d = 1).
template <int d>
using Crossing = std::conditional_t<d == 2, EdgeCrossing, VertexCrossing>;

/// A point where an S2 edge crosses S1's boundary (d = 2: a boundary edge, d = 1: a boundary
/// vertex); a walk from there may enter S1.
template <int d>
struct BoundaryEntry {
  Place<d> place;
  Crossing<d> crossing;
  double eta;
};

/// The points where S2 edges cross S1's boundary, by S2 edge and along it by the edge parameter,
/// in one flat list: one list per S2 edge would first-touch a vector for each of S2's edges
/// (7 MB on the 200k planes) on one thread, for the few edges that cross the boundary.
template <int d>
struct BoundaryEntries {
  std::vector<Index> edge;              ///< the S2 edge of each entry, non-decreasing
  std::vector<BoundaryEntry<d>> entry;  ///< the entries, of each edge by increasing eta

  bool empty() const { return entry.empty(); }
  std::size_t size() const { return entry.size(); }
  /// S2 edge e's entries, by increasing eta (none if it does not cross S1's boundary).
  std::span<const BoundaryEntry<d>> of(Index e) const {
    const auto [first, last] = std::equal_range(edge.begin(), edge.end(), e);
    return {entry.data() + (first - edge.begin()), static_cast<std::size_t>(last - first)};
  }
};

/// The local coordinates of S1 element t's corner at vertex v.
template <int d>
LocalPoint<d> local_of_corner(const Surface<d>& s, Index t, Index v) {
  return reference_corner<d>(s.local_corner(t, v));
}

/// Local coordinates on triangle t of the point at parameter `param` along its edge `edge` (0 at
/// the edge's first vertex, Surface::edge_vertices, 1 at its second).
inline LocalPoint<2> local_on_edge_of(const Surface<2>& s, Index t, Index edge, double param) {
  const auto ev = s.edge_vertices(edge);
  Barycentric<2> b = Barycentric<2>::Zero();
  b(s.local_corner(t, ev[0])) = 1.0 - param;
  b(s.local_corner(t, ev[1])) = param;
  return local_from_barycentric<2>(b);
}

/// The element across the facet opposite corner k of element t on surface s, if exactly one.
template <int d>
Index element_across(const Surface<d>& s, Index t, int k) {
  if constexpr (d == 2) {
    const Index e = s.element_edge(t, (k + 1) % 3);
    const auto inc = s.edge_elements(e);
    if (inc.size() != 2) return invalid_index;
    return inc[0].element == t ? inc[1].element : inc[0].element;
  } else {
    const Index w = s.element(t)[1 - k];
    const auto star = s.vertex_elements(w);
    if (star.size() != 2) return invalid_index;
    return star[0] == t ? star[1] : star[0];
  }
}

/// A bound of the admissible band of distances mu along the rays (ProjectionContext::
/// rim_level): D ends where the rays' distance to S2 reaches it. `lower`: the band lies above mu.
struct RimLevel {
  double mu = 0.0;
  bool lower = true;
};

/// What every phase reads. Built once (the set-up phase: the direction field, the focal-free
/// distances, the kd-trees, the limits from the options); the phases only read it, except for
/// the solver counters, which they add to.
template <int d>
struct ProjectionContext {
  /// Checks the options (plmap::Error names what is out of range) and derives the rest.
  ProjectionContext(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
                    const ProjectionOptions& options);

  std::shared_ptr<const Surface<d>> s1_shared, s2_shared;
  const Surface<d>& s1;
  const Surface<d>& s2;
  ProjectionOptions options;
  /// The unit projection direction nu at every S1 vertex.
  std::vector<WorldPoint<d>> vertex_directions;
  /// Averaged vertex normals of S2, only if options.normal_check asks for them.
  std::vector<WorldPoint<d>> s2_vertex_normals;
  /// Per S1 element: up to this |mu| no ray of the element passes a focal point (focal_points.hpp).
  std::vector<double> focal_free_reach;
  /// Largest admissible |mu|, a length (options.max_distance, relative or not).
  double distance_limit = 0.0;
  /// How far from its point of S1 an admissible hit can lie: distance_limit times the longest
  /// direction (the field interpolates the vertex directions linearly, so no ray is longer per
  /// unit of mu). Infinite without a distance limit (segment_reach.hpp).
  double band_reach = std::numeric_limits<double>::infinity();
  /// Rounding of a distance between points of S1 and S2: 1e-12 of their largest coordinate.
  double coordinate_rounding = 0.0;
  /// Nearest elements that seed a search (options.search_seeds, clamped to 1..max_search_seeds).
  int seed_count = 8;
  /// Seeds of the repeated vertex preimage search (search_limits.retry_seeds).
  int retry_seed_count = 32;
  unsigned threads = 1;
  /// Crossings one walk along an S2 edge may make (search_limits.edge_walk_steps, or derived
  /// from |T1|).
  int edge_walk_steps = 16;
  std::unique_ptr<ElementIndex<d>> s1_index, s2_index;
  /// S1's elements by their bounding boxes, for the long elements a vertex preimage search adds.
  std::unique_ptr<ElementBoxIndex<d>> s1_boxes;
  /// The solver counters every thread adds to, each on a cache line of its own: next to the
  /// fields above, which every walk step reads, each addition evicted them from the other
  /// threads' caches (the two-thread edge walks took 40 % more CPU than one thread's). They are
  /// the last fields, so the struct's own alignment pads the second one's line.
  alignas(64) mutable std::atomic<long long> solver_calls{0};
  alignas(64) mutable std::atomic<long long> solver_failures{0};

  /// Frees the search data (indexes, directions, focal distances) once the walks are done.
  void release_search_data();

  // ---- places and the tests on rays ----------------------------------------------------------
  // The snapping rule is core/snapping.hpp's, the one MapBuilder applies to what it is given.
  Barycentric<d> clean_barycentric(const LocalPoint<d>& xi) const {
    return snap_barycentric<d>(barycentric_from_local<d>(xi), options.snap_tolerance);
  }

  LocalPoint<d> place_local(const SurfacePoint<d>& p) const {
    return local_from_barycentric<d>(clean_barycentric(p.local));
  }

  Place<d> place_of(const SurfacePoint<d>& p) const {
    const Barycentric<d> b = clean_barycentric(p.local);
    std::array<int, d + 1> which{};
    int nonzero = 0;
    for (int k = 0; k <= d; ++k)
      if (b(k) > 0.0) which[nonzero++] = k;
    Place<d> place;
    const auto& c = s1.element(p.element);
    if (nonzero == 1) {
      place.kind = PlaceKind::vertex;
      place.index = c[which[0]];
    } else if (nonzero == 2 && d == 2) {
      if constexpr (d == 2) {
        place.kind = PlaceKind::edge;
        const Index u = c[which[0]], v = c[which[1]];
        place.index = s1.find_edge(u, v);
        place.t = u < v ? b(which[1]) : b(which[0]);
      }
    } else {
      place.kind = PlaceKind::element;
      place.index = p.element;
      place.local = local_from_barycentric<d>(b);
    }
    return place;
  }

  /// Place on S1 edge `edge` at parameter lambda (from its smaller vertex), snapped.
  Place<d> edge_place(Index edge, double lambda) const
    requires(d == 2)
  {
    Place<d> p;
    const auto ev = s1.edge_vertices(edge);
    const EdgeSnap snap = snap_edge_parameter(lambda, options.snap_tolerance);
    if (snap != EdgeSnap::inside) {
      p.kind = PlaceKind::vertex;
      p.index = ev[snap == EdgeSnap::first_vertex ? 0 : 1];
    } else {
      p.kind = PlaceKind::edge;
      p.index = edge;
      p.t = lambda;
    }
    return p;
  }

  // elements_of and unfolded_in_at run at every step of every edge walk; GCC stopped inlining
  // them there once the walks moved into a unit of their own (+4% instructions in the walks).
  [[gnu::always_inline]] void elements_of(const Place<d>& p, std::vector<Index>& out) const {
    out.clear();
    if (p.kind == PlaceKind::vertex) {
      const auto star = s1.vertex_elements(p.index);
      out.assign(star.begin(), star.end());
    } else if (p.kind == PlaceKind::edge) {
      if constexpr (d == 2)
        for (const auto& inc : s1.edge_elements(p.index)) out.push_back(inc.element);
    } else {
      out.push_back(p.index);
    }
  }

  WorldPoint<d> world_of(const Place<d>& p) const {
    if (p.kind == PlaceKind::vertex) return s1.vertex(p.index);
    if constexpr (d == 2)
      if (p.kind == PlaceKind::edge) {
        const auto ev = s1.edge_vertices(p.index);
        return (1.0 - p.t) * s1.vertex(ev[0]) + p.t * s1.vertex(ev[1]);
      }
    return s1.world_position(p.index, p.local);
  }

  bool distance_ok(double mu, double scale) const {
    const double slack = 1e-9 * scale;
    if (!options.allow_negative_distance && mu < -slack) return false;
    return std::abs(mu) <= distance_limit + slack;
  }

  double rank(double mu) const { return options.allow_negative_distance ? std::abs(mu) : std::max(mu, 0.0); }

  /// The ray from local point xi of S1 element t reaches distance mu before any focal point of
  /// the direction field (solvers/focal_points.hpp): beyond one the projection is folded.
  bool unfolded_in(Index t, const LocalPoint<d>& xi, double mu) const {
    return std::abs(mu) <= focal_free_reach[t] || reaches_without_focal_point_in(t, xi, mu);
  }

  /// Eq. (3) on S1 element t for target point q: the element's corners and vertex directions.
  VertexProjectionSystem<d> element_system(Index t, const WorldPoint<d>& q) const {
    VertexProjectionSystem<d> sys;
    for (int k = 0; k <= d; ++k) {
      sys.corners[k] = s1.corner(t, k);
      sys.directions[k] = vertex_directions[s1.element(t)[k]];
    }
    sys.target = q;
    return sys;
  }

  /// The focal test itself, for distances beyond the element's focal-free distance.
  bool reaches_without_focal_point_in(Index t, const LocalPoint<d>& xi, double mu) const {
    std::array<WorldPoint<d>, d + 1> corners, directions;
    for (int k = 0; k <= d; ++k) {
      corners[k] = s1.corner(t, k);
      directions[k] = vertex_directions[s1.element(t)[k]];
    }
    return reaches_without_focal_point<d>(corners, directions, xi, mu);
  }

  /// The focal test for the ray from place p (a vertex, edge or interior point of S1) as a
  /// point of element t, which contains it.
  [[gnu::always_inline]] bool unfolded_in_at(Index t, const Place<d>& p, double mu) const {
    if (std::abs(mu) <= focal_free_reach[t]) return true;
    if (p.kind == PlaceKind::element) return reaches_without_focal_point_in(t, p.local, mu);
    if (p.kind == PlaceKind::vertex) return reaches_without_focal_point_in(t, local_of_corner(s1, t, p.index), mu);
    if constexpr (d == 2) return reaches_without_focal_point_in(t, local_on_edge_of(s1, t, p.index, p.t), mu);
    return true;
  }

  /// The same for a ray from an S1 vertex or edge point: it must be unfolded in every element
  /// that contains the point, since the regions on all of them end there.
  bool unfolded_at(const Place<d>& p, double mu) const {
    if (p.kind == PlaceKind::element) return unfolded_in(p.index, p.local, mu);
    const double distance = std::abs(mu);
    if (p.kind == PlaceKind::vertex) {
      for (Index t : s1.vertex_elements(p.index))
        if (!(distance <= focal_free_reach[t]) && !reaches_without_focal_point_in(t, local_of_corner(s1, t, p.index), mu))
          return false;
      return true;
    }
    if constexpr (d == 2)
      for (const auto& incidence : s1.edge_elements(p.index)) {
        const Index t = incidence.element;
        if (!(distance <= focal_free_reach[t]) &&
            !reaches_without_focal_point_in(t, local_on_edge_of(s1, t, p.index, p.t), mu))
          return false;
      }
    return true;
  }

  /// The ghost ray from S1 vertex v reaches distance mu unfolded in at least one element at v
  /// (walk_acceptance.hpp: the per-element rule of the walks and the ray check).
  bool ghost_ray_unfolded(Index v, double mu) const {
    return unfolded_in_some_element(s1.vertex_elements(v), [&](Index t) {
      return std::abs(mu) <= focal_free_reach[t] || reaches_without_focal_point_in(t, local_of_corner(s1, t, v), mu);
    });
  }

  bool normal_ok(const WorldPoint<d>& direction, const WorldPoint<d>& target_normal) const {
    if (options.normal_check == TargetNormalCheck::none) return true;
    const double c = direction.dot(target_normal);
    return options.normal_check == TargetNormalCheck::facing ? c < 0.0 : c > 0.0;
  }

  bool on_boundary(const Place<d>& p) const {
    if (p.kind == PlaceKind::vertex) return s1.is_boundary_vertex(p.index);
    if constexpr (d == 2)
      if (p.kind == PlaceKind::edge) return s1.edge_elements(p.index).size() == 1;
    return false;
  }

  /// The vertices of S2 edge e (d = 1: of S2 segment e), in the edge's direction.
  /// Whether D ends on a rim (ProjectionOptions::end_on_rim): on the curves where the rays'
  /// distance to S2 reaches a bound of the admissible band, mu = 0 where S2 passes behind S1
  /// (unless negative distances are allowed) and mu = +-distance_limit where that is finite
  /// (rim_geometry.hpp). With negative distances and no limit the band has no bound.
  bool ends_on_rim() const { return d == 2 && options.end_on_rim && rim_level_count() > 0; }

  /// The bounds of the admissible band of mu, in a fixed order (index = RimPoint::level): the
  /// lower one first (0, or -distance_limit with negative distances), then the upper one
  /// (distance_limit) if finite.
  int rim_level_count() const {
    const bool lower = !options.allow_negative_distance || std::isfinite(distance_limit);
    return (lower ? 1 : 0) + (std::isfinite(distance_limit) ? 1 : 0);
  }
  RimLevel rim_level(int index) const {
    const bool has_lower = !options.allow_negative_distance || std::isfinite(distance_limit);
    if (index == 0 && has_lower) return {options.allow_negative_distance ? -distance_limit : 0.0, true};
    return {distance_limit, false};
  }

  /// Which way the S2 segment qa -> qb runs into the band where it meets the level set of bound
  /// `level` over S1 element t, at local coordinates xi there: +1 forwards (towards qb), -1
  /// backwards, 0 along the level set. Across the lower bound the distance along the rays grows
  /// into the band, across the upper one it shrinks.
  int direction_into_band(Index t, int level, const LocalPoint<d>& xi, const WorldPoint<d>& qa,
                          const WorldPoint<d>& qb) const
    requires(d == 2)
  {
    const RimLevel bound = rim_level(level);
    const auto tri = corners_at_distance(t, bound.mu);
    const WorldPoint<2> normal = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    const Barycentric<2> b = barycentric_from_local<2>(xi);
    WorldPoint<2> nu = WorldPoint<2>::Zero();
    for (int k = 0; k < 3; ++k) nu += b(k) * vertex_directions[s1.element(t)[k]];
    const double growth = normal.dot(qb - qa) * normal.dot(nu);
    if (growth == 0.0 || !std::isfinite(growth)) return 0;
    return (growth > 0.0) == bound.lower ? 1 : -1;
  }

  /// The corners of S1 element t moved along their directions to distance mu: the element's
  /// points at distance mu along their rays. The directions are interpolated linearly (not
  /// normalised inside the element), so p(xi) + mu nu(xi) is affine in xi and this triangle is
  /// exactly the level set mu of the element's rays, with the same local coordinates.
  std::array<WorldPoint<d>, d + 1> corners_at_distance(Index t, double mu) const {
    std::array<WorldPoint<d>, d + 1> c;
    for (int k = 0; k <= d; ++k) c[k] = s1.corner(t, k) + mu * vertex_directions[s1.element(t)[k]];
    return c;
  }

  std::array<Index, 2> target_edge_vertices(Index e) const {
    if constexpr (d == 2)
      return s2.edge_vertices(e);
    else
      return {s2.element(e)[0], s2.element(e)[1]};
  }
};

/// What one phase leaves for the next ones.
template <int d>
struct ProjectionState {
  /// Per S2 vertex: where its inserted preimage lies on S1 (nothing if it has none, or lost it).
  std::vector<std::optional<Place<d>>> target_place;
  /// Per S1 vertex: free, a corner node or a ghost node.
  std::vector<VertexState> vertex_state;
  /// Per S1 vertex that is a node: its image on S2.
  std::vector<std::optional<SurfacePoint<d>>> vertex_image;
  /// Where S2 edges cross S1's boundary (edge walks); empty if no S2 edge does.
  BoundaryEntries<d> boundary_entries;
  /// d = 2, end_on_rim: per S1 vertex whose ray meets S2 only outside the band of admissible
  /// distances, the distance of that hit, else NaN (cast_rays_from_s1_vertices); empty without
  /// a rim.
  std::vector<float> ray_outside_band;
  /// d = 2: per S1 vertex, the rank (ProjectionContext::rank) of its ray's nearest admissible hit
  /// on S2 (+inf if none) and the S2 triangle hit (invalid_index if none), from the ghost rays:
  /// a walk's crossing that lies farther than the hits of the S1 vertices around it may be
  /// hidden by the sheet they hit (nearer_sheet.hpp, EdgeFailureReason::hidden).
  std::vector<double> nearest_hit_rank;
  std::vector<Index> nearest_hit_element;
  /// The S2 vertex that hit is, within rounding, or invalid_index.
  std::vector<Index> nearest_hit_vertex;

  /// `threads`: how many threads may first-touch the arrays (parallel_first_touch.hpp).
  ProjectionState(Index s1_vertices, Index s2_vertices, unsigned threads) {
    // per vertex of a large surface: on huge pages (huge_page_allocator.hpp)
    assign_on_huge_pages(target_place, static_cast<std::size_t>(s2_vertices), {}, threads);
    assign_on_huge_pages(vertex_state, static_cast<std::size_t>(s1_vertices), VertexState::free, threads);
    assign_on_huge_pages(vertex_image, static_cast<std::size_t>(s1_vertices), {}, threads);
  }

  void release() {
    auto release = [](auto& v) { std::decay_t<decltype(v)>().swap(v); };
    release(target_place);
    release(vertex_state);
    release(vertex_image);
    release(ray_outside_band);
    release(nearest_hit_rank);
    release(nearest_hit_element);
    release(nearest_hit_vertex);
    boundary_entries = {};
  }
};

}  // namespace plmap::projection
