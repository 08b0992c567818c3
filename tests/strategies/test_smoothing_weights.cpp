// The smoothing-weights models: positive, summing to one, the closed forms on symmetric stars,
// and linear precision (a planar star's centre is reproduced) for the geometric models.

#include <plmap/strategies/smoothing/floater_weights.hpp>
#include <plmap/strategies/smoothing/mean_value_weights.hpp>
#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>
#include <plmap/strategies/smoothing/uniform_weights.hpp>

#include <plmap/core/errors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace plmap {
namespace {

std::vector<Eigen::Vector3d> regular_ring(int k, double radius) {
  std::vector<Eigen::Vector3d> ring;
  for (int j = 0; j < k; ++j) {
    const double a = 2.0 * std::numbers::pi * j / k;
    ring.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
  }
  return ring;
}

// An irregular planar star around (0.1, -0.2, 0): the centre is inside, angles below π.
std::vector<Eigen::Vector3d> irregular_ring() {
  return {{1.0, 0.1, 0.0}, {0.7, 0.9, 0.0}, {-0.3, 1.4, 0.0}, {-1.1, 0.2, 0.0}, {-0.6, -1.0, 0.0}, {0.9, -1.3, 0.0}};
}

void expect_convex_weights(const std::vector<double>& w, std::size_t k) {
  ASSERT_EQ(w.size(), k);
  double sum = 0.0;
  for (double x : w) {
    EXPECT_GT(x, 0.0);
    sum += x;
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
}

TEST(SmoothingWeights, UniformIsOneOverDegree) {
  const auto w = UniformWeights{}.weights(Eigen::Vector3d(0.3, 0, 0), irregular_ring());
  ASSERT_TRUE(w);
  for (double x : *w) EXPECT_DOUBLE_EQ(x, 1.0 / 6.0);
}

TEST(SmoothingWeights, GeometricWeightsAreEqualOnARegularStar) {
  const auto ring = regular_ring(7, 2.5);
  for (const auto& w : {FloaterWeights{}.weights(Eigen::Vector3d::Zero(), ring),
                        MeanValueWeights{}.weights(Eigen::Vector3d::Zero(), ring)}) {
    ASSERT_TRUE(w);
    expect_convex_weights(*w, 7);
    for (double x : *w) EXPECT_NEAR(x, 1.0 / 7.0, 1e-14);
  }
}

TEST(SmoothingWeights, GeometricWeightsReproduceThePlanarCentre) {
  const Eigen::Vector3d centre(0.1, -0.2, 0.0);
  const auto ring = irregular_ring();
  for (const auto& [name, w] : {std::pair{"floater", FloaterWeights{}.weights(centre, ring)},
                                std::pair{"mean-value", MeanValueWeights{}.weights(centre, ring)}}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(w);
    expect_convex_weights(*w, ring.size());
    Eigen::Vector3d combination = Eigen::Vector3d::Zero();
    for (std::size_t j = 0; j < ring.size(); ++j) combination += (*w)[j] * ring[j];
    EXPECT_LT((combination - centre).norm(), 1e-14);
    // and they are not the uniform weights (the test would pass trivially for a centroid)
    EXPECT_GT(std::abs((*w)[0] - 1.0 / 6.0), 1e-3);
  }
}

TEST(SmoothingWeights, ANonPlanarStarStillGivesConvexWeights) {
  auto ring = irregular_ring();
  for (std::size_t j = 0; j < ring.size(); ++j) ring[j].z() = (j % 2 ? 0.8 : -0.5);
  const Eigen::Vector3d centre(0.1, -0.2, 0.3);
  for (const auto& w : {FloaterWeights{}.weights(centre, ring), MeanValueWeights{}.weights(centre, ring)}) {
    ASSERT_TRUE(w);
    expect_convex_weights(*w, ring.size());
  }
}

TEST(SmoothingWeights, ADegenerateStarIsRefused) {
  auto ring = irregular_ring();
  const Eigen::Vector3d centre = ring[2];  // a zero-length spoke
  EXPECT_FALSE(FloaterWeights{}.weights(centre, ring));
  EXPECT_FALSE(MeanValueWeights{}.weights(centre, ring));
}

TEST(SmoothingWeights, RegistryKnowsTheModelsAndRefusesOthers) {
  for (std::string_view name : smoothing_weights_names()) {
    const auto w = make_smoothing_weights(name)(Eigen::Vector3d::Zero(), regular_ring(5, 1.0));
    ASSERT_TRUE(w) << name;
    expect_convex_weights(*w, 5);
  }
  try {
    (void)make_smoothing_weights("cotangent");
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown smoothing weights 'cotangent' (valid: floater, mean-value, uniform)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace plmap
