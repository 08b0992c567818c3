#include <plmap/core/predicates.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace plmap {

namespace detail {

int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const auto o = CGAL::orientation(K::Point_2(ax, ay), K::Point_2(bx, by), K::Point_2(cx, cy));
  return o == CGAL::LEFT_TURN ? 1 : (o == CGAL::RIGHT_TURN ? -1 : 0);
}

int incircle_exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const auto side = CGAL::side_of_oriented_circle(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()),
                                                  K::Point_2(c.x(), c.y()), K::Point_2(d.x(), d.y()));
  return side == CGAL::ON_POSITIVE_SIDE ? 1 : (side == CGAL::ON_NEGATIVE_SIDE ? -1 : 0);
}

}  // namespace detail

bool segments_cross_properly(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                             const Eigen::Vector2d& r, const Eigen::Vector2d& s) {
  // Segments that share an endpoint meet there by construction of the graph; anything else in
  // common (a proper crossing, a touching point, or a collinear overlap) is a crossing.
  const bool shared_endpoint = p == r || p == s || q == r || q == s;
  const int o1 = orient2d(p, q, r), o2 = orient2d(p, q, s);
  const int o3 = orient2d(r, s, p), o4 = orient2d(r, s, q);
  if (o1 == 0 && o2 == 0) {
    // Collinear: overlap of the projections onto the dominant axis, beyond a shared endpoint.
    const int axis = std::abs(q.x() - p.x()) >= std::abs(q.y() - p.y()) ? 0 : 1;
    double a0 = p(axis), a1 = q(axis), b0 = r(axis), b1 = s(axis);
    if (a0 > a1) std::swap(a0, a1);
    if (b0 > b1) std::swap(b0, b1);
    const double lo = std::max(a0, b0), hi = std::min(a1, b1);
    return shared_endpoint ? lo < hi : lo <= hi;
  }
  if (shared_endpoint) return false;
  return o1 * o2 <= 0 && o3 * o4 <= 0;
}

}  // namespace plmap
