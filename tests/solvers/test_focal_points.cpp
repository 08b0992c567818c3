// Focal points of the projection (solvers/focal_points.hpp): the Jacobian determinant along a
// ray, and the rule that rejects solutions beyond a focal point, on direction fields whose
// focal distances are known: constant (none), converging to a line (a cylinder's axis) and to a
// point (a sphere's centre), diverging (convex), in both dimensions and at every scale.
#include <plmap/solvers/focal_points.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

using namespace plmap;

namespace {

using Corners2 = std::array<WorldPoint<2>, 3>;
using Corners1 = std::array<WorldPoint<1>, 2>;

/// Directions from each corner towards `focus` (not normalised: every ray reaches it at t = 1).
template <int d>
std::array<WorldPoint<d>, d + 1> towards(const std::array<WorldPoint<d>, d + 1>& corners, const WorldPoint<d>& focus) {
  std::array<WorldPoint<d>, d + 1> n;
  for (int k = 0; k <= d; ++k) n[k] = focus - corners[k];
  return n;
}

const Corners2 triangle = {WorldPoint<2>(0, 0, 0), WorldPoint<2>(1, 0, 0), WorldPoint<2>(0, 1, 0)};
const LocalPoint<2> inside(0.3, 0.25);

TEST(FocalPoints, ConstantDirectionsHaveNone) {
  const std::array<WorldPoint<2>, 3> up = {WorldPoint<2>(0, 0, 1), WorldPoint<2>(0, 0, 1), WorldPoint<2>(0, 0, 1)};
  const auto a = ray_jacobian_polynomial<2>(triangle, up, inside);
  EXPECT_DOUBLE_EQ(a[0], 1.0);  // (e1 x e2) . nu
  EXPECT_EQ(a[1], 0.0);
  EXPECT_EQ(a[2], 0.0);
  for (double mu : {-1e6, -1.0, 0.0, 1e-3, 1.0, 1e6}) EXPECT_TRUE(reaches_without_focal_point<2>(triangle, up, inside, mu));
}

TEST(FocalPoints, DirectionsConvergingToALineFoldAtTheLine) {
  // nu(x, y) = (-x, 0, 1): the rays of each line y = const meet on the line x = 0, z = 1 (the
  // axis of a cylinder seen from inside), so J(t) = 1 - t.
  std::array<WorldPoint<2>, 3> n;
  for (int k = 0; k < 3; ++k) n[k] = WorldPoint<2>(-triangle[k].x(), 0, 1);
  const auto a = ray_jacobian_polynomial<2>(triangle, n, inside);
  EXPECT_NEAR(a[0], 1.0, 1e-15);
  EXPECT_NEAR(a[1], -1.0, 1e-15);
  EXPECT_NEAR(a[2], 0.0, 1e-15);
  EXPECT_TRUE(reaches_without_focal_point<2>(triangle, n, inside, 0.5));
  EXPECT_TRUE(reaches_without_focal_point<2>(triangle, n, inside, 1.0));  // at the focal line itself
  EXPECT_FALSE(reaches_without_focal_point<2>(triangle, n, inside, 1.5));
  EXPECT_FALSE(reaches_without_focal_point<2>(triangle, n, inside, 40.0));
  EXPECT_TRUE(reaches_without_focal_point<2>(triangle, n, inside, -40.0));  // behind S1 they diverge
}

TEST(FocalPoints, DirectionsConvergingToAPointFoldThereEvenThoughJKeepsItsSign) {
  // All rays meet at the focus at t = 1: J(t) = J(0) (1 - t)^2 has a double root, the sheet
  // beyond is turned by 180 degrees (same orientation) but folded.
  const auto n = towards<2>(triangle, WorldPoint<2>(0.2, 0.3, 1.0));
  const auto a = ray_jacobian_polynomial<2>(triangle, n, inside);
  EXPECT_NEAR(a[1], -2.0 * a[0], 1e-14);
  EXPECT_NEAR(a[2], a[0], 1e-14);
  EXPECT_TRUE(reaches_without_focal_point<2>(triangle, n, inside, 0.9));
  EXPECT_FALSE(reaches_without_focal_point<2>(triangle, n, inside, 1.1));
  EXPECT_FALSE(reaches_without_focal_point<2>(triangle, n, inside, 3.0));
  EXPECT_TRUE(reaches_without_focal_point<2>(triangle, n, inside, -3.0));
}

TEST(FocalPoints, DivergingDirectionsNeverFoldAhead) {
  // the outward normals of a sphere of radius 1 around (0.2, 0.3, -1): focal point behind S1
  const auto n = towards<2>(triangle, WorldPoint<2>(0.2, 0.3, -1.0));
  std::array<WorldPoint<2>, 3> out;
  for (int k = 0; k < 3; ++k) out[k] = -n[k];
  for (double mu : {0.1, 1.0, 10.0, 1e4}) EXPECT_TRUE(reaches_without_focal_point<2>(triangle, out, inside, mu)) << mu;
  EXPECT_FALSE(reaches_without_focal_point<2>(triangle, out, inside, -1.5));
}

TEST(FocalPoints, CurvesConvergeToTheirCentreOfCurvature) {
  const Corners1 segment = {WorldPoint<1>(-1, 0), WorldPoint<1>(1, 0)};
  const auto n = towards<1>(segment, WorldPoint<1>(0.0, 1.0));
  const LocalPoint<1> xi(0.3);
  const auto a = ray_jacobian_polynomial<1>(segment, n, xi);
  EXPECT_NEAR(a[0], 2.0, 1e-15);
  EXPECT_NEAR(a[1], -2.0, 1e-15);
  EXPECT_TRUE(reaches_without_focal_point<1>(segment, n, xi, 0.99));
  EXPECT_FALSE(reaches_without_focal_point<1>(segment, n, xi, 1.01));
  EXPECT_TRUE(reaches_without_focal_point<1>(segment, n, xi, -100.0));
}

TEST(FocalPoints, NonFiniteDistancesAreNotJudged) {
  const auto n = towards<2>(triangle, WorldPoint<2>(0.2, 0.3, 1.0));
  EXPECT_TRUE(reaches_without_focal_point<2>(triangle, n, inside, std::nan("")));
  EXPECT_TRUE(reaches_without_focal_point<2>(triangle, n, inside, INFINITY));
}

// The verdict depends on the shape only: scaling the element, the directions' length and mu
// (mu scales with the element when the directions do not) changes nothing.
RC_GTEST_PROP(FocalPoints, TheVerdictIsScaleInvariant, ()) {
  const double focus_height = *rc::gen::inRange(1, 100) / 10.0;
  const double mu = *rc::gen::inRange(-300, 300) / 10.0;
  const int element_exponent = *rc::gen::inRange(-6, 7);
  const int direction_exponent = *rc::gen::inRange(-6, 7);
  // Exactly at the focal distance (|mu| = 1, where the determinant vanishes) the verdict is
  // rounding's, and scaling may flip it (found with 1000 cases: mu = 1, s = 1e-6, l = 0.1).
  RC_PRE(std::abs(std::abs(mu) - 1.0) > 1e-6);
  const double s = std::pow(10.0, element_exponent), l = std::pow(10.0, direction_exponent);
  const auto n = towards<2>(triangle, WorldPoint<2>(0.4, 0.1, focus_height));
  Corners2 scaled;
  std::array<WorldPoint<2>, 3> scaled_n;
  for (int k = 0; k < 3; ++k) scaled[k] = s * triangle[k], scaled_n[k] = l * n[k];
  // with the directions scaled by l, the same point of space is reached at mu s / l
  RC_ASSERT(reaches_without_focal_point<2>(scaled, scaled_n, inside, mu * s / l) ==
            reaches_without_focal_point<2>(triangle, n, inside, mu));
  // and the focal distance is where the verdict changes: the focus lies at t = 1
  if (std::abs(mu) > 0) RC_ASSERT(reaches_without_focal_point<2>(triangle, n, inside, mu) == (mu < 1.0));
}

}  // namespace

