// fold_curve.hpp: the fold function of an S1 element projected onto the plane of an S2 triangle,
// against a closed form and against the projection's own Jacobian taken by finite differences.
#include "fold_curve.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

using namespace plmap;
using namespace plmap::projection;

namespace {

/// The reference triangle at z = 0 with directions (alpha x, 0, 1 + beta x) (linear, so the
/// corners' directions interpolate to exactly this), projected onto the plane z = h: there
/// y_x = x (1 + h alpha / (1 + beta x)), y_y = y, and the map folds where
/// (1 + beta x)^2 = -h alpha.
ElementOntoPlane sheared_rays(double alpha, double beta, double h) {
  return ElementOntoPlane({WorldPoint<2>(0, 0, 0), WorldPoint<2>(1, 0, 0), WorldPoint<2>(0, 1, 0)},
                          {WorldPoint<2>(0, 0, 1), WorldPoint<2>(alpha, 0, 1 + beta), WorldPoint<2>(0, 0, 1)},
                          {WorldPoint<2>(-5, -5, h), WorldPoint<2>(5, -5, h), WorldPoint<2>(0, 5, h)});
}

/// A number in [0, 1] in steps of 1/1000, from RapidCheck (inside a property only).
double unit() { return *rc::gen::inRange(0, 1001) / 1000.0; }

/// The sheared rays with the fold put at a random x* in [x_low, x_low + x_span], with random h
/// and beta (away from 0: with beta = 0 the field folds everywhere at once or nowhere), the whole
/// configuration rotated and moved at random (inside a property only).
struct PosedShear {
  double x_star = 0.0, h = 0.0, beta = 0.0, alpha = 0.0;
  Eigen::Matrix3d rotation;
  WorldPoint<2> shift;

  static PosedShear random(double x_low, double x_span) {
    PosedShear c;
    c.x_star = x_low + x_span * unit();
    c.h = 0.2 + 2.8 * unit();
    c.beta = *rc::gen::arbitrary<bool>() ? 0.2 + 2.3 * unit() : -(0.2 + 0.6 * unit());
    c.alpha = -(1.0 + c.beta * c.x_star) * (1.0 + c.beta * c.x_star) / c.h;
    c.rotation =
        Eigen::Quaterniond(unit() - 0.5, unit() - 0.5, unit() - 0.5, unit() + 0.1).normalized().toRotationMatrix();
    c.shift = WorldPoint<2>(10 * unit(), -10 * unit(), 5 * unit());
    return c;
  }
  WorldPoint<2> place(const WorldPoint<2>& x) const { return rotation * x + shift; }
  ElementOntoPlane projection() const {
    return ElementOntoPlane(
        {place(WorldPoint<2>(0, 0, 0)), place(WorldPoint<2>(1, 0, 0)), place(WorldPoint<2>(0, 1, 0))},
        {rotation * WorldPoint<2>(0, 0, 1), rotation * WorldPoint<2>(alpha, 0, 1 + beta), rotation * WorldPoint<2>(0, 0, 1)},
        {place(WorldPoint<2>(-5, -5, h)), place(WorldPoint<2>(5, -5, h)), place(WorldPoint<2>(0, 5, h))});
  }
};

/// The sign of the Jacobian of u -> image(u) in the plane (its normal N), by central differences.
int image_orientation(const ElementOntoPlane& p, const LocalPoint<2>& u, const WorldPoint<2>& normal) {
  const double h = 1e-6;
  auto y = [&](double du, double dv) { return *p.image(u + LocalPoint<2>(du, dv)); };
  const WorldPoint<2> d1 = (y(h, 0) - y(-h, 0)) / (2 * h), d2 = (y(0, h) - y(0, -h)) / (2 * h);
  const double area = d1.cross(d2).dot(normal);
  return area > 0 ? 1 : (area < 0 ? -1 : 0);
}

}  // namespace

