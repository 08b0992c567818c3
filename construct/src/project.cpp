// Maps by normal projection (paper section 3.2). Phases:
//  1. vertex preimages: for every S2 vertex q, solve eq. (3) on S1 elements, starting from the
//     elements nearest to q (kd-tree) and walking across S1 towards the solution;
//  2. ghost nodes: for every S1 vertex v without a node, cast the ray v + t nu(v) against S2,
//     starting from the S2 elements nearest to v and walking across S2 towards the hit;
//  3. edge preimages: walk across S1 along the preimage of every S2 edge, solving eq. (4) on the
//     edges of the current S1 element(s). Walks start at the preimage of the edge's first vertex
//     and at every point where the edge enters S1 across S1's boundary, and end at the preimage of
//     the second vertex or where the edge leaves S1 across its boundary (then the piece is entered
//     with MapBuilder::add_edge_piece).
// Phases 1-3 compute into per-item slots, in parallel; the builder is then fed sequentially in
// index order, so the result does not depend on the number of threads.

#include "element_index.hpp"
#include "folded_regions.hpp"
#include "image_overlaps.hpp"
#include "unit_scale.hpp"
#include "walk_acceptance.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/face_removal.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/core/snapping.hpp>
#include <plmap/solvers/focal_points.hpp>
#include <plmap/solvers/projection_systems.hpp>
#include <plmap/solvers/small_lu.hpp>
#include <plmap/solvers/solver_kind.hpp>

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>

namespace plmap {

std::string_view to_string(EdgeFailureReason reason) {
  switch (reason) {
    case EdgeFailureReason::discontinuity: return "discontinuity";
    case EdgeFailureReason::solver_failure: return "solver_failure";
    case EdgeFailureReason::distance_limit: return "distance_limit";
    case EdgeFailureReason::vertex_conflict: return "vertex_conflict";
    case EdgeFailureReason::endpoint_without_preimage: return "endpoint_without_preimage";
    case EdgeFailureReason::walk_limit: return "walk_limit";
    case EdgeFailureReason::builder_rejected: return "builder_rejected";
    case EdgeFailureReason::overlap: return "overlap";
    case EdgeFailureReason::fold: return "fold";
  }
  return "unknown";
}

namespace {

using projection::ElementIndex;
using projection::NearestElements;
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
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

enum class VertexState : std::uint8_t { free, corner, ghost };

template <int d>
using Crossing = std::conditional_t<d == 2, EdgeCrossing, VertexCrossing>;

enum class WalkEnd : std::uint8_t { reached, left_boundary, failed };

/// How a walk along the preimage of an S2 edge ended; its crossings are appended to the
/// PlanBuffer it was given.
template <int d>
struct WalkResult {
  WalkEnd end = WalkEnd::failed;
  int crossing_count = 0;
  EdgeFailureReason reason = EdgeFailureReason::discontinuity;
  Place<d> stop;
  double eta = 0.0;
  int steps = 0;
};

/// What phase 3 plans for the S2 edges of one block, in flat arrays owned by one worker thread
/// and reused from block to block: once they have grown, planning allocates nothing per edge or
/// per walk (the per-edge vectors of pieces and crossings this replaces were millions of small
/// allocations).
template <int d>
struct PlanBuffer {
  /// A piece of an S2 edge's preimage: crossings [begin, end) of `crossings`.
  struct Piece {
    std::uint32_t begin, end;
    bool from_first, to_second;
  };
  std::vector<Crossing<d>> crossings;
  std::vector<Piece> pieces;
  std::vector<EdgeNotInserted<d>> failures;
  /// scratch of the walks: the S1 elements at the current point and at the walk's end
  std::vector<Index> candidates, end_elements;

  void clear() {
    crossings.clear();
    pieces.clear();
    failures.clear();
  }
};

/// The plan of one S2 edge: which worker's PlanBuffer holds it and where.
struct PlannedEdge {
  unsigned worker = 0;
  std::uint32_t pieces_begin = 0, pieces_end = 0, failures_begin = 0, failures_end = 0;
  bool outside = false;
};

/// A point where an S2 edge crosses S1's boundary (d = 2: a boundary edge, d = 1: a boundary
/// vertex); a walk from there may enter S1.
template <int d>
struct BoundaryEntry {
  Place<d> place;
  Crossing<d> crossing;
  double eta;
};

template <int d, class Solver>
class Projector {
 public:
  Projector(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
            const ProjectionOptions& options, Solver solver)
      : s1_ptr_(std::move(s1)), s2_ptr_(std::move(s2)), s1_(*s1_ptr_), s2_(*s2_ptr_), opt_(options),
        solver_(solver) {}

  ProjectionResult<d> run() {
    const auto t_total = Clock::now();
    ProjectionReport<d> report;
    auto t0 = Clock::now();
    setup();
    report.seconds.setup = seconds_since(t0);

    // ---- 1. rays from S1 vertices, then vertex preimages -------------------------------------
    // The rays come first (they do not depend on the preimages): their hits on S2 seed the
    // second search for S2 vertices that the search from nearby S1 elements does not map.
    t0 = Clock::now();
    const Index n2v = s2_.vertex_count(), n1v = s1_.vertex_count();
    report_progress(opt_.progress, "rays from S1 vertices", 0, n1v);
    std::vector<std::optional<SurfacePoint<d>>> hit(n1v);
    parallel_for_chunks(n1v, search_chunk, threads_, [&](Index begin, Index end) {
      std::optional<double> mu;  // ray parameter of the previous hit
      NearestElements<d> nearest(*index2_);
      for (Index v = begin; v < end; ++v) hit[v] = cast_ray(v, mu, nearest);
    });
    report.seconds.ghost_nodes = seconds_since(t0);
    report_progress(opt_.progress, "rays from S1 vertices", n1v, n1v);

    t0 = Clock::now();
    report_progress(opt_.progress, "S2 vertex preimages", 0, n2v);
    std::vector<std::optional<SurfacePoint<d>>> preimage(n2v);
    parallel_for_chunks(n2v, search_chunk, threads_, [&](Index begin, Index end) {
      SearchOffset offset;  // target minus preimage of the previous vertex found
      NearestElements<d> nearest(*index1_);
      for (Index q = begin; q < end; ++q) {
        // an isolated S2 vertex (no element) is not part of S2: it needs no preimage
        if (s2_.vertex_elements(q).empty()) continue;
        preimage[q] = find_vertex_preimage(q, offset, nearest);
        offset.valid = preimage[q].has_value();
        if (offset.valid)
          offset.value = s2_.vertex(q) - s1_.world_position(preimage[q]->element, preimage[q]->local);
      }
    });
    report.vertices_found_by_ray_hits = find_remaining_preimages_from_hits(hit, preimage);
    report.seconds.vertex_preimages = seconds_since(t0);
    report_progress(opt_.progress, "S2 vertex preimages", n2v, n2v);

    t0 = Clock::now();
    BuilderOptions bopt;
    bopt.snap_tolerance = opt_.snap_tolerance;
    bopt.orientation = opt_.orientation;
    bopt.threads = threads_;
    // Where the projection folds, preimages of S2 edges cross on S1; those edges are left out
    // and reported (EdgeFailureReason::overlap) instead of losing the whole map.
    bopt.drop_conflicting_edges = true;
    MapBuilder<d> builder(s1_ptr_, s2_ptr_, bopt);
    target_place_.assign(n2v, std::nullopt);
    if constexpr (d == 2) used_first_.assign(s1_.edge_count(), invalid_index);
    crossed_vertex_.assign(n1v, invalid_index);
    vertex_state_.assign(n1v, VertexState::free);
    vertex_image_.assign(n1v, std::nullopt);
    report.target_vertices = n2v;
    report.domain_vertices = n1v;
    // target_place_ first holds every preimage's place; those that are not inserted lose it below
    for (Index q = 0; q < n2v; ++q)
      if (preimage[q]) target_place_[q] = place_of(*preimage[q]);
    const std::vector<bool> loses = coincident_preimage_losers();
    for (Index q = 0; q < n2v; ++q) {
      if (!preimage[q]) continue;
      const Place<d> place = *target_place_[q];
      if (loses[q] || (place.kind == PlaceKind::vertex && vertex_state_[place.index] != VertexState::free)) {
        ++report.vertex_conflicts;
        target_place_[q].reset();
        continue;
      }
      builder.add_vertex_preimage(q, {preimage[q]->element, place_local(*preimage[q])});
      if constexpr (d == 2)
        if (place.kind == PlaceKind::edge) add_used_parameter(place.index, place.t, -1 - q);
      ++report.vertex_preimages;
      if (place.kind == PlaceKind::vertex) {
        vertex_state_[place.index] = VertexState::corner;
        vertex_image_[place.index] = SurfacePoint<d>{s2_.vertex_elements(q).front(),
                                                     local_of_corner(s2_, s2_.vertex_elements(q).front(), q)};
      }
    }
    report.seconds.insertion += seconds_since(t0);
    std::vector<std::optional<SurfacePoint<d>>>().swap(preimage);

    // ---- 2. ghost nodes ------------------------------------------------------------------------
    // S1 vertices that became preimages of S2 vertices in phase 1 are no longer free.
    t0 = Clock::now();
    for (Index v = 0; v < n1v; ++v) {
      if (!hit[v] || vertex_state_[v] != VertexState::free) continue;
      Barycentric<d> b = clean_barycentric(hit[v]->local);
      int at_vertex = -1;
      for (int k = 0; k <= d; ++k)
        if (b(k) == 1.0) at_vertex = k;
      const SurfacePoint<d> image{hit[v]->element, local_from_barycentric<d>(b)};
      if (at_vertex >= 0) {
        const Index q = s2_.element(hit[v]->element)[at_vertex];
        if (target_place_[q]) {
          ++report.ghost_conflicts;
          continue;
        }
        builder.add_ghost_node(v, image);  // becomes the preimage of q (a corner node)
        Place<d> p;
        p.kind = PlaceKind::vertex;
        p.index = v;
        target_place_[q] = p;
        vertex_state_[v] = VertexState::corner;
        ++report.vertices_mapped_by_ray;
        ++report.vertex_preimages;
      } else {
        builder.add_ghost_node(v, image);
        vertex_state_[v] = VertexState::ghost;
        ++report.ghost_nodes;
      }
      vertex_image_[v] = image;
    }
    report.seconds.insertion += seconds_since(t0);
    std::vector<std::optional<SurfacePoint<d>>>().swap(hit);

    // ---- 3. edge preimages ---------------------------------------------------------------------
    t0 = Clock::now();
    const Index n2e = s2_.edge_count();
    report_progress(opt_.progress, "S2 edges", 0, n2e);
    entries_.assign(n2e, {});
    find_boundary_entries();
    for (const auto& list : entries_) report.boundary_entries += static_cast<Index>(list.size());
    report.seconds.edge_walks += seconds_since(t0);

    report.target_edges = n2e;
    // per edge: bit 31 set if inserted whole, the lower bits count the pieces inserted
    std::vector<std::uint32_t> counted(n2e, 0);
    plan_and_insert_edges(builder, report, counted);
    // what the projection no longer needs, freed before finalize (which has the memory peak);
    // the directions are kept for the fold test of the finished regions
    const std::vector<WorldPoint<d>> directions = std::move(nu_);
    release_search_data();

    t0 = Clock::now();
    report_progress(opt_.progress, "finalize", 0, 1);
    FinalizeReport dropped;
    PlMap<d> map = std::move(builder).finalize(&dropped);
    // faces closed on an element where the ray of a ghost node accepted from another element at
    // its vertex is folded (folded_regions.hpp)
    if (const std::vector<Index> folded = projection::regions_with_folded_corners<d>(map, directions, threads_);
        !folded.empty()) {
      FaceRemovalReport removal;
      map = remove_faces(map, std::span<const Index>(folded), &removal);
      report.folded_faces = removal.removed_faces;
      report.folded_regions = removal.removed_regions;
    }
    // The image measures give the covered measures and show where images overlap on S2: two
    // sheets of S1 whose rays reach the same part of S2, of which the farther one leaves D.
    ImageMeasures images = image_measures(map, threads_);
    if (opt_.keep_nearer_sheet) {
      const std::vector<Index> farther = projection::farther_overlapping_regions(map, images);
      if (!farther.empty()) {
        FaceRemovalReport removal;
        map = remove_faces(map, std::span<const Index>(farther), &removal);
        report.occluded_faces = removal.removed_faces;
        report.occluded_regions = removal.removed_regions;
        images = image_measures(map, threads_);
      }
    }
    report.seconds.finalize = seconds_since(t0);
    report.reversed_faces = dropped.reversed_faces;
    for (std::size_t i = 0; i < dropped.dropped_edges.size(); ++i) {
      const Index e = dropped.dropped_edges[i];
      const Index pieces = static_cast<Index>(counted[e] & ~inserted_whole);
      if (counted[e] & inserted_whole) --report.edges_inserted;
      if (pieces > 0) --report.edges_partly_inserted;
      report.edge_pieces -= pieces;
      EdgeNotInserted<d> f;
      f.target_edge = e;
      f.reason = EdgeFailureReason::overlap;
      f.domain_element = dropped.dropped_edge_element[i];
      f.domain_point = s1_.world_position(f.domain_element, LocalPoint<d>::Constant(1.0 / (d + 1)));
      f.detail = "its preimage crosses another edge's preimage, runs through a node, or meets this S1 "
                 "element twice: the projection is not injective or not continuous there";
      report.edges_not_inserted.push_back(std::move(f));
    }

    report.solver_calls = solver_calls_.load();
    report.solver_failures = solver_failures_.load();
    ProjectionMeasures measures;
    measures.domain = s1_.measure();
    measures.target = s2_.measure();
    measures.covered_domain = images.covered.domain;
    measures.covered_target = images.covered.target;
    report.seconds.total = seconds_since(t_total);
    report_progress(opt_.progress, "finalize", 1, 1);
    return ProjectionResult<d>{std::move(map), std::move(report), measures};
  }

