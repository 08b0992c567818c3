#pragma once
// Normal projection, phase 4: the walker along one S2 edge's preimage (EdgeWalker), shared by the
// walks of every edge (projection_edge_walks.cpp, plan_edge_block) and the walks from the rim
// (projection_rim_walks.cpp, plan_rim_walks). Internal to construct/.

#include "projection_edge_walks.hpp"

#include "fold_reentry.hpp"
#include "nearer_sheet.hpp"
#include "rim_geometry.hpp"
#include "rim_reentry.hpp"
#include "seen_indices.hpp"
#include "segment_reach.hpp"
#include "projection_edge_crossings.hpp"
#include "walk_acceptance.hpp"

#include <plmap/core/parallel_ranges.hpp>
#include <plmap/solvers/projection_systems.hpp>
#include <plmap/solvers/solver_kind.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace plmap::projection {

enum class WalkEnd : std::uint8_t { reached, left_boundary, failed };

/// Walks that stop for these reasons are restarted where the S2 edge's preimage comes out again
/// (fold_reentry.hpp): beyond a fold, beyond a stretch where the edge passes behind S1 or out of
/// the distance limit (distance_limit), beyond a stretch that a nearer sheet of S2 hides
/// (hidden), or beyond a place where no continuation was found.
inline bool restartable(EdgeFailureReason r) {
  return r == EdgeFailureReason::fold || r == EdgeFailureReason::discontinuity ||
         r == EdgeFailureReason::distance_limit || r == EdgeFailureReason::hidden;
}

/// Which way a walk runs along its S2 edge; backwards, every edge parameter it gives is measured
/// from the second vertex.
enum class WalkDirection : std::uint8_t { from_first_vertex, from_second_vertex };

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
  /// A walk that stopped because its S2 edge leaves the band of distances (end_on_rim): where the edge
  /// reaches the band's bound beyond the stop, its parameter measured in the walk's direction.
  std::optional<RimPoint<d>> rim;
  /// A walk that stopped at a fold: the element ahead of the stop in which the crossings were
  /// folded (the stop's sheet goes on in it up to the fold).
  Index fold_element = invalid_index;
};

/// The walks along the preimages of S2 edges.
template <int d, class Solver>
class EdgeWalker {
 public:
  EdgeWalker(const ProjectionContext<d>& ctx, const ProjectionState<d>& state, const Solver& solver)
      : ctx_(ctx), state_(state), crossings_(ctx, solver) {}

