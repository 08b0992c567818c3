// Vertex removal planning, the last phase: the straightened pieces that the cut put in one new
// triangle must not meet except at shared ends, with exact predicates on the shared planar
// coordinates.
//
// Nor may they come closer than the clearance: a node of one piece (a vertex preimage, a
// crossing) within rounding of another S2 edge's piece passes the exact test on the rounded
// planar positions on either side, but the hand-over to S1's barycentric coordinates can put it
// on that piece, and the S2 triangle between them loses its region (the images no longer tile
// S2). So a node within edge_clearance times the star's size of another piece is refused like a
// crossing, as a vertex preimage on a new edge is (node_on_new_edge).

#include "piece_clearance.hpp"
#include "removal_planning.hpp"

#include <plmap/core/predicates.hpp>

#include <algorithm>

namespace plmap {

using removal::Piece;
using removal::Vec2;

namespace {

double min_x(const Piece& p) { return std::min(p.from.x(), p.to.x()); }

/// True if pieces a and b of one new triangle cross, or come within `margin` of each other
/// other than at a shared end.
bool pieces_meet(const Piece& a, const Piece& b, double margin) {
  const Vec2 &p = a.from, &q = a.to, &r = b.from, &t = b.to;
  // Most pairs that get here share an end (consecutive pieces of a polyline, pieces ending at
  // one node): those cross only if they are collinear, which one orientation of b's other end
  // decides (segments_cross_properly's answer, at a quarter of its predicates), and come too
  // close only if they leave the shared end at an angle so small that the shorter one's other
  // end is within the margin of the longer one.
  if (p == r || p == t || q == r || q == t) {
    const Vec2& shared = (p == r || p == t) ? p : q;
    const Vec2& end_a = shared == p ? q : p;
    const Vec2& end_b = r == shared ? t : r;
    if (orient2d(shared, end_a, end_b) != 0) return detail::pieces_leave_too_close(end_a - shared, end_b - shared, margin);
  } else if (detail::within_margin(p, r, t, margin) || detail::within_margin(q, r, t, margin) ||
             detail::within_margin(r, p, q, margin) || detail::within_margin(t, p, q, margin)) {
    return true;
  }
  return segments_cross_properly(p, q, r, t);
}

}  // namespace

/// Sorted by triangle, then by the left end of the piece's x-range: two pieces that cross or
/// come that close have x-ranges that overlap within the margin, and the scan over the later
/// pieces of a triangle stops at the first one that starts right of the current piece's end (a
/// sweep along x instead of all pairs: late coarse triangles carry many pieces).
RemovalRefusal EditableMap::RemovalPlanning::check_pieces() {
  const double margin = clearance * star_size();
  std::vector<Piece>& pieces = scratch.pieces;
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) {
    return a.triangle != b.triangle ? a.triangle < b.triangle : min_x(a) < min_x(b);
  });
  for (std::size_t a = 0; a < pieces.size(); ++a) {
    const double max_x = std::max(pieces[a].from.x(), pieces[a].to.x()) + margin;
    const double low_y = std::min(pieces[a].from.y(), pieces[a].to.y()) - margin;
    const double high_y = std::max(pieces[a].from.y(), pieces[a].to.y()) + margin;
    for (std::size_t b = a + 1; b < pieces.size() && pieces[b].triangle == pieces[a].triangle; ++b) {
      if (min_x(pieces[b]) > max_x) break;
      if (std::max(pieces[b].from.y(), pieces[b].to.y()) < low_y || std::min(pieces[b].from.y(), pieces[b].to.y()) > high_y)
        continue;
      if (pieces_meet(pieces[a], pieces[b], margin)) return RemovalRefusal::crossing_edges;
    }
  }
  return RemovalRefusal::none;
}

}  // namespace plmap
