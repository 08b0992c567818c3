// Counterexamples that the projection properties found once their seed changed per CI run
// (issue 14), kept as deterministic regression tests: each input is the shrunk RapidCheck case,
// rebuilt from its generator recipe, with the property's assertion.
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>


using namespace plmap;
using namespace plmap::test;
namespace gen = plmap::generators;

// AnyCurveOntoItselfIsTheIdentity, seed 7: an open polyline of 33 segments projected onto
// itself; segment 8 was reported as endpoint_without_preimage and segment 10 as overlap.
TEST(ProjectSeededRegressions, OpenCurveOntoItselfIsTheIdentity) {
  const gen::CurveRecipe recipe{.shape = gen::CurveShape::open, .segments = 33, .seed = 14826768686467693935ULL};
  auto s = std::make_shared<const Surface<1>>(gen::make_curve(recipe));
  const auto r = project<1>(s, s);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe_failures(r.report);
  EXPECT_EQ(r.map.region_count(), s->element_count());
  EXPECT_EQ(r.measures.covered_domain, r.measures.domain);
}
