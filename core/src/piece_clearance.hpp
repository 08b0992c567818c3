#pragma once
// Clearance tests between pieces of S2-edge preimages in a flattened star or a traced corridor,
// shared by the per-step cut's check (editable_map_removal_check.cpp) and the deferred cut's
// trace check (editable_map_trace.cpp).

#include <Eigen/Core>

#include <algorithm>

namespace plmap::detail {

/// True if x is within `margin` of the segment [a, b].
inline bool within_margin(const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                          double margin) {
  const Eigen::Vector2d d = b - a;
  const double length2 = d.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((x - a).dot(d) / length2, 0.0, 1.0) : 0.0;
  return (x - (a + t * d)).squaredNorm() <= margin * margin;
}

/// Two pieces leaving one node along u and w (not collinear): true if the shorter one's other
/// end is within `margin` of the longer one. That end projects inside the longer piece when the
/// angle between them is acute, and its distance to it is then |u x w| / the longer length.
inline bool pieces_leave_too_close(const Eigen::Vector2d& u, const Eigen::Vector2d& w, double margin) {
  if (u.dot(w) <= 0.0) return false;
  const double cross = u.x() * w.y() - u.y() * w.x();
  return cross * cross <= margin * margin * std::max(u.squaredNorm(), w.squaredNorm());
}

}  // namespace plmap::detail
