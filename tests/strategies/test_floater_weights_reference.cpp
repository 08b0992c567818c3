// Floater's shape-preserving weights (Floater 1997, paper 3.3.2) checked against an independent
// reference written from the definition, on hundreds of random non-planar stars: the polar map
// as complex numbers z_j = r_j exp(i θ_j) (θ_j the 3D angles at the centre, scaled to sum to 2π);
// for each j the triangle (z_j, z_r, z_r+1) whose angular sector [θ_r, θ_r+1) contains the
// direction opposite z_j (so it contains the origin), the barycentric coordinates of the origin
// in it by a 3 x 3 solve, averaged over j. The model under test picks the triangle differently
// (largest smallest barycentric coordinate) and computes the coordinates by cross products.

#include <plmap/strategies/smoothing/floater_weights.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace plmap {
namespace {

std::vector<double> reference_floater(const Eigen::Vector3d& centre, const std::vector<Eigen::Vector3d>& ring) {
  const std::size_t k = ring.size();
  const double two_pi = 2.0 * std::numbers::pi;
  std::vector<double> angle(k);
  double total = 0.0;
  for (std::size_t j = 0; j < k; ++j) {
    const Eigen::Vector3d a = (ring[j] - centre).normalized(), b = (ring[(j + 1) % k] - centre).normalized();
    angle[j] = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
    total += angle[j];
  }
  std::vector<double> theta(k + 1, 0.0);
  for (std::size_t j = 0; j < k; ++j) theta[j + 1] = theta[j] + angle[j] * two_pi / total;
  std::vector<std::complex<double>> z(k);
  for (std::size_t j = 0; j < k; ++j) z[j] = std::polar((ring[j] - centre).norm(), theta[j]);
  std::vector<double> w(k, 0.0);
  for (std::size_t j = 0; j < k; ++j) {
    const double opposite = std::fmod(theta[j] + std::numbers::pi, two_pi);
    // The sector [theta[r], theta[r+1]) holding the opposite direction. theta[k] is 2π only up
    // to rounding, so an opposite direction just below 2π can lie past it: that is the last
    // sector (the search ran off the end of theta before, a crash at seed 26120360).
    std::size_t r = 0;
    while (r + 1 < k && !(theta[r] <= opposite && opposite < theta[r + 1])) ++r;
    const std::size_t s = (r + 1) % k;
    Eigen::Matrix3d m;
    m << z[j].real(), z[r].real(), z[s].real(), z[j].imag(), z[r].imag(), z[s].imag(), 1.0, 1.0, 1.0;
    const Eigen::Vector3d lambda = m.fullPivLu().solve(Eigen::Vector3d(0.0, 0.0, 1.0));
    w[j] += lambda(0) / static_cast<double>(k);
    w[r] += lambda(1) / static_cast<double>(k);
    w[s] += lambda(2) / static_cast<double>(k);
  }
  return w;
}

/// A star of k spokes in random directions around the z axis (angles each well below π), with
/// random lengths and heights: the S2 star of a vertex on a curved surface.
std::vector<Eigen::Vector3d> random_star(int k, double height_scale) {
  std::vector<double> gaps;
  double sum = 0.0;
  for (int j = 0; j < k; ++j) {
    gaps.push_back(*rc::gen::inRange(20, 100) / 100.0);
    sum += gaps.back();
  }
  // "well below π": for k = 3 a gap can be half the sum (e.g. 65 of 25 + 65 + 40), an angle of π
  // to rounding, where the weights are ill-conditioned and differ from the reference by ~1e-8
  RC_PRE(2.0 * *std::max_element(gaps.begin(), gaps.end()) < sum);
  std::vector<Eigen::Vector3d> ring;
  double phi = 0.0;
  for (int j = 0; j < k; ++j) {
    const double r = *rc::gen::inRange(20, 300) / 100.0;
    const double h = height_scale * *rc::gen::inRange(-100, 100) / 100.0;
    ring.emplace_back(r * std::cos(phi), r * std::sin(phi), h);
    phi += gaps[static_cast<std::size_t>(j)] * 2.0 * std::numbers::pi / sum;
  }
  return ring;
}

RC_GTEST_PROP(FloaterWeightsReference, AgreeWithTheDefinitionOnRandomNonPlanarStars, ()) {
  const int k = *rc::gen::inRange(3, 11);
  const double height = *rc::gen::elementOf(std::vector<double>{0.0, 0.1, 0.5});
  const auto ring = random_star(k, height);
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  const auto w = FloaterWeights{}.weights(centre, ring);
  RC_PRE(w.has_value());  // a star with a scaled angle >= π has no Floater weights
  const auto expected = reference_floater(centre, ring);
  for (int j = 0; j < k; ++j) {
    const auto i = static_cast<std::size_t>(j);
    RC_ASSERT(std::abs((*w)[i] - expected[i]) <= 1e-12);
  }
}

TEST(FloaterWeightsReference, PlanarRingIsReproducedAndRegularRingIsUniform) {
  // regular hexagon: every weight 1/6 by symmetry
  std::vector<Eigen::Vector3d> hexagon;
  for (int j = 0; j < 6; ++j) hexagon.emplace_back(std::cos(j * std::numbers::pi / 3), std::sin(j * std::numbers::pi / 3), 0.0);
  const auto uniform = FloaterWeights{}.weights(Eigen::Vector3d::Zero(), hexagon);
  ASSERT_TRUE(uniform);
  for (double x : *uniform) EXPECT_NEAR(x, 1.0 / 6.0, 1e-15);
  // a square ring with the centre off-centre: Σ w_j p_j = p (linear precision)
  const std::vector<Eigen::Vector3d> square = {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}};
  const Eigen::Vector3d p(0.3, 0.6, 0.0);
  const auto w = FloaterWeights{}.weights(p, square);
  ASSERT_TRUE(w);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t j = 0; j < 4; ++j) sum += (*w)[j] * square[j];
  EXPECT_LT((sum - p).norm(), 1e-15);
}

}  // namespace
}  // namespace plmap
