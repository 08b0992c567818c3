// Maps built by normal projection pass every invariant check of plmap::verify (DESIGN.md §4).
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>

#include <sstream>

using namespace plmap;
using namespace plmap::test;

namespace {

template <int d>
void expect_valid(const PlMap<d>& map) {
  const VerificationReport report = verify(map);
  std::ostringstream why;
  for (const auto& check : report.checks)
    for (const auto& v : check.violations) why << check.name << "/" << v.rule << " element " << v.element << ": " << v.message << "\n";
  EXPECT_TRUE(report.ok()) << why.str();
}

}  // namespace

TEST(ProjectVerify, FacingPlanesWithPartialOverlap) {
  auto s1 = grid(6, 6, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  auto s2 = grid(7, 5, 0.3, 1.3, 0.2, 1.2, 0.1, true, 0.2);
  expect_valid(project<2>(s1, s2, {.normal_check = TargetNormalCheck::facing}).map);
}

TEST(ProjectVerify, ConcentricSpheresAndCircles) {
  expect_valid(project<2>(sphere(1, 1.0), sphere(2, 1.2, false, 0.4)).map);
  expect_valid(project<1>(circle(30, 1.0), circle(41, 1.3, 0.05)).map);
}

TEST(ProjectVerify, IdentityAndShiftedGrids) {
  auto s = grid(4, 5, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  expect_valid(project<2>(s, s).map);
  expect_valid(project<2>(grid(4, 4, 0.0, 1.0, 0.0, 1.0, 0.0), grid(4, 4, 0.125, 1.125, 0.0, 1.0, 0.3)).map);
}
