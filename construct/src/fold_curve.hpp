#pragma once
// Where the projection of one S1 element onto the plane of one S2 triangle folds: the geometry
// of a "fold level" of the rim (projection_rim.cpp), so that D can end on the fold curve inside
// the folding element instead of at the last S1 edge before it (docs/projection.md,
// Limitations, "D does not end on a fold"). Internal to construct/; not used by the projection
// yet.
//
// Over S1 element t the rays are p(u) + sigma nu(u), with p and nu linear in the local point u
// (nu: the corners' directions, interpolated). The ray from u meets the plane of S2 triangle A
// (point a0, normal N) at
//     sigma_A(u) = N.(a0 - p(u)) / N.nu(u),
// and the projection onto that plane, y(u) = p(u) + sigma_A(u) nu(u), has the Jacobian
// determinant (in the plane, up to the factor N.nu / |N|^2, which keeps its sign where the ray
// is not parallel to the plane)
//     J(u) = det[ dp/du1 + sigma_A dnu/du1, dp/du2 + sigma_A dnu/du2, nu(u) ],
// the ray's focal polynomial (solvers/focal_points.hpp) evaluated at sigma_A(u). Its zero set in
// t is the fold curve: there a neighbouring ray meets the plane at the same point, and beyond it
// the map y folds back. Multiplied by (N.nu)^2, J is a polynomial of degree 3 in u (the focal
// polynomial is quadratic in sigma with coefficients linear in u, and sigma_A is a ratio of two
// linear functions), so along a straight segment of t it is a cubic in the segment's parameter:
// `fold_on_segment` finds its roots from four samples, exactly up to rounding. `fold_on_target_line`
// finds where the preimage of an S2 edge's line meets the fold curve, and `fold_segment` the two
// ends of the fold curve's piece over one (element, S2 triangle) pair, as `rim_segment` does for
// a level set of the ray distance.

#include "rim_geometry.hpp"

#include <plmap/core/types.hpp>
#include <plmap/solvers/focal_points.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

namespace plmap::projection {

/// The projection of one S1 element onto the plane of one S2 triangle.
class ElementOntoPlane {
 public:
  ElementOntoPlane(const std::array<WorldPoint<2>, 3>& corners, const std::array<WorldPoint<2>, 3>& directions,
                   const std::array<WorldPoint<2>, 3>& triangle)
      : corners_(corners), directions_(directions), a0_(triangle[0]),
        normal_((triangle[1] - triangle[0]).cross(triangle[2] - triangle[0])) {}

  /// The point of t at local coordinates u, and the direction of its ray.
  WorldPoint<2> point(const LocalPoint<2>& u) const { return interpolate(corners_, u); }
  WorldPoint<2> direction(const LocalPoint<2>& u) const { return interpolate(directions_, u); }

  /// The plane's normal N (not normalized: the cross product of the triangle's edges).
  const WorldPoint<2>& plane_normal() const { return normal_; }

  /// N.nu(u), the rate at which the ray from u approaches the plane (0: parallel to it).
  double approach(const LocalPoint<2>& u) const { return normal_.dot(direction(u)); }

  /// sigma_A(u): the ray parameter where the ray from u meets the plane; nullopt where the ray
  /// runs parallel to it (within rounding).
  std::optional<double> sigma(const LocalPoint<2>& u) const {
    const WorldPoint<2> nu = direction(u);
    const double along = normal_.dot(nu);
    if (!(std::abs(along) > 1e-12 * normal_.norm() * nu.norm())) return std::nullopt;
    return normal_.dot(a0_ - point(u)) / along;
  }

  /// y(u), the point where the ray from u meets the plane.
  std::optional<WorldPoint<2>> image(const LocalPoint<2>& u) const {
    const std::optional<double> s = sigma(u);
    if (!s) return std::nullopt;
    return point(u) + *s * direction(u);
  }

