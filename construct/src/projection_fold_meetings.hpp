#pragma once
// Normal projection, phase 4: where the sheets on both sides of a fold meet on an S2 edge
// (projection_fold_rim.hpp says why). The edge walker (projection_edge_walker.hpp) asks after a
// fold exit (meet_after_exit) and once an edge's walks are done (meet_across_gaps); what it
// finds turns the ends of two pieces into rim points of level fold_rim_level, which the
// insertion makes nodes and trace_fold_rims joins across S2 triangles. d = 2 only. Internal to
// construct/.

#include "nearer_sheet.hpp"
#include "projection_edge_crossings.hpp"
#include "projection_edge_walks.hpp"

#include <algorithm>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace plmap::projection {

template <class Solver>
class FoldMeetings {
 public:
  FoldMeetings(const ProjectionContext<2>& ctx, const ProjectionState<2>& state,
               const EdgeCrossings<2, Solver>& crossings)
      : ctx_(ctx), state_(state), crossings_(crossings) {}

  /// A walk along S2 edge e stopped at a fold (edge parameter stop_eta; fold_element: the
  /// element ahead of the stop in which its crossings were folded, or invalid_index), and `exit`
  /// is where the edge comes out over the sheet beyond it. If the edge's last piece (of those from
  /// first_piece on) ends at that stop, it now ends where the stop's sheet meets the sheet beyond
  /// (fold_meeting below), and the point on the sheet beyond is returned: the walk on starts
  /// there. Else nullopt, and the piece stays. `walk_back`: see fold_meeting.
  template <class WalkBack>
  std::optional<RimPoint<2>> meet_after_exit(Index e, double stop_eta, Index fold_element, const EdgeCrossing& exit,
                                             std::size_t first_piece, const std::optional<Place<2>>& first_vertex,
                                             PlanBuffer<2>& buffer, WalkBack&& walk_back, long long& calls,
                                             long long& failures) const {
    if (buffer.pieces.size() <= first_piece) return std::nullopt;
    auto& last = buffer.pieces.back();  // (the walk back appends crossings only, no pieces)
    const auto& crossings = buffer.crossings;
    if (last.ends_at != PieceEnd::last_crossing || last.end != crossings.size() || last.end == last.begin ||
        crossings[last.end - 1].target_parameter != stop_eta)
      return std::nullopt;
    const std::optional<FoldMeeting> meeting =
        fold_meeting(e, stop_eta, fold_element, exit,
                     std::vector<EdgeCrossing>(crossings.begin() + last.begin, crossings.begin() + last.end),
                     origin_of(last, buffer, first_vertex), buffer, walk_back, calls, failures);
    if (!meeting) return std::nullopt;
    // (a crossing taken off stays in the buffer, unused)
    last.end = static_cast<std::uint32_t>(last.begin + meeting->kept_crossings);
    last.ends_at = PieceEnd::rim_node;
    last.end_rim = buffer.keep_rim(meeting->near, false);
    return meeting->far;
  }

