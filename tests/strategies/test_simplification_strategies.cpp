// The simplification strategies: flattenings give star-shaped polygons, hole triangulations
// give n - 2 positive triangles that tile the polygon and avoid forbidden diagonals, the
// constrained Delaunay model is locally Delaunay, the oracles rank and veto as documented.

#include <plmap/core/predicates.hpp>
#include <plmap/strategies/simplification/constrained_delaunay_hole.hpp>
#include <plmap/strategies/simplification/min_max_aspect_triangulation.hpp>
#include <plmap/strategies/simplification/polar_map_flattening.hpp>
#include <plmap/strategies/simplification/simplification_registry.hpp>
#include <plmap/strategies/simplification/weighted_oracles.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <numbers>

namespace plmap {
namespace {

/// A random star-shaped polygon around the origin: n angles in increasing order (gaps below π),
/// random radii.
std::vector<Eigen::Vector2d> random_star_polygon(int n) {
  std::vector<double> gaps(n);
  double total = 0.0;
  for (double& g : gaps) total += (g = *rc::gen::inRange(20, 100));
  std::vector<Eigen::Vector2d> p(n);
  double angle = 0.0;
  for (int i = 0; i < n; ++i) {
    const double r = *rc::gen::inRange(20, 100) / 100.0;
    p[i] = {r * std::cos(angle), r * std::sin(angle)};
    angle += 2.0 * std::numbers::pi * gaps[i] / total;
  }
  return p;
}

double area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

void check_triangulation(const std::vector<Eigen::Vector2d>& p, const HoleTriangles& t,
                         const std::vector<std::array<int, 2>>& forbidden) {
  const int n = static_cast<int>(p.size());
  RC_ASSERT(static_cast<int>(t.size()) == n - 2);
  double polygon_area = 0.0, sum = 0.0;
  for (int i = 0; i < n; ++i) polygon_area += area(Eigen::Vector2d::Zero(), p[i], p[(i + 1) % n]);
  for (const auto& tri : t) {
    RC_ASSERT(orient2d(p[tri[0]], p[tri[1]], p[tri[2]]) > 0);
    sum += area(p[tri[0]], p[tri[1]], p[tri[2]]);
    for (int m = 0; m < 3; ++m) {
      const std::array<int, 2> key{std::min(tri[m], tri[(m + 1) % 3]), std::max(tri[m], tri[(m + 1) % 3])};
      RC_ASSERT(std::find(forbidden.begin(), forbidden.end(), key) == forbidden.end());
    }
  }
  RC_ASSERT(std::abs(sum - polygon_area) <= 1e-12 * polygon_area);
}

RC_GTEST_PROP(HoleTriangulation, TilesStarPolygonsAndAvoidsForbiddenDiagonals, ()) {
  const int n = *rc::gen::inRange(3, 12);
  const auto p = random_star_polygon(n);
  std::vector<std::array<int, 2>> forbidden;
  if (n >= 5) forbidden.push_back({0, *rc::gen::inRange(2, n - 1)});
  const DiagonalAllowed allowed = [&](int i, int j) {
    const std::array<int, 2> key{std::min(i, j), std::max(i, j)};
    return std::find(forbidden.begin(), forbidden.end(), key) == forbidden.end();
  };
  // With random radii the polygon is not convex, and a forbidden diagonal can leave it without
  // any triangulation (seed 26120390: n = 5, gaps 28, 81, 20, 20, 20). The min-max-aspect
  // programme tries every triangulation, so it decides whether one exists by brute force; then
  // every model must find one, and otherwise every model must say that there is none.
  const bool exists = MinMaxAspectTriangulation{}.triangulate(p, allowed).has_value();
  RC_CLASSIFY(!exists, "no triangulation exists");
  for (std::string_view name : hole_triangulation_names()) {
    const auto t = make_hole_triangulation(name)(p, allowed);
    RC_ASSERT(t.has_value() == exists);
    if (t) check_triangulation(p, *t, forbidden);
  }
  if (!exists) return;
  // Constrained Delaunay: no flippable diagonal has the fourth point inside the circumcircle.
  const auto t = *ConstrainedDelaunayHole{}.triangulate(p, allowed);
  for (const auto& a : t)
    for (const auto& b : t)
      for (int m = 0; m < 3; ++m) {
        const int u = a[m], v = a[(m + 1) % 3], w = a[(m + 2) % 3];
        for (int k = 0; k < 3; ++k)
          if (b[k] == v && b[(k + 1) % 3] == u) {
            const int x = b[(k + 2) % 3];
            const bool flippable = allowed(w, x) && orient2d(p[x], p[v], p[w]) > 0 && orient2d(p[u], p[x], p[w]) > 0;
            if (flippable) RC_ASSERT(incircle(p[u], p[v], p[w], p[x]) <= 0);
          }
      }
}

TEST(HoleTriangulation, SymmetricHexagonWithoutItsLongDiagonalsStillHasATriangulation) {
  // Greedy ear clipping can cut ears that leave only forbidden diagonals; the DP cannot.
  std::vector<Eigen::Vector2d> p = {{1, 0}, {1, 1}, {0, 1}, {-1, 0}, {-1, -1}, {0, -1}};
  const DiagonalAllowed allowed = [](int i, int j) { return std::abs(i - j) != 3; };
  const auto t = MinMaxAspectTriangulation{}.triangulate(p, allowed);
  ASSERT_TRUE(t.has_value());
  EXPECT_EQ(t->size(), 4u);
  EXPECT_FALSE(MinMaxAspectTriangulation{}.triangulate(p, [](int, int) { return false; }).has_value());
}

RC_GTEST_PROP(PolarMapFlattening, GivesAStarShapedPolygonWithTheSpokesOrder, ()) {
  const int n = *rc::gen::inRange(3, 10);
  std::vector<Eigen::Vector3d> ring(n);
  const double height = *rc::gen::inRange(-100, 100) / 100.0;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * (i + *rc::gen::inRange(0, 40) / 100.0) / n;
    const double r = *rc::gen::inRange(30, 100) / 100.0;
    ring[i] = {r * std::cos(a), r * std::sin(a), height * *rc::gen::inRange(0, 100) / 100.0};
  }
  const auto flat = PolarMapFlattening{}.flatten(Eigen::Vector3d::Zero(), ring);
  RC_ASSERT(flat.has_value());
  for (int i = 0; i < n; ++i) RC_ASSERT(orient2d(Eigen::Vector2d::Zero(), (*flat)[i], (*flat)[(i + 1) % n]) > 0);
  RC_ASSERT(std::abs((*flat)[0].y()) == 0.0);
}

TEST(PolarMapFlattening, RefusesAZeroLengthSpoke) {
  std::vector<Eigen::Vector3d> ring = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_FALSE(PolarMapFlattening{}.flatten(Eigen::Vector3d::Zero(), ring).has_value());
}

struct ConstantOracle {
  double cost;
  bool veto;
  OracleVerdict evaluate(const RemovalCandidate&) const { return {cost, veto}; }
};

TEST(WeightedOracles, SumsWeightedCostsAndAnyVetoWins) {
  auto surface = std::make_shared<const Surface<2>>(std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                                    std::vector<ElementCorners<2>>{{0, 1, 2}});
  const EditableMap map(surface);
  VertexRemovalPlan plan;
  const RemovalCandidate candidate{map, plan, 1.0};
  WeightedOracles sum;
  sum.add(ConstantOracle{2.0, false}, 0.5).add(ConstantOracle{3.0, false}, 2.0);
  EXPECT_DOUBLE_EQ(sum.evaluate(candidate).cost, 7.0);
  EXPECT_FALSE(sum.evaluate(candidate).veto);
  sum.add(ConstantOracle{0.0, true}, 0.0);
  EXPECT_TRUE(sum.evaluate(candidate).veto);
  WeightedOracles named;
  named.add_spec("hausdorff:2.5").add_spec("long-edge");
  EXPECT_EQ(named.description(), "hausdorff:2.5,long-edge:1");
  for (std::string_view name : error_oracle_names()) EXPECT_NO_THROW(WeightedOracles{}.add(name));
}

TEST(ErrorOracles, HausdorffIsTheLargestNodeDistanceOverTheLengthScale) {
  auto surface = std::make_shared<const Surface<2>>(std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                                    std::vector<ElementCorners<2>>{{0, 1, 2}});
  const EditableMap map(surface);
  VertexRemovalPlan plan;
  plan.max_node_distance = 0.3;
  WeightedOracles h;
  h.add("hausdorff");
  EXPECT_DOUBLE_EQ(h.evaluate({map, plan, 2.0}).cost, 0.15);
}

}  // namespace
}  // namespace plmap
