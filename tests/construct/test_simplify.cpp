// simplify(): the map after simplification is a valid parametrization of the fine surface.

#include <plmap/construct/simplify.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <gtest/gtest.h>

namespace plmap {
namespace {

std::shared_ptr<const Surface<2>> bumpy_sphere(int subdivisions, std::uint64_t seed) {
  generators::Rng rng(seed);
  return std::make_shared<const Surface<2>>(generators::icosphere({subdivisions, 0.05}, rng));
}

VerifyOptions parametrization_checks() {
  VerifyOptions v;
  v.expect_parametrization = true;
  return v;
}

TEST(Simplify, SphereDownToATargetIsAValidParametrization) {
  auto fine = bumpy_sphere(3, 1);
  SimplifyOptions options;
  options.target_elements = 200;
  const SimplifyResult result = simplify(fine, options);
  EXPECT_TRUE(result.report.target_reached);
  EXPECT_LE(result.map.domain().element_count(), 200);
  const VerificationReport report = verify(result.map, parametrization_checks());
  EXPECT_TRUE(report.ok()) << summary(report);
}

}  // namespace
}  // namespace plmap