TEST(FoldCurve, TheShearedRaysFoldWhereTheClosedFormSays) {
  // h = 1, alpha = -2, beta = 1: (1 + x)^2 = 2, x* = sqrt(2) - 1
  const ElementOntoPlane p = sheared_rays(-2.0, 1.0, 1.0);
  const double x_star = std::sqrt(2.0) - 1.0;
  // along the bottom edge and along the hypotenuse x runs from 0 to 1 with the parameter
  for (const auto& [a, b] : {std::pair{LocalPoint<2>(0, 0), LocalPoint<2>(1, 0)},
                             std::pair{LocalPoint<2>(0, 1), LocalPoint<2>(1, 0)}}) {
    const std::vector<double> roots = fold_on_segment(p, a, b);
    ASSERT_EQ(roots.size(), 1u);
    EXPECT_NEAR(roots[0], x_star, 1e-14);
  }
  // along x = 0 the map is folded throughout (1 + h alpha < 0), and nothing is crossed
  EXPECT_TRUE(fold_on_segment(p, LocalPoint<2>(0, 0), LocalPoint<2>(0, 1)).empty());
  EXPECT_LT(p.fold_function(LocalPoint<2>(0, 0.5)) * p.fold_function(LocalPoint<2>(0.9, 0.05)), 0.0);
  // the map itself: y_x stops growing at x*
  EXPECT_NEAR(p.sigma(LocalPoint<2>(0.5, 0.2)).value(), 1.0 / 1.5, 1e-15);
  const auto yx = [&](double x) { return p.image(LocalPoint<2>(x, 0))->x(); };
  // y_x = x (x - 1) / (x + 1): a minimum at x*, where the sheet turns back
  EXPECT_GT(yx(x_star - 1e-3), yx(x_star));
  EXPECT_GT(yx(x_star + 1e-3), yx(x_star));
}

TEST(FoldCurve, RaysParallelToThePlaneHaveNoImageButAFiniteFoldFunction) {
  // beta = -1 at x = 1: the ray (alpha, 0, 0) runs parallel to z = h
  const ElementOntoPlane p = sheared_rays(0.5, -1.0, 1.0);
  EXPECT_FALSE(p.sigma(LocalPoint<2>(1, 0)).has_value());
  EXPECT_FALSE(p.image(LocalPoint<2>(1, 0)).has_value());
  EXPECT_TRUE(std::isfinite(p.fold_function(LocalPoint<2>(1, 0))));
}

RC_GTEST_PROP(FoldCurve, ShearedRaysInAnyPoseFoldWhereTheClosedFormSays, ()) {
  // a segment of the element at height c crosses the fold once, at x = x*
  const PosedShear shear = PosedShear::random(0.1, 0.8);
  const double c = 0.05 * unit();
  const std::vector<double> roots = fold_on_segment(shear.projection(), LocalPoint<2>(0, c), LocalPoint<2>(1 - c, c));
  RC_ASSERT(roots.size() == 1u);
  RC_ASSERT(std::abs(roots[0] * (1 - c) - shear.x_star) < 1e-9);
}

RC_GTEST_PROP(FoldCurve, RootsAreWhereTheProjectionsJacobianChangesSign, ()) {
  // a random element with random directions over a random plane; the Jacobian of the image map
  // by finite differences must change sign across every root, and a scan of the fold function
  // must find no sign change that the roots miss
  auto coordinate = [] { return *rc::gen::inRange(-1000, 1001) / 1000.0; };
  auto point = [&] { return WorldPoint<2>(coordinate(), coordinate(), coordinate()); };
  // the reference triangle moved by up to 0.3 per corner and coordinate: never degenerate
  std::array<WorldPoint<2>, 3> corners{WorldPoint<2>(0, 0, 0) + 0.3 * point(), WorldPoint<2>(1, 0, 0) + 0.3 * point(),
                                       WorldPoint<2>(0, 1, 0) + 0.3 * point()};
  std::array<WorldPoint<2>, 3> directions;
  const double spread = 3.0 * std::abs(coordinate());
  for (auto& n : directions) n = WorldPoint<2>(0, 0, 1) + spread * point();
  const double h = 0.3 + 3.0 * std::abs(coordinate());
  const WorldPoint<2> tilt(0.3 * coordinate(), 0.3 * coordinate(), 1.0);
  const WorldPoint<2> a0(0, 0, h);
  const WorldPoint<2> e1 = tilt.unitOrthogonal(), e2 = tilt.cross(e1);
  const ElementOntoPlane p(corners, directions, {a0, WorldPoint<2>(a0 + e1), WorldPoint<2>(a0 + e2)});
  const WorldPoint<2> normal = e1.cross(e2);
  const LocalPoint<2> a(coordinate() * 0.5 + 0.25, 0.0), b(0.0, coordinate() * 0.5 + 0.5);
  const std::vector<double> roots = fold_on_segment(p, a, b);
  RC_CLASSIFY(!roots.empty(), "crosses the fold");
  // every root: the image's orientation flips across it (where the rays meet the plane there)
  for (double s : roots) {
    const LocalPoint<2> u = a + s * (b - a), step = 1e-4 * (b - a);
    const auto before = p.sigma(u - step), after = p.sigma(u + step);
    if (!before || !after || std::abs(p.approach(u)) < 1e-3) continue;
    const int o0 = image_orientation(p, u - step, normal), o1 = image_orientation(p, u + step, normal);
    RC_ASSERT(o0 * o1 == -1);
  }
  // no sign change between the roots (a scan; changes closer than its step to a root count)
  const int scan = 2000;
  double previous = p.fold_function(a);
  for (int i = 1; i <= scan; ++i) {
    const double s = double(i) / scan;
    const double value = p.fold_function(a + s * (b - a));
    if (previous != 0.0 && value != 0.0 && (previous < 0.0) != (value < 0.0)) {
      bool explained = false;
      for (double r : roots) explained = explained || (r >= double(i - 1) / scan - 1e-9 && r <= s + 1e-9);
      RC_ASSERT(explained);
    }
    previous = value;
  }
}

