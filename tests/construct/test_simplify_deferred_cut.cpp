// simplify()'s deferred cut (SimplifyOptions::cut = "deferred"): the steps only relocate the S2
// vertex preimages and every S2 edge is traced once through the final S1. Whatever the trace
// finds, the result must be a valid parametrization: a traced graph that passed its check, or
// the per-step run it fell back to. The properties below run the generators of the
// simplification's other properties (closed, with boundary or non-manifold, long feature lines,
// curves) and assert every verify check, one preimage per S2 vertex and the tiling of S2 by the
// region images; the fixed tests show that the trace itself is taken (not always the fallback).

#include "simplify_test_support.hpp"

#include <plmap/construct/simplify.hpp>
#include <plmap/construct/simplify_curve.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace plmap {
namespace {

/// Every check a simplification result must pass, with `cut` deferred.
void check_valid(const std::shared_ptr<const Surface<2>>& s2, const SimplifyOptions& options, const SimplifyResult& result) {
  RC_ASSERT(result.report.cut == std::string("deferred"));
  RC_LOG() << (result.report.cut_fell_back ? "fell back: " + result.report.cut_failure : std::string("traced")) << "\n";
  VerifyOptions v;
  v.expect_parametrization = true;
  const VerificationReport report = verify(result.map, v);
  RC_LOG() << summary(report) << "\n";
  RC_ASSERT(report.ok());
  RC_ASSERT(simplify_test::vertices_without_one_preimage(result.map).empty());
  const double area = s2->measure();
  RC_ASSERT(std::abs(simplify_test::image_area(result.map) - area) <= 1e-8 * area);
  RC_ASSERT(simplify_test::lost_features(result.map, options.feature_angle_degrees).empty());
  RC_ASSERT(result.report.target_reached == (options.target_elements > 0
                                                 ? result.report.elements_after <= options.target_elements
                                                 : result.report.vertices_after <= options.target_vertices));
  RC_CLASSIFY(result.report.removed_vertices > 0 && !result.report.cut_fell_back, "traced");
  RC_CLASSIFY(result.report.cut_fell_back, "fell back to the per-step cut");
}

void check_deferred(const std::shared_ptr<const Surface<2>>& s2, const std::string& description) {
  RC_LOG() << description << "\n";
  SimplifyOptions options;
  const double fraction = *rc::gen::inRange(5, 95) / 100.0;
  options.target_elements = std::max<Index>(1, static_cast<Index>(fraction * s2->element_count()));
  RC_PRE(options.target_elements < s2->element_count());
  options.feature_angle_degrees = *rc::gen::element(30.0, 60.0, 180.0);
  options.hole_triangulation = *rc::gen::element(std::string("constrained-delaunay"), std::string("min-max-aspect"));
  options.flattening = *rc::gen::element(std::string("polar-map"), std::string("plane-projection"));
  options.oracles.add(*rc::gen::element(std::string("hausdorff"), std::string("aspect-ratio"), std::string("long-edge"),
                                        std::string("normal-deviation")),
                      1.0)
      .add("self-intersection");
  options.ranking = *rc::gen::element(std::string("exact"), std::string("estimate"));
  options.cut = "deferred";
  check_valid(s2, options, simplify(s2, options));
}

RC_GTEST_PROP(SimplifyDeferredCut, ClosedSurfacesStayValidParametrizations, ()) {
  const int subdivisions = *rc::gen::weightedElement<int>({{1, 0}, {3, 1}, {1, 2}});
  const int jitter_percent = *rc::gen::inRange(0, 20);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  generators::Rng rng(seed);
  auto s = std::make_shared<const Surface<2>>(generators::icosphere({subdivisions, jitter_percent / 100.0}, rng));
  check_deferred(s, "icosphere " + std::to_string(subdivisions) + " jitter " + std::to_string(jitter_percent) + "% seed " +
                        std::to_string(seed));
}

RC_GTEST_PROP(SimplifyDeferredCut, SurfacesWithBoundaryOrNonManifoldStayValidParametrizations, ()) {
  const generators::TriangleSurfaceRecipe r = *generators::triangle_surface_recipes();
  check_deferred(std::make_shared<const Surface<2>>(generators::make_triangle_surface(r)), generators::describe(r));
}

RC_GTEST_PROP(SimplifyDeferredCut, SheetsWithBoundaryAndFinsKeepTheirFeatures, ()) {
  const int cells = *rc::gen::inRange(2, 7);
  const int fins = *rc::gen::inRange(0, 4);
  const bool lifted = *rc::gen::arbitrary<bool>();
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  RC_LOG() << cells << " cells, " << fins << " fins, lifted " << lifted << ", seed " << seed << "\n";
  generators::Rng rng(seed);
  Surface<2> sheet = generators::grid_triangulation({.cells = cells, .jitter = 0.2, .with_hole = false}, rng);
  if (lifted) sheet = generators::lift_to_height_field(sheet, generators::random_height_field(rng));
  if (fins > 0) sheet = generators::add_fins(sheet, fins, rng);
  auto s2 = std::make_shared<const Surface<2>>(std::move(sheet));
  SimplifyOptions options;
  options.target_vertices = *rc::gen::inRange<Index>(1, s2->vertex_count());
  options.feature_angle_degrees = *rc::gen::element(30.0, 60.0, 180.0);
  options.oracles.add(*rc::gen::element(std::string("hausdorff"), std::string("long-edge"), std::string("normal-deviation")), 1.0);
  options.ranking = *rc::gen::element(std::string("exact"), std::string("estimate"));
  options.cut = "deferred";
  check_valid(s2, options, simplify(s2, options));
}

// Curves (d = 1) have no S2 edges to cut (a segment's preimage is a chain of S1 vertices): the
// option is accepted and the map is as valid as ever.
RC_GTEST_PROP(SimplifyDeferredCut, CurvesIgnoreTheCut, ()) {
  const std::shared_ptr<const Surface<1>> s2 = *generators::curves();
  SimplifyOptions options;
  options.target_vertices = *rc::gen::inRange<Index>(1, std::max<Index>(2, s2->vertex_count()));
  RC_PRE(options.target_vertices < s2->vertex_count());
  options.oracles.add("hausdorff", 1.0);
  options.cut = "deferred";
  const CurveSimplifyResult result = simplify_curve(s2, options);
  VerifyOptions v;
  v.expect_parametrization = true;
  RC_ASSERT(verify(result.map, v).ok());
  RC_ASSERT(result.report.vertices_after <= s2->vertex_count());
}

std::shared_ptr<const Surface<2>> bumpy_sphere(int subdivisions, std::uint64_t seed) {
  generators::Rng rng(seed);
  return std::make_shared<const Surface<2>>(generators::icosphere({subdivisions, 0.1}, rng));
}

SimplifyOptions sphere_options(const std::string& cut) {
  SimplifyOptions options;
  options.target_elements = 160;
  options.feature_angle_degrees = 180.0;
  options.oracles.add("hausdorff", 1.0).add("aspect-ratio", 1.0);
  options.ranking = "estimate";
  options.cut = cut;
  return options;
}

// The trace path itself: on bumpy spheres every straight trace is valid, so the result is the
// traced map (not the per-step run's), valid, of a quality close to the per-step cut's.
TEST(SimplifyDeferredCut, TracesBumpySpheresWithoutFallingBack) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const auto fine = bumpy_sphere(3, seed);
    const SimplifyResult deferred = simplify(fine, sphere_options("deferred"));
    const SimplifyResult per_step = simplify(fine, sphere_options("per-step"));
    EXPECT_EQ(deferred.report.cut, "deferred");
    EXPECT_FALSE(deferred.report.cut_fell_back) << deferred.report.cut_failure;
    EXPECT_TRUE(deferred.report.target_reached);
    VerifyOptions v;
    v.expect_parametrization = true;
    const VerificationReport report = verify(deferred.map, v);
    EXPECT_TRUE(report.ok()) << summary(report);
    EXPECT_TRUE(simplify_test::vertices_without_one_preimage(deferred.map).empty());
    EXPECT_NEAR(simplify_test::image_area(deferred.map), fine->measure(), 1e-8 * fine->measure());
    EXPECT_LE(deferred.report.hausdorff_error, 2.0 * per_step.report.hausdorff_error) << "seed " << seed;
  }
}