// focal_free_distance lets the projection skip the focal test: below it, the test must accept
// every point of the element (with the projection's slack) at every distance.
RC_GTEST_PROP(FocalPoints, NoFocalPointWithinTheFocalFreeDistance, ()) {
  const auto coord = [] { return *rc::gen::inRange(-1000, 1001) / 1000.0; };
  const double s = std::pow(10.0, *rc::gen::inRange(-6, 7));
  Corners2 corners;
  for (auto& c : corners) c = s * WorldPoint<2>(coord(), coord(), 0.2 * coord());
  std::array<WorldPoint<2>, 3> n;
  // from parallel to strongly converging or diverging fields
  const double spread = *rc::gen::element(0.0, 0.01, 0.3, 1.0, 3.0);
  for (auto& d : n) d = WorldPoint<2>(spread * coord(), spread * coord(), 1.0).normalized();
  const double m = focal_free_distance<2>(corners, n);
  RC_ASSERT(m >= 0.0);
  if (m == 0.0) return;
  for (int i = 0; i < 20; ++i) {
    // barycentric weights down to -1e-9
    const double b1 = (coord() + 1.0) / 2.0, b2 = (1.0 - b1) * (coord() + 1.0) / 2.0;
    const LocalPoint<2> xi(i == 0 ? -1e-9 : b1, i == 1 ? -1e-9 : b2);
    const double mu = std::isfinite(m) ? m * coord() : s * 1e6 * coord();
    RC_ASSERT(reaches_without_focal_point<2>(corners, n, xi, mu));
  }
}

TEST(FocalPoints, TheFocalFreeDistanceIsAPartOfTheFocalDistance) {
  // converging to a line at t = 1: J(t) = 1 - t
  std::array<WorldPoint<2>, 3> n;
  for (int k = 0; k < 3; ++k) n[k] = WorldPoint<2>(-triangle[k].x(), 0, 1);
  const double m = focal_free_distance<2>(triangle, n);
  EXPECT_GT(m, 0.1);
  EXPECT_LT(m, 1.0);
  // constant directions never fold; tangential ones get no free distance
  const std::array<WorldPoint<2>, 3> up = {WorldPoint<2>(0, 0, 1), WorldPoint<2>(0, 0, 1), WorldPoint<2>(0, 0, 1)};
  EXPECT_EQ(focal_free_distance<2>(triangle, up), std::numeric_limits<double>::infinity());
  const std::array<WorldPoint<2>, 3> flat = {WorldPoint<2>(1, 0, 0), WorldPoint<2>(1, 0, 0), WorldPoint<2>(1, 0, 0)};
  EXPECT_EQ(focal_free_distance<2>(triangle, flat), 0.0);
  // a curve converging to its centre of curvature at t = 1
  const Corners1 segment = {WorldPoint<1>(-1, 0), WorldPoint<1>(1, 0)};
  const auto towards_centre = towards<1>(segment, WorldPoint<1>(0.0, 1.0));
  const double c = focal_free_distance<1>(segment, towards_centre);
  EXPECT_GT(c, 0.1);
  EXPECT_LT(c, 1.0);
  EXPECT_TRUE(reaches_without_focal_point<1>(segment, towards_centre, LocalPoint<1>(0.0), c));
}
