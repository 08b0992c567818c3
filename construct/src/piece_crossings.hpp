#pragma once
// Whether two of a quadrilateral step's straight pieces meet other than at a common endpoint:
// exactly the answer of any_segments_cross (core/segment_sweep.hpp) and of
// segments_cross_properly over all pairs, for less work. The step checks every piece of every
// quadrilateral (hundreds on a late coarse one) after each solve, and the pairs the sweep finds
// are mostly pieces that share an unknown: for those one exact orientation decides (the shared end
// makes another one zero), where segments_cross_properly evaluates all four. The sweep keeps each
// piece's bounding box instead of recomputing it for every pair. On the femur → 500 map this check
// was 12 % of `plmap::smooth`. Also the exact order of directions by angle, with which the step
// checks that the segments around an unknown wind once.

#include <plmap/core/predicates.hpp>
#include <plmap/core/segment_sweep.hpp>

#include <algorithm>
#include <array>
#include <vector>

namespace plmap::smoothing {

/// segments_cross_properly(p, q, r, s), decided with as few orientations as the answer needs:
/// an orientation of a triple with two equal points is exactly zero, so for a shared endpoint
/// only the other one is evaluated, and the last two are evaluated only when the first two leave
/// the answer open.
inline bool pieces_meet(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r,
                        const Eigen::Vector2d& s) {
  int o1 = 0, o2 = 0;  // orient2d(p, q, r), orient2d(p, q, s)
  bool shared_endpoint = true;
  if (p == r || q == r)
    o2 = orient2d(p, q, s);
  else if (p == s || q == s)
    o1 = orient2d(p, q, r);
  else {
    shared_endpoint = false;
    o1 = orient2d(p, q, r);
    o2 = orient2d(p, q, s);
  }
  if (o1 == 0 && o2 == 0) {
    // collinear: overlap of the projections onto the dominant axis, beyond a shared endpoint
    const int axis = std::abs(q.x() - p.x()) >= std::abs(q.y() - p.y()) ? 0 : 1;
    double a0 = p(axis), a1 = q(axis), b0 = r(axis), b1 = s(axis);
    if (a0 > a1) std::swap(a0, a1);
    if (b0 > b1) std::swap(b0, b1);
    const double lo = std::max(a0, b0), hi = std::min(a1, b1);
    return shared_endpoint ? lo < hi : lo <= hi;
  }
  if (shared_endpoint || o1 * o2 > 0) return false;
  return orient2d(r, s, p) * orient2d(r, s, q) <= 0;
}

/// any_segments_cross(segments), by the same sweep along x with pieces_meet as the pair test.
/// `boxes` is scratch space (kept by the caller so that it is not allocated per step).
struct PieceBox {
  double min_x, max_x, min_y, max_y;
  const PlanarSegment* segment;
};

/// The sweep: true if two pieces meet, skipping the pairs `skip(x, y)` names (pointers into
/// `segments`).
template <typename SkipPair>
bool pieces_meet_in_sweep(const std::vector<PlanarSegment>& segments, std::vector<PieceBox>& boxes, SkipPair skip) {
  boxes.clear();
  for (const PlanarSegment& s : segments)
    boxes.push_back({std::min(s[0].x(), s[1].x()), std::max(s[0].x(), s[1].x()), std::min(s[0].y(), s[1].y()),
                     std::max(s[0].y(), s[1].y()), &s});
  std::sort(boxes.begin(), boxes.end(), [](const PieceBox& a, const PieceBox& b) { return a.min_x < b.min_x; });
  for (std::size_t a = 0; a < boxes.size(); ++a) {
    const PieceBox& s = boxes[a];
    for (std::size_t b = a + 1; b < boxes.size(); ++b) {
      const PieceBox& o = boxes[b];
      if (o.min_x > s.max_x) break;
      if (o.max_y < s.min_y || o.min_y > s.max_y) continue;
      if (skip(s.segment, o.segment)) continue;
      const PlanarSegment& x = *s.segment;
      const PlanarSegment& y = *o.segment;
      if (pieces_meet(x[0], x[1], y[0], y[1])) return true;
    }
  }
  return false;
}

inline bool any_pieces_meet(const std::vector<PlanarSegment>& segments, std::vector<PieceBox>& boxes) {
  return pieces_meet_in_sweep(segments, boxes, [](const PlanarSegment*, const PlanarSegment*) { return false; });
}

/// any_pieces_meet, except that pairs of pieces that end at the same unknown are not tested:
/// `ends[i]` names the unknown (>= 0) or not (-1) at each end of segments[i]. Such a pair meets
/// exactly when both leave the unknown in the same direction, which the step's winding check
/// refuses with the same reason (directions that wind once are distinct), so the step decides as
/// with any_pieces_meet; and these pairs, every two spokes of an unknown, are most of the pairs
/// the sweep finds.
inline bool pieces_apart_from_shared_ends_meet(const std::vector<PlanarSegment>& segments,
                                               const std::vector<std::array<int, 2>>& ends, std::vector<PieceBox>& boxes) {
  return pieces_meet_in_sweep(segments, boxes, [&](const PlanarSegment* x, const PlanarSegment* y) {
    const auto& a = ends[static_cast<std::size_t>(x - segments.data())];
    const auto& b = ends[static_cast<std::size_t>(y - segments.data())];
    return (a[0] >= 0 && (a[0] == b[0] || a[0] == b[1])) || (a[1] >= 0 && (a[1] == b[0] || a[1] == b[1]));
  });
}

/// 0 for a direction whose angle from +x, counter-clockwise, is in [0, π), 1 for [π, 2π).
inline int half_turn(const Eigen::Vector2d& d) { return d.y() < 0.0 || (d.y() == 0.0 && d.x() < 0.0) ? 1 : 0; }

/// True if the angle of direction `from` (counter-clockwise from +x, in [0, 2π)) is strictly
/// smaller than that of `to`; `turn` is orient2d(0, from, to). Exact for non-zero directions.
/// Around a point, the counter-clockwise turns from each direction to the next add up to 2π
/// times the number of turns for which this is false: directions wind once around the point iff
/// it is false exactly once.
inline bool direction_precedes(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int turn) {
  const int hf = half_turn(from), ht = half_turn(to);
  return hf != ht ? hf < ht : turn > 0;
}

}  // namespace plmap::smoothing
