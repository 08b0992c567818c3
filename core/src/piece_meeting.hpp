#pragma once
// The pair test of the per-step cut's check (editable_map_removal_check.cpp): whether two
// straightened pieces of one new triangle meet other than at a shared end, or come within the
// clearance of each other. In a header of its own so that a test can compare it with the test
// without its shortcuts (tests/core/test_piece_meeting.cpp).

#include "piece_clearance.hpp"

#include <plmap/core/predicates.hpp>

#include <Eigen/Core>

namespace plmap::detail {

/// True if pieces [p, q] and [r, t] cross, or come within `margin` of each other other than at
/// a shared end. Always inlined: the check calls it for every pair of pieces whose boxes meet,
/// and as a function of its own (as GCC leaves an inline function of a header) the call cost
/// more than the shortcut below saves (femur -> 500: check_pieces 68.1 -> 73.4 M instructions).
[[gnu::always_inline]] inline bool pieces_meet(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                               const Eigen::Vector2d& r, const Eigen::Vector2d& t,
                                               double margin) {
  // Most pairs that get here share an end (consecutive pieces of a polyline, pieces ending at
  // one node): those cross only if they are collinear, which one orientation of b's other end
  // decides (segments_cross_properly's answer, at a quarter of its predicates), and come too
  // close only if they leave the shared end at an angle so small that the shorter one's other
  // end is within the margin of the longer one.
  if (p == r || p == t || q == r || q == t) {
    const Eigen::Vector2d& shared = (p == r || p == t) ? p : q;
    const Eigen::Vector2d& end_a = shared == p ? q : p;
    const Eigen::Vector2d& end_b = r == shared ? t : r;
    const Eigen::Vector2d u = end_a - shared, w = end_b - shared;
    // Leaving the shared end at an obtuse angle (the most common case: consecutive pieces of a
    // polyline), they meet in neither way, and the orientation is not needed. Not collinear,
    // pieces_leave_too_close answers false for this very dot product. Collinear, they cross
    // only if they overlap beyond the shared end, that is if they leave it in the same
    // direction; then every rounded difference has the sign of the exact one (the subtraction
    // of two doubles is monotone and zero only for equal operands), the two products of each
    // coordinate are >= 0 and so is their sum: a negative dot product rules that out. (Not <= 0:
    // the products of tiny differences in the same direction underflow to zero.)
    if (u.dot(w) < 0.0) return false;
    if (orient2d(shared, end_a, end_b) != 0) return pieces_leave_too_close(u, w, margin);
  } else if (within_margin(p, r, t, margin) || within_margin(q, r, t, margin) || within_margin(r, p, q, margin) ||
             within_margin(t, p, q, margin)) {
    return true;
  }
  return segments_cross_properly(p, q, r, t);
}

}  // namespace plmap::detail