  /// Walks along the preimage of S2 edge e from `start` (at parameter eta0) towards `end`.
  /// From the second vertex, the walk runs towards the first: eta (and every
  /// parameter in the result) is then measured from the second vertex; see plan_edge.
  WalkResult<d> walk(Index e, const Place<d>& start, double eta0, const std::optional<Place<d>>& end, WalkDirection direction,
                     PlanBuffer<d>& buffer) const {
    WalkResult<d> w;
    auto tv = ctx_.target_edge_vertices(e);
    if (direction == WalkDirection::from_second_vertex) std::swap(tv[0], tv[1]);
    const WorldPoint<d> qa = ctx_.s2.vertex(tv[0]), qb = ctx_.s2.vertex(tv[1]);
    const double eta_slack = ctx_.options.search_limits.edge_parameter_slack;
    Place<d> cur = start;
    double eta = eta0;
    std::vector<Index>& cand = buffer.candidates;
    std::vector<Index>& end_elements = buffer.end_elements;
    if (end) ctx_.elements_of(*end, end_elements);
    CrossingMemo memo;
    long long calls = 0, failures = 0;
    // The distance along the ray at the current point, once the walk has made a crossing. A
    // crossing is taken if its ray is unfolded in the element the walk crosses to reach it; the
    // walk then goes on only into elements where that ray is unfolded as well. So a walk that
    // meets a fold stops at the last crossing before it, which becomes the end of a piece
    // (partial insertion), instead of stopping one element earlier.
    std::optional<double> cur_mu;
    auto unfolded_here = [&](Index t) { return !cur_mu || ctx_.unfolded_in_at(t, cur, *cur_mu); };
    bool start_folded = false;
    for (w.steps = 0; w.steps < ctx_.edge_walk_steps; ++w.steps) {
      ctx_.elements_of(cur, cand);
      start_folded = false;
      if (end) {
        for (Index t : cand)
          if (std::find(end_elements.begin(), end_elements.end(), t) != end_elements.end() && unfolded_here(t)) {
            w.end = WalkEnd::reached;
            ctx_.solver_calls += calls;
            ctx_.solver_failures += failures;
            return w;
          }
      }
      bool solver_failed = false, beyond_limit = false, folded = false;
      Index folded_in = invalid_index;
      double best_eta = std::numeric_limits<double>::infinity(), best_mu = 0.0;
      Place<d> best_place;
      Crossing<d> best_crossing{};
      // From a point shared by several S1 elements (an S1 vertex; an edge of a non-manifold S1)
      // the preimage can seem to continue into more than one of them: an element whose own
      // projection is a nearer part of S2 still reaches this S2 edge farther along its rays
      // (remeshed copies of a zigzag polyline, folds). Like the vertex preimages, the
      // continuation with the smallest distance wins; inside one element the exit is the
      // crossing with the smallest eta beyond the current one.
      double best_rank = std::numeric_limits<double>::infinity();
      const double rank_tie = 1e-9 * ctx_.s1.max_edge_length();
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
            const Index edge = ctx_.s1.element_edge(t, k);
            if (cur.kind == PlaceKind::edge && cur.index == edge) continue;
            c = memo.get(edge, [&] { return crossings_.solve(edge, qa, qb, calls, failures); });
            if (!c.valid) {
              solver_failed |= c.solver_failed;
              beyond_limit |= c.beyond_limit;
              continue;
            }
            place = ctx_.edge_place(edge, c.lambda);
            crossing = EdgeCrossing{edge, c.lambda, c.eta};
          } else {
            const Index vtx = ctx_.s1.element(t)[k];
            if (cur.kind == PlaceKind::vertex && cur.index == vtx) continue;
            c = crossings_.ray(vtx, qa, qb);
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
          if (!ctx_.unfolded_in_at(t, place, c.mu)) {
            folded = true;
            if (folded_in == invalid_index) folded_in = t;
            continue;
          }
          element_eta = c.eta;
          element_mu = c.mu;
          element_place = place;
          element_crossing = crossing;
        }
        if (!std::isfinite(element_eta)) continue;
        const double r = ctx_.rank(element_mu);
        const bool nearer = r < best_rank - rank_tie;
        const bool tie = !nearer && r <= best_rank + rank_tie;
        if (!nearer && !(tie && element_eta < best_eta)) continue;
        best_rank = std::min(best_rank, r);
        best_mu = element_mu;
        best_eta = element_eta;
        best_place = element_place;
        best_crossing = element_crossing;
      }
      ctx_.solver_calls += calls;
      ctx_.solver_failures += failures;
      calls = failures = 0;
      w.stop = cur;
      w.eta = eta;
      if (!std::isfinite(best_eta)) {
        if (ctx_.on_boundary(cur)) {
          // the preimage leaves S1 here (possibly right at its start), unless the edge runs on
          // into the element at this boundary point and leaves the band of distances inside
          // it: then the walk ends on the rim there (a walk back from where the edge leaves S1,
          // whose other end lies beyond the band)
          if (beyond_limit && !solver_failed && !folded && !start_folded && ctx_.ends_on_rim())
            w.rim = rim_ahead(cand, eta, qa, qb, unfolded_here);
          if (w.rim) {
            w.end = WalkEnd::failed;
            w.reason = EdgeFailureReason::distance_limit;
            return w;
          }
          w.end = WalkEnd::left_boundary;
          return w;
        }
        w.end = WalkEnd::failed;
        w.reason = folded || start_folded ? EdgeFailureReason::fold
                   : solver_failed ? EdgeFailureReason::solver_failure
                   : beyond_limit  ? EdgeFailureReason::distance_limit
                                   : EdgeFailureReason::discontinuity;
        if (folded) w.fold_element = folded_in;
        if (w.reason == EdgeFailureReason::distance_limit && ctx_.ends_on_rim())
          w.rim = rim_ahead(cand, eta, qa, qb, unfolded_here);
        return w;
      }
      if (best_eta >= 1.0 - ctx_.options.search_limits.end_parameter_slack) {
        // The walk reaches the image of the second vertex, but that vertex has no preimage here.
        w.end = WalkEnd::failed;
        w.reason = EdgeFailureReason::endpoint_without_preimage;
        w.stop = best_place;
        w.eta = best_eta;
        return w;
      }
      if (best_place.kind == PlaceKind::vertex && state_.vertex_state[best_place.index] == VertexState::corner) {
        w.end = WalkEnd::failed;
        w.reason = EdgeFailureReason::vertex_conflict;
        w.stop = best_place;
        w.eta = best_eta;
        return w;
      }
      if (crossing_hidden_by_nearer_sheet(ctx_, state_, best_place, best_mu)) {
        // the points beyond take a nearer sheet's hit: the piece ends at the last visible crossing
        w.end = WalkEnd::failed;
        w.reason = EdgeFailureReason::hidden;
        return w;
      }
      if constexpr (d == 2) best_crossing.target_parameter = best_eta;
      buffer.crossings.push_back(best_crossing);
      ++w.crossing_count;
      cur = best_place;
      cur_mu = best_mu;
      eta = best_eta;
      if constexpr (d == 2) {
        if (cur.kind == PlaceKind::edge && ctx_.s1.edge_elements(cur.index).size() == 1) {
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

  /// Where the S2 edge qa -> qb, beyond parameter eta, leaves the admissible band over one of
  /// the S1 elements at the walk's stop: the first point along the edge, strictly inside an
  /// element, where it pierces that element's level set of a bound of the band (rim_geometry.hpp;
  /// the element itself for mu = 0). The stop's elements gave crossings only outside the band,
  /// so the edge's preimage ends inside one of them where its distance reaches the bound.
  template <class Unfolded>
  std::optional<RimPoint<d>> rim_ahead(const std::vector<Index>& elements, double eta, const WorldPoint<d>& qa,
                                       const WorldPoint<d>& qb, Unfolded&& unfolded_here) const {
    std::optional<RimPoint<d>> best;
    if constexpr (d == 2) {
      const auto& limits = ctx_.options.search_limits;
      const WorldPoint<d> from = qa + eta * (qb - qa);
      for (Index t : elements) {
        if (!unfolded_here(t)) continue;
        for (int level = 0; level < ctx_.rim_level_count(); ++level) {
          const auto tri = ctx_.corners_at_distance(t, ctx_.rim_level(level).mu);
          const std::optional<Pierce> p = segment_through_triangle(from, qb, tri);
          if (!p || !strictly_inside(p->barycentric, 1e3 * ctx_.options.snap_tolerance)) continue;
          const double at = eta + p->s * (1.0 - eta);
          if (!(at > eta + limits.edge_parameter_slack) || !(at < 1.0 - limits.end_parameter_slack)) continue;
          if (best && best->eta <= at) continue;
          best = RimPoint<d>{t, LocalPoint<d>(p->barycentric[1], p->barycentric[2]), at, level};
        }
      }
    }
    return best;
  }

  EdgeNotInserted<d> failure(Index e, EdgeFailureReason reason, const Place<d>& at, double eta,
                             std::string detail = {}) const {
    EdgeNotInserted<d> f;
    f.target_edge = e;
    f.reason = reason;
    std::vector<Index> els;
    ctx_.elements_of(at, els);
    f.domain_element = els.empty() ? invalid_index : els.front();
    f.domain_point = ctx_.world_of(at);
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
    const double piece_slack = ctx_.options.search_limits.piece_parameter_slack;
    auto& crossings = buffer.crossings;
    const std::size_t begin = crossings.size();
    const WalkResult<d> w = walk(e, exit.place, 1.0 - exit.eta, std::nullopt, WalkDirection::from_second_vertex, buffer);
    const double back_to = 1.0 - w.eta;  // in the edge's direction
    // a walk that stops at a fold (or another restartable place) gives the stretch from there to
    // the exit (partial insertion)
    const bool at_fold = w.end == WalkEnd::failed && restartable(w.reason);
    // a walk back that ended on the rim (the edge leaves the band of distances there) starts the
    // piece there, even in the exit's own element (no S1 edge crossed in between)
    const bool from_rim = at_fold && w.rim && 1.0 - w.rim->eta > covered_until + piece_slack;
    if ((w.end != WalkEnd::left_boundary && !at_fold) || (w.crossing_count == 0 && !from_rim) ||
        !(back_to >= covered_until - piece_slack)) {
      crossings.resize(begin);  // nothing over S1 before the exit, or not a clean piece
      return false;
    }
    // measured from the first vertex again, in the edge's direction, ending at the exit
    std::reverse(crossings.begin() + static_cast<std::ptrdiff_t>(begin), crossings.end());
    for (std::size_t i = begin; i < crossings.size(); ++i)
      crossings[i].target_parameter = 1.0 - crossings[i].target_parameter;
    crossings.push_back(exit.crossing);
    add_piece(buffer, begin, from_rim ? PieceStart::rim_node : PieceStart::first_crossing, PieceEnd::last_crossing,
              PlanBuffer<d>::no_rim, from_rim ? keep_rim(buffer, *w.rim, true) : PlanBuffer<d>::no_rim);
    if constexpr (d == 2) {
      if (at_fold) walk_back_after_folds(e, w, covered_until, buffer);
    }
    return true;
  }

  /// How far the walks along one S2 edge have come (plan_edge and its three walks).
  struct EdgeProgress {
    EdgeProgress(const std::optional<Place<d>>& first_place, const std::optional<Place<d>>& second_place)
        : first(first_place), second(second_place) {}
    /// Where the preimages of the edge's first and second vertex were inserted, if they were.
    const std::optional<Place<d>>& first;
    const std::optional<Place<d>>& second;
    /// The first of the edge's pieces in the plan buffer.
    std::size_t pieces_begin = 0;
    bool reached_second = false;
    bool first_walk_failed = false;
    /// The entry whose walk reached the second vertex, if that was no walk from the first vertex:
    /// the boundary-entry search also finds points where the edge only touches S1's boundary
    /// from inside (it comes over S1 and meets a boundary vertex, then runs along the boundary),
    /// and the stretch before such a point would be lost (see walk_back_from_second_vertex).
    /// (A flag and a value: GCC 12 warns falsely on a std::optional<double> here.)
    bool second_reached_from_entry = false;
    double reaching_entry_eta = 0.0;
    /// Pieces are disjoint intervals of the edge parameter; an entry inside an interval already
    /// walked is where that walk left S1 (or a re-detection of it), not a new piece.
    double covered_until = -1.0;
  };

  /// Appends the piece of crossings [begin, end of the buffer).
  static void add_piece(PlanBuffer<d>& buffer, std::size_t begin, PieceStart starts_at, PieceEnd ends_at,
                        std::uint32_t end_rim = PlanBuffer<d>::no_rim,
                        std::uint32_t start_rim = PlanBuffer<d>::no_rim) {
    buffer.pieces.push_back({static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(buffer.crossings.size()),
                             starts_at, ends_at, start_rim, end_rim});
  }

  /// How many of a walk back's crossings [begin, end), from the first on, lie beyond `covered`
  /// (an edge parameter measured from the first vertex; theirs are measured from the second).
  static std::size_t crossings_beyond(const std::vector<Crossing<d>>& crossings, std::size_t begin, double covered) {
    std::size_t kept = 0;
    while (begin + kept < crossings.size() && 1.0 - crossings[begin + kept].target_parameter > covered) ++kept;
    return kept;
  }

  /// Keeps a walk's rim point for a piece, its parameter measured from the edge's first vertex
  /// (`backwards`: the walk ran from the second vertex); returns its index.
  static std::uint32_t keep_rim(PlanBuffer<d>& buffer, RimPoint<d> rim, bool backwards) {
    if (backwards) rim.eta = 1.0 - rim.eta;
    buffer.rim_points.push_back(rim);
    return static_cast<std::uint32_t>(buffer.rim_points.size() - 1);
  }

  /// Walks along S2 edge e and appends its pieces (and what could not be walked) to `buffer`.
  PlannedEdge plan_edge(Index e, unsigned worker, PlanBuffer<d>& buffer) const {
    PlannedEdge plan;
    plan.worker = worker;
    plan.pieces_begin = static_cast<std::uint32_t>(buffer.pieces.size());
    plan.failures_begin = static_cast<std::uint32_t>(buffer.failures.size());
    const auto tv = ctx_.target_edge_vertices(e);
    EdgeProgress progress(state_.target_place[tv[0]], state_.target_place[tv[1]]);
    progress.pieces_begin = buffer.pieces.size();
    if (progress.first) walk_from_first_vertex(e, progress, buffer);
    walk_from_boundary_entries(e, progress, buffer);
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
    if (progress.second && (!progress.reached_second || progress.second_reached_from_entry))
      walk_back_from_second_vertex(e, progress, buffer);
    if (progress.second && !progress.reached_second && buffer.failures.size() == plan.failures_begin &&
        !ctx_.on_boundary(*progress.second))
      buffer.failures.push_back(failure(e, EdgeFailureReason::endpoint_without_preimage, *progress.second, 1.0,
                                        fmt::format("the S2 vertex {} has no preimage", tv[0])));
    if constexpr (d == 2)
      if (ctx_.options.fold_rim) meet_across_gaps(e, progress.pieces_begin, progress.first, buffer);
    plan.pieces_end = static_cast<std::uint32_t>(buffer.pieces.size());
    plan.failures_end = static_cast<std::uint32_t>(buffer.failures.size());
    // No piece and nothing wrong: the edge lies outside D (it may touch S1's boundary at an
    // endpoint and leave at once).
    plan.outside = plan.pieces_begin == plan.pieces_end && plan.failures_begin == plan.failures_end;
    return plan;
  }

  /// The walk from the preimage of the edge's first vertex towards its second vertex.
  void walk_from_first_vertex(Index e, EdgeProgress& progress, PlanBuffer<d>& buffer) const {
    auto& crossings = buffer.crossings;
    const std::size_t begin = crossings.size();
    const WalkResult<d> w = walk(e, *progress.first, 0.0, progress.second, WalkDirection::from_first_vertex, buffer);
    if (w.end == WalkEnd::failed) {
      // What was walked before the failure is inserted as a piece ending at the last crossing
      // (partial insertion): the S2 elements on both sides of e then keep their regions away
      // from the failure, and only the faces around its far end stay outside D.
      buffer.failures.push_back(failure(e, w.reason, w.stop, w.eta));
      if (w.rim)  // the edge leaves the band (e.g. passes behind S1): the piece ends on the rim
        add_piece(buffer, begin, PieceStart::first_vertex, PieceEnd::rim_node, keep_rim(buffer, *w.rim, false));
      else if (w.crossing_count > 0)
        add_piece(buffer, begin, PieceStart::first_vertex, PieceEnd::last_crossing);
      else
        crossings.resize(begin);
      progress.covered_until = w.rim ? w.rim->eta : w.eta;
      progress.first_walk_failed = true;
      if constexpr (d == 2) walk_on_after_folds(e, w, progress, buffer);
    } else {
      const bool reached = w.end == WalkEnd::reached;
      progress.reached_second |= reached;
      progress.covered_until = reached ? 1.0 : w.eta;
      if (w.crossing_count > 0 || reached)
        add_piece(buffer, begin, PieceStart::first_vertex, reached ? PieceEnd::second_vertex : PieceEnd::last_crossing);
      else
        crossings.resize(begin);
    }
  }

  /// Where the preimage of S2 edge e comes out of the fold at which the walk `stopped` ended
  /// (fold_reentry.hpp): the nearest unfolded crossing in (stopped.eta, before) along the walk's
  /// `direction`, inside an S1 edge, as the walks solve it; its parameters are measured in that
  /// direction. Searched in the S1 elements within search_limits.fold_exit_reach rings around
  /// the stop (see below).
  struct FoldExit {
    Place<d> place;
    CrossingCandidate crossing;
  };
  std::optional<FoldExit> find_fold_exit(Index e, const WalkResult<d>& stopped, double before, WalkDirection direction,
                                         long long& calls, long long& failures) const
    requires(d == 2)
  {
    const auto& limits = ctx_.options.search_limits;
    auto tv = ctx_.target_edge_vertices(e);
    if (direction == WalkDirection::from_second_vertex) std::swap(tv[0], tv[1]);
    const WorldPoint<d> qa = ctx_.s2.vertex(tv[0]), qb = ctx_.s2.vertex(tv[1]);
    std::vector<Index> ring, next_ring, ring_edges, at_exit;
    SeenIndices seen_elements, seen_edges;
    std::vector<FoldExitCandidate> exits;
    // the rest of the edge, where an exit may lie (nearest_fold_exit keeps none elsewhere)
    const SegmentReach<d> rest(ctx_, qa + stopped.eta * (qb - qa), qa + before * (qb - qa));
    auto solve = [&](Index edge) -> std::optional<FoldExitCandidate> {
      // the closed-form root of eq. (4)'s quadratic, without the solver: dozens of S1 edges
      // are tried per search, and only the one chosen is solved (below)
      const auto ev = ctx_.s1.edge_vertices(edge);
      const WorldPoint<d>& p0 = ctx_.s1.vertex(ev[0]);
      const WorldPoint<d>& p1 = ctx_.s1.vertex(ev[1]);
      if (rest.out_of_reach(0.5 * (p0 + p1), 0.5 * (p1 - p0).norm())) return std::nullopt;
      EdgeCrossingSystem sys;
      sys.edge = {p0, p1};
      sys.directions = {ctx_.vertex_directions[ev[0]], ctx_.vertex_directions[ev[1]]};
      sys.target = {qa, qb};
      const auto root = sys.root_on_the_edges();
      if (!root || !ctx_.distance_ok((*root)(1), sys.scale())) return std::nullopt;
      return FoldExitCandidate{edge, std::clamp((*root)(0), 0.0, 1.0), (*root)(2), (*root)(1)};
    };
    auto accept = [&](const FoldExitCandidate& c) {
      // inside the S1 edge (an S1 vertex is a ghost node's or vertex preimage's place), and
      // unfolded in an element at it, as the walks judge a crossing
      const Place<d> at = ctx_.edge_place(c.domain_edge, c.lambda);
      if (at.kind != PlaceKind::edge) return false;
      ctx_.elements_of(at, at_exit);
      return unfolded_in_some_element(at_exit, [&](Index t) { return ctx_.unfolded_in_at(t, at, c.mu); });
    };
    // A fold band is a few elements wide: the exit is looked for ring by ring around the stop
    // (ring 0: the elements at it; ring r + 1: the elements sharing a vertex with ring r, not
    // seen yet; one element size per ring), up to fold_exit_reach rings, and the first ring whose S1 edges give an exit ends the search. A
    // crossing in a nearer ring is, but for a preimage that doubles back, also the nearer one
    // along the S2 edge, and most stops have their exit in the first two rings: far fewer
    // edges are solved than by a search of every element within the reach.
    std::vector<Index> candidates;
    ctx_.elements_of(stopped.stop, candidates);
    take_unseen_into(candidates, seen_elements, ring);
    const int rings = static_cast<int>(std::ceil(limits.fold_exit_reach));
    std::optional<FoldExitCandidate> exit;
    for (int r = 0; r <= rings && !ring.empty(); ++r) {
      candidates.clear();
      for (Index t : ring)
        for (int k = 0; k < 3; ++k) candidates.push_back(ctx_.s1.element_edge(t, k));
      take_unseen_into(candidates, seen_edges, ring_edges);
      exit = nearest_fold_exit(stopped.eta, before, limits.edge_parameter_slack, ring_edges, exits, solve, accept);
      if (exit || r == rings) break;
      candidates.clear();
      for (Index t : ring)
        for (Index v : ctx_.s1.element(t))
          for (Index n : ctx_.s1.vertex_elements(v)) candidates.push_back(n);
      take_unseen_into(candidates, seen_elements, next_ring);
      std::swap(ring, next_ring);
    }
    if (!exit) return std::nullopt;
    // the chosen crossing as the walks solve it
    const CrossingCandidate c = crossings_.solve(exit->domain_edge, qa, qb, calls, failures);
    const double slack = limits.edge_parameter_slack;
    if (!c.valid || !(c.eta > stopped.eta + slack) || !(c.eta < before - slack)) return std::nullopt;
    const Place<d> at = ctx_.edge_place(exit->domain_edge, c.lambda);
    if (at.kind != PlaceKind::edge) return std::nullopt;
    return FoldExit{at, c};
  }

  /// Where S2 edge e comes out in front of S1 again after the walk `stopped` ended on the rim,
  /// before `before`; parameters in the walk's `direction` (rim_reentry.hpp).
  std::optional<RimPoint<d>> find_rim_reentry(Index e, const WalkResult<d>& stopped, double before,
                                              WalkDirection direction) const
    requires(d == 2)
  {
    if (!stopped.rim) return std::nullopt;
    auto tv = ctx_.target_edge_vertices(e);
    if (direction == WalkDirection::from_second_vertex) std::swap(tv[0], tv[1]);
    return rim_reentry(ctx_, *stopped.rim, ctx_.s2.vertex(tv[0]), ctx_.s2.vertex(tv[1]), before);
  }

  /// The point at parameter eta of S2 edge e, if both a sheet through one of the `near` elements
  /// and another through one of the `far` elements reach it: strictly inside the element,
  /// unfolded, within the band and not behind a nearer sheet; the two preimages (the first such
  /// near element, then the first such far element other than it).
  std::optional<std::pair<RimPoint<d>, RimPoint<d>>> meeting_at(Index e, double eta, std::span<const Index> near,
                                                                std::span<const Index> far, long long& calls,
                                                                long long& failures) const
    requires(d == 2)
  {
    constexpr double inside = 1e-6;  // a rim node strictly inside its element, not snapped to a side
    const auto tv = ctx_.target_edge_vertices(e);
    const WorldPoint<d> q = ctx_.s2.vertex(tv[0]) + eta * (ctx_.s2.vertex(tv[1]) - ctx_.s2.vertex(tv[0]));
    auto seen_from = [&](Index t) -> std::optional<RimPoint<d>> {
      const auto p = crossings_.unfolded_preimage_in(t, q, inside, calls, failures);
      if (!p) return std::nullopt;
      Place<d> place;
      place.kind = PlaceKind::element;
      place.index = t;
      place.local = p->local;
      if (crossing_hidden_by_nearer_sheet(ctx_, state_, place, p->mu)) return std::nullopt;
      return RimPoint<d>{t, p->local, eta, fold_rim_level};
    };
    for (Index a : near) {
      const std::optional<RimPoint<d>> near_point = seen_from(a);
      if (!near_point) continue;
      for (Index b : far)
        if (b != a && within_two_rings(a, b))
          if (const std::optional<RimPoint<d>> far_point = seen_from(b)) return std::pair{*near_point, *far_point};
      return std::nullopt;
    }
    return std::nullopt;
  }

  /// Whether S1 element b shares a vertex with a or with an element that shares one with a: the
  /// sheets on both sides of a fold are joined through the folded band, a few elements wide;
  /// two sheets farther apart (two bodies, one hidden behind the other) do not meet.
  bool within_two_rings(Index a, Index b) const {
    const auto& of_b = ctx_.s1.element(b);
    auto shares_vertex_with_b = [&](Index t) {
      for (Index v : ctx_.s1.element(t))
        if (std::find(of_b.begin(), of_b.end(), v) != of_b.end()) return true;
      return false;
    };
    for (Index v : ctx_.s1.element(a))
      for (Index t : ctx_.s1.vertex_elements(v))
        if (shares_vertex_with_b(t)) return true;
    return false;
  }

  /// The S1 elements at the stretch of a piece's preimage between crossings i and i + 1 (the
  /// element both their S1 edges bound), or at the single crossing's S1 edge if there is no i + 1.
  std::vector<Index> elements_between(const EdgeCrossing& a, const EdgeCrossing* b) const {
    std::vector<Index> out;
    for (const auto& incidence : ctx_.s1.edge_elements(a.domain_edge)) {
      const Index t = incidence.element;
      if (!b || ctx_.s1.element_edge(t, 0) == b->domain_edge || ctx_.s1.element_edge(t, 1) == b->domain_edge ||
          ctx_.s1.element_edge(t, 2) == b->domain_edge)
        out.push_back(t);
    }
    return out;
  }

  /// The S1 elements at crossing a's S1 edge that are among `of`.
  std::vector<Index> elements_between(const EdgeCrossing& a, const std::vector<Index>& of) const {
    std::vector<Index> out;
    for (const auto& incidence : ctx_.s1.edge_elements(a.domain_edge))
      if (std::find(of.begin(), of.end(), incidence.element) != of.end()) out.push_back(incidence.element);
    return out;
  }

  /// Where a piece starts, if not at a crossing: the edge parameter and the S1 elements at that
  /// node (none for a piece that starts at a crossing: its stretch before its first crossing is
  /// not its own).
  struct PieceOrigin {
    double eta = 0.0;
    std::vector<Index> elements;
  };
  PieceOrigin origin_of(const typename PlanBuffer<d>::Piece& p, const PlanBuffer<d>& buffer,
                        const std::optional<Place<d>>& first_vertex) const {
    PieceOrigin o;
    if (p.starts_at == PieceStart::first_vertex && first_vertex) {
      ctx_.elements_of(*first_vertex, o.elements);
    } else if (p.starts_at == PieceStart::rim_node) {
      o.eta = buffer.rim_points[p.start_rim].eta;
      o.elements.push_back(buffer.rim_points[p.start_rim].element);
    }
    return o;
  }

  /// Where two pieces of S2 edge e leave a gap between them, the one before ending at its last
  /// crossing and the one after starting at its first (a fold crossed by walks from both ends, or
  /// a fold exit whose sheet holds the edge farther back than the exit's element), both pieces
  /// now meet at a point of the gap that the sheets of both reach (meeting_at): tried at a half,
  /// a quarter and three quarters of the gap, then a quarter, a half and three quarters of the
  /// way back from the gap along the piece before it (without its last crossing), then of the
  /// way on along the piece after it (without its first).
  void meet_across_gaps(Index e, std::size_t first_piece, const std::optional<Place<d>>& first_vertex,
                        PlanBuffer<d>& buffer) const
    requires(d == 2)
  {
    auto& pieces = buffer.pieces;
    auto& crossings = buffer.crossings;
    if (pieces.size() < first_piece + 2) return;
    using Piece = typename PlanBuffer<d>::Piece;
    auto start_eta = [&](const Piece& p) {
      return p.starts_at == PieceStart::first_vertex     ? 0.0
             : p.starts_at == PieceStart::first_crossing ? crossings[p.begin].target_parameter
                                                         : buffer.rim_points[p.start_rim].eta;
    };
    std::vector<std::size_t> order;
    for (std::size_t i = first_piece; i < pieces.size(); ++i) order.push_back(i);
    std::sort(order.begin(), order.end(),
              [&](std::size_t x, std::size_t y) { return start_eta(pieces[x]) < start_eta(pieces[y]); });
    const double slack = ctx_.options.search_limits.piece_parameter_slack;
    long long calls = 0, failures = 0;
    for (std::size_t k = 0; k + 1 < order.size(); ++k) {
      Piece& p = pieces[order[k]];
      Piece& q = pieces[order[k + 1]];
      if (p.ends_at != PieceEnd::last_crossing || q.starts_at != PieceStart::first_crossing || p.end == p.begin ||
          q.end == q.begin)
        continue;
      const EdgeCrossing& p_last = crossings[p.end - 1];
      const EdgeCrossing& q_first = crossings[q.begin];
      const double a = p_last.target_parameter, b = q_first.target_parameter;
      if (!(b > a + slack)) continue;
      const std::vector<Index> after_p = elements_between(p_last, nullptr);
      const std::vector<Index> before_q = elements_between(q_first, nullptr);
      std::optional<std::pair<RimPoint<d>, RimPoint<d>>> met;
      bool drop_p_last = false, drop_q_first = false;
      for (const double f : {0.5, 0.25, 0.75})
        if (!met) met = meeting_at(e, a + f * (b - a), after_p, before_q, calls, failures);
      // back along p (to its crossing before, or its start node), or on along q (to its second
      // crossing)
      if (!met && (p.end - p.begin >= 2 || p.starts_at != PieceStart::first_crossing)) {
        const bool single = p.end - p.begin < 2;
        const PieceOrigin origin = single ? origin_of(p, buffer, first_vertex) : PieceOrigin{};
        const double before = single ? origin.eta : crossings[p.end - 2].target_parameter;
        const std::vector<Index> behind =
            single ? elements_between(p_last, origin.elements) : elements_between(p_last, &crossings[p.end - 2]);
        for (const double g : {0.25, 0.5, 0.75})
          if (!met) met = meeting_at(e, a - g * (a - before), behind, before_q, calls, failures);
        drop_p_last = met.has_value();
      }
      if (!met && q.end - q.begin >= 2) {
        const double after = crossings[q.begin + 1].target_parameter;
        const std::vector<Index> ahead = elements_between(q_first, &crossings[q.begin + 1]);
        for (const double g : {0.25, 0.5, 0.75})
          if (!met) met = meeting_at(e, b + g * (after - b), after_p, ahead, calls, failures);
        drop_q_first = met.has_value();
      }
      if (!met) continue;
      if (drop_p_last) --p.end;
      if (drop_q_first) ++q.begin;
      p.ends_at = PieceEnd::rim_node;
      p.end_rim = keep_rim(buffer, met->first, false);
      q.starts_at = PieceStart::rim_node;
      q.start_rim = keep_rim(buffer, met->second, false);
    }
    ctx_.solver_calls += calls;
    ctx_.solver_failures += failures;
  }

  /// Where the stop's sheet and the sheet beyond a fold meet on S2 edge e (projection_fold_rim.hpp):
  /// a point of the edge that both reach unfolded, its preimage on each, and how many of the
  /// stopped piece's crossings lie before it.
  struct FoldMeeting {
    RimPoint<d> near, far;
    std::size_t kept_crossings = 0;
  };
  /// The walk `stopped` ended at a fold after the crossings `piece` of the last piece, and `exit`
  /// is where the edge comes out over the sheet beyond it. Tried, in this order: a half and a
  /// quarter of the way from the stop to the exit, inside the element ahead of the stop where the
  /// crossings were folded (stopped.fold_element); a quarter, a half and three quarters of the
  /// way back to the crossing before the stop, inside the element between the two (where the
  /// fold lies on the stop's S1 edge itself, or just beyond). The preimage on the sheet beyond is
  /// looked for in the element where a walk back from the exit along that sheet holds that point
  /// of the edge. (The ring of elements around the exit, tried first, made 12 % more meeting
  /// nodes on the femur pair but no fewer defects, for twice the added solver calls.)
  std::optional<FoldMeeting> fold_meeting(Index e, const WalkResult<d>& stopped, const FoldExit& exit,
                                          std::vector<Crossing<d>> piece, const PieceOrigin& start,
                                          PlanBuffer<d>& buffer, long long& calls, long long& failures) const
    requires(d == 2)
  {
    // (`piece` is a copy: the walk below appends to the buffer it came from)
    if (stopped.rim || piece.empty()) return std::nullopt;
    const std::size_t n = piece.size();
    // The sheet beyond, walked back from the exit towards the stop (its crossings are taken off
    // the buffer again): the element of each stretch between two of its crossings, and beyond
    // the last one the element where that walk met the sheet's own fold.
    struct Stretch {
      double low, high;  // edge parameters, from the first vertex
      Index element;
    };
    std::vector<Stretch> beyond;
    {
      const std::size_t mark = buffer.crossings.size();
      const WalkResult<d> back =
          walk(e, exit.place, 1.0 - exit.crossing.eta, std::nullopt, WalkDirection::from_second_vertex, buffer);
      EdgeCrossing previous{exit.place.index, exit.crossing.lambda, exit.crossing.eta};
      double high = exit.crossing.eta;
      for (std::size_t i = mark; i < buffer.crossings.size(); ++i) {
        const EdgeCrossing& c = buffer.crossings[i];
        const double low = 1.0 - c.target_parameter;
        for (Index t : elements_between(previous, &c)) beyond.push_back({low, high, t});
        previous = c;
        high = low;
      }
      if (back.fold_element != invalid_index) beyond.push_back({-1.0, high, back.fold_element});
      buffer.crossings.resize(mark);
    }
    auto meet = [&](double eta, Index near_element, std::size_t kept) -> std::optional<FoldMeeting> {
      std::vector<Index> far;
      for (const Stretch& stretch : beyond)
        if (eta >= stretch.low && eta <= stretch.high) far.push_back(stretch.element);
      const auto points = meeting_at(e, eta, std::span<const Index>(&near_element, 1), std::span<const Index>(far),
                                     calls, failures);
      if (!points) return std::nullopt;
      return FoldMeeting{points->first, points->second, kept};
    };
    if (stopped.fold_element != invalid_index)
      for (const double f : {0.5, 0.25})
        if (auto m = meet(stopped.eta + f * (exit.crossing.eta - stopped.eta), stopped.fold_element, n)) return m;
    // behind the stop: the element between the last two crossings, or between the piece's start
    // and its only crossing
    const double eta_before = n >= 2 ? piece[n - 2].target_parameter : start.eta;
    const std::vector<Index> behind = n >= 2 ? elements_between(piece[n - 1], &piece[n - 2])
                                             : elements_between(piece[n - 1], start.elements);
    for (const double g : {0.25, 0.5, 0.75})
      for (Index t : behind)
        if (auto m = meet(stopped.eta - g * (stopped.eta - eta_before), t, n - 1)) return m;
    return std::nullopt;
  }

  /// After the walk `stopped` from the first vertex or a boundary entry of S2 edge e ended at a
  /// fold (or another restartable place): new pieces from where the edge's preimage comes out
  /// of it, each walked on towards the second vertex, up to search_limits.fold_exits times while
  /// they stop so again.
  void walk_on_after_folds(Index e, WalkResult<d> stopped, EdgeProgress& progress, PlanBuffer<d>& buffer) const
    requires(d == 2)
  {
    long long calls = 0, failures = 0;
    for (int round = 0; round < ctx_.options.search_limits.fold_exits && stopped.end == WalkEnd::failed &&
                        restartable(stopped.reason);
         ++round) {
      stopped.eta = std::max(stopped.eta, progress.covered_until);
      const std::optional<FoldExit> exit = find_fold_exit(e, stopped, 1.0, WalkDirection::from_first_vertex, calls, failures);
      // where the edge comes out from behind S1, if that is before the exit
      const std::optional<RimPoint<d>> reentry =
          find_rim_reentry(e, stopped, exit ? exit->crossing.eta : 1.0, WalkDirection::from_first_vertex);
      if (!exit && !reentry) break;
      auto& crossings = buffer.crossings;
      // The stop's sheet and the one beyond the fold both reach a stretch of the edge (a fold
      // maps three sheets onto it: before, folded, beyond): where the stop's piece ended at its
      // last crossing, it now ends at a point of that stretch, and the walk beyond starts at the
      // same point on the other sheet; the rim traced through such points
      // (projection_fold_rim.hpp) lets the faces on both sides close.
      std::optional<FoldMeeting> meeting;
      if (exit && !reentry && ctx_.options.fold_rim && stopped.reason == EdgeFailureReason::fold &&
          buffer.pieces.size() > progress.pieces_begin) {
        auto& last = buffer.pieces.back();
        if (last.ends_at == PieceEnd::last_crossing && last.end == crossings.size() && last.end > last.begin &&
            crossings[last.end - 1].target_parameter == stopped.eta) {
          meeting = fold_meeting(e, stopped, *exit,
                                 std::vector<Crossing<d>>(crossings.begin() + last.begin, crossings.begin() + last.end),
                                 origin_of(last, buffer, progress.first), buffer, calls, failures);
          if (meeting) {
            // (a crossing taken off stays in the buffer, unused)
            last.end = static_cast<std::uint32_t>(last.begin + meeting->kept_crossings);
            last.ends_at = PieceEnd::rim_node;
            last.end_rim = keep_rim(buffer, meeting->near, false);
          }
        }
      }
      const std::size_t begin = crossings.size();
      std::uint32_t start_rim = PlanBuffer<d>::no_rim;
      if (meeting) {
        start_rim = keep_rim(buffer, meeting->far, false);
        Place<d> inside;
        inside.kind = PlaceKind::element;
        inside.index = meeting->far.element;
        inside.local = meeting->far.local;
        stopped = walk(e, inside, meeting->far.eta, progress.second, WalkDirection::from_first_vertex, buffer);
        // one rim node per S1 element and S2 edge, as after a reentry (below)
        if (stopped.rim && stopped.rim->element == meeting->far.element) stopped.rim.reset();
      } else if (reentry) {
        start_rim = keep_rim(buffer, *reentry, false);
        Place<d> inside;
        inside.kind = PlaceKind::element;
        inside.index = reentry->element;
        inside.local = reentry->local;
        stopped = walk(e, inside, reentry->eta, progress.second, WalkDirection::from_first_vertex, buffer);
        // one rim node per S1 element and S2 edge: passing behind S1 again in the same element,
        // the piece ends at its last crossing
        if (stopped.rim && stopped.rim->element == reentry->element) stopped.rim.reset();
      } else {
        crossings.push_back(EdgeCrossing{exit->place.index, exit->crossing.lambda, exit->crossing.eta});
        stopped = walk(e, exit->place, exit->crossing.eta, progress.second, WalkDirection::from_first_vertex, buffer);
      }
      const bool reached = stopped.end == WalkEnd::reached;
      const bool from_rim_node = reentry || meeting;
      if (stopped.crossing_count == 0 && !reached && !(from_rim_node && stopped.rim)) {
        crossings.resize(begin);
        if (from_rim_node) buffer.rim_points.pop_back();
        break;
      }
      const PieceStart starts_at = from_rim_node ? PieceStart::rim_node : PieceStart::first_crossing;
      if (!reached && stopped.rim)
        add_piece(buffer, begin, starts_at, PieceEnd::rim_node, keep_rim(buffer, *stopped.rim, false), start_rim);
      else
        add_piece(buffer, begin, starts_at, reached ? PieceEnd::second_vertex : PieceEnd::last_crossing,
                  PlanBuffer<d>::no_rim, start_rim);
      progress.covered_until = reached ? 1.0 : (stopped.rim ? stopped.rim->eta : stopped.eta);
      progress.reached_second |= reached;
    }
    ctx_.solver_calls += calls;
    ctx_.solver_failures += failures;
  }

  /// After the walk `stopped` backwards from the second vertex, or from where the edge leaves
  /// S1, of S2 edge e ended at a fold or another restartable place (its parameters measured
  /// from the second vertex): new pieces from where the edge's preimage comes out of it — where
  /// the edge comes out from behind S1 (a rim node, as walk_on_after_folds does forwards) or
  /// else the fold exit's crossing — each walked on towards the first vertex and kept only short
  /// of what the forward walks covered (`covered_until`), up to search_limits.fold_exits times
  /// while they stop so again.
  void walk_back_after_folds(Index e, WalkResult<d> stopped, double covered_until, PlanBuffer<d>& buffer) const
    requires(d == 2)
  {
    const double piece_slack = ctx_.options.search_limits.piece_parameter_slack;
    // the forward walks' end, measured from the second vertex
    const double before = 1.0 - std::max(covered_until, 0.0);
    long long calls = 0, failures = 0;
    auto& crossings = buffer.crossings;
    for (int round = 0; round < ctx_.options.search_limits.fold_exits && stopped.end == WalkEnd::failed &&
                        restartable(stopped.reason);
         ++round) {
      const std::optional<FoldExit> exit = find_fold_exit(e, stopped, before, WalkDirection::from_second_vertex, calls, failures);
      // where the edge comes out from behind S1, if that is before the exit
      const std::optional<RimPoint<d>> reentry =
          find_rim_reentry(e, stopped, exit ? exit->crossing.eta : before, WalkDirection::from_second_vertex);
      if (!exit && !reentry) break;
      const std::size_t begin = crossings.size();
      if (reentry) {
        Place<d> inside;
        inside.kind = PlaceKind::element;
        inside.index = reentry->element;
        inside.local = reentry->local;
        stopped = walk(e, inside, reentry->eta, std::nullopt, WalkDirection::from_second_vertex, buffer);
        // one rim node per S1 element and S2 edge (see walk_on_after_folds)
        if (stopped.rim && stopped.rim->element == reentry->element) stopped.rim.reset();
      } else {
        crossings.push_back(EdgeCrossing{exit->place.index, exit->crossing.lambda, exit->crossing.eta});
        stopped = walk(e, exit->place, exit->crossing.eta, std::nullopt, WalkDirection::from_second_vertex, buffer);
      }
      // a walk that comes into the stretch the forward walks covered stops short of it
      std::size_t end = begin;
      while (end < crossings.size() && crossings[end].target_parameter < before - piece_slack) ++end;
      const bool cut = end < crossings.size();
      crossings.resize(end);
      // the walk back ended on the rim short of the forward walks: the piece starts there
      const bool from_rim = !cut && stopped.end == WalkEnd::failed && stopped.rim &&
                            stopped.rim->eta < before - piece_slack;
      if ((end - begin) + (reentry ? 1 : 0) + (from_rim ? 1 : 0) < 2) {  // no stretch beyond the restart point
        crossings.resize(begin);
        break;
      }
      // measured from the first vertex again, in the edge's direction, ending where the walk
      // back restarted
      std::reverse(crossings.begin() + static_cast<std::ptrdiff_t>(begin), crossings.end());
      for (std::size_t i = begin; i < crossings.size(); ++i)
        crossings[i].target_parameter = 1.0 - crossings[i].target_parameter;
      const std::uint32_t end_rim = reentry ? keep_rim(buffer, *reentry, true) : PlanBuffer<d>::no_rim;
      const std::uint32_t start_rim = from_rim ? keep_rim(buffer, *stopped.rim, true) : PlanBuffer<d>::no_rim;
      add_piece(buffer, begin, from_rim ? PieceStart::rim_node : PieceStart::first_crossing,
                reentry ? PieceEnd::rim_node : PieceEnd::last_crossing, end_rim, start_rim);
      if (cut) break;
    }
    ctx_.solver_calls += calls;
    ctx_.solver_failures += failures;
  }

  /// The walks from the points where the edge enters S1 across its boundary, beyond what the
  /// walks before them covered.
  void walk_from_boundary_entries(Index e, EdgeProgress& progress, PlanBuffer<d>& buffer) const {
    if (state_.boundary_entries.empty()) return;  // no S2 edge enters S1 across its boundary
    const double piece_slack = ctx_.options.search_limits.piece_parameter_slack;
    auto& crossings = buffer.crossings;
    for (const auto& entry : state_.boundary_entries.of(e)) {
      if (entry.eta <= progress.covered_until + piece_slack) continue;
      const std::size_t begin = crossings.size();
      crossings.push_back(entry.crossing);  // the piece starts where the edge enters S1
      const WalkResult<d> w = walk(e, entry.place, entry.eta, progress.second, WalkDirection::from_first_vertex, buffer);
      const double walked_until = progress.covered_until;  // before this entry
      progress.covered_until = w.end == WalkEnd::reached ? 1.0 : w.eta;
      if (w.end == WalkEnd::failed) {
        if (w.crossing_count > 0) {  // partial insertion, as for the walk from the first vertex
          buffer.failures.push_back(failure(e, w.reason, w.stop, w.eta));
          if (w.rim) {
            add_piece(buffer, begin, PieceStart::first_crossing, PieceEnd::rim_node, keep_rim(buffer, *w.rim, false));
            progress.covered_until = w.rim->eta;
          } else {
            add_piece(buffer, begin, PieceStart::first_crossing, PieceEnd::last_crossing);
          }
          if constexpr (d == 2) walk_on_after_folds(e, w, progress, buffer);
          continue;
        }
        if (w.rim) {  // right after the entry the edge passes behind S1: a piece from the entry to the rim
          buffer.failures.push_back(failure(e, w.reason, w.stop, w.eta));
          add_piece(buffer, begin, PieceStart::first_crossing, PieceEnd::rim_node, keep_rim(buffer, *w.rim, false));
          progress.covered_until = w.rim->eta;
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
      progress.reached_second |= reached;
      if (reached) {
        progress.second_reached_from_entry = true;
        progress.reaching_entry_eta = entry.eta;
      }
      add_piece(buffer, begin, PieceStart::first_crossing, reached ? PieceEnd::second_vertex : PieceEnd::last_crossing);
    }
  }

  /// The walk from the preimage of the second vertex backwards (see plan_edge for when it runs).
  void walk_back_from_second_vertex(Index e, EdgeProgress& progress, PlanBuffer<d>& buffer) const {
    const double piece_slack = ctx_.options.search_limits.piece_parameter_slack;
    auto& crossings = buffer.crossings;
    const std::size_t begin = crossings.size();
    const WalkResult<d> w = walk(e, *progress.second, 0.0, std::nullopt, WalkDirection::from_second_vertex, buffer);
    auto reverse_into_piece = [&](std::size_t piece_begin) {
      std::reverse(crossings.begin() + static_cast<std::ptrdiff_t>(piece_begin), crossings.end());
      for (std::size_t i = piece_begin; i < crossings.size(); ++i)
        crossings[i].target_parameter = 1.0 - crossings[i].target_parameter;
      add_piece(buffer, piece_begin, PieceStart::first_crossing, PieceEnd::second_vertex);
      progress.reached_second = true;
    };
    // A walk that stopped because the edge passes behind S1 starts the piece at the rim, if
    // that lies beyond what the forward walks covered.
    if (w.end == WalkEnd::failed && w.rim && !progress.second_reached_from_entry &&
        1.0 - w.rim->eta > progress.covered_until + piece_slack) {
      std::reverse(crossings.begin() + static_cast<std::ptrdiff_t>(begin), crossings.end());
      for (std::size_t i = begin; i < crossings.size(); ++i)
        crossings[i].target_parameter = 1.0 - crossings[i].target_parameter;
      add_piece(buffer, begin, PieceStart::rim_node, PieceEnd::second_vertex, PlanBuffer<d>::no_rim,
                keep_rim(buffer, *w.rim, true));
      progress.reached_second = true;
      if (!progress.first_walk_failed) buffer.failures.push_back(failure(e, w.reason, w.stop, 1.0 - w.eta));
      if constexpr (d == 2) walk_back_after_folds(e, w, progress.covered_until, buffer);
      return;
    }
    // where the backward walk's last crossing lies, measured from the first vertex
    const double walked_back_to = w.crossing_count > 0 ? 1.0 - crossings.back().target_parameter : 1.0;
    const bool partial = w.crossing_count > 0 && !progress.second_reached_from_entry &&
                         (w.end == WalkEnd::failed || (progress.first_walk_failed && w.end == WalkEnd::left_boundary));
    if (partial) {
      if (walked_back_to > progress.covered_until + piece_slack) {
        reverse_into_piece(begin);
      } else if (const std::size_t kept = crossings_beyond(crossings, begin, progress.covered_until + piece_slack);
                 kept > 0) {
        // the walk back ran on into what the forward walks covered: its stretch up to the last
        // crossing short of that is still reached from nowhere else
        crossings.resize(begin + kept);
        reverse_into_piece(begin);
      } else {
        crossings.resize(begin);
      }
      if (w.end == WalkEnd::failed && !progress.first_walk_failed && w.reason != EdgeFailureReason::endpoint_without_preimage)
        buffer.failures.push_back(failure(e, w.reason, w.stop, 1.0 - w.eta));
    } else if (w.end == WalkEnd::left_boundary && w.crossing_count > 0) {
      // measured from the first vertex again, in the edge's direction
      if (progress.second_reached_from_entry && !(1.0 - w.eta < progress.reaching_entry_eta - piece_slack)) {
        crossings.resize(begin);  // no farther back than the entry: the entry's piece stands
      } else {
        std::size_t piece_begin = begin;
        if (progress.second_reached_from_entry) {  // the entry's piece is the last one: replace it
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
      if (w.end == WalkEnd::failed && !progress.second_reached_from_entry && !progress.first_walk_failed &&
          w.reason != EdgeFailureReason::endpoint_without_preimage)
        buffer.failures.push_back(failure(e, w.reason, w.stop, 1.0 - w.eta));
    }
    // a fold (or another restartable stop) on the way back: the stretch between it and what the
    // forward walks covered may be reached from nowhere else
    if constexpr (d == 2) {
      if (w.end == WalkEnd::failed && !progress.second_reached_from_entry)
        walk_back_after_folds(e, w, progress.covered_until, buffer);
    }
  }

 private:
  const ProjectionContext<d>& ctx_;
  const ProjectionState<d>& state_;
  EdgeCrossings<d, Solver> crossings_;
};

}  // namespace plmap::projection
