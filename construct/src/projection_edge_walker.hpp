#pragma once
// Normal projection, phase 4: the walker along one S2 edge's preimage (EdgeWalker), shared by the
// walks of every edge (projection_edge_walks.cpp, plan_edge_block) and the walks from the rim
// (projection_rim_walks.cpp, plan_rim_walks). Internal to construct/.

#include "projection_edge_walks.hpp"

#include "nearer_sheet.hpp"
#include "projection_edge_crossings.hpp"
#include "projection_fold_exits.hpp"
#include "projection_fold_meetings.hpp"
#include "rim_geometry.hpp"
#include "rim_reentry.hpp"
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
              PlanBuffer<d>::no_rim, from_rim ? buffer.keep_rim(*w.rim, true) : PlanBuffer<d>::no_rim);
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
      if (ctx_.options.fold_rim)
        FoldMeetings<Solver>(ctx_, state_, crossings_).meet_across_gaps(e, progress.pieces_begin, progress.first, buffer);
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
        add_piece(buffer, begin, PieceStart::first_vertex, PieceEnd::rim_node, buffer.keep_rim(*w.rim, false));
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

  /// find_fold_exit (projection_fold_exits.hpp) for the walk `stopped` along S2 edge e, in its
  /// `direction`; parameters measured in that direction.
  std::optional<FoldExit> find_fold_exit(Index e, const WalkResult<d>& stopped, double before, WalkDirection direction,
                                         long long& calls, long long& failures) const
    requires(d == 2)
  {
    auto tv = ctx_.target_edge_vertices(e);
    if (direction == WalkDirection::from_second_vertex) std::swap(tv[0], tv[1]);
    return projection::find_fold_exit(ctx_, crossings_, ctx_.s2.vertex(tv[0]), ctx_.s2.vertex(tv[1]), stopped.stop,
                                      stopped.eta, before, calls, failures);
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
      std::optional<RimPoint<d>> meeting;
      if (exit && !reentry && ctx_.options.fold_rim && stopped.reason == EdgeFailureReason::fold && !stopped.rim) {
        // the sheet beyond, walked back from the exit (FoldMeetings::fold_meeting)
        auto walk_back = [&](const EdgeCrossing& from) {
          return walk(e, ctx_.edge_place(from.domain_edge, from.domain_parameter), 1.0 - from.target_parameter,
                      std::nullopt, WalkDirection::from_second_vertex, buffer)
              .fold_element;
        };
        meeting = FoldMeetings<Solver>(ctx_, state_, crossings_)
                      .meet_after_exit(e, stopped.eta, stopped.fold_element,
                                       EdgeCrossing{exit->place.index, exit->crossing.lambda, exit->crossing.eta},
                                       progress.pieces_begin, progress.first, buffer, walk_back, calls, failures);
      }
      const std::size_t begin = crossings.size();
      std::uint32_t start_rim = PlanBuffer<d>::no_rim;
      // from a point inside an element: where the sheets meet, or where the edge comes out from
      // behind S1
      if (const std::optional<RimPoint<d>> from = meeting ? meeting : reentry) {
        start_rim = buffer.keep_rim(*from, false);
        Place<d> inside;
        inside.kind = PlaceKind::element;
        inside.index = from->element;
        inside.local = from->local;
        stopped = walk(e, inside, from->eta, progress.second, WalkDirection::from_first_vertex, buffer);
        // one rim node per S1 element and S2 edge: passing behind S1 again in the same element,
        // the piece ends at its last crossing
        if (stopped.rim && stopped.rim->element == from->element) stopped.rim.reset();
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
        add_piece(buffer, begin, starts_at, PieceEnd::rim_node, buffer.keep_rim(*stopped.rim, false), start_rim);
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
      const std::uint32_t end_rim = reentry ? buffer.keep_rim(*reentry, true) : PlanBuffer<d>::no_rim;
      const std::uint32_t start_rim = from_rim ? buffer.keep_rim(*stopped.rim, true) : PlanBuffer<d>::no_rim;
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
            add_piece(buffer, begin, PieceStart::first_crossing, PieceEnd::rim_node, buffer.keep_rim(*w.rim, false));
            progress.covered_until = w.rim->eta;
          } else {
            add_piece(buffer, begin, PieceStart::first_crossing, PieceEnd::last_crossing);
          }
          if constexpr (d == 2) walk_on_after_folds(e, w, progress, buffer);
          continue;
        }
        if (w.rim) {  // right after the entry the edge passes behind S1: a piece from the entry to the rim
          buffer.failures.push_back(failure(e, w.reason, w.stop, w.eta));
          add_piece(buffer, begin, PieceStart::first_crossing, PieceEnd::rim_node, buffer.keep_rim(*w.rim, false));
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
                buffer.keep_rim(*w.rim, true));
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
