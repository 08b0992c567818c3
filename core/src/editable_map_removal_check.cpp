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

#include "piece_meeting.hpp"
#include "removal_planning.hpp"

#include <algorithm>

namespace plmap {

using removal::Piece;
using removal::Vec2;

namespace {

double min_x(const Piece& p) { return std::min(p.from.x(), p.to.x()); }

}  // namespace

/// Ordered by triangle, then by the left end of the piece's x-range: two pieces that cross or
/// come that close have x-ranges that overlap within the margin, and the scan over the later
/// pieces of a triangle stops at the first one that starts right of the current piece's end (a
/// sweep along x instead of all pairs: late coarse triangles carry many pieces). Every pair of
/// one triangle whose x-ranges overlap within the margin is tested, whatever the order among
/// equal left ends, so the answer does not depend on it. The order is of indices: the pieces are
/// bucketed by triangle (a plan has few new triangles) and each bucket sorted by the left ends
/// kept beside it, which moves and compares far less than sorting the pieces themselves.
RemovalRefusal EditableMap::RemovalPlanning::check_pieces() {
  const double margin = clearance * star_size();
  const std::vector<Piece>& pieces = scratch.pieces;
  std::vector<int>& start = scratch.piece_start;
  std::vector<int>& order = scratch.piece_order;
  std::vector<double>& left = scratch.piece_left;
  const std::size_t triangle_count = plan.new_triangles.size();
  start.assign(triangle_count + 1, 0);
  left.resize(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    ++start[static_cast<std::size_t>(pieces[i].triangle) + 1];
    left[i] = min_x(pieces[i]);
  }
  for (std::size_t n = 0; n < triangle_count; ++n) start[n + 1] += start[n];
  order.resize(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) order[static_cast<std::size_t>(start[static_cast<std::size_t>(pieces[i].triangle)]++)] = static_cast<int>(i);
  // The fill moved each start to the next triangle's: shift them back.
  for (std::size_t n = triangle_count; n > 0; --n) start[n] = start[n - 1];
  start[0] = 0;
  for (std::size_t n = 0; n < triangle_count; ++n) {
    const auto first = order.begin() + start[n], last = order.begin() + start[n + 1];
    std::sort(first, last, [&left](int x, int y) { return left[static_cast<std::size_t>(x)] < left[static_cast<std::size_t>(y)]; });
    for (auto a = first; a != last; ++a) {
      const Piece& pa = pieces[static_cast<std::size_t>(*a)];
      const double max_x = std::max(pa.from.x(), pa.to.x()) + margin;
      const double low_y = std::min(pa.from.y(), pa.to.y()) - margin;
      const double high_y = std::max(pa.from.y(), pa.to.y()) + margin;
      for (auto b = a + 1; b != last; ++b) {
        if (left[static_cast<std::size_t>(*b)] > max_x) break;
        const Piece& pb = pieces[static_cast<std::size_t>(*b)];
        if (std::max(pb.from.y(), pb.to.y()) < low_y || std::min(pb.from.y(), pb.to.y()) > high_y) continue;
        if (detail::pieces_meet(pa.from, pa.to, pb.from, pb.to, margin)) return RemovalRefusal::crossing_edges;
      }
    }
  }
  return RemovalRefusal::none;
}

}  // namespace plmap