 private:
  // ---- set-up -------------------------------------------------------------------------------------
  void setup() {
    nu_ = opt_.directions.empty() ? averaged_vertex_normals(s1_)
                                  : directions_from_values(s1_, std::span<const double>(opt_.directions));
    if (opt_.normal_check != TargetNormalCheck::none) n2_ = averaged_vertex_normals(s2_);
    const double diagonal = (s1_.bounding_box_max() - s1_.bounding_box_min()).norm();
    limit_ = opt_.max_distance_is_relative ? opt_.max_distance * diagonal : opt_.max_distance;
    if (!(limit_ >= 0.0)) throw Error(fmt::format("max_distance {} is not >= 0", opt_.max_distance));
    seeds_ = std::clamp(opt_.search_seeds, 1, 32);
    threads_ = resolve_thread_count(opt_.threads);
    index1_ = std::make_unique<ElementIndex<d>>(s1_);
    index2_ = std::make_unique<ElementIndex<d>>(s2_);
    const ProjectionSearchLimits& limits = opt_.search_limits;
    if (!(limits.seed_walk_steps > 0) || !(limits.edge_walk_steps >= 0) || !(limits.inside_tolerance >= 0.0) ||
        !(limits.inside_tolerance < 0.5) || !(limits.edge_parameter_slack >= 0.0) ||
        !(limits.edge_parameter_slack < 0.5) || !(limits.second_search_hits > 0) ||
        !(limits.second_search_hits <= 32) || !(limits.second_search_reach >= 0.0) ||
        !(limits.farther_hit_retry >= 0.0))
      throw Error(fmt::format(
          "projection search limits out of range (seed_walk_steps {} > 0, edge_walk_steps {} >= 0, "
          "inside_tolerance {} and edge_parameter_slack {} in [0, 0.5), second_search_hits {} in 1..32, "
          "second_search_reach {} and farther_hit_retry {} >= 0)",
          limits.seed_walk_steps, limits.edge_walk_steps, limits.inside_tolerance, limits.edge_parameter_slack,
          limits.second_search_hits, limits.second_search_reach, limits.farther_hit_retry));
    walk_limit_ = limits.edge_walk_steps > 0 ? limits.edge_walk_steps : 2 * static_cast<int>(s1_.element_count()) + 16;
    focal_free_.resize(s1_.element_count());
    parallel_ranges(s1_.element_count(), threads_, [&](std::size_t begin, std::size_t end) {
      for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t) {
        std::array<WorldPoint<d>, d + 1> corners, directions;
        for (int k = 0; k <= d; ++k) {
          corners[k] = s1_.corner(t, k);
          directions[k] = nu_[s1_.element(t)[k]];
        }
        focal_free_[t] = focal_free_distance<d>(corners, directions);
      }
    });
  }

  // ---- helpers on places ------------------------------------------------------------------------
  // The snapping rule is core/snapping.hpp's, the one MapBuilder applies to what it is given.
  Barycentric<d> clean_barycentric(const LocalPoint<d>& xi) const {
    return snap_barycentric<d>(barycentric_from_local<d>(xi), opt_.snap_tolerance);
  }

  LocalPoint<d> place_local(const SurfacePoint<d>& p) const {
    return local_from_barycentric<d>(clean_barycentric(p.local));
  }

  static LocalPoint<d> local_of_corner(const Surface<d>& s, Index t, Index v) {
    return reference_corner<d>(s.local_corner(t, v));
  }