  /// J(u) (N.nu(u))^2: the fold function, finite everywhere, a cubic polynomial in u, with the
  /// sign of J where the ray is not parallel to the plane. Zero on the fold curve.
  double fold_function(const LocalPoint<2>& u) const {
    const auto a = ray_jacobian_polynomial<2>(corners_, directions_, u);
    // J(sigma) = a0 + a1 sigma + a2 sigma^2 with sigma = num / den:
    // J den^2 = a0 den^2 + a1 num den + a2 num^2
    const double den = approach(u);
    const double num = normal_.dot(a0_ - point(u));
    return a[0] * den * den + a[1] * num * den + a[2] * num * num;
  }

 private:
  static WorldPoint<2> interpolate(const std::array<WorldPoint<2>, 3>& v, const LocalPoint<2>& u) {
    return v[0] + u(0) * (v[1] - v[0]) + u(1) * (v[2] - v[0]);
  }

  std::array<WorldPoint<2>, 3> corners_, directions_;
  WorldPoint<2> a0_, normal_;
};

/// The parameters s in (0, 1), in increasing order, where the segment from a to b (local points
/// of the element) crosses the fold curve: the roots of the cubic f(s) = fold_function(a + s (b -
/// a)) where it changes sign. The cubic is taken through its values at s = 0, 1/3, 2/3 and 1,
/// split at its critical points into monotone pieces, and each piece with a sign change is
/// bisected to the last bit. A root where f touches zero without changing sign (the segment
/// tangent to the fold curve) is not a crossing and is not returned.
inline std::vector<double> fold_on_segment(const ElementOntoPlane& projection, const LocalPoint<2>& a,
                                           const LocalPoint<2>& b) {
  auto at = [&](double s) { return projection.fold_function(a + s * (b - a)); };
  // the cubic's coefficients c0 + c1 s + c2 s^2 + c3 s^3 from four samples (Newton's divided
  // differences on the equidistant nodes, expanded)
  const double f0 = at(0.0), f1 = at(1.0 / 3.0), f2 = at(2.0 / 3.0), f3 = at(1.0);
  const double c0 = f0;
  const double c1 = (-11.0 * f0 + 18.0 * f1 - 9.0 * f2 + 2.0 * f3) / 2.0;
  const double c2 = (18.0 * f0 - 45.0 * f1 + 36.0 * f2 - 9.0 * f3) / 2.0;
  const double c3 = (-9.0 * f0 + 27.0 * f1 - 27.0 * f2 + 9.0 * f3) / 2.0;
  auto cubic = [&](double s) { return ((c3 * s + c2) * s + c1) * s + c0; };
  // the critical points in (0, 1): roots of c1 + 2 c2 s + 3 c3 s^2
  std::vector<double> cuts{0.0};
  const double qa = 3.0 * c3, qb = 2.0 * c2, qc = c1;
  if (qa != 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc > 0.0) {
      const double r = std::sqrt(disc);
      for (double s : {(-qb - r) / (2.0 * qa), (-qb + r) / (2.0 * qa)})
        if (s > 0.0 && s < 1.0) cuts.push_back(s);
    }
  } else if (qb != 0.0) {
    const double s = -qc / qb;
    if (s > 0.0 && s < 1.0) cuts.push_back(s);
  }
  cuts.push_back(1.0);
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> roots;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    double lo = cuts[i], hi = cuts[i + 1];
    double flo = cubic(lo), fhi = cubic(hi);
    if (flo == 0.0 || fhi == 0.0 || (flo < 0.0) == (fhi < 0.0)) continue;
    // monotone on [lo, hi] with a sign change: one root, bisected until the interval stops
    // shrinking
    while (true) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;
      const double fm = cubic(mid);
      if (fm == 0.0) {
        lo = hi = mid;
        break;
      }
      if ((fm < 0.0) == (flo < 0.0)) {
        lo = mid;
        flo = fm;
      } else {
        hi = mid;
      }
    }
    const double s = 0.5 * (lo + hi);
    if (s > 0.0 && s < 1.0) roots.push_back(s);
  }
  return roots;
}

/// A point of the fold curve on the preimage of a line of the plane: the element's local point,
/// and the parameter along the line (0 at q0, 1 at q1) of its image.
struct FoldOnLine {
  LocalPoint<2> local;
  double eta = 0.0;
};