  /// Where two pieces of S2 edge e leave a gap between them, the one before ending at its last
  /// crossing and the one after starting at its first (a fold crossed by walks from both ends, or
  /// a fold exit whose sheet holds the edge farther back than the exit's element), both pieces
  /// now meet at a point of the gap that the sheets of both reach (meeting_at): tried at a half,
  /// a quarter and three quarters of the gap, then a quarter, a half and three quarters of the
  /// way back from the gap along the piece before it (without its last crossing), then of the
  /// way on along the piece after it (without its first).
  void meet_across_gaps(Index e, std::size_t first_piece, const std::optional<Place<2>>& first_vertex,
                        PlanBuffer<2>& buffer) const {
    auto& pieces = buffer.pieces;
    auto& crossings = buffer.crossings;
    if (pieces.size() < first_piece + 2) return;
    using Piece = PlanBuffer<2>::Piece;
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
      std::optional<std::pair<RimPoint<2>, RimPoint<2>>> met;
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
      p.end_rim = buffer.keep_rim(met->first, false);
      q.starts_at = PieceStart::rim_node;
      q.start_rim = buffer.keep_rim(met->second, false);
    }
    ctx_.solver_calls += calls;
    ctx_.solver_failures += failures;
  }

 private:
  /// The point at parameter eta of S2 edge e, if both a sheet through one of the `near` elements
  /// and another through one of the `far` elements reach it: strictly inside the element,
  /// unfolded, within the band and not behind a nearer sheet; the two preimages (the first such
  /// near element, then the first such far element other than it).
  std::optional<std::pair<RimPoint<2>, RimPoint<2>>> meeting_at(Index e, double eta, std::span<const Index> near,
                                                                std::span<const Index> far, long long& calls,
                                                                long long& failures) const {
    constexpr double inside = 1e-6;  // a rim node strictly inside its element, not snapped to a side
    const auto tv = ctx_.target_edge_vertices(e);
    const WorldPoint<2> q = ctx_.s2.vertex(tv[0]) + eta * (ctx_.s2.vertex(tv[1]) - ctx_.s2.vertex(tv[0]));
    auto seen_from = [&](Index t) -> std::optional<RimPoint<2>> {
      const auto p = crossings_.unfolded_preimage_in(t, q, inside, calls, failures);
      if (!p) return std::nullopt;
      Place<2> place;
      place.kind = PlaceKind::element;
      place.index = t;
      place.local = p->local;
      if (crossing_hidden_by_nearer_sheet(ctx_, state_, place, p->mu)) return std::nullopt;
      return RimPoint<2>{t, p->local, eta, fold_rim_level};
    };
    for (Index a : near) {
      const std::optional<RimPoint<2>> near_point = seen_from(a);
      if (!near_point) continue;
      for (Index b : far)
        if (b != a && within_two_rings(a, b))
          if (const std::optional<RimPoint<2>> far_point = seen_from(b)) return std::pair{*near_point, *far_point};
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
  PieceOrigin origin_of(const PlanBuffer<2>::Piece& p, const PlanBuffer<2>& buffer,
                        const std::optional<Place<2>>& first_vertex) const {
    PieceOrigin o;
    if (p.starts_at == PieceStart::first_vertex && first_vertex) {
      ctx_.elements_of(*first_vertex, o.elements);
    } else if (p.starts_at == PieceStart::rim_node) {
      o.eta = buffer.rim_points[p.start_rim].eta;
      o.elements.push_back(buffer.rim_points[p.start_rim].element);
    }
    return o;
  }

  /// Where the stop's sheet and the sheet beyond a fold meet on S2 edge e (projection_fold_rim.hpp):
  /// a point of the edge that both reach unfolded, its preimage on each, and how many of the
  /// stopped piece's crossings lie before it.
  struct FoldMeeting {
    RimPoint<2> near, far;
    std::size_t kept_crossings = 0;
  };
  /// A walk along S2 edge e stopped at a fold (edge parameter stop_eta) after the crossings
  /// `piece` of its piece, and `exit` is where the edge comes out over the sheet beyond it. Tried,
  /// in this order: a half and a quarter of the way from the stop to the exit, inside the element
  /// ahead of the stop where the crossings were folded (fold_element); a quarter, a half and
  /// three quarters of the way back to the crossing before the stop, inside the element between
  /// the two (where the fold lies on the stop's S1 edge itself, or just beyond); the same
  /// fractions of the part of that last stretch that the sheet beyond holds too; and without a
  /// fold_element, of the way from the stop to where the sheet beyond holds the edge, inside the
  /// element across the stop's S1 edge. The preimage on the sheet beyond is looked for in the
  /// element where a walk back from the exit along that sheet holds that point of the edge
  /// (`walk_back(exit)` appends that walk's crossings to the buffer, parameters from the second
  /// vertex, and returns the element where it met the sheet's own fold, or invalid_index; they
  /// are taken off again). (The ring of elements around the exit, tried first, made 12 % more
  /// meeting nodes on the femur pair but no fewer defects, for twice the added solver calls.)
  template <class WalkBack>
  std::optional<FoldMeeting> fold_meeting(Index e, double stop_eta, Index fold_element, const EdgeCrossing& exit,
                                          std::vector<EdgeCrossing> piece, const PieceOrigin& start,
                                          PlanBuffer<2>& buffer, WalkBack&& walk_back, long long& calls,
                                          long long& failures) const {
    // (`piece` is a copy: the walk below appends to the buffer it came from)
    if (piece.empty()) return std::nullopt;
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
      const Index fold_beyond = walk_back(exit);
      EdgeCrossing previous = exit;
      double high = exit.target_parameter;
      for (std::size_t i = mark; i < buffer.crossings.size(); ++i) {
        const EdgeCrossing& c = buffer.crossings[i];
        const double low = 1.0 - c.target_parameter;
        for (Index t : elements_between(previous, &c)) beyond.push_back({low, high, t});
        previous = c;
        high = low;
      }
      if (fold_beyond != invalid_index) beyond.push_back({-1.0, high, fold_beyond});
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
    if (fold_element != invalid_index)
      for (const double f : {0.5, 0.25})
        if (auto m = meet(stop_eta + f * (exit.target_parameter - stop_eta), fold_element, n)) return m;
    // behind the stop: the element between the last two crossings, or between the piece's start
    // and its only crossing
    const double eta_before = n >= 2 ? piece[n - 2].target_parameter : start.eta;
    const std::vector<Index> behind = n >= 2 ? elements_between(piece[n - 1], &piece[n - 2])
                                             : elements_between(piece[n - 1], start.elements);
    for (const double g : {0.25, 0.5, 0.75})
      for (Index t : behind)
        if (auto m = meet(stop_eta - g * (stop_eta - eta_before), t, n - 1)) return m;
    // Where the two sheets' stretches overlap: the sheet beyond, walked back from the exit, holds
    // the edge down to `covered_beyond`; if that lies inside the stop's last stretch, both reach
    // the part of the stretch above it (a narrow zone, near a cusp of the fold, that the fixed
    // fractions above miss; below the stretch's start they would be the same points again).
    double covered_beyond = exit.target_parameter;
    for (const Stretch& stretch : beyond)
      if (stretch.low >= 0.0) covered_beyond = std::min(covered_beyond, stretch.low);
    if (covered_beyond < stop_eta && covered_beyond > eta_before)
      for (const double g : {0.5, 0.25, 0.75})
        for (Index t : behind)
          if (auto m = meet(covered_beyond + g * (stop_eta - covered_beyond), t, n - 1)) return m;
    // A walk that recorded no element ahead of its stop (it stopped where its own point was
    // folded): the stop's sheet goes on into the element across the stop's S1 edge, up to its
    // fold, between the stop and where the sheet beyond is known to hold the edge.
    if (fold_element == invalid_index) {
      const double high = covered_beyond > stop_eta ? covered_beyond : exit.target_parameter;
      for (const double f : {0.5, 0.25, 0.75})
        for (const auto& incidence : ctx_.s1.edge_elements(piece[n - 1].domain_edge))
          if (std::find(behind.begin(), behind.end(), incidence.element) == behind.end())
            if (auto m = meet(stop_eta + f * (high - stop_eta), incidence.element, n)) return m;
    }
    return std::nullopt;
  }


  const ProjectionContext<2>& ctx_;
  const ProjectionState<2>& state_;
  const EdgeCrossings<2, Solver>& crossings_;
};

}  // namespace plmap::projection
