// power_of_two_scale (core/scaled_geometry.hpp) clears the mantissa of a normal largest
// coordinate instead of calling ilogb and ldexp; every element measure and normal goes through
// it, so it must give exactly the power of two the library calls give, at every scale, and fall
// back for subnormal, zero and non-finite coordinates.
#include <plmap/core/scaled_geometry.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace plmap;

namespace {

double by_library_calls(double largest) {
  if (!(largest > 0.0) || !std::isfinite(largest)) return 1.0;
  return std::ldexp(1.0, std::ilogb(largest));
}

}  // namespace

TEST(PowerOfTwoScale, EqualsTheLibraryCallsAtEveryScale) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> mantissa(-2.0, 2.0);
  std::uniform_int_distribution<int> exponent(-1074, 1023);
  for (int i = 0; i < 100000; ++i) {
    WorldPoint<2> u(std::ldexp(mantissa(random), exponent(random)), mantissa(random), std::ldexp(mantissa(random), exponent(random)));
    WorldPoint<2> v(std::ldexp(mantissa(random), exponent(random)), 0.0, -std::ldexp(mantissa(random), exponent(random)));
    const double largest = std::max(u.cwiseAbs().maxCoeff(), v.cwiseAbs().maxCoeff());
    ASSERT_EQ(power_of_two_scale<2>({u, v}), by_library_calls(largest)) << u.transpose() << " / " << v.transpose();
  }
}

TEST(PowerOfTwoScale, PowersOfTwoSubnormalsZeroAndNonFinite) {
  constexpr double smallest_normal = std::numeric_limits<double>::min();
  constexpr double smallest_subnormal = std::numeric_limits<double>::denorm_min();
  constexpr double largest_finite = std::numeric_limits<double>::max();
  for (const double x : {1.0, 0.75, 1.5, 2.0, 3.0, smallest_normal, std::nextafter(smallest_normal, 0.0),
                         smallest_subnormal, 3 * smallest_subnormal, largest_finite, std::nextafter(1.0, 0.0), 1e-300,
                         1e300}) {
    EXPECT_EQ(power_of_two_scale<1>({WorldPoint<1>(x, -0.5 * x)}), by_library_calls(x)) << x;
    EXPECT_EQ(power_of_two_scale<1>({WorldPoint<1>(0.0, -x)}), by_library_calls(x)) << x;
  }
  EXPECT_EQ(power_of_two_scale<2>({WorldPoint<2>::Zero()}), 1.0);
  EXPECT_EQ(power_of_two_scale<2>({WorldPoint<2>(std::numeric_limits<double>::infinity(), 1.0, 0.0)}), 1.0);
  EXPECT_EQ(power_of_two_scale<2>({WorldPoint<2>(std::nan(""), 1.0, 0.0)}), 1.0);
  EXPECT_EQ(power_of_two_scale<2>({WorldPoint<2>(0.75, -6.0, 0.0)}), 4.0);
}