  Place<d> place_of(const SurfacePoint<d>& p) const {
    const Barycentric<d> b = clean_barycentric(p.local);
    std::array<int, d + 1> which{};
    int nonzero = 0;
    for (int k = 0; k <= d; ++k)
      if (b(k) > 0.0) which[nonzero++] = k;
    Place<d> place;
    const auto& c = s1_.element(p.element);
    if (nonzero == 1) {
      place.kind = PlaceKind::vertex;
      place.index = c[which[0]];
    } else if (nonzero == 2 && d == 2) {
      if constexpr (d == 2) {
        place.kind = PlaceKind::edge;
        const Index u = c[which[0]], v = c[which[1]];
        place.index = s1_.find_edge(u, v);
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
    const auto ev = s1_.edge_vertices(edge);
    const EdgeSnap snap = snap_edge_parameter(lambda, opt_.snap_tolerance);
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

  void elements_of(const Place<d>& p, std::vector<Index>& out) const {
    out.clear();
    if (p.kind == PlaceKind::vertex) {
      const auto star = s1_.vertex_elements(p.index);
      out.assign(star.begin(), star.end());
    } else if (p.kind == PlaceKind::edge) {
      if constexpr (d == 2)
        for (const auto& inc : s1_.edge_elements(p.index)) out.push_back(inc.element);
    } else {
      out.push_back(p.index);
    }
  }

  WorldPoint<d> world_of(const Place<d>& p) const {
    if (p.kind == PlaceKind::vertex) return s1_.vertex(p.index);
    if constexpr (d == 2)
      if (p.kind == PlaceKind::edge) {
        const auto ev = s1_.edge_vertices(p.index);
        return (1.0 - p.t) * s1_.vertex(ev[0]) + p.t * s1_.vertex(ev[1]);
      }
    return s1_.world_position(p.index, p.local);
  }

  bool distance_ok(double mu, double scale) const {
    const double slack = 1e-9 * scale;
    if (!opt_.allow_negative_distance && mu < -slack) return false;
    return std::abs(mu) <= limit_ + slack;
  }

  double rank(double mu) const { return opt_.allow_negative_distance ? std::abs(mu) : std::max(mu, 0.0); }

  /// The ray from local point xi of S1 element t reaches distance mu before any focal point of
  /// the direction field (solvers/focal_points.hpp): beyond one the projection is folded.
  bool unfolded_in(Index t, const LocalPoint<d>& xi, double mu) const {
    return std::abs(mu) <= focal_free_[t] || reaches_without_focal_point_in(t, xi, mu);
  }

  /// The focal test itself, for distances beyond the element's focal-free distance.
  bool reaches_without_focal_point_in(Index t, const LocalPoint<d>& xi, double mu) const {
    std::array<WorldPoint<d>, d + 1> corners, directions;
    for (int k = 0; k <= d; ++k) {
      corners[k] = s1_.corner(t, k);
      directions[k] = nu_[s1_.element(t)[k]];
    }
    return reaches_without_focal_point<d>(corners, directions, xi, mu);
  }

  /// The focal test for the ray from place p (a vertex, edge or interior point of S1) as a
  /// point of element t, which contains it.
  bool unfolded_in_at(Index t, const Place<d>& p, double mu) const {
    if (std::abs(mu) <= focal_free_[t]) return true;
    if (p.kind == PlaceKind::element) return reaches_without_focal_point_in(t, p.local, mu);
    if (p.kind == PlaceKind::vertex) return reaches_without_focal_point_in(t, local_of_corner(s1_, t, p.index), mu);
    if constexpr (d == 2) {
      const auto ev = s1_.edge_vertices(p.index);
      Barycentric<2> b = Barycentric<2>::Zero();
      b(s1_.local_corner(t, ev[0])) = 1.0 - p.t;
      b(s1_.local_corner(t, ev[1])) = p.t;
      return reaches_without_focal_point_in(t, local_from_barycentric<2>(b), mu);
    }
    return true;
  }

  /// The same for a ray from an S1 vertex or edge point: it must be unfolded in every element
  /// that contains the point, since the regions on all of them end there.
  bool unfolded_at(const Place<d>& p, double mu) const {
    if (p.kind == PlaceKind::element) return unfolded_in(p.index, p.local, mu);
    const double distance = std::abs(mu);
    if (p.kind == PlaceKind::vertex) {
      for (Index t : s1_.vertex_elements(p.index))
        if (!(distance <= focal_free_[t]) && !reaches_without_focal_point_in(t, local_of_corner(s1_, t, p.index), mu))
          return false;
      return true;
    }
    if constexpr (d == 2) {
      const auto ev = s1_.edge_vertices(p.index);
      for (const auto& incidence : s1_.edge_elements(p.index)) {
        const Index t = incidence.element;
        if (distance <= focal_free_[t]) continue;
        Barycentric<2> b = Barycentric<2>::Zero();
        b(s1_.local_corner(t, ev[0])) = 1.0 - p.t;
        b(s1_.local_corner(t, ev[1])) = p.t;
        if (!reaches_without_focal_point_in(t, local_from_barycentric<2>(b), mu)) return false;
      }
    }
    return true;
  }

  /// The ghost ray from S1 vertex v reaches distance mu unfolded in at least one element at v
  /// (walk_acceptance.hpp: the per-element rule of the walks and the ray check).
  bool ghost_ray_unfolded(Index v, double mu) const {
    return projection::unfolded_in_some_element(s1_.vertex_elements(v), [&](Index t) {
      return std::abs(mu) <= focal_free_[t] || reaches_without_focal_point_in(t, local_of_corner(s1_, t, v), mu);
    });
  }

  bool normal_ok(const WorldPoint<d>& direction, const WorldPoint<d>& target_normal) const {
    if (opt_.normal_check == TargetNormalCheck::none) return true;
    const double c = direction.dot(target_normal);
    return opt_.normal_check == TargetNormalCheck::facing ? c < 0.0 : c > 0.0;
  }

  /// The element across the facet opposite corner k of element t on surface s, if exactly one.
  static Index across(const Surface<d>& s, Index t, int k) {
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

  // ---- insertion: points of S1 already taken ------------------------------------------------------
  /// Two S2 edges whose preimages cross an S1 edge (or pass an S1 vertex) at the same point would
  /// give the builder two nodes at one point (it throws in finalize), and the map could not be
  /// injective there: S2 edges meet only at S2 vertices. This happens where the directions are
  /// tangential to S2 (S2 perpendicular to S1, a vertical wall): edges of S2 then project onto
  /// the same curve. The first edge (in index order, so independent of threads) keeps the point;
  /// a later piece through it is reported, not inserted.
  struct UsedPoint {
    Index element;
    WorldPoint<d> point;
    std::string detail;
  };

  std::optional<UsedPoint> find_used_point(std::span<const Crossing<d>> crossings) const {
    for (const auto& c : crossings) {
      Index vertex = invalid_index;
      if constexpr (d == 2) {
        const auto ev = s1_.edge_vertices(c.domain_edge);
        const EdgeSnap snap = snap_edge_parameter(c.domain_parameter, opt_.snap_tolerance);
        if (snap == EdgeSnap::first_vertex) vertex = ev[0];
        else if (snap == EdgeSnap::second_vertex) vertex = ev[1];
        else {
          for (Index i = used_first_[c.domain_edge]; i != invalid_index; i = used_parameters_[i].next)
            if (const Index owner = used_parameters_[i].owner;
                std::abs(used_parameters_[i].t - c.domain_parameter) <= opt_.snap_tolerance) {
              const Place<d> at = edge_place(c.domain_edge, c.domain_parameter);
              return UsedPoint{s1_.edge_elements(c.domain_edge).front().element, world_of(at),
                               fmt::format("its preimage meets {} on S1 edge {} at {:.17g}: the projection is not "
                                           "injective there (directions tangential to S2?)",
                                           owner < 0 ? fmt::format("the preimage of S2 vertex {}", -1 - owner)
                                                     : fmt::format("the preimage of S2 edge {}", owner),
                                           c.domain_edge, c.domain_parameter)};
            }
          continue;
        }
      } else {
        vertex = c.domain_vertex;
      }
      if (crossed_vertex_[vertex] != invalid_index)
        return UsedPoint{s1_.vertex_elements(vertex).front(), s1_.vertex(vertex),
                         fmt::format("its preimage passes S1 vertex {}, which the preimage of S2 {} {} passes too: "
                                     "the projection is not injective there (directions tangential to S2?)",
                                     vertex, d == 2 ? "edge" : "segment", crossed_vertex_[vertex])};
    }
    return std::nullopt;
  }

  void mark_used_points(std::span<const Crossing<d>> crossings, Index e) {
    for (const auto& c : crossings) {
      if constexpr (d == 2) {
        const auto ev = s1_.edge_vertices(c.domain_edge);
        const EdgeSnap snap = snap_edge_parameter(c.domain_parameter, opt_.snap_tolerance);
        if (snap == EdgeSnap::first_vertex) crossed_vertex_[ev[0]] = e;
        else if (snap == EdgeSnap::second_vertex) crossed_vertex_[ev[1]] = e;
        else add_used_parameter(c.domain_edge, c.domain_parameter, e);
      } else {
        crossed_vertex_[c.domain_vertex] = e;
      }
    }
  }

  /// Appends to S1 edge `edge`'s list of used parameters (see used_first_).
  void add_used_parameter(Index edge, double t, Index owner) {
    const Index entry = static_cast<Index>(used_parameters_.size());
    used_parameters_.push_back({t, owner, invalid_index});
    Index* link = &used_first_[edge];
    while (*link != invalid_index) link = &used_parameters_[*link].next;
    *link = entry;
  }

  // ---- phase 1: eq. (3) ---------------------------------------------------------------------------
  /// Several S2 vertices can project onto the same point of S1 when the directions are tangential
  /// to S2 (a vertical wall over S1, S2 standing on S1): the builder cannot hold two nodes at one
  /// point (it throws in finalize), and the map could not be injective anyway. Among preimages that
  /// coincide under the snapping rule, the one whose S2 vertex is nearest (smallest |mu|, then the
  /// smallest index) is kept; the others are marked here and counted as vertex conflicts, and
  /// their edges are reported by the walks. Preimages on the same S1 vertex keep the old rule
  /// (first come), which gives the same winner as long as only one of them is nearest.
  /// Reads the places of all preimages from target_place_.
  std::vector<bool> coincident_preimage_losers() const {
    // Group the preimages by the S1 edge or element they lie on (a counting sort: almost every
    // group has a single member, which keeps its place without further work).
    const Index n2v = static_cast<Index>(target_place_.size());
    const Index edge_keys = d == 2 ? s1_.edge_count() : 0;
    auto key = [&](const Place<d>& p) { return p.kind == PlaceKind::edge ? p.index : edge_keys + p.index; };
    std::vector<Index> group_begin(static_cast<std::size_t>(edge_keys + s1_.element_count()) + 1, 0);
    auto grouped = [&](Index q) { return target_place_[q] && target_place_[q]->kind != PlaceKind::vertex; };
    for (Index q = 0; q < n2v; ++q)
      if (grouped(q)) ++group_begin[key(*target_place_[q]) + 1];
    for (std::size_t k = 1; k < group_begin.size(); ++k) group_begin[k] += group_begin[k - 1];
    std::vector<Index> members(static_cast<std::size_t>(group_begin.back()));
    {
      std::vector<Index> cursor(group_begin.begin(), group_begin.end() - 1);
      for (Index q = 0; q < n2v; ++q)
        if (grouped(q)) members[cursor[key(*target_place_[q])]++] = q;
    }
    std::vector<bool> loses(target_place_.size(), false);
    struct Item {
      double distance;
      Index q;
    };
    std::vector<Item> group;
    std::vector<const Place<d>*> kept;
    for (std::size_t g = 0; g + 1 < group_begin.size(); ++g) {
      if (group_begin[g + 1] - group_begin[g] < 2) continue;
      // within one S1 edge or element, nearest first (then the smallest q): a point loses if it
      // coincides with a kept one
      group.clear();
      for (Index i = group_begin[g]; i < group_begin[g + 1]; ++i) {
        const Index q = members[i];
        group.push_back({(s2_.vertex(q) - world_of(*target_place_[q])).norm(), q});
      }
      std::sort(group.begin(), group.end(), [](const Item& a, const Item& b) {
        return a.distance != b.distance ? a.distance < b.distance : a.q < b.q;
      });
      kept.clear();
      for (const Item& item : group) {
        const Place<d>& place = *target_place_[item.q];
        const bool same = std::any_of(kept.begin(), kept.end(), [&](const Place<d>* w) {
          const double gap = place.kind == PlaceKind::edge
                                 ? std::abs(place.t - w->t)
                                 : (place.local - w->local).template lpNorm<Eigen::Infinity>();
          return gap <= opt_.snap_tolerance;
        });
        if (same)
          loses[item.q] = true;
        else
          kept.push_back(&place);
      }
    }
    return loses;
  }

  // ---- seeds of the searches of phases 1 and 2 -------------------------------------------------
  // Both phases start their walks from the elements whose centroids are nearest to a point. For
  // the point itself, a kd-tree query costs O(gap / h) leaves when the point lies a gap of many
  // element sizes away from the indexed surface (nanoflann bounds a subtree by its partition
  // cell, which reaches right up to the query), e.g. 1,600 segment lengths on the 1M circles.
  // Neighbouring items of a chunk have nearly the same offset to the other surface, so the
  // search first asks for the centroids nearest to the point moved by the previous item's
  // offset, which lies next to the indexed surface; only if that finds nothing does it ask
  // at the point itself. Chunks have a fixed size, so the seeds, and the result, do not depend
  // on the thread count.
  static constexpr Index search_chunk = 256;

  /// The k elements nearest to x; for the moved seed points of a curve from `nearest`. Along a
  /// curve the moved seed points of consecutive items follow each other, and most answers come
  /// from the centroids kept from an earlier, wider query. On a surface the vertex order is at
  /// best row by row, and a wide query covers too few of the following points to pay (3 answers
  /// from 21,000 queries on the L5 spheres): there the tree answers every query.
  static int nearest_seeds(const ElementIndex<d>& index, NearestElements<d>* nearest, const WorldPoint<d>& x, int k,
                           std::array<std::uint32_t, 32>& seeds) {
    if (d == 1 && nearest) return nearest->nearest(x, k, seeds);
    std::array<double, 32> squared_distances;
    return index.nearest(x, k, seeds.data(), squared_distances.data());
  }

  /// A plain flag and value rather than std::optional, on which GCC 12 warns falsely
  /// (maybe-uninitialized) for Eigen members.
  struct SearchOffset {
    bool valid = false;
    WorldPoint<d> value = WorldPoint<d>::Zero();
  };

  std::optional<SurfacePoint<d>> find_vertex_preimage(Index q, const SearchOffset& offset,
                                                      NearestElements<d>& nearest) {
    bool solver_failed = false;
    if (offset.valid) {
      auto found = find_vertex_preimage(q, s2_.vertex(q) - offset.value, seeds_, solver_failed, &nearest);
      if (found) return found;
    }
    return find_vertex_preimage(q);
  }

  std::optional<SurfacePoint<d>> find_vertex_preimage(Index q) {
    bool solver_failed = false;
    auto found = find_vertex_preimage(q, s2_.vertex(q), seeds_, solver_failed, nullptr);
    // The elements nearest to q may all be tangential to the directions (eq. 3 is singular there),
    // e.g. the horizontal sheets of a T-junction when the vertical sheet is the one that sees S2:
    // their walks end at once, before reaching the element that holds the preimage. Only then is
    // the search repeated from more seeds, so the usual case costs nothing extra.
    if (!found && solver_failed && seeds_ < 32)
      found = find_vertex_preimage(q, s2_.vertex(q), 32, solver_failed, nullptr);
    return found;
  }

  /// Eq. (3) for S2 vertex q on walks across S1 that start at the `seed_count` elements nearest
  /// to `seed_point` (found with `nearest` for the moved seed points, which follow each other
  /// closely, else with the kd-tree).
  std::optional<SurfacePoint<d>> find_vertex_preimage(Index q, const WorldPoint<d>& seed_point, int seed_count,
                                                      bool& solver_failed, NearestElements<d>* nearest) {
    std::array<std::uint32_t, 32> seeds;
    int count = nearest_seeds(*index1_, nearest, seed_point, seed_count, seeds);
    count = add_long_elements_through(seed_point, seeds, count);
    return walk_to_preimage(q, seeds, count, solver_failed);
  }

  /// The nearest centroids miss an element that passes right by x when its centroid lies
  /// farther than theirs (a long element among short ones: the steep sides of a zigzag curve),
  /// and the walks from the seeds stop at the first element that holds a solution, which may rank
  /// worse than the one on the missed element (an S2 vertex on S1 then takes a preimage off
  /// itself). Such elements are added as seeds, nearest centroid first, up to 32: those whose
  /// bounding box lies nearer to x than the nearest seed's centroid. Every element within that
  /// distance of x has its centroid within it plus the largest centroid-to-corner distance, and
  /// on meshes of even element size those are seeds already, so this adds none and costs no query.
  int add_long_elements_through(const WorldPoint<d>& x, std::array<std::uint32_t, 32>& seeds, int count) const {
    if (count == 0 || count >= 32) return count;
    double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
    for (int i = 0; i < count; ++i) {
      const double squared = index1_->squared_distance(x, seeds[i]);
      nearest = std::min(nearest, squared);
      farthest = std::max(farthest, squared);
    }
    nearest = std::sqrt(nearest);
    // The seeds are the nearest centroids: if they reach beyond that bound, or are all there are,
    // every candidate is a seed already (the usual case, at the cost of no tree query).
    if (count >= index1_->size() || std::sqrt(farthest) > nearest + index1_->radius) return count;
    std::vector<std::pair<double, Index>> added;
    for (Index t : index1_->within(x, nearest + index1_->radius)) {
      if (std::find(seeds.begin(), seeds.begin() + count, static_cast<std::uint32_t>(t)) != seeds.begin() + count)
        continue;
      WorldPoint<d> low = s1_.corner(t, 0), high = low;
      for (int k = 1; k <= d; ++k) {
        low = low.cwiseMin(s1_.corner(t, k));
        high = high.cwiseMax(s1_.corner(t, k));
      }
      const double box_distance = (x.cwiseMax(low).cwiseMin(high) - x).norm();
      if (box_distance < nearest) added.emplace_back(index1_->squared_distance(x, static_cast<std::uint32_t>(t)), t);
    }
    std::sort(added.begin(), added.end());
    for (const auto& [unused, t] : added) {
      if (count == 32) break;
      seeds[count++] = static_cast<std::uint32_t>(t);
    }
    return count;
  }

  /// Eq. (3) for S2 vertex q on walks across S1 from the first `count` of `seeds`: the solution
  /// of least rank among those that pass every check, or nothing.
  std::optional<SurfacePoint<d>> walk_to_preimage(Index q, const std::array<std::uint32_t, 32>& seeds, int count,
                                                  bool& solver_failed) {
    const WorldPoint<d>& target = s2_.vertex(q);
    std::optional<SurfacePoint<d>> best;
    double best_rank = std::numeric_limits<double>::infinity();
    std::array<Index, 64> visited;
    int nvisited = 0;
    long long calls = 0, failures = 0;
    for (int s = 0; s < count; ++s) {
      Index t = static_cast<Index>(seeds[s]);
      for (int step = 0; step < opt_.search_limits.seed_walk_steps && t != invalid_index; ++step) {
        if (std::find(visited.begin(), visited.begin() + nvisited, t) != visited.begin() + nvisited) break;
        if (nvisited < 64) visited[nvisited++] = t;
        VertexProjectionSystem<d> sys;
        for (int k = 0; k <= d; ++k) {
          sys.corners[k] = s1_.corner(t, k);
          sys.directions[k] = nu_[s1_.element(t)[k]];
        }
        sys.target = target;
        ++calls;
        const auto r = solver_.solve(sys, sys.initial_guess());
        if (!r.converged) {
          ++failures;
          break;
        }
        const LocalPoint<d> xi = r.x.template head<d>();
        const Barycentric<d> b = barycentric_from_local<d>(xi);
        int worst = 0;
        for (int k = 1; k <= d; ++k)
          if (b(k) < b(worst)) worst = k;
        if (b(worst) >= -opt_.search_limits.inside_tolerance) {
          const double mu = r.x(d);
          WorldPoint<d> direction = sys.directions[0];
          for (int k = 0; k < d; ++k) direction += xi(k) * (sys.directions[k + 1] - sys.directions[0]);
          if (distance_ok(mu, sys.scale()) && (n2_.empty() || normal_ok(direction, n2_[q])) &&
              rank(mu) < best_rank && unfolded_in(t, xi, mu)) {
            best_rank = rank(mu);
            Barycentric<d> bc = b.cwiseMax(0.0);
            bc /= bc.sum();
            best = SurfacePoint<d>{t, local_from_barycentric<d>(bc)};
          }
          break;
        }
        t = across(s1_, t, worst);
      }
    }
    solver_calls_ += calls;
    solver_failures_ += failures;
    solver_failed = failures > 0;
    return best;
  }

  /// Whether the rays from the corners of S1 element t all hit S2 and their hits span a simplex
  /// of the element's orientation (seen along the mean direction). Preimages found by the second
  /// search must pass this: where rays have crossed (beyond a focal line of the field, which a
  /// twisted discrete field can hide from the focal test, whose polynomial then has no real
  /// root) the hits are mirrored, and such an element does not see S2 as a sheet.
  bool rays_keep_orientation(Index t, const projection::PointCloud<d + 1>& hits,
                             const std::vector<Index>& hit_id) const {
    std::array<WorldPoint<d>, d + 1> c, h;
    WorldPoint<d> direction = WorldPoint<d>::Zero();
    for (int k = 0; k <= d; ++k) {
      const Index v = s1_.element(t)[k];
      if (hit_id[v] == invalid_index) return false;
      c[k] = s1_.vertex(v);
      h[k] = hits.points[hit_id[v]];
      direction += nu_[v];
    }
    const auto side = [&](const std::array<WorldPoint<d>, d + 1>& p) {
      if constexpr (d == 2)
        return (p[1] - p[0]).cross(p[2] - p[0]).dot(direction);
      else
        return (p[1] - p[0]).x() * direction.y() - (p[1] - p[0]).y() * direction.x();
    };
    return side(c) * side(h) > 0.0;
  }

  /// The second search, for the S2 vertices that find_vertex_preimage left without a preimage;
  /// returns how many it maps. The first search walks from the S1 elements whose centroids lie
  /// nearest to q, and those can all lie on a sheet of S1 that is nearer to S2 but does not
  /// reach q (a body above a wider one: the upper body's elements are the nearest to every S2
  /// vertex above both). The rays know better: an S1 vertex whose ray hits S2 next to q lies on
  /// a sheet that sees q, so here the walks start from the stars of the S1 vertices with the
  /// hits nearest to q. A hit farther from q than the largest distance between the hits of two
  /// corners of an element around its vertex (with a margin) cannot belong to an element holding
  /// q's preimage and is not tried, so S2 vertices far outside S1's shadow cost one tree query.
  Index find_remaining_preimages_from_hits(const std::vector<std::optional<SurfacePoint<d>>>& hit,
                                           std::vector<std::optional<SurfacePoint<d>>>& preimage) {
    std::vector<Index> missing;
    for (Index q = 0; q < s2_.vertex_count(); ++q)
      if (!preimage[q] && !s2_.vertex_elements(q).empty()) missing.push_back(q);
    if (missing.empty()) return 0;
    // the hits as a point cloud, and the S1 vertex of each
    projection::PointCloud<d + 1> cloud;
    std::vector<Index> hit_vertex, cloud_id(s1_.vertex_count(), invalid_index);
    for (Index v = 0; v < s1_.vertex_count(); ++v) {
      if (!hit[v]) continue;
      cloud_id[v] = static_cast<Index>(cloud.points.size());
      cloud.points.push_back(s2_.world_position(hit[v]->element, hit[v]->local));
      hit_vertex.push_back(v);
    }
    if (cloud.points.empty()) return 0;
    // reach[i]: 1.5 times the largest distance between the hits of two corners of an element
    // around the S1 vertex of hit i (a local bound: grazing rays elsewhere do not widen it)
    std::vector<double> reach(cloud.points.size(), 0.0);
    for (Index t = 0; t < s1_.element_count(); ++t) {
      const auto corners = s1_.element(t);
      double diameter = 0.0;
      for (int a = 0; a <= d; ++a)
        for (int b = a + 1; b <= d; ++b) {
          const Index ia = cloud_id[corners[a]], ib = cloud_id[corners[b]];
          if (ia != invalid_index && ib != invalid_index)
            diameter = std::max(diameter, (cloud.points[ia] - cloud.points[ib]).norm());
        }
      for (Index v : corners)
        if (cloud_id[v] != invalid_index)
          reach[cloud_id[v]] = std::max(reach[cloud_id[v]], opt_.search_limits.second_search_reach * diameter);
    }
    const projection::KdTree<d + 1> tree(d + 1, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    std::vector<std::optional<SurfacePoint<d>>> found(missing.size());
    parallel_for_chunks(missing.size(), search_chunk, threads_, [&](Index begin, Index end) {
      const int nearest_hits = opt_.search_limits.second_search_hits;
      for (Index i = begin; i < end; ++i) {
        const Index q = missing[i];
        std::array<std::uint32_t, 32> ids;
        std::array<double, 32> squared;
        const int n = static_cast<int>(tree.knnSearch(s2_.vertex(q).data(), nearest_hits, ids.data(), squared.data()));
        std::array<std::uint32_t, 32> seeds;
        int count = 0;
        for (int j = 0; j < n; ++j) {
          if (!(squared[j] <= reach[ids[j]] * reach[ids[j]])) continue;
          for (Index t : s1_.vertex_elements(hit_vertex[ids[j]]))
            if (count < 32 && std::find(seeds.begin(), seeds.begin() + count, t) == seeds.begin() + count)
              seeds[count++] = static_cast<std::uint32_t>(t);
        }
        if (count == 0) continue;
        bool solver_failed = false;
        found[i] = walk_to_preimage(q, seeds, count, solver_failed);
        if (found[i] && !rays_keep_orientation(found[i]->element, cloud, cloud_id)) found[i].reset();
      }
    });
    Index mapped = 0;
    for (std::size_t i = 0; i < missing.size(); ++i)
      if (found[i]) {
        preimage[missing[i]] = found[i];
        ++mapped;
      }
    return mapped;
  }

  // ---- phase 2: rays from S1 vertices ---------------------------------------------------------------
  /// The ray from S1 vertex v; `mu` is the ray parameter of the chunk's previous hit (see
  /// search_chunk), updated on return.
  std::optional<SurfacePoint<d>> cast_ray(Index v, std::optional<double>& mu, NearestElements<d>& nearest) {
    const WorldPoint<d>& direction = nu_[v];
    std::optional<SurfacePoint<d>> hit;
    // Seeds next to the previous vertex's hit (v moved by its ray parameter) are for S2 many
    // element sizes away, where a search from v visits O(gap / h) kd-tree leaves. They lie on
    // the sheet of S2 that the previous ray reached, and a nearer sheet that this ray meets
    // first is found only from the elements nearest to v (the bones of a joint, whose gap is
    // smaller than an edge; the previous ray may have passed beside that sheet). So within
    // `farther_hit_retry` longest edges of v the search starts from v (as cheap there), and
    // beyond, a hit that jumped away from the previous one is searched for from v too; the
    // nearer admissible hit wins.
    const double margin = opt_.search_limits.farther_hit_retry * longest_edge_at(v);
    const std::optional<double> previous = mu;
    if (mu && rank(*mu) > margin) {
      const double previous_mu = *mu;
      hit = cast_ray(v, s1_.vertex(v) + previous_mu * direction, *mu, &nearest);
      if (hit && rank(*mu) > rank(previous_mu) + margin) {
        double near_mu = 0.0;
        if (auto near = cast_ray(v, s1_.vertex(v), near_mu, nullptr); near && rank(near_mu) < rank(*mu)) {
          hit = near;
          *mu = near_mu;
        }
      }
    }
    if (!hit) hit = cast_ray(v, s1_.vertex(v), mu.emplace(), nullptr);
    // near S2, the seeds from v came first; the previous hit's may still reach a hit they miss
    // (the elements nearest to v lie on another part of S2 whose walks end at its boundary)
    if (!hit && previous && rank(*previous) <= margin)
      hit = cast_ray(v, s1_.vertex(v) + *previous * direction, *mu, &nearest);
    if (!hit) mu.reset();
    return hit;
  }

  /// The longest S1 edge at vertex v (d = 1: segment).
  double longest_edge_at(Index v) const {
    double longest = 0.0;
    for (Index t : s1_.vertex_elements(v))
      for (int k = 0; k <= d; ++k) longest = std::max(longest, (s1_.corner(t, k) - s1_.vertex(v)).norm());
    return longest;
  }

  /// The ray from S1 vertex v against S2, walking from the elements of S2 nearest to
  /// `seed_point`; `hit_mu` receives the ray parameter of the hit.
  std::optional<SurfacePoint<d>> cast_ray(Index v, const WorldPoint<d>& seed_point, double& hit_mu,
                                          NearestElements<d>* nearest) {
    const WorldPoint<d>& origin = s1_.vertex(v);
    const WorldPoint<d>& direction = nu_[v];
    // an isolated S1 vertex (no element) is not part of S1: no ghost node, whatever its direction
    if (direction.squaredNorm() == 0.0 || s1_.vertex_elements(v).empty()) return std::nullopt;
    std::array<std::uint32_t, 32> seeds;
    const int count = nearest_seeds(*index2_, nearest, seed_point, seeds_, seeds);
    std::optional<SurfacePoint<d>> best;
    double best_rank = std::numeric_limits<double>::infinity();
    std::array<Index, 64> visited;
    int nvisited = 0;
    for (int s = 0; s < count; ++s) {
      Index t = static_cast<Index>(seeds[s]);
      for (int step = 0; step < opt_.search_limits.seed_walk_steps && t != invalid_index; ++step) {
        if (std::find(visited.begin(), visited.begin() + nvisited, t) != visited.begin() + nvisited) break;
        if (nvisited < 64) visited[nvisited++] = t;
        // origin + mu direction = c0 + sum_i y_i (c_{i+1} - c0): linear in (y, mu)
        Eigen::Matrix<double, d + 1, d + 1> a;
        double scale = 0.0;
        for (int i = 0; i < d; ++i) {
          a.col(i) = s2_.corner(t, i + 1) - s2_.corner(t, 0);
          scale = std::max(scale, a.col(i).norm());
        }
        a.col(d) = -direction;
        const double det = a.determinant();
        if (!(std::abs(det) > 1e-12 * integer_power(scale, d))) break;  // ray parallel to the element
        const Eigen::Matrix<double, d + 1, 1> x = solve_with_partial_pivoting<d + 1>(a, origin - s2_.corner(t, 0));
        const LocalPoint<d> y = x.template head<d>();
        const Barycentric<d> b = barycentric_from_local<d>(y);
        int worst = 0;
        for (int k = 1; k <= d; ++k)
          if (b(k) < b(worst)) worst = k;
        if (b(worst) >= -opt_.search_limits.inside_tolerance) {
          const double mu = x(d);
          WorldPoint<d> target_normal = s2_.element_normal(t);
          if (distance_ok(mu, scale) && normal_ok(direction, target_normal) && rank(mu) < best_rank &&
              ghost_ray_unfolded(v, mu)) {
            best_rank = rank(mu);
            hit_mu = mu;
            Barycentric<d> bc = b.cwiseMax(0.0);
            bc /= bc.sum();
            best = SurfacePoint<d>{t, local_from_barycentric<d>(bc)};
          }
          break;
        }
        t = across(s2_, t, worst);
      }
    }
    return best;
  }

  // ---- phase 3: edges ------------------------------------------------------------------------------
  std::array<Index, 2> target_edge_vertices(Index e) const {
    if constexpr (d == 2)
      return s2_.edge_vertices(e);
    else
      return {s2_.element(e)[0], s2_.element(e)[1]};
  }

  struct CrossingCandidate {
    bool valid = false;
    bool solver_failed = false;
    bool beyond_limit = false;
    double lambda = 0.0, mu = 0.0, eta = 0.0;
  };

  /// The answers of eq. (4) for the S2 edge of one walk, by S1 edge. Consecutive steps of a walk
  /// share an element whose other edges were solved in the step before, and a walk from an S1
  /// vertex meets each edge at the vertex in two elements: the answer depends only on the two
  /// edges, so it is looked up instead of solved again. The last `capacity` answers are kept,
  /// enough for a step from a vertex of any usual valence and the step after it.
  struct CrossingMemo {
    static constexpr int capacity = 16;
    std::array<Index, capacity> edges;
    std::array<CrossingCandidate, capacity> answers;
    int size = 0, next = 0;

    template <class Solve>
    const CrossingCandidate& get(Index edge, Solve&& solve) {
      for (int i = 0; i < size; ++i)
        if (edges[i] == edge) return answers[i];
      const int slot = next;
      next = (next + 1) % capacity;
      if (size < capacity) ++size;
      edges[slot] = edge;
      answers[slot] = solve();
      return answers[slot];
    }
  };


  /// Eq. (4): where the projection of S2 edge (qa, qb) crosses S1 edge `edge` (d = 2).
  CrossingCandidate solve_crossing(Index edge, const WorldPoint<d>& qa, const WorldPoint<d>& qb,
                                   long long& calls, long long& failures) const
    requires(d == 2)
  {
    CrossingCandidate c;
    const auto ev = s1_.edge_vertices(edge);
    EdgeCrossingSystem sys;
    sys.edge = {s1_.vertex(ev[0]), s1_.vertex(ev[1])};
    sys.directions = {nu_[ev[0]], nu_[ev[1]]};
    sys.target = {qa, qb};
    // A crossing outside [-slack, 1 + slack] is rejected below whatever the solver returns.
    const double crossing_lambda_slack = opt_.search_limits.edge_parameter_slack;
    if (sys.misses_the_edge(opt_.solver_tolerance, crossing_lambda_slack)) return c;
    ++calls;
    const auto r = solver_.solve(sys, sys.initial_guess());
    if (!r.converged) {
      ++failures;
      c.solver_failed = true;
      return c;
    }
    c.lambda = r.x(0);
    c.mu = r.x(1);
    c.eta = r.x(2);
    // A (nearly) singular Jacobian at the solution means the S2 edge runs along the projection
    // of the S1 edge: there is no isolated crossing (the walk passes the edge's end vertices).
    {
      const Eigen::Matrix3d j = sys.jacobian(r.x);
      const double s = sys.scale();
      if (!(std::abs(j.determinant()) > 1e-10 * s * s * j.col(1).norm())) return c;
    }
    if (c.lambda < -crossing_lambda_slack || c.lambda > 1.0 + crossing_lambda_slack) return c;
    if (!distance_ok(c.mu, sys.scale())) {
      c.beyond_limit = true;
      return c;
    }
    c.lambda = std::clamp(c.lambda, 0.0, 1.0);
    c.valid = true;
    return c;
  }

  /// For d = 1: the ray from S1 vertex w meets the line of the S2 segment (qa, qb).
  CrossingCandidate ray_crossing(Index w, const WorldPoint<d>& qa, const WorldPoint<d>& qb) const
    requires(d == 1)
  {
    CrossingCandidate c;
    Eigen::Matrix2d a;
    a.col(0) = nu_[w];
    a.col(1) = qa - qb;
    const double scale = (qb - qa).norm();
    if (!(std::abs(a.determinant()) > 1e-12 * scale)) return c;
    const Eigen::Vector2d x = solve_with_partial_pivoting<2>(a, qa - s1_.vertex(w));
    c.mu = x(0);
    c.eta = x(1);
    c.lambda = 0.0;
    if (!distance_ok(c.mu, scale)) {
      c.beyond_limit = true;
      return c;
    }
    c.valid = true;
    return c;
  }

  /// Walks along the preimage of S2 edge e from `start` (at parameter eta0) towards `end`.
  /// With `reversed`, the walk runs from the second vertex towards the first: eta (and every
  /// parameter in the result) is then measured from the second vertex; see plan_edge.
  WalkResult<d> walk(Index e, const Place<d>& start, double eta0, const std::optional<Place<d>>& end, bool reversed,
                     PlanBuffer<d>& buffer) const {
    WalkResult<d> w;
    auto tv = target_edge_vertices(e);
    if (reversed) std::swap(tv[0], tv[1]);
    const WorldPoint<d> qa = s2_.vertex(tv[0]), qb = s2_.vertex(tv[1]);
    const double eta_slack = opt_.search_limits.edge_parameter_slack;
    Place<d> cur = start;
    double eta = eta0;
    std::vector<Index>& cand = buffer.candidates;
    std::vector<Index>& end_elements = buffer.end_elements;
    if (end) elements_of(*end, end_elements);
    CrossingMemo memo;
    long long calls = 0, failures = 0;
    // The distance along the ray at the current point, once the walk has made a crossing. A
    // crossing is taken if its ray is unfolded in the element the walk crosses to reach it; the
    // walk then goes on only into elements where that ray is unfolded as well. So a walk that
    // meets a fold stops at the last crossing before it, which becomes the end of a piece
    // (partial insertion), instead of stopping one element earlier.
    std::optional<double> cur_mu;
    auto unfolded_here = [&](Index t) { return !cur_mu || unfolded_in_at(t, cur, *cur_mu); };
    bool start_folded = false;
    for (w.steps = 0; w.steps < walk_limit_; ++w.steps) {
      elements_of(cur, cand);
      start_folded = false;
      if (end) {
        for (Index t : cand)
          if (std::find(end_elements.begin(), end_elements.end(), t) != end_elements.end() && unfolded_here(t)) {
            w.end = WalkEnd::reached;
            solver_calls_ += calls;
            solver_failures_ += failures;
            return w;
          }
      }
      bool solver_failed = false, beyond_limit = false, folded = false;
      double best_eta = std::numeric_limits<double>::infinity(), best_mu = 0.0;
      Place<d> best_place;
      Crossing<d> best_crossing{};
      // From a point shared by several S1 elements (an S1 vertex; an edge of a non-manifold S1)
      // the preimage can seem to continue into more than one of them: an element whose own
      // projection is a nearer part of S2 still reaches this S2 edge farther along its rays
      // (remeshed copies of a zigzag polyline, folds). Like the vertex preimages (phase 1), the
      // continuation with the smallest distance wins; inside one element the exit is the
      // crossing with the smallest eta beyond the current one.
      double best_rank = std::numeric_limits<double>::infinity();
      const double rank_tie = 1e-9 * s1_.max_edge_length();
      for (Index t : cand) {
        if (!unfolded_here(t)) {
          start_folded = true;
          continue;
        }
        double element_eta = std::numeric_limits<double>::infinity(), element_mu = 0.0;
        Place<d> element_place;
        Crossing<d> element_crossing{};
        for (int k = 0; k <= d; ++k) {
          CrossingCandidate c;
          Place<d> place;
          Crossing<d> crossing{};
          if constexpr (d == 2) {
            const Index edge = s1_.element_edge(t, k);
            if (cur.kind == PlaceKind::edge && cur.index == edge) continue;
            c = memo.get(edge, [&] { return solve_crossing(edge, qa, qb, calls, failures); });
            if (!c.valid) {
              solver_failed |= c.solver_failed;
              beyond_limit |= c.beyond_limit;
              continue;
            }
            place = edge_place(edge, c.lambda);
            crossing = EdgeCrossing{edge, c.lambda, c.eta};
          } else {
            const Index vtx = s1_.element(t)[k];
            if (cur.kind == PlaceKind::vertex && cur.index == vtx) continue;
            c = ray_crossing(vtx, qa, qb);
            if (!c.valid) {
              beyond_limit |= c.beyond_limit;
              continue;
            }
            place.kind = PlaceKind::vertex;
            place.index = vtx;
            crossing = VertexCrossing{vtx, c.eta};
          }
          if (!(c.eta > eta + eta_slack) || c.eta > 1.0 + eta_slack || c.eta >= element_eta || place == cur) continue;
          // beyond a focal point the continuation belongs to a folded sheet of the projection
          if (!unfolded_in_at(t, place, c.mu)) {
            folded = true;
            continue;
          }
          element_eta = c.eta;
          element_mu = c.mu;
          element_place = place;
          element_crossing = crossing;
        }
        if (!std::isfinite(element_eta)) continue;
        const double r = rank(element_mu);
        const bool nearer = r < best_rank - rank_tie;
        const bool tie = !nearer && r <= best_rank + rank_tie;
        if (!nearer && !(tie && element_eta < best_eta)) continue;
        best_rank = std::min(best_rank, r);
        best_mu = element_mu;
        best_eta = element_eta;
        best_place = element_place;
        best_crossing = element_crossing;
      }
      solver_calls_ += calls;
      solver_failures_ += failures;
      calls = failures = 0;
      w.stop = cur;
      w.eta = eta;
      if (!std::isfinite(best_eta)) {
        if (on_boundary(cur)) {  // the preimage leaves S1 here (possibly right at its start)
          w.end = WalkEnd::left_boundary;
          return w;
        }
        w.end = WalkEnd::failed;
        w.reason = folded || start_folded ? EdgeFailureReason::fold
                   : solver_failed ? EdgeFailureReason::solver_failure
                   : beyond_limit  ? EdgeFailureReason::distance_limit
                                   : EdgeFailureReason::discontinuity;
        return w;
      }
      if (best_eta >= 1.0 - 1e-12) {
        // The walk reaches the image of the second vertex, but that vertex has no preimage here.
        w.end = WalkEnd::failed;
        w.reason = EdgeFailureReason::endpoint_without_preimage;
        w.stop = best_place;
        w.eta = best_eta;
        return w;
      }
      if (best_place.kind == PlaceKind::vertex && vertex_state_[best_place.index] == VertexState::corner) {
        w.end = WalkEnd::failed;
        w.reason = EdgeFailureReason::vertex_conflict;
        w.stop = best_place;
        w.eta = best_eta;
        return w;
      }
      if constexpr (d == 2) best_crossing.target_parameter = best_eta;
      buffer.crossings.push_back(best_crossing);
      ++w.crossing_count;
      cur = best_place;
      cur_mu = best_mu;
      eta = best_eta;
      if constexpr (d == 2) {
        if (cur.kind == PlaceKind::edge && s1_.edge_elements(cur.index).size() == 1) {
          w.end = WalkEnd::left_boundary;
          w.stop = cur;
          w.eta = eta;
          return w;
        }
      }
    }
    w.end = WalkEnd::failed;
    w.reason = EdgeFailureReason::walk_limit;
    return w;
  }

  bool on_boundary(const Place<d>& p) const {
    if (p.kind == PlaceKind::vertex) return s1_.is_boundary_vertex(p.index);
    if constexpr (d == 2)
      if (p.kind == PlaceKind::edge) return s1_.edge_elements(p.index).size() == 1;
    return false;
  }

  EdgeNotInserted<d> failure(Index e, EdgeFailureReason reason, const Place<d>& at, double eta,
                             std::string detail = {}) const {
    EdgeNotInserted<d> f;
    f.target_edge = e;
    f.reason = reason;
    std::vector<Index> els;
    elements_of(at, els);
    f.domain_element = els.empty() ? invalid_index : els.front();
    f.domain_point = world_of(at);
    f.target_parameter = eta;
    f.detail = std::move(detail);
    return f;
  }

  /// For plan_edge: the piece of S2 edge e that ends where the edge leaves S1 at `exit`, found by
  /// walking from there towards the first vertex until the walk leaves S1 (as the walk from the
  /// second vertex in plan_edge). Appended as a piece if it is one and lies beyond
  /// `covered_until` (where the walks before it ended); returns whether it was.
  bool walk_back_from_exit(Index e, const BoundaryEntry<d>& exit, double covered_until,
                             PlanBuffer<d>& buffer) const {
    auto& crossings = buffer.crossings;
    const std::size_t begin = crossings.size();
    const WalkResult<d> w = walk(e, exit.place, 1.0 - exit.eta, std::nullopt, true, buffer);
    const double back_to = 1.0 - w.eta;  // in the edge's direction
    if (w.end != WalkEnd::left_boundary || w.crossing_count == 0 || !(back_to >= covered_until - 1e-9)) {
      crossings.resize(begin);  // nothing over S1 before the exit, or not a clean piece
      return false;
    }
    // measured from the first vertex again, in the edge's direction, ending at the exit
    std::reverse(crossings.begin() + static_cast<std::ptrdiff_t>(begin), crossings.end());
    for (std::size_t i = begin; i < crossings.size(); ++i)
      crossings[i].target_parameter = 1.0 - crossings[i].target_parameter;
    crossings.push_back(exit.crossing);
    buffer.pieces.push_back({static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(crossings.size()), false, false});
    return true;
  }

  /// Walks along S2 edge e and appends its pieces (and what could not be walked) to `buffer`.
  PlannedEdge plan_edge(Index e, unsigned worker, PlanBuffer<d>& buffer) const {
    PlannedEdge plan;
    plan.worker = worker;
    plan.pieces_begin = static_cast<std::uint32_t>(buffer.pieces.size());
    plan.failures_begin = static_cast<std::uint32_t>(buffer.failures.size());
    auto& crossings = buffer.crossings;
    // a piece ends at the last crossing appended
    auto add_piece = [&](std::size_t begin, bool from_first, bool to_second) {
      buffer.pieces.push_back(
          {static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(crossings.size()), from_first, to_second});
    };
    const auto tv = target_edge_vertices(e);
    const auto& pa = target_place_[tv[0]];
    const auto& pb = target_place_[tv[1]];
    bool reached_second = false, first_walk_failed = false;
    // The entry whose walk reached the second vertex, if that was no walk from the first vertex:
    // the boundary-entry search also finds points where the edge only touches S1's boundary
    // from inside (it comes over S1 and meets a boundary vertex, then runs along the boundary),
    // and the stretch before such a point would be lost (see the backward walk below).
    std::optional<double> second_reached_from_entry;
    // Pieces are disjoint intervals of the edge parameter; an entry inside an interval already
    // walked is where that walk left S1 (or a re-detection of it), not a new piece.
    double covered_until = -1.0;
    if (pa) {
      const std::size_t begin = crossings.size();
      const WalkResult<d> w = walk(e, *pa, 0.0, pb, false, buffer);
      if (w.end == WalkEnd::failed) {
        // What was walked before the failure is inserted as a piece ending at the last crossing
        // (partial insertion): the S2 elements on both sides of e then keep their regions away
        // from the failure, and only the faces around its far end stay outside D.
        buffer.failures.push_back(failure(e, w.reason, w.stop, w.eta));
        if (w.crossing_count > 0)
          add_piece(begin, true, false);
        else
          crossings.resize(begin);
        covered_until = w.eta;
        first_walk_failed = true;
      } else {
        const bool reached = w.end == WalkEnd::reached;
        reached_second |= reached;
        covered_until = reached ? 1.0 : w.eta;
        if (w.crossing_count > 0 || reached)
          add_piece(begin, true, reached);
        else
          crossings.resize(begin);
      }
    }
    for (const auto& entry : entries_[e]) {
      if (entry.eta <= covered_until + 1e-9) continue;
      const std::size_t begin = crossings.size();
      crossings.push_back(entry.crossing);  // the piece starts where the edge enters S1
      const WalkResult<d> w = walk(e, entry.place, entry.eta, pb, false, buffer);
      const double walked_until = covered_until;  // before this entry
      covered_until = w.end == WalkEnd::reached ? 1.0 : w.eta;
      if (w.end == WalkEnd::failed) {
        if (w.crossing_count > 0) {  // partial insertion, as for the walk from the first vertex
          buffer.failures.push_back(failure(e, w.reason, w.stop, w.eta));
          add_piece(begin, false, false);
          continue;
        }
        crossings.resize(begin);
        if (w.steps == 0 && w.reason != EdgeFailureReason::solver_failure) {
          // An exit: the edge leaves S1 here. If no walk has come this far, the stretch before
          // it may still lie over S1 with neither of its ends found (it enters across a
          // boundary edge whose end vertices both miss S2, and the first vertex has no
          // preimage): walking backwards from the exit finds it.
          walk_back_from_exit(e, entry, walked_until, buffer);
          continue;
        }
        buffer.failures.push_back(failure(e, w.reason, w.stop, w.eta));
        continue;
      }
      if (w.end == WalkEnd::left_boundary && w.crossing_count == 0) {  // an exit, as above
        crossings.resize(begin);
        walk_back_from_exit(e, entry, walked_until, buffer);
        continue;
      }
      const bool reached = w.end == WalkEnd::reached;
      reached_second |= reached;
      if (reached) second_reached_from_entry = entry.eta;
      add_piece(begin, false, reached);
    }
    // The second vertex has a preimage that no walk reached: the edge enters S1 across its boundary
    // at a point the boundary-entry search cannot see (that search needs an image of one end of
    // the S1 boundary edge; both may lie outside S2 or over a hole of S2). Walking backwards from
    // the second vertex finds the entry as the point where the reversed walk leaves S1.
    // It also runs when the second vertex was reached only from an entry: if it leaves S1
    // before that entry, the entry was a touch of the boundary from inside, and its piece is
    // replaced by the longer one (whose crossings follow it in the buffer).
    // After a failed walk from the first vertex, it also inserts the stretch from the second
    // vertex back to where its own walk fails (partial insertion), if the two stretches are
    // disjoint along the edge.
    if (pb && (!reached_second || second_reached_from_entry)) {
      const std::size_t begin = crossings.size();
      const WalkResult<d> w = walk(e, *pb, 0.0, std::nullopt, true, buffer);
      auto reverse_into_piece = [&](std::size_t piece_begin) {
        std::reverse(crossings.begin() + static_cast<std::ptrdiff_t>(piece_begin), crossings.end());
        for (std::size_t i = piece_begin; i < crossings.size(); ++i)
          crossings[i].target_parameter = 1.0 - crossings[i].target_parameter;
        add_piece(piece_begin, false, true);
        reached_second = true;
      };
      // where the backward walk's last crossing lies, measured from the first vertex
      const double walked_back_to = w.crossing_count > 0 ? 1.0 - crossings.back().target_parameter : 1.0;
      const bool partial = w.crossing_count > 0 && !second_reached_from_entry &&
                           (w.end == WalkEnd::failed || (first_walk_failed && w.end == WalkEnd::left_boundary));
      if (partial) {
        if (walked_back_to > covered_until + 1e-9) {
          reverse_into_piece(begin);
        } else {
          crossings.resize(begin);
        }
        if (w.end == WalkEnd::failed && !first_walk_failed && w.reason != EdgeFailureReason::endpoint_without_preimage)
          buffer.failures.push_back(failure(e, w.reason, w.stop, 1.0 - w.eta));
      } else if (w.end == WalkEnd::left_boundary && w.crossing_count > 0) {
        // measured from the first vertex again, in the edge's direction
        if (second_reached_from_entry && !(1.0 - w.eta < *second_reached_from_entry - 1e-9)) {
          crossings.resize(begin);  // no farther back than the entry: the entry's piece stands
        } else {
          std::size_t piece_begin = begin;
          if (second_reached_from_entry) {  // the entry's piece is the last one: replace it
            piece_begin = buffer.pieces.back().begin;
            crossings.erase(crossings.begin() + static_cast<std::ptrdiff_t>(piece_begin),
                            crossings.begin() + static_cast<std::ptrdiff_t>(begin));
            buffer.pieces.pop_back();
          }
          reverse_into_piece(piece_begin);
        }
      } else {
        crossings.resize(begin);
        // after an entry's piece, a failure may lie where that piece's walk passed: not reported;
        // after a failed walk from the first vertex, that walk's failure names the missing stretch
        if (w.end == WalkEnd::failed && !second_reached_from_entry && !first_walk_failed &&
            w.reason != EdgeFailureReason::endpoint_without_preimage)
          buffer.failures.push_back(failure(e, w.reason, w.stop, 1.0 - w.eta));
      }
    }
    if (pb && !reached_second && buffer.failures.size() == plan.failures_begin && !on_boundary(*pb))
      buffer.failures.push_back(failure(e, EdgeFailureReason::endpoint_without_preimage, *pb, 1.0,
                                        fmt::format("the S2 vertex {} has no preimage", tv[0])));
    plan.pieces_end = static_cast<std::uint32_t>(buffer.pieces.size());
    plan.failures_end = static_cast<std::uint32_t>(buffer.failures.size());
    // No piece and nothing wrong: the edge lies outside D (it may touch S1's boundary at an
    // endpoint and leave at once).
    plan.outside = plan.pieces_begin == plan.pieces_end && plan.failures_begin == plan.failures_end;
    return plan;
  }

  // ---- insertion of the planned edges -----------------------------------------------------------
  /// S2 edges planned and inserted per block (see run()): large enough that the threads of a
  /// block have work, small enough that a block's plans take little memory.
  static constexpr Index plan_block = 4096;
  /// In the per-edge count of what was inserted: the edge was inserted whole.
  static constexpr std::uint32_t inserted_whole = 1u << 31;

  /// Phase 3 proper. The edges are planned in blocks of consecutive indices (in parallel, into
  /// per-worker flat buffers) and each block is fed to the builder, in index order, before the
  /// next one is planned: the walks read nothing the insertion changes, so this is the same as
  /// planning all edges first, and only one block's plans are ever held in memory.
  void plan_and_insert_edges(MapBuilder<d>& builder, ProjectionReport<d>& report, std::vector<std::uint32_t>& counted) {
    const Index n2e = s2_.edge_count();
    std::vector<PlanBuffer<d>> buffers(std::max(1u, threads_));
    std::vector<PlannedEdge> planned(static_cast<std::size_t>(std::min(n2e, plan_block)));
    for (Index block = 0; block < n2e; block += plan_block) {
      const Index block_end = std::min(n2e, block + plan_block);
      auto t0 = Clock::now();
      for (auto& buffer : buffers) buffer.clear();
      // one piece (and buffer) per thread; a short block is not worth a second thread
      const auto count = static_cast<std::size_t>(block_end - block);
      parallel_for_pieces(count, count < 64 ? 1 : buffers.size(), threads_, [&](std::size_t worker, std::size_t begin, std::size_t end) {
        for (auto i = static_cast<Index>(begin); i < static_cast<Index>(end); ++i)
          planned[i] = plan_edge(block + i, static_cast<unsigned>(worker), buffers[worker]);
      });
      report.seconds.edge_walks += seconds_since(t0);
      t0 = Clock::now();
      for (Index e = block; e < block_end; ++e)
        counted[e] = insert_planned_edge(e, planned[e - block], buffers[planned[e - block].worker], builder, report);
      report.seconds.insertion += seconds_since(t0);
      report_progress(opt_.progress, "S2 edges", block_end, n2e);
    }
  }

  /// Feeds the planned pieces of S2 edge e to the builder and reports what was left out. Returns
  /// inserted_whole if the edge was inserted whole, or'ed with the number of pieces inserted.
  std::uint32_t insert_planned_edge(Index e, const PlannedEdge& plan, PlanBuffer<d>& buffer, MapBuilder<d>& builder,
                                    ProjectionReport<d>& report) {
    if (plan.outside) {
      ++report.edges_outside;
      builder.add_edge_outside_domain(e);
    }
    bool whole = false;
    std::uint32_t pieces = 0;
    std::vector<EdgeNotInserted<d>> rejected;
    for (std::uint32_t p = plan.pieces_begin; p < plan.pieces_end; ++p) {
      const auto& piece = buffer.pieces[p];
      const std::span<const Crossing<d>> crossings(buffer.crossings.data() + piece.begin, piece.end - piece.begin);
      if (const auto clash = find_used_point(crossings)) {
        EdgeNotInserted<d> f;
        f.target_edge = e;
        f.reason = EdgeFailureReason::builder_rejected;
        f.domain_element = clash->element;
        f.domain_point = clash->point;
        f.detail = clash->detail;
        rejected.push_back(std::move(f));
        continue;
      }
      try {
        if (piece.from_first && piece.to_second) {
          builder.add_edge(e, crossings);
          whole = true;
        } else {
          builder.add_edge_piece(e, crossings, piece.from_first ? PieceStart::first_vertex : PieceStart::first_crossing,
                                 piece.to_second ? PieceEnd::second_vertex : PieceEnd::last_crossing);
          ++pieces;
        }
        mark_used_points(crossings, e);
      } catch (const BuilderError& error) {
        EdgeNotInserted<d> f;
        f.target_edge = e;
        f.reason = EdgeFailureReason::builder_rejected;
        f.detail = error.what();
        rejected.push_back(std::move(f));
      }
    }
    // An edge of which no stretch could be inserted (its walks fail at once from both ends)
    // still closes its S2 triangles' regions, as one beyond S1's boundary does: the faces it
    // would split have nodes on both of its sides, so no single S2 element holds their images
    // and they stay outside D, while the triangles' other faces keep their regions.
    if (!whole && pieces == 0 && !plan.outside && !builder.has_edge(e)) builder.add_edge_outside_domain(e);
    if (whole) ++report.edges_inserted;
    if (pieces > 0) ++report.edges_partly_inserted;
    report.edge_pieces += static_cast<Index>(pieces);
    for (std::uint32_t f = plan.failures_begin; f < plan.failures_end; ++f)
      report.edges_not_inserted.push_back(std::move(buffer.failures[f]));
    for (auto& f : rejected) report.edges_not_inserted.push_back(std::move(f));
    return (whole ? inserted_whole : 0u) | pieces;
  }

  /// Frees what only the phases before finalize need.
  void release_search_data() {
    index1_.reset();
    index2_.reset();
    auto release = [](auto& v) { std::decay_t<decltype(v)>().swap(v); };
    release(entries_);
    release(target_place_);
    release(vertex_state_);
    release(vertex_image_);
    release(used_first_);
    release(used_parameters_);
    release(crossed_vertex_);
    release(focal_free_);
    release(nu_);
    release(n2_);
  }

  /// Points where S2 edges cross S1's boundary, per S2 edge, sorted by the edge parameter.
  void find_boundary_entries() {
    if constexpr (d == 1) {
      for (Index v = 0; v < s1_.vertex_count(); ++v) {
        if (!s1_.is_boundary_vertex(v) || vertex_state_[v] != VertexState::ghost || !vertex_image_[v]) continue;
        const auto& image = *vertex_image_[v];
        BoundaryEntry<1> entry;
        entry.place.kind = PlaceKind::vertex;
        entry.place.index = v;
        entry.eta = image.local(0);
        entry.crossing = VertexCrossing{v, entry.eta};
        entries_[image.element].push_back(entry);
      }
    } else {
      long long calls = 0, failures = 0;
      std::vector<Index> edges;
      for (Index edge = 0; edge < s1_.edge_count(); ++edge) {
        if (s1_.edge_elements(edge).size() != 1) continue;
        const auto ev = s1_.edge_vertices(edge);
        const auto& ia = vertex_image_[ev[0]];
        const auto& ib = vertex_image_[ev[1]];
        if (!ia && !ib) continue;
        const double length = (s1_.vertex(ev[0]) - s1_.vertex(ev[1])).norm();
        WorldPoint<2> centre;
        double radius;
        if (ia && ib) {
          const WorldPoint<2> a = s2_.world_position(ia->element, ia->local);
          const WorldPoint<2> b = s2_.world_position(ib->element, ib->local);
          centre = 0.5 * (a + b);
          radius = 0.5 * (a - b).norm();
        } else {
          const auto& i = ia ? *ia : *ib;
          centre = s2_.world_position(i.element, i.local);
          radius = 2.0 * length;
        }
        edges.clear();
        for (Index t : index2_->within(centre, radius + index2_->radius * 1.01 + 1e-9 * length))
          for (int k = 0; k < 3; ++k) edges.push_back(s2_.element_edge(t, k));
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        for (Index e : edges) {
          const auto tv = s2_.edge_vertices(e);
          const CrossingCandidate c = solve_crossing(edge, s2_.vertex(tv[0]), s2_.vertex(tv[1]), calls, failures);
          if (!c.valid || !(c.eta > 1e-9 && c.eta < 1.0 - 1e-9)) continue;
          if (!unfolded_at(edge_place(edge, c.lambda), c.mu)) continue;
          BoundaryEntry<2> entry;
          entry.place = edge_place(edge, c.lambda);
          entry.eta = c.eta;
          entry.crossing = EdgeCrossing{edge, c.lambda, c.eta};
          auto& list = entries_[e];
          const bool duplicate = std::any_of(list.begin(), list.end(), [&](const BoundaryEntry<2>& x) {
            return x.place == entry.place;
          });
          if (!duplicate) list.push_back(entry);
        }
      }
      solver_calls_ += calls;
      solver_failures_ += failures;
    }
    for (auto& list : entries_)
      std::sort(list.begin(), list.end(), [](const auto& x, const auto& y) { return x.eta < y.eta; });
  }

  std::shared_ptr<const Surface<d>> s1_ptr_, s2_ptr_;
  const Surface<d>& s1_;
  const Surface<d>& s2_;
  ProjectionOptions opt_;
  Solver solver_;
  std::vector<WorldPoint<d>> nu_, n2_;
  /// Per S1 element: up to this |mu| no ray of the element passes a focal point (focal_points.hpp).
  std::vector<double> focal_free_;
  double limit_ = 0.0;
  int seeds_ = 8;
  unsigned threads_ = 1;
  int walk_limit_ = 16;
  std::unique_ptr<ElementIndex<d>> index1_, index2_;
  std::vector<std::optional<Place<d>>> target_place_;
  std::vector<VertexState> vertex_state_;
  std::vector<std::optional<SurfacePoint<d>>> vertex_image_;
  std::vector<std::vector<BoundaryEntry<d>>> entries_;
  /// Per S1 edge (d = 2): the parameters already holding a node, with their owner (an S2 edge,
  /// or -1 - q for the preimage of S2 vertex q), as lists in insertion order linked through one
  /// array (used_first_[edge] is the first entry). Per S1 vertex: the S2 edge whose preimage passes it.
  struct UsedParameter {
    double t;
    Index owner, next;
  };
  std::vector<Index> used_first_;
  std::vector<UsedParameter> used_parameters_;
  std::vector<Index> crossed_vertex_;
  mutable std::atomic<long long> solver_calls_{0}, solver_failures_{0};
};

}  // namespace

template <int d>
  requires SurfaceDimension<d>
ProjectionResult<d> project(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
                            const ProjectionOptions& options) {
  if (!s1 || !s2) throw Error("project: both surfaces are required");
  const SolverKind kind = solver_kind_from_string(options.solver);
  // computed on unit-size copies, so that no product of lengths overflows or underflows
  const auto unit = projection::unit_scaled<d>(s1, s2);
  const ProjectionOptions unit_options = projection::options_for_unit_scale(options, unit.exponent);
  auto result = with_solver(kind, options.solver_tolerance, [&](const auto& solver) {
    Projector<d, std::decay_t<decltype(solver)>> projector(unit.s1, unit.s2, unit_options, solver);
    return projector.run();
  });
  return projection::in_user_units<d>(std::move(result), s1, s2, unit.exponent);
}

template ProjectionResult<1> project<1>(std::shared_ptr<const Surface<1>>, std::shared_ptr<const Surface<1>>,
                                        const ProjectionOptions&);
template ProjectionResult<2> project<2>(std::shared_ptr<const Surface<2>>, std::shared_ptr<const Surface<2>>,
                                        const ProjectionOptions&);

}  // namespace plmap