/// Where the preimage of the line through S2 points q0 and q1 (in the plane) meets the fold
/// curve: the local point u whose ray meets the plane on that line, y(u) = q0 + eta (q1 - q0),
/// and where fold_function(u) = 0. This is the end of a fold level's rim segment on an S2 edge,
/// and the point where a walk along that edge's preimage reaches the fold. Found by Newton's
/// method on the two equations from `start` (the walk's last point before the fold, say), with
/// the Jacobian by central differences; nullopt if it does not converge within 50 steps or a ray
/// on the way runs parallel to the plane. The point may lie outside the element: the caller
/// decides what it wants.
inline std::optional<FoldOnLine> fold_on_target_line(const ElementOntoPlane& projection, const WorldPoint<2>& q0,
                                                     const WorldPoint<2>& q1, const LocalPoint<2>& start) {
  // the line's normal in the plane, and the two equations scaled to comparable size: distance of
  // y(u) from the line (in units of the line's length), and the fold function relative to its
  // value's scale at the start
  const WorldPoint<2> along = q1 - q0;
  const WorldPoint<2> across = projection.plane_normal().cross(along);
  const double across_scale = across.squaredNorm();
  if (!(across_scale > 0.0)) return std::nullopt;
  auto line_distance = [&](const LocalPoint<2>& u) -> std::optional<double> {
    const std::optional<WorldPoint<2>> y = projection.image(u);
    if (!y) return std::nullopt;
    return across.dot(*y - q0) / std::sqrt(across_scale);
  };
  double fold_scale = 0.0;
  for (const LocalPoint<2>& corner : {LocalPoint<2>(0, 0), LocalPoint<2>(1, 0), LocalPoint<2>(0, 1)})
    fold_scale = std::max(fold_scale, std::abs(projection.fold_function(corner)));
  if (!(fold_scale > 0.0)) return std::nullopt;
  auto equations = [&](const LocalPoint<2>& u) -> std::optional<Eigen::Vector2d> {
    const std::optional<double> h = line_distance(u);
    if (!h) return std::nullopt;
    return Eigen::Vector2d(*h / std::sqrt(along.squaredNorm()), projection.fold_function(u) / fold_scale);
  };
  LocalPoint<2> u = start;
  const double step = 1e-7;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const std::optional<Eigen::Vector2d> f = equations(u);
    if (!f) return std::nullopt;
    if (f->lpNorm<Eigen::Infinity>() < 1e-13) {
      const std::optional<WorldPoint<2>> y = projection.image(u);
      return FoldOnLine{u, along.dot(*y - q0) / along.squaredNorm()};
    }
    Eigen::Matrix2d jacobian;
    for (int k = 0; k < 2; ++k) {
      LocalPoint<2> du = LocalPoint<2>::Zero();
      du(k) = step;
      const std::optional<Eigen::Vector2d> plus = equations(u + du), minus = equations(u - du);
      if (!plus || !minus) return std::nullopt;
      jacobian.col(k) = (*plus - *minus) / (2.0 * step);
    }
    const double det = jacobian.determinant();
    if (!(std::abs(det) > 1e-300)) return std::nullopt;
    u -= jacobian.inverse() * *f;
    if (!u.allFinite()) return std::nullopt;
  }
  return std::nullopt;
}

/// One end of the piece of the fold curve that an S1 element and an S2 triangle share (the
/// counterpart of a rim segment's end, projection_rim.cpp): where the fold curve crosses side
/// `side` of the S1 element with its image inside the S2 triangle (on_target_edge false: `local`
/// is the image's local point on the S2 triangle), or where the preimage of side `side` of the
/// S2 triangle meets the fold curve inside the element (on_target_edge true: `local` is the
/// point on the element). Sides are local: side k runs from corner k to corner k + 1 (mod 3), and
/// `parameter` is measured along it from corner k.
struct FoldEnd {
  bool on_target_edge = false;
  int side = 0;
  double parameter = 0.0;
  LocalPoint<2> local = LocalPoint<2>::Zero();
};

