// Nearest point of a surface (strategies/nearest_point): the AABB-tree model agrees with brute
// force on random surfaces of every shape (d = 1 and 2), points of the surface are their own
// nearest points, and bad queries are refused.
#include <plmap/core/errors.hpp>
#include <plmap/core/evaluation_at_boundaries.hpp>
#include <plmap/strategies/nearest_point/nearest_point.hpp>
#include <plmap/strategies/point_locator_registry.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

using namespace plmap;

namespace {

template <int d>
void check_against_brute_force(const std::shared_ptr<const Surface<d>>& s, std::uint64_t seed) {
  const AabbNearestPoint<d> tree(s);
  const BruteForceNearestPoint<d> brute(s);
  generators::Rng rng(seed);
  const WorldPoint<d> lo = s->bounding_box_min(), hi = s->bounding_box_max();
  const double scale = (hi - lo).norm();
  for (int k = 0; k < 20; ++k) {
    // Points around the surface's box (up to half its size outside) ...
    WorldPoint<d> x;
    for (int i = 0; i <= d; ++i) x(i) = lo(i) + (hi(i) - lo(i)) * (2.0 * generators::uniform_unit(rng) - 0.5);
    const NearestPoint<d> a = tree.nearest(x), b = brute.nearest(x);
    RC_ASSERT(std::abs(a.distance - b.distance) <= 1e-12 * scale);
    RC_ASSERT((s->world_position(a.point.element, a.point.local) - a.world).norm() <= 1e-12 * scale);
    RC_ASSERT(std::abs((a.world - x).norm() - a.distance) <= 1e-12 * scale);
    // ... and points of the surface, which are their own nearest points.
    const Index t = generators::uniform_index(rng, s->element_count());
    LocalPoint<d> xi;
    for (int i = 0; i < d; ++i) xi(i) = generators::uniform_unit(rng) / d;
    const WorldPoint<d> on = s->world_position(t, xi);
    RC_ASSERT(tree.nearest(on).distance <= 1e-12 * scale);
  }
}

}  // namespace

RC_GTEST_PROP(NearestPoint, AabbTreeAgreesWithBruteForceOnTriangleSurfaces, (std::uint64_t seed)) {
  check_against_brute_force<2>(*generators::triangle_surfaces(), seed);
}

RC_GTEST_PROP(NearestPoint, AabbTreeAgreesWithBruteForceOnCurves, (std::uint64_t seed)) {
  check_against_brute_force<1>(*generators::curves(), seed);
}

TEST(NearestPoint, PointAboveATriangleProjectsOntoIt) {
  auto s = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, std::vector<ElementCorners<2>>{{0, 1, 2}});
  const AabbNearestPoint<2> tree(s);
  const NearestPoint<2> p = tree.nearest({0.5, 0.25, 3.0});
  EXPECT_EQ(p.point.element, 0);
  EXPECT_NEAR(p.point.local(0), 0.25, 1e-15);
  EXPECT_NEAR(p.point.local(1), 0.125, 1e-15);
  EXPECT_NEAR(p.distance, 3.0, 1e-15);
  // beyond the corner (2, 0, 0): the corner itself
  const NearestPoint<2> q = tree.nearest({3.0, -1.0, 0.0});
  EXPECT_NEAR(q.point.local(0), 1.0, 1e-15);
  EXPECT_NEAR(q.point.local(1), 0.0, 1e-15);
  EXPECT_THROW(tree.nearest({std::nan(""), 0.0, 0.0}), Error);
}

TEST(NearestPoint, BatchAgreesWithSingleQueriesAndRefusesNonFinitePoints) {
  const auto s = generators::bumpy_grid(5);
  const AabbNearestPoint<2> tree(s);
  generators::Rng rng(4);
  std::vector<WorldPoint<2>> xs(500);
  for (auto& x : xs) x = WorldPoint<2>(2 * generators::uniform_unit(rng) - 0.5, 2 * generators::uniform_unit(rng) - 0.5, generators::uniform_unit(rng));
  std::vector<NearestPoint<2>> out(xs.size());
  nearest_points_batch<2>(tree, xs, out, 2);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    EXPECT_EQ(out[i].point, tree.nearest(xs[i]).point);
    EXPECT_EQ(out[i].distance, tree.nearest(xs[i]).distance);
  }
  xs[7](1) = std::nan("");
  EXPECT_THROW(nearest_points_batch<2>(tree, xs, out, 2), Error);
}

TEST(EvaluatePointsBatch, PointsJustOutsideTheirElementAreFoundWhereEvaluateMissesThem) {
  // Points on an element's slanted side, moved outside by one rounding: the exact locators miss
  // them, evaluate_points_batch finds them (issue 15: world points placed on the surface's edges).
  const auto sub = generators::subdivision_map(generators::bumpy_grid(3), 2, 0.0, 1);
  const PlMap<2>& map = *sub.map;
  std::vector<SurfacePoint<2>> points;
  for (Index t = 0; t < map.domain().element_count(); ++t) {
    const double u = 0.7;  // 1 - u is exact (Sterbenz), so u + next(1 - u) exceeds 1 by one ulp
    points.push_back({t, LocalPoint<2>(u, std::nextafter(1.0 - u, 1.0))});
  }
  std::vector<Evaluation<2>> plain(points.size()), robust(points.size());
  evaluate_batch<2>(map, points, plain, point_location::BrownFaigleWalk{}, 1);
  evaluate_points_batch<2>(map, points, robust, point_location::BrownFaigleWalk{}, 2);
  int missed_by_plain = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    missed_by_plain += !plain[i].in_domain;
    ASSERT_TRUE(robust[i].in_domain) << "point " << i;
    point_location::BruteForce<2> brute;
    const Evaluation<2> at_side = evaluate(map, SurfacePoint<2>{points[i].element, LocalPoint<2>(0.7, 1.0 - 0.7)}, brute);
    ASSERT_TRUE(at_side.in_domain);
    EXPECT_NEAR((robust[i].world - at_side.world).norm(), 0.0, 1e-12);
  }
  EXPECT_GT(missed_by_plain, 0);  // the case this test is about did occur
}
