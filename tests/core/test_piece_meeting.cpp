// The removal check's pair test (core/src/piece_meeting.hpp): pieces that share an end and
// leave it at an obtuse angle are answered without the orientation. Checked against the test
// without that shortcut on random pairs of pieces: on a small grid (many shared ends, collinear
// and touching pairs, overlapping collinear ones), shifted by offsets that round the
// differences, and scaled down to where the products of the differences underflow.
#include "piece_meeting.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <array>

using namespace plmap;
using Eigen::Vector2d;

namespace {

/// The pair test before the obtuse-angle shortcut (simp-speed5's pieces_meet).
bool pieces_meet_reference(const Vector2d& p, const Vector2d& q, const Vector2d& r, const Vector2d& t, double margin) {
  if (p == r || p == t || q == r || q == t) {
    const Vector2d& shared = (p == r || p == t) ? p : q;
    const Vector2d& end_a = shared == p ? q : p;
    const Vector2d& end_b = r == shared ? t : r;
    if (orient2d(shared, end_a, end_b) != 0) return detail::pieces_leave_too_close(end_a - shared, end_b - shared, margin);
  } else if (detail::within_margin(p, r, t, margin) || detail::within_margin(q, r, t, margin) ||
             detail::within_margin(r, p, q, margin) || detail::within_margin(t, p, q, margin)) {
    return true;
  }
  return segments_cross_properly(p, q, r, t);
}

void expect_same_answer(const Vector2d& p, const Vector2d& q, const Vector2d& r, const Vector2d& t, double margin) {
  EXPECT_EQ(detail::pieces_meet(p, q, r, t, margin), pieces_meet_reference(p, q, r, t, margin))
      << "p " << p.transpose() << " q " << q.transpose() << " r " << r.transpose() << " t " << t.transpose()
      << " margin " << margin;
}

}  // namespace

TEST(PieceMeeting, SharedEndCases) {
  const Vector2d o(0, 0), e(1, 0), w(-1, 0), far(2, 0), up(0, 1), up_left(-1, 1), down_left(-1, -0.001);
  // collinear, opposite directions: they meet only at the shared end
  EXPECT_FALSE(detail::pieces_meet(o, e, o, w, 0.0));
  EXPECT_FALSE(detail::pieces_meet(e, o, w, o, 0.0));
  // collinear, same direction: they overlap
  EXPECT_TRUE(detail::pieces_meet(o, e, o, far, 0.0));
  EXPECT_TRUE(detail::pieces_meet(o, far, e, o, 0.0));
  // right and obtuse angles: apart
  EXPECT_FALSE(detail::pieces_meet(o, e, o, up, 0.1));
  EXPECT_FALSE(detail::pieces_meet(o, e, up_left, o, 0.1));
  EXPECT_FALSE(detail::pieces_meet(o, e, o, down_left, 0.1));
  // a small acute angle: too close
  EXPECT_TRUE(detail::pieces_meet(o, far, o, Vector2d(1, 0.001), 0.01));
  // tiny differences in one direction: their products underflow to a zero dot product, and the
  // pieces still overlap
  const Vector2d a(1e-200, 0), b(2e-200, 0);
  ASSERT_EQ((a - o).dot(b - o), 0.0);
  EXPECT_TRUE(detail::pieces_meet(o, a, o, b, 0.0));
  EXPECT_TRUE(pieces_meet_reference(o, a, o, b, 0.0));
  for (const auto& [x, y] : std::array<std::pair<Vector2d, Vector2d>, 5>{{{e, w}, {e, far}, {e, up}, {e, up_left}, {a, b}}})
    for (double margin : {0.0, 0.01, 0.5}) {
      expect_same_answer(o, x, o, y, margin);
      expect_same_answer(x, o, y, o, margin);
      expect_same_answer(o, x, y, o, margin);
    }
}

RC_GTEST_PROP(PieceMeeting, SameAnswerAsWithoutTheShortcut, ()) {
  const auto coordinate = rc::gen::inRange(-3, 4);
  const auto point = [&] {
    const int x = *coordinate, y = *coordinate;
    return Vector2d(x, y);
  };
  // shared ends and repeated points are frequent: each end is a fresh grid point or one of the
  // earlier ones
  std::array<Vector2d, 4> ends;
  ends[0] = point();
  for (int i = 1; i < 4; ++i) ends[i] = *rc::gen::inRange(0, 3) == 0 ? ends[*rc::gen::inRange(0, i)] : point();
  const double scale = *rc::gen::element(1.0, 0.1, 1e-3, 1e-200, 1e200);
  const Vector2d offset(*rc::gen::element(0.0, 0.1, 1.0 / 3.0, 1e5), *rc::gen::element(0.0, 0.7, -2.0 / 7.0));
  for (auto& x : ends) x = scale * x + offset;
  const double margin = scale * *rc::gen::element(0.0, 1e-9, 0.01, 0.3, 1.0);
  RC_ASSERT(detail::pieces_meet(ends[0], ends[1], ends[2], ends[3], margin) ==
            pieces_meet_reference(ends[0], ends[1], ends[2], ends[3], margin));
}