// The fallback itself: strongly jittered spheres simplified far down by the long-edge oracle
// (which lets the preimages drift far), where the traces of 6 of these 24 seeds cross or come
// within the clearance. Each run that fell back says why and is the per-step run's valid map
// (the same plans and error); the others are traced and valid too.
TEST(SimplifyDeferredCut, RunsThatFallBackAreTheValidPerStepRuns) {
  int fell_back_on_the_trace = 0, traced = 0;
  for (std::uint64_t seed = 1; seed <= 24; ++seed) {
    generators::Rng rng(seed);
    auto fine = std::make_shared<const Surface<2>>(generators::icosphere({3, 0.3}, rng));
    SimplifyOptions options = sphere_options("deferred");
    options.target_elements = 40;
    options.oracles = WeightedOracles{};
    options.oracles.add("long-edge", 1.0);
    const SimplifyResult deferred = simplify(fine, options);
    VerifyOptions v;
    v.expect_parametrization = true;
    const VerificationReport report = verify(deferred.map, v);
    EXPECT_TRUE(report.ok()) << "seed " << seed << ": " << summary(report);
    EXPECT_TRUE(simplify_test::vertices_without_one_preimage(deferred.map).empty()) << "seed " << seed;
    EXPECT_NEAR(simplify_test::image_area(deferred.map), fine->measure(), 1e-8 * fine->measure()) << "seed " << seed;
    if (!deferred.report.cut_fell_back) {
      ++traced;
      continue;
    }
    EXPECT_EQ(deferred.report.cut_failure.rfind("deferred cut: ", 0), 0u) << deferred.report.cut_failure;
    if (deferred.report.cut_failure.find("above its target") == std::string::npos) ++fell_back_on_the_trace;
    // The result is the per-step run's.
    SimplifyOptions again = options;
    again.cut = "per-step";
    const SimplifyResult reference = simplify(fine, again);
    EXPECT_EQ(deferred.report.full_plans, reference.report.full_plans) << "seed " << seed;
    EXPECT_EQ(deferred.report.hausdorff_error, reference.report.hausdorff_error) << "seed " << seed;
  }
  EXPECT_GT(fell_back_on_the_trace, 0);
  EXPECT_GT(traced, 0);
}

TEST(SimplifyDeferredCut, AnUnknownCutIsAnErrorNamingIt) {
  SimplifyOptions options = sphere_options("sometimes");
  try {
    (void)simplify(bumpy_sphere(3, 2), options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sometimes"), std::string::npos);
  }
}

}  // namespace
}  // namespace plmap
