#pragma once
/// \file
/// Which of two equally near preimages of an S2 vertex lies on the sheet of S1 that sees the
/// vertex's star.
///
/// Where S1 or S2 has a seam (vertices at one position that the elements do not share: CGAL's
/// quads_to_stitch.off, elephant-with-holes.off, the welded-nowhere boeing.off), an S2 vertex q
/// has preimages of the same rank on both sides of the seam, and the walks used to keep whichever
/// they met first. On the wrong side the edges of q's star start on S1 elements that see other
/// S2 elements, and their walks fail: a surface projected onto a copy of itself lost the whole
/// map (quads_to_stitch) instead of being the identity. The probe tells the sides apart: the ray
/// from a point just inside the candidate's element must meet an element of q's star.
///
/// Private to the projection.

#include "projection_context.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace plmap::projection {

/// Whether the ray from the point of S1 element t a thousandth of the way from xi to the
/// element's centroid, along the interpolated direction field, meets an S2 element at vertex q
/// near distance mu (the candidate preimage's distance).
/// An element without a corner on S1's boundary is taken to see it without a probe: a seam of
/// S1 is a pair of boundary edges, so only there do two sheets of S1 meet at one point with
/// candidates that tie at any distance (which keeps the probe off the closed surfaces of most
/// projections). Two fans of a closed surface that touch at copies of one vertex (CGAL's
/// cow.off has one such point) are not told apart: they touch tangentially there, and the probe
/// from either fan meets the other's star too.
template <int d>
bool probe_sees_star(const ProjectionContext<d>& ctx, Index t, const LocalPoint<d>& xi, double mu, Index q) {
  const auto& corners = ctx.s1.element(t);
  bool at_boundary = false;
  for (Index v : corners) at_boundary = at_boundary || ctx.s1.is_boundary_vertex(v);
  if (!at_boundary) return true;
  constexpr double step = 1e-3;
  const LocalPoint<d> probe = xi + step * (LocalPoint<d>::Constant(1.0 / (d + 1)) - xi);
  const WorldPoint<d> x = ctx.s1.world_position(t, probe);
  WorldPoint<d> nu = ctx.vertex_directions[corners[0]];
  for (int k = 0; k < d; ++k) nu += probe(k) * (ctx.vertex_directions[corners[k + 1]] - ctx.vertex_directions[corners[0]]);
  for (Index tau : ctx.s2.vertex_elements(q)) {
    // x + s nu = a + sum_k lambda_k (c_k - a): d + 1 equations in lambda and s
    const WorldPoint<d>& a = ctx.s2.corner(tau, 0);
    Eigen::Matrix<double, d + 1, d + 1> m;
    double longest = 0.0;
    for (int k = 0; k < d; ++k) {
      m.col(k) = ctx.s2.corner(tau, k + 1) - a;
      longest = std::max(longest, m.col(k).norm());
    }
    m.col(d) = -nu;
    // closed-form inverse of the 2x2 or 3x3 matrix; a ray parallel to tau meets it nowhere
    Eigen::Matrix<double, d + 1, d + 1> inverse;
    double determinant = 0.0;
    bool invertible = false;
    // the determinant is a d-volume of tau times |nu|: the threshold scales alike
    double volume_scale = nu.norm();
    for (int k = 0; k < d; ++k) volume_scale *= longest;
    m.computeInverseAndDetWithCheck(inverse, determinant, invertible, 1e-14 * volume_scale);
    if (!invertible) continue;
    const Eigen::Matrix<double, d + 1, 1> solution = inverse * (x - a);
    constexpr double slack = 1e-9;
    const double s = solution(d);
    double sum = 0.0;
    bool inside = true;
    for (int k = 0; k < d; ++k) {
      inside = inside && solution(k) >= -slack;
      sum += solution(k);
    }
    // the probe lies a thousandth of an element from the candidate, so its hit lies about as
    // near to q: a hit on the plane of the star ten times farther along the ray is another sheet
    if (inside && sum <= 1.0 + slack && std::abs(s - mu) <= 10.0 * step * longest) return true;
  }
  return false;
}

}  // namespace plmap::projection
