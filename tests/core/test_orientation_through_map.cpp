// The filter that spares judge_face_orientation a closure triangle's affine map
// (core/src/orientation_through_map.hpp): where it says the orientation survives, the map
// (affine_through, as the regions get it) applied to the corners must give the images'
// orientation, exactly; checked on slivers and nearly flat images, where it must not say so
// lightly.
#include "orientation_through_map.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/predicates.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>

using namespace plmap;
using namespace plmap::detail;

namespace {

double uniform(double lo, double hi) { return lo + (hi - lo) * (*rc::gen::inRange(0, 1 << 24)) / double(1 << 24); }

LocalPoint<2> in_the_reference_triangle() {
  const double x = uniform(0.0, 1.0), y = uniform(0.0, 1.0);
  return x + y <= 1.0 ? LocalPoint<2>(x, y) : LocalPoint<2>(1.0 - x, 1.0 - y);
}

/// Corners at `scale` around a point of the reference triangle; with `thin`, the third corner
/// lies within about `thin` of the line through the first two (a sliver, or a nearly flat image).
std::array<LocalPoint<2>, 3> triangle(double scale, double thin) {
  const LocalPoint<2> a = in_the_reference_triangle();
  const LocalPoint<2> b = a + scale * LocalPoint<2>(uniform(-1.0, 1.0), uniform(-1.0, 1.0));
  const double s = uniform(-0.5, 1.5);
  const LocalPoint<2> along = a + s * (b - a);
  const LocalPoint<2> normal(-(b - a)(1), (b - a)(0));
  return {a, b, along + thin * uniform(-1.0, 1.0) * normal};
}

int applied_orientation(const std::array<LocalPoint<2>, 3>& from, const std::array<LocalPoint<2>, 3>& image) {
  const AffineMap<2> map = affine_through<2>(from, image);
  return orient2d(apply<2>(map, from[0]), apply<2>(map, from[1]), apply<2>(map, from[2]));
}

}  // namespace

TEST(OrientationThroughMap, OrdinaryTrianglesPassAndFlatImagesDoNot) {
  const std::array<LocalPoint<2>, 3> from{LocalPoint<2>(0.1, 0.1), LocalPoint<2>(0.3, 0.1), LocalPoint<2>(0.1, 0.3)};
  EXPECT_TRUE(orientation_survives_the_map(from, {LocalPoint<2>(0.2, 0.2), LocalPoint<2>(0.9, 0.1), LocalPoint<2>(0.3, 0.6)}));
  // three images on one line (S2's edge x + y = 1): the map decides, not the filter
  EXPECT_FALSE(orientation_survives_the_map(from, {LocalPoint<2>(0.2, 0.8), LocalPoint<2>(0.5, 0.5), LocalPoint<2>(0.7, 0.3)}));
  // a degenerate S1 triangle has no map
  EXPECT_FALSE(orientation_survives_the_map({LocalPoint<2>(0.1, 0.1), LocalPoint<2>(0.2, 0.2), LocalPoint<2>(0.3, 0.3)},
                                            {LocalPoint<2>(0.2, 0.2), LocalPoint<2>(0.9, 0.1), LocalPoint<2>(0.3, 0.6)}));
}

RC_GTEST_PROP(OrientationThroughMapProperties, WhereTheFilterPassesTheMapKeepsTheOrientation, ()) {
  const double from_scale = std::pow(10.0, uniform(-6.0, 0.0)), image_scale = std::pow(10.0, uniform(-6.0, 0.0));
  const double from_thin = *rc::gen::element(1.0, std::pow(10.0, uniform(-12.0, 0.0)));
  const double image_thin = *rc::gen::element(1.0, std::pow(10.0, uniform(-16.0, 0.0)), 0.0);
  const auto from = triangle(from_scale, from_thin);
  const auto image = triangle(image_scale, image_thin);
  const int sign = orient2d(image[0], image[1], image[2]);
  const bool passes = orientation_survives_the_map(from, image);
  RC_CLASSIFY(passes, "filter passes");
  if (passes) {
    RC_ASSERT(sign != 0);
    RC_ASSERT(applied_orientation(from, image) == sign);
  }
}