RC_GTEST_PROP(FoldCurve, TheFoldOnAnS2LineIsWhereTheClosedFormSays, ()) {
  // the plane's line y = c is the image of the element's row y = c (y_y = y), which meets the
  // fold at (x*, c), where the image's first coordinate is x* (1 + h alpha / (1 + beta x*))
  const PosedShear shear = PosedShear::random(0.1, 0.6);
  const double c = 0.25 * unit();
  // started up to a tenth of the element away, as a walk's last point before the fold would be
  const LocalPoint<2> start(shear.x_star - 0.1 * unit(), c + 0.05 * (unit() - 0.5));
  const std::optional<FoldOnLine> fold = fold_on_target_line(
      shear.projection(), shear.place(WorldPoint<2>(0, c, shear.h)), shear.place(WorldPoint<2>(1, c, shear.h)), start);
  RC_ASSERT(fold.has_value());
  RC_ASSERT(std::abs(fold->local(0) - shear.x_star) < 1e-9);
  RC_ASSERT(std::abs(fold->local(1) - c) < 1e-9);
  RC_ASSERT(std::abs(fold->eta - shear.x_star * (1.0 + shear.h * shear.alpha / (1.0 + shear.beta * shear.x_star))) < 1e-9);
}

TEST(FoldCurve, TheFoldSegmentEndsOnTheS2TrianglesSidesWhereTheClosedFormSays) {
  // x* = 0.4 (alpha from (1 + beta x*)^2 = -h alpha with beta = 1, h = 1): the fold's image is
  // the plane's line X = X* = x* (1 + h alpha / (1 + beta x*)), y in [0, 1 - x*]. The triangle's
  // sides 0 (P0 -> P1) and 2 (P2 -> P0) cross that line at y = 0.125 and y = 0.38; their
  // preimages meet the fold at (x*, 0.125) and (x*, 0.38)
  const double x_star = 0.4, beta = 1.0, h = 1.0;
  const double alpha = -(1 + beta * x_star) * (1 + beta * x_star) / h;
  const double big_x = x_star * (1 + h * alpha / (1 + beta * x_star));
  const ElementOntoPlane p = sheared_rays(alpha, beta, h);
  const std::array<WorldPoint<2>, 3> triangle{WorldPoint<2>(big_x - 0.2, 0.1, h), WorldPoint<2>(big_x + 0.2, 0.15, h),
                                              WorldPoint<2>(big_x + 0.05, 0.45, h)};
  std::array<FoldEnd, 2> ends;
  ASSERT_EQ(fold_segment(p, triangle, ends), 2);
  if (ends[0].side > ends[1].side) std::swap(ends[0], ends[1]);
  EXPECT_TRUE(ends[0].on_target_edge && ends[1].on_target_edge);
  EXPECT_EQ(ends[0].side, 0);
  EXPECT_EQ(ends[1].side, 2);
  EXPECT_NEAR(ends[0].local(0), x_star, 1e-9);
  EXPECT_NEAR(ends[0].local(1), 0.125, 1e-9);
  EXPECT_NEAR(ends[0].parameter, 0.5, 1e-9);  // X* is half-way along side 0 in x
  EXPECT_NEAR(ends[1].local(0), x_star, 1e-9);
  EXPECT_NEAR(ends[1].local(1), 0.38, 1e-9);
  EXPECT_NEAR(ends[1].parameter, 0.2, 1e-9);
}

