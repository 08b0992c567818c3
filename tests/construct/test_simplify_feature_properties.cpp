// Properties of simplify() on random meshes whose feature lines are long (boundaries of jittered
// squares, with non-manifold fins standing on them, lifted onto height fields; icospheres with a
// low feature angle), stopped after a random number of removal steps: the map passes every
// verify check as a parametrization, every S2 vertex has exactly one preimage, the region images
// tile S2 by measure, every feature edge of S2 lies along an S1 edge and every corner survives.

#include "simplify_test_support.hpp"

#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace plmap {
namespace {

void check_steps(std::shared_ptr<const Surface<2>> s2, double feature_angle) {
  SimplifyOptions options;
  // Any number of removal steps: a vertex target anywhere between 1 and all but one vertex.
  options.target_vertices = *rc::gen::inRange<Index>(1, s2->vertex_count());
  options.feature_angle_degrees = feature_angle;
  options.hole_triangulation = *rc::gen::element(std::string("constrained-delaunay"), std::string("min-max-aspect"));
  options.oracles.add(*rc::gen::element(std::string("hausdorff"), std::string("long-edge"), std::string("normal-deviation")), 1.0);
  const SimplifyResult result = simplify(s2, options);

  RC_ASSERT(simplify_test::parametrization_problems(result, feature_angle, 1e-8).empty());
  RC_ASSERT(result.report.removed_along_lines <= result.report.removed_vertices);
  RC_CLASSIFY(result.report.removed_along_lines > 0, "removed along feature lines");
  RC_CLASSIFY(result.report.target_reached, "target reached");
}

RC_GTEST_PROP(SimplifyFeatureProperties, SheetsWithBoundaryAndFinsKeepTheirFeatures, ()) {
  const int cells = *rc::gen::inRange(2, 7);
  const int fins = *rc::gen::inRange(0, 4);
  const bool lifted = *rc::gen::arbitrary<bool>();
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  RC_LOG() << cells << " cells, " << fins << " fins, lifted " << lifted << ", seed " << seed << "\n";
  generators::Rng rng(seed);
  Surface<2> sheet = generators::grid_triangulation({.cells = cells, .jitter = 0.2, .with_hole = false}, rng);
  if (lifted) sheet = generators::lift_to_height_field(sheet, generators::random_height_field(rng));
  if (fins > 0) sheet = generators::add_fins(sheet, fins, rng);
  check_steps(std::make_shared<const Surface<2>>(std::move(sheet)), *rc::gen::element(30.0, 60.0, 180.0));
}

RC_GTEST_PROP(SimplifyFeatureProperties, ClosedSurfacesWithSharpLinesKeepThem, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const int jitter_percent = *rc::gen::inRange(5, 30);
  RC_LOG() << "icosphere jitter " << jitter_percent << "% seed " << seed << "\n";
  generators::Rng rng(seed);
  auto sphere = std::make_shared<const Surface<2>>(generators::icosphere({1, jitter_percent / 100.0}, rng));
  check_steps(sphere, *rc::gen::element(15.0, 25.0, 40.0));
}

}  // namespace
}  // namespace plmap
