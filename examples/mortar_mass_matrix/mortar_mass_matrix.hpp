#pragma once
/// \file
/// The mortar mass matrix of two non-matching P1 spaces, assembled over the regions of a map.
///
/// With phi_i the P1 (hat) basis of S1 and psi_j that of S2, the mortar (coupling) mass matrix is
///   M_ij = integral over D of phi_i(x) psi_j(Xi(x)) dx.
/// On each region of the map both factors are affine (phi_i is affine on the S1 element, psi_j on
/// the S2 element, and Xi is affine on the region), so the integrand is a quadratic polynomial
/// and a degree-2 quadrature rule on the region is exact: the edge-midpoint rule for triangles,
/// Simpson's rule for segments. This is why the regions (remote intersections) are what mortar
/// methods need.
///
/// Header-only and depending on plmap::core alone, so the example and the tests share it.

#include <plmap/core/regions.hpp>

#include <Eigen/Core>

namespace plmap::mortar {

/// A quadrature point on a region: barycentric weights of the region's corners and the
/// fraction of the region's measure it carries.
struct RegionQuadraturePoint {
  std::array<double, 3> corner_weight;
  double weight;
};

/// Degree-2 exact rules in barycentric coordinates of the region.
template <int d>
std::vector<RegionQuadraturePoint> degree_two_rule() {
  if constexpr (d == 2)  // edge midpoints, 1/3 each
    return {{{0.5, 0.5, 0.0}, 1.0 / 3}, {{0.0, 0.5, 0.5}, 1.0 / 3}, {{0.5, 0.0, 0.5}, 1.0 / 3}};
  else  // Simpson
    return {{{1.0, 0.0, 0.0}, 1.0 / 6}, {{0.5, 0.5, 0.0}, 4.0 / 6}, {{0.0, 1.0, 0.0}, 1.0 / 6}};
}

/// M_ij = integral of phi_i * (psi_j o Xi) over the domain of the map; rows are S1 vertices,
/// columns S2 vertices. Dense: meant for small examples and tests.
template <int d>
Eigen::MatrixXd mortar_mass_matrix(const PlMap<d>& map) {
  const Surface<d>& s1 = map.domain();
  const Surface<d>& s2 = map.target();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(s1.vertex_count(), s2.vertex_count());
  for (const RemoteIntersection<d>& region : remote_intersections(map)) {
    const double measure = region.domain_measure();
    for (const RegionQuadraturePoint& q : degree_two_rule<d>()) {
      // The same barycentric combination of the corners on both sides, since Xi is affine here.
      LocalPoint<d> on_s1 = LocalPoint<d>::Zero(), on_s2 = LocalPoint<d>::Zero();
      for (int c = 0; c <= d; ++c) {
        on_s1 += q.corner_weight[c] * region.domain_local[c];
        on_s2 += q.corner_weight[c] * region.target_local[c];
      }
      // The P1 basis functions on an element are its barycentric coordinates.
      const Barycentric<d> phi = barycentric_from_local<d>(on_s1);
      const Barycentric<d> psi = barycentric_from_local<d>(on_s2);
      for (int a = 0; a <= d; ++a)
        for (int b = 0; b <= d; ++b)
          m(s1.element(region.domain_element)[a], s2.element(region.target_element)[b]) +=
              q.weight * measure * phi(a) * psi(b);
    }
  }
  return m;
}

/// The standard P1 mass matrix of one surface: |T| / ((d+1)(d+2)) * (1 + delta_ab) per element.
template <int d>
Eigen::MatrixXd p1_mass_matrix(const Surface<d>& s) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(s.vertex_count(), s.vertex_count());
  for (Index t = 0; t < s.element_count(); ++t) {
    const double scale = s.element_measure(t) / ((d + 1) * (d + 2));
    for (int a = 0; a <= d; ++a)
      for (int b = 0; b <= d; ++b) m(s.element(t)[a], s.element(t)[b]) += scale * (a == b ? 2.0 : 1.0);
  }
  return m;
}

/// The lumped mass: integral of each hat function, |T| / (d+1) from every element at the vertex.
template <int d>
Eigen::VectorXd lumped_mass(const Surface<d>& s) {
  Eigen::VectorXd l = Eigen::VectorXd::Zero(s.vertex_count());
  for (Index t = 0; t < s.element_count(); ++t)
    for (Index v : s.element(t)) l(v) += s.element_measure(t) / (d + 1);
  return l;
}

/// How far M is from the exact identities that hold whenever D = S1 and Xi(D) = S2 with Xi
/// measure-preserving (e.g. the identity of the plane): all three are zero up to rounding.
struct MortarIdentityErrors {
  double total = 0.0;        ///< |sum of all entries - |S1||
  double row_sums = 0.0;     ///< max_i |sum_j M_ij - integral of phi_i|
  double column_sums = 0.0;  ///< max_j |sum_i M_ij - integral of psi_j|
};

template <int d>
MortarIdentityErrors mortar_identity_errors(const Eigen::MatrixXd& m, const Surface<d>& s1,
                                            const Surface<d>& s2) {
  MortarIdentityErrors e;
  e.total = std::abs(m.sum() - s1.measure());
  e.row_sums = (m.rowwise().sum() - lumped_mass(s1)).cwiseAbs().maxCoeff();
  e.column_sums = (m.colwise().sum().transpose() - lumped_mass(s2)).cwiseAbs().maxCoeff();
  return e;
}

}  // namespace plmap::mortar