TEST(FoldCurve, TheFoldSegmentEndsOnTheElementsSidesInsideALargeTriangle) {
  // the same fold under a triangle that holds its whole image: it crosses the element's side 0
  // (y = 0) at x* and side 1 (from (1, 0) to (0, 1)) at parameter 1 - x*
  const double x_star = 0.4, beta = 1.0, h = 1.0;
  const double alpha = -(1 + beta * x_star) * (1 + beta * x_star) / h;
  const ElementOntoPlane p = sheared_rays(alpha, beta, h);
  const std::array<WorldPoint<2>, 3> triangle{WorldPoint<2>(-5, -5, h), WorldPoint<2>(5, -5, h), WorldPoint<2>(0, 5, h)};
  std::array<FoldEnd, 2> ends;
  ASSERT_EQ(fold_segment(p, triangle, ends), 2);
  if (ends[0].side > ends[1].side) std::swap(ends[0], ends[1]);
  EXPECT_FALSE(ends[0].on_target_edge || ends[1].on_target_edge);
  EXPECT_EQ(ends[0].side, 0);
  EXPECT_NEAR(ends[0].parameter, x_star, 1e-12);
  EXPECT_EQ(ends[1].side, 1);
  EXPECT_NEAR(ends[1].parameter, 1 - x_star, 1e-12);
  // a triangle away from the fold's image shares no fold with the element
  const std::array<WorldPoint<2>, 3> away{WorldPoint<2>(3, 3, h), WorldPoint<2>(4, 3, h), WorldPoint<2>(3, 4, h)};
  EXPECT_EQ(fold_segment(p, away, ends), 0);
}

RC_GTEST_PROP(FoldCurve, FoldSegmentEndsLieOnTheFoldAndOnTheSidesTheyName, ()) {
  // the posed sheared rays under a random triangle of the plane near the fold's image: every
  // end found lies on the fold (x = x* in the element) and on the side it names
  const PosedShear shear = PosedShear::random(0.2, 0.5);
  const double big_x = shear.x_star * (1 + shear.h * shear.alpha / (1 + shear.beta * shear.x_star));
  auto plane_point = [&] {
    return WorldPoint<2>(big_x + 0.6 * (unit() - 0.5), 0.8 * unit() - 0.1, shear.h);
  };
  const std::array<WorldPoint<2>, 3> flat{plane_point(), plane_point(), plane_point()};
  RC_PRE((flat[1] - flat[0]).cross(flat[2] - flat[0]).norm() > 1e-3);
  const std::array<WorldPoint<2>, 3> triangle{shear.place(flat[0]), shear.place(flat[1]), shear.place(flat[2])};
  const ElementOntoPlane p = shear.projection();
  std::array<FoldEnd, 2> ends;
  const int count = fold_segment(p, triangle, ends);
  RC_CLASSIFY(count == 2, "the fold crosses the triangle");
  // independently: the fold's image is the segment x = X*, y in [0, 1 - x*] of the flat plane;
  // where a clear stretch of it lies inside the triangle, the two ends must be found
  double low = 0.0, high = 1.0 - shear.x_star;
  bool clear = true;
  {
    // clip the segment's y range by each side's half-plane (the side that holds the third corner)
    for (int k = 0; k < 3; ++k) {
      const WorldPoint<2>&a = flat[k], &b = flat[(k + 1) % 3], &c = flat[(k + 2) % 3];
      clear = clear && std::abs(a.x() - big_x) > 1e-6;
      auto side = [&](double y) { return (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (big_x - a.x()); };
      const double sc = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
      // side(y) is linear in y: side(y) = s0 + s1 y
      const double s0 = side(0.0), s1 = side(1.0) - s0;
      if (s1 == 0.0) {
        if (s0 * sc <= 0.0) high = low - 1.0;
        continue;
      }
      const double root = -s0 / s1;
      if ((s1 > 0.0) == (sc > 0.0)) low = std::max(low, root);  // inside for y above the root
      else high = std::min(high, root);
    }
  }
  if (clear && high - low > 1e-3 && low > 1e-6 && high < 1.0 - shear.x_star - 1e-6) RC_ASSERT(count == 2);
  for (int i = 0; i < count; ++i) {
    const FoldEnd& end = ends[static_cast<std::size_t>(i)];
    const LocalPoint<2> a = reference_corner<2>(end.side), b = reference_corner<2>((end.side + 1) % 3);
    const LocalPoint<2> u = end.on_target_edge ? end.local : LocalPoint<2>(a + end.parameter * (b - a));
    RC_ASSERT(std::abs(u(0) - shear.x_star) < 1e-9);
    if (end.on_target_edge) {
      // the image of u is the point of the triangle's side at the parameter
      const WorldPoint<2> expected =
          triangle[end.side] + end.parameter * (triangle[(end.side + 1) % 3] - triangle[end.side]);
      RC_ASSERT((*p.image(u) - expected).norm() < 1e-8);
    }
  }
}
