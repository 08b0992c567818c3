#pragma once
/// \file
/// Robust orientation predicate for combinatorial decisions in local (planar) coordinates.
///
/// plmap never decides "which side of a line" by a raw floating-point sign: orient2d returns the
/// exact sign of the determinant for the given doubles. The fast path is the classic static
/// error bound on the double evaluation (inline, a few flops), then exact collinearity checks by
/// comparison for the common degenerate cases; only when neither decides does it call the exact
/// predicate of CGAL (Epick), out of line.

#include <plmap/core/types.hpp>

#include <algorithm>
#include <cmath>

namespace plmap {

namespace detail {
/// Exact orientation via CGAL; used when the floating-point filter is inconclusive.
int orient2d_exact(double ax, double ay, double bx, double by, double cx, double cy);

/// Whether x + y == 1 holds exactly (not just after rounding): the sum rounds to 1 and its
/// rounding error (Knuth's two-sum) is zero.
inline bool on_antidiagonal(const Eigen::Vector2d& p) {
  const double s = p.x() + p.y();
  const double y_part = s - p.x();
  const double error = (p.x() - (s - y_part)) + (p.y() - y_part);
  return s == 1.0 && error == 0.0;
}

/// Exactly collinear triples the filter cannot certify but plain comparisons can: two equal
/// points (segments that share an endpoint, tested against each other), and three points on one
/// horizontal or vertical line or on the line x + y = 1 (the nodes on the sides of the reference
/// triangle). The closure of every element makes many such tests; without this check each would
/// go to the exact predicate.
inline bool obviously_collinear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return a == c || b == c || a == b || (a.y() == c.y() && b.y() == c.y()) || (a.x() == c.x() && b.x() == c.x()) ||
         (on_antidiagonal(a) && on_antidiagonal(b) && on_antidiagonal(c));
}
}  // namespace detail

/// orient2d's sign when its floating-point filter decides it (+1 or -1), else 0 (undecided, not
/// "collinear"). A few flops and no call: hot loops that test once per query (a point locator's
/// cells) inline it and call orient2d only when it returns 0.
inline int orient2d_by_filter(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double detleft = (a.x() - c.x()) * (b.y() - c.y());
  const double detright = (a.y() - c.y()) * (b.x() - c.x());
  const double det = detleft - detright;
  // Bound on the rounding error of det (Shewchuk's ccwerrboundA = (3 + 16 eps) eps). It assumes
  // no underflow; a product that underflows errs by at most 2^-1075, which the bound's eps^2
  // slack covers once it is at least 2^-950. So it is never taken below 2^-940, where such tiny
  // determinants go to the exact path.
  constexpr double error_factor = 3.3306690738754716e-16;
  const double bound = std::max(error_factor * (std::abs(detleft) + std::abs(detright)), 0x1p-940);
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return 0;
}

/// +1 if a, b, c are counter-clockwise, -1 if clockwise, 0 if exactly collinear.
inline int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  if (const int sign = orient2d_by_filter(a, b, c)) return sign;
  if (detail::obviously_collinear(a, b, c)) return 0;
  return detail::orient2d_exact(a.x(), a.y(), b.x(), b.y(), c.x(), c.y());
}

namespace detail {
/// Exact in-circle test via CGAL; used when the floating-point filter is inconclusive.
int incircle_exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d);
}  // namespace detail

/// +1 if d lies strictly inside the circle through the counter-clockwise points a, b, c, 0 if on
/// it, -1 if outside. Exact. Inline, like orient2d: the Lawson flips of every element's closure
/// ask it, and the static error bound decides nearly all of them without the out-of-line call.
inline int incircle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy, blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady, clift = cdx * cdx + cdy * cdy;
  const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * alift +
                           (std::abs(cdxady) + std::abs(adxcdy)) * blift +
                           (std::abs(adxbdy) + std::abs(bdxady)) * clift;
  // Bound on the rounding error of det (Shewchuk's iccerrboundA = (10 + 96 eps) eps). It assumes
  // no underflow: with every non-zero difference at least 2^-250 (local coordinates are O(1)),
  // only the three final products can underflow, by at most 2^-1075 each, which the absolute
  // term covers. Tinier differences, and overflow (NaN or infinite det), take the exact path.
  constexpr double error_factor = 1.1102230246251568e-15;
  constexpr double smallest_difference = 0x1p-250;
  auto tiny = [](double x) { return x != 0.0 && std::abs(x) < smallest_difference; };
  if (!(tiny(adx) || tiny(ady) || tiny(bdx) || tiny(bdy) || tiny(cdx) || tiny(cdy))) {
    const double bound = error_factor * permanent + 0x1p-1060;
    if (det > bound) return 1;
    if (-det > bound) return -1;
  }
  return detail::incircle_exact(a, b, c, d);
}

/// Exact sign of a . b - style comparisons are not needed elsewhere; for segments:
/// true if the closed segments [p, q] and [r, s] share a point other than a common endpoint.
bool segments_cross_properly(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                             const Eigen::Vector2d& r, const Eigen::Vector2d& s);

}  // namespace plmap