/// The ends of the piece of the fold curve in which S1 element t (as `projection`) and S2
/// `triangle` (in the projection's plane) meet: exactly two, each strictly inside its side and
/// triangle (by `margin` in barycentric coordinates and side parameters), or none (they do not
/// meet, or the curve enters and leaves more than once, or touches a corner). The ends on the
/// S2 triangle's sides are found by Newton's method (fold_on_target_line) from points of the fold
/// curve on 12 rows and 12 columns of the element and on its sides.
inline int fold_segment(const ElementOntoPlane& projection, const std::array<WorldPoint<2>, 3>& triangle,
                        std::array<FoldEnd, 2>& ends, double margin = 1e-9) {
  const WorldPoint<2> normal = (triangle[1] - triangle[0]).cross(triangle[2] - triangle[0]);
  const double normal_squared = normal.squaredNorm();
  int count = 0;
  auto add = [&](const FoldEnd& end) {
    if (count < 2) ends[count] = end;
    ++count;
  };
  // where the fold curve crosses the element's sides, with its image inside the triangle
  for (int k = 0; k < 3; ++k) {
    const LocalPoint<2> a = reference_corner<2>(k), b = reference_corner<2>((k + 1) % 3);
    for (double s : fold_on_segment(projection, a, b)) {
      if (!(s > margin && s < 1.0 - margin)) return 0;  // at a corner of the element: degenerate
      const std::optional<WorldPoint<2>> y = projection.image(a + s * (b - a));
      if (!y) continue;
      const std::array<double, 3> bary = barycentric_in_plane(triangle, normal, normal_squared, *y);
      if (!strictly_inside(bary, -margin)) continue;
      if (!strictly_inside(bary, margin)) return 0;  // on a side of the triangle: degenerate
      add({false, k, s, LocalPoint<2>(bary[1], bary[2])});
    }
  }
  // where the preimages of the triangle's sides meet the fold curve inside the element: Newton
  // from points of the fold curve (its crossings of 12 rows, 12 columns and the sides of the
  // element). Seeds on the curve itself: a grid of cells tested for sign changes of both
  // equations missed the side whose preimage touches the fold's turning point (the image of the
  // fold is where the map turns back, so a side's preimage is tangent to the row there)
  constexpr int lines = 12;
  std::vector<LocalPoint<2>> seeds;
  auto add_seeds = [&](const LocalPoint<2>& a, const LocalPoint<2>& b) {
    for (double s : fold_on_segment(projection, a, b)) seeds.push_back(a + s * (b - a));
  };
  for (int i = 0; i < lines; ++i) {
    const double c = (i + 0.5) / lines;
    add_seeds(LocalPoint<2>(0, c), LocalPoint<2>(1 - c, c));
    add_seeds(LocalPoint<2>(c, 0), LocalPoint<2>(c, 1 - c));
  }
  for (int k = 0; k < 3; ++k) add_seeds(reference_corner<2>(k), reference_corner<2>((k + 1) % 3));
  for (int k = 0; k < 3; ++k) {
    const WorldPoint<2>& q0 = triangle[k];
    const WorldPoint<2>& q1 = triangle[(k + 1) % 3];
    std::vector<LocalPoint<2>> found;
    for (const LocalPoint<2>& seed : seeds) {
      const std::optional<FoldOnLine> hit = fold_on_target_line(projection, q0, q1, seed);
      if (!hit) continue;
      const std::array<double, 3> bary{1.0 - hit->local(0) - hit->local(1), hit->local(0), hit->local(1)};
      if (!strictly_inside(bary, -margin) || !(hit->eta >= -margin && hit->eta <= 1.0 + margin)) continue;
      if (!strictly_inside(bary, margin) || !(hit->eta > margin && hit->eta < 1.0 - margin)) return 0;
      // the same point from another seed (Newton stops within about 1e-10 of it)
      bool seen = false;
      for (const LocalPoint<2>& f : found) seen = seen || (f - hit->local).norm() < 1e-7;
      if (seen) continue;
      found.push_back(hit->local);
      add({true, k, hit->eta, hit->local});
    }
  }
  return count == 2 ? 2 : 0;
}

}  // namespace plmap::projection
