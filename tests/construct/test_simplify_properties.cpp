// Properties of simplify() on random meshes (closed, with boundary, non-manifold), stopped after
// a random number of steps: the map passes every verify check as a parametrization, every S2
// vertex has exactly one preimage, the region images tile S2 by measure, features are kept.
// The same properties for both rankings (SimplifyOptions::ranking): the estimate ranking takes
// other removal orders and other paths through the planner (ranking plans made when a vertex
// comes up, kept holes, plans kept for a vertex queued again).

#include "simplify_test_support.hpp"

#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace plmap {
namespace {

struct Case {
  std::shared_ptr<const Surface<2>> surface;
  std::string description;
};

rc::Gen<Case> closed_surfaces() {
  return rc::gen::map(rc::gen::tuple(rc::gen::weightedElement<int>({{1, 0}, {3, 1}}), rc::gen::inRange(0, 20), rc::gen::arbitrary<std::uint32_t>()),
                      [](const std::tuple<int, int, std::uint32_t>& t) {
                        const auto [subdivisions, jitter_percent, seed] = t;
                        generators::Rng rng(seed);
                        auto s = std::make_shared<const Surface<2>>(
                            generators::icosphere({subdivisions, jitter_percent / 100.0}, rng));
                        return Case{s, "icosphere " + std::to_string(subdivisions) + " jitter " +
                                           std::to_string(jitter_percent) + "% seed " + std::to_string(seed)};
                      });
}

rc::Gen<Case> open_surfaces() {
  return rc::gen::map(generators::triangle_surface_recipes(), [](const generators::TriangleSurfaceRecipe& r) {
    return Case{std::make_shared<const Surface<2>>(generators::make_triangle_surface(r)), generators::describe(r)};
  });
}

void check_simplification(const Case& c, const std::string& ranking) {
  RC_LOG() << c.description << " ranking " << ranking << "\n";
  const Surface<2>& s2 = *c.surface;
  SimplifyOptions options;
  const double fraction = *rc::gen::inRange(5, 95) / 100.0;
  options.target_elements = std::max<Index>(1, static_cast<Index>(fraction * s2.element_count()));
  RC_PRE(options.target_elements < s2.element_count());
  options.feature_angle_degrees = *rc::gen::element(30.0, 60.0, 180.0);
  options.hole_triangulation = *rc::gen::element(std::string("constrained-delaunay"), std::string("min-max-aspect"));
  options.flattening = *rc::gen::element(std::string("polar-map"), std::string("plane-projection"));
  const std::string oracle = *rc::gen::element(std::string("hausdorff"), std::string("aspect-ratio"),
                                               std::string("long-edge"), std::string("normal-deviation"));
  options.oracles.add(oracle, 1.0).add("self-intersection");
  options.ranking = ranking;
  const SimplifyResult result = simplify(c.surface, options);
  RC_ASSERT(result.report.ranking == ranking);

  VerifyOptions v;
  v.expect_parametrization = true;
  const VerificationReport report = verify(result.map, v);
  RC_LOG() << summary(report) << "\n";
  RC_ASSERT_FALSE(!report.ok());
  RC_ASSERT(simplify_test::vertices_without_one_preimage(result.map).empty());
  const double area = s2.measure();
  RC_ASSERT(std::abs(simplify_test::image_area(result.map) - area) <= 1e-8 * area);
  RC_ASSERT(simplify_test::lost_features(result.map, options.feature_angle_degrees).empty());
  RC_CLASSIFY(result.report.removed_vertices == 0, "nothing removed");
  RC_CLASSIFY(result.report.removed_vertices > 0, "vertices removed");
  RC_CLASSIFY(result.report.removed_along_lines > 0, "vertices removed along feature lines");
  RC_ASSERT(result.map.domain().element_count() == result.report.elements_after);
  RC_ASSERT(result.report.elements_after <= s2.element_count());
  RC_ASSERT(result.report.target_reached == (result.report.elements_after <= options.target_elements));
}

RC_GTEST_PROP(SimplifyProperties, ClosedSurfacesStayValidParametrizations, ()) {
  check_simplification(*closed_surfaces(), "exact");
}

RC_GTEST_PROP(SimplifyProperties, SurfacesWithBoundaryOrNonManifoldStayValidParametrizations, ()) {
  check_simplification(*open_surfaces(), "exact");
}

RC_GTEST_PROP(SimplifyProperties, ClosedSurfacesStayValidParametrizationsWithTheEstimateRanking, ()) {
  check_simplification(*closed_surfaces(), "estimate");
}

RC_GTEST_PROP(SimplifyProperties, SurfacesWithBoundaryOrNonManifoldStayValidParametrizationsWithTheEstimateRanking, ()) {
  check_simplification(*open_surfaces(), "estimate");
}

}  // namespace
}  // namespace plmap
