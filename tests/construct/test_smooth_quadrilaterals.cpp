// Smoothing over edge quadrilaterals (paper 3.3.2): the PreimageGraph round trip, one step
// never moves a node off its quadrilateral nor anything outside it, whole sweeps keep the map a
// valid parametrization (zero fold-overs stay zero) on random simplified spheres, and κ_Ξ falls
// on a simplified sphere for every weights model (paper Fig. 10).

#include "preimage_graph.hpp"
#include "quad_smoothing.hpp"
#include "simplified_spheres.hpp"
#include "simplify_test_support.hpp"

#include <plmap/construct/simplify.hpp>
#include <plmap/construct/smooth.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>
#include <plmap/verify/generators/random_maps.hpp>
#include <plmap/verify/generators/rc_generators.hpp>
#include <plmap/verify/quality.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <iostream>
#include <random>

namespace plmap {
namespace {

using smoothing::DomainPlace;
using smoothing::PreimageGraph;
using smoothing::QuadSmoother;

const std::vector<std::string> weight_models = {"floater", "mean-value", "uniform"};

using simplify_test::simplified_sphere;

bool verified_parametrization(const PlMap<2>& map) {
  VerifyOptions v;
  v.expect_parametrization = true;
  const VerificationReport report = verify(map, v);
  return report.ok();
}

bool same_place(const DomainPlace& a, const DomainPlace& b) {
  return a.kind == b.kind && a.where == b.where && a.edge_parameter == b.edge_parameter && a.local == b.local;
}

TEST(QuadSmoothing, PreimageGraphRoundTripRebuildsAValidMap) {
  const SimplifyResult s = simplified_sphere(2, 0.1, 7, 20);
  std::string why;
  const auto graph = PreimageGraph::from_map(s.map, &why);
  ASSERT_TRUE(graph) << why;
  FinalizeReport built;
  const PlMap<2> again = graph->to_map(s.map.domain_ptr(), s.map.target_ptr(), &built);
  EXPECT_EQ(built.reversed_faces, 0);
  EXPECT_TRUE(built.dropped_edges.empty());
  EXPECT_TRUE(verified_parametrization(again));
  EXPECT_EQ(again.region_count(), s.map.region_count());
  // and the graph of the rebuilt map is the same graph
  const auto twice = PreimageGraph::from_map(again, &why);
  ASSERT_TRUE(twice);
  for (std::size_t v = 0; v < graph->vertex.size(); ++v) EXPECT_TRUE(same_place(graph->vertex[v], twice->vertex[v])) << v;
  for (std::size_t e = 0; e < graph->crossings.size(); ++e) {
    ASSERT_EQ(graph->crossings[e].size(), twice->crossings[e].size()) << e;
    for (std::size_t i = 0; i < graph->crossings[e].size(); ++i) {
      EXPECT_EQ(graph->crossings[e][i].domain_edge, twice->crossings[e][i].domain_edge);
      EXPECT_NEAR(graph->crossings[e][i].domain_parameter, twice->crossings[e][i].domain_parameter, 1e-12);
    }
  }
}

// One step on a random interior edge of a random simplified sphere: nothing outside the
// quadrilateral changes, the preimages inside stay inside it, and the rebuilt map is valid.
RC_GTEST_PROP(QuadSmoothingProperties, OneStepStaysInItsQuadrilateral, ()) {
  const int subdivisions = *rc::gen::inRange(1, 3);
  const int jitter_percent = *rc::gen::inRange(0, 25);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const int percent = *rc::gen::inRange(10, 60);
  RC_LOG() << "icosphere " << subdivisions << " jitter " << jitter_percent << "% seed " << seed << " to " << percent << "%\n";
  const SimplifyResult s = simplified_sphere(subdivisions, jitter_percent / 100.0, seed, percent);
  std::string why;
  auto graph = PreimageGraph::from_map(s.map, &why);
  RC_ASSERT(graph.has_value());
  const PreimageGraph before = *graph;
  const Surface<2>& s1 = s.map.domain();
  QuadSmoother smoother(*graph, s1, s.map.target(), make_smoothing_weights(*rc::gen::elementOf(weight_models)));
  const Index e = *rc::gen::inRange<Index>(0, s1.edge_count());
  RC_PRE(smoother.has_quadrilateral(e));
  const auto outcome = smoother.smooth(e);
  RC_CLASSIFY(outcome.skipped == nullptr, "kept");
  RC_CLASSIFY(outcome.nodes_crossed > 0, "a node crossed the shared edge");
  const auto inc = s1.edge_elements(e);
  const auto in_quad = [&](const DomainPlace& p) {
    return (p.kind == DomainPlace::Kind::element && (p.where == inc[0].element || p.where == inc[1].element)) ||
           (p.kind == DomainPlace::Kind::edge && p.where == e);
  };
  for (std::size_t v = 0; v < before.vertex.size(); ++v) {
    if (in_quad(before.vertex[v])) {
      RC_ASSERT(in_quad(graph->vertex[v]));
    } else {
      RC_ASSERT(same_place(before.vertex[v], graph->vertex[v]));
    }
  }
  // crossings of S1 edges other than e are untouched
  for (std::size_t te = 0; te < before.crossings.size(); ++te) {
    std::vector<std::pair<Index, double>> a, b;
    for (const auto& c : before.crossings[te])
      if (c.domain_edge != e) a.push_back({c.domain_edge, c.domain_parameter});
    for (const auto& c : graph->crossings[te])
      if (c.domain_edge != e) b.push_back({c.domain_edge, c.domain_parameter});
    RC_ASSERT(a == b);
  }
  if (outcome.skipped != nullptr) {
    for (std::size_t v = 0; v < before.vertex.size(); ++v) RC_ASSERT(same_place(before.vertex[v], graph->vertex[v]));
    return;
  }
  FinalizeReport built;
  const PlMap<2> after = graph->to_map(s.map.domain_ptr(), s.map.target_ptr(), &built);
  RC_ASSERT(built.reversed_faces == 0);
  RC_ASSERT(verified_parametrization(after));
  RC_ASSERT(simplify_test::vertices_without_one_preimage(after).empty());
}

// After steps on random edges, the smoother's index (per S1 triangle, the S2 edges with a segment
// in it), which a kept step updates from its pieces, is the index of the edited graph computed from
// scratch. Fails if a step's update misses a triangle a piece now lies in, or keeps a stale edge.
RC_GTEST_PROP(QuadSmoothingProperties, StepsKeepTheEdgeIndexOfTheGraph, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const SimplifyResult s = simplified_sphere(*rc::gen::inRange(1, 3), *rc::gen::inRange(0, 25) / 100.0, seed,
                                             *rc::gen::inRange(10, 60));
  std::string why;
  auto graph = PreimageGraph::from_map(s.map, &why);
  RC_ASSERT(graph.has_value());
  const Surface<2>& s1 = s.map.domain();
  QuadSmoother smoother(*graph, s1, s.map.target(), make_smoothing_weights(*rc::gen::elementOf(weight_models)));
  const int steps = *rc::gen::inRange(1, 40);
  Index kept = 0;
  for (int i = 0; i < steps; ++i) {
    const Index e = *rc::gen::inRange<Index>(0, s1.edge_count());
    if (smoother.has_quadrilateral(e) && smoother.smooth(e).skipped == nullptr) ++kept;
  }
  RC_CLASSIFY(kept > 0, "a step was kept");
  PreimageGraph copy = *graph;
  const QuadSmoother fresh(copy, s1, s.map.target(), make_smoothing_weights("uniform"));
  for (Index t = 0; t < s1.element_count(); ++t) {
    std::vector<Index> kept_list = smoother.edges_in_element()[t], fresh_list = fresh.edges_in_element()[t];
    std::sort(kept_list.begin(), kept_list.end());
    std::sort(fresh_list.begin(), fresh_list.end());
    RC_ASSERT(kept_list == fresh_list);
  }
}

// The checks of a step, exercised: weights that break the convex-combination rule (some negative,
// drawn at random) put preimages outside the quadrilateral, turn segments over and make them
// cross. Whatever the step does, nothing may leave the quadrilateral and the rebuilt map must be
// a valid parametrization: the step must refuse what the geometric checks find.
RC_GTEST_PROP(QuadSmoothingProperties, StepsWithBrokenWeightsAreRefusedNotApplied, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const SimplifyResult s = simplified_sphere(*rc::gen::inRange(1, 3), *rc::gen::inRange(0, 25) / 100.0, seed,
                                             *rc::gen::inRange(10, 60));
  auto graph = PreimageGraph::from_map(s.map, nullptr);
  RC_ASSERT(graph.has_value());
  const double spread = *rc::gen::element(0.5, 2.0, 10.0);
  auto rng = std::make_shared<generators::Rng>(seed ^ 0x5eedu);
  const AnySmoothingWeights broken = [rng, spread](const Eigen::Vector3d&, std::span<const Eigen::Vector3d> ring) {
    std::uniform_real_distribution<double> draw(-spread, 1.0);
    std::vector<double> w(ring.size());
    double sum = 0.0;
    for (double& x : w) sum += (x = draw(*rng));
    if (!(std::abs(sum) > 1e-3)) return std::optional<std::vector<double>>{};
    for (double& x : w) x /= sum;
    return std::optional<std::vector<double>>(std::move(w));
  };
  const Surface<2>& s1 = s.map.domain();
  QuadSmoother smoother(*graph, s1, s.map.target(), broken);
  Index kept = 0;
  for (Index e = 0; e < s1.edge_count(); ++e) {
    if (!smoother.has_quadrilateral(e)) continue;
    const std::vector<DomainPlace> places = graph->vertex;
    const auto outcome = smoother.smooth(e);
    kept += outcome.skipped == nullptr ? 1 : 0;
    const auto inc = s1.edge_elements(e);
    const auto in_quad = [&](const DomainPlace& p) {
      return (p.kind == DomainPlace::Kind::element && (p.where == inc[0].element || p.where == inc[1].element)) ||
             (p.kind == DomainPlace::Kind::edge && p.where == e);
    };
    for (std::size_t v = 0; v < places.size(); ++v) {
      if (!same_place(places[v], graph->vertex[v])) {
        RC_ASSERT(in_quad(places[v]));
        RC_ASSERT(in_quad(graph->vertex[v]));
      }
    }
  }
  RC_CLASSIFY(kept > 0, "some steps kept");
  FinalizeReport built;
  const PlMap<2> after = graph->to_map(s.map.domain_ptr(), s.map.target_ptr(), &built);
  RC_ASSERT(built.reversed_faces == 0);
  RC_ASSERT(verified_parametrization(after));
  RC_ASSERT(simplify_test::vertices_without_one_preimage(after).empty());
}

// Whole sweeps, every weights model: still a valid parametrization (no fold-over: zero stays
// zero), each S2 vertex with one preimage, the region images tile S2, the rebuilt map accepted.
RC_GTEST_PROP(QuadSmoothingProperties, RefinementMapsStayValid, ()) {
  const auto c = *generators::refinement_maps<2>();
  RC_LOG() << c.description << "\n";
  SmoothOptions options;
  options.weights = *rc::gen::elementOf(weight_models);
  options.sweeps = *rc::gen::inRange(1, 3);
  const SmoothResult r = smooth(*c.map, options);
  for (const auto& sweep : r.report.sweeps) RC_ASSERT(!sweep.quadrilateral_pass_rejected);
  RC_ASSERT(verify(r.map).ok());
  RC_CLASSIFY(r.report.quadrilaterals_not_applicable.empty(), "quadrilaterals applicable");
  RC_CLASSIFY(r.report.sweeps.front().nodes_crossed > 0, "nodes crossed edges");
}

RC_GTEST_PROP(QuadSmoothingProperties, SweepsKeepSimplifiedSpheresValid, ()) {
  const int subdivisions = *rc::gen::inRange(1, 3);
  const int jitter_percent = *rc::gen::inRange(0, 25);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const int percent = *rc::gen::inRange(10, 60);
  RC_LOG() << "icosphere " << subdivisions << " jitter " << jitter_percent << "% seed " << seed << " to " << percent << "%\n";
  const SimplifyResult s = simplified_sphere(subdivisions, jitter_percent / 100.0, seed, percent);
  SmoothOptions options;
  options.weights = *rc::gen::elementOf(weight_models);
  options.sweeps = *rc::gen::inRange(1, 4);
  const SmoothResult r = smooth(s.map, options);
  RC_ASSERT(r.report.quadrilaterals_not_applicable.empty());
  for (const auto& sweep : r.report.sweeps) RC_ASSERT(!sweep.quadrilateral_pass_rejected);
  RC_ASSERT(verified_parametrization(r.map));
  RC_ASSERT(simplify_test::vertices_without_one_preimage(r.map).empty());
  const double area = r.map.target().measure();
  RC_ASSERT(std::abs(simplify_test::image_area(r.map) - area) <= 1e-9 * area);
  RC_CLASSIFY(r.report.sweeps.front().nodes_crossed > 0, "nodes crossed edges");
}

// Paper Fig. 10: a sphere simplified hard (5,120 -> 152 triangles; κ max 19, mean 1.66) gets a
// better map. Floater's and mean-value weights lower κ max and mean (to 4.27 and 4.87); uniform
// weights (Tutte) ignore the geometry: unguarded they raised κ max to about 170, now the κ
// guards keep it below the start (13.7) but refuse the steps that would cross edges, so for
// them only validity and the guard are asserted (numbers in docs/algorithms/smoothing.md).
// Simplified surfaces with boundary or non-manifold edges (feature lines kept by simplify):
// quadrilaterals next to the boundary or a non-manifold edge must be refused or handled, never
// break the map.
RC_GTEST_PROP(QuadSmoothingProperties, SweepsKeepSimplifiedOpenAndNonManifoldSurfacesValid, ()) {
  const generators::TriangleSurfaceRecipe recipe = *generators::triangle_surface_recipes();
  RC_LOG() << generators::describe(recipe) << "\n";
  auto fine = std::make_shared<const Surface<2>>(generators::make_triangle_surface(recipe));
  SimplifyOptions so;
  so.target_elements = std::max<Index>(1, fine->element_count() * *rc::gen::inRange(10, 90) / 100);
  so.feature_angle_degrees = *rc::gen::element(60.0, 180.0);
  const SimplifyResult s = simplify(fine, so);
  SmoothOptions options;
  options.weights = *rc::gen::elementOf(weight_models);
  options.sweeps = *rc::gen::inRange(1, 3);
  const SmoothResult r = smooth(s.map, options);
  for (const auto& sweep : r.report.sweeps) RC_ASSERT(!sweep.quadrilateral_pass_rejected);
  RC_ASSERT(verified_parametrization(r.map));
  RC_ASSERT(simplify_test::vertices_without_one_preimage(r.map).empty());
  const double area = fine->measure();
  RC_ASSERT(std::abs(simplify_test::image_area(r.map) - area) <= 1e-8 * area);
  RC_CLASSIFY(r.report.sweeps.front().nodes_crossed > 0, "nodes crossed edges");
}

TEST(QuadSmoothing, KappaFallsOnAHardSimplifiedSphere) {
  const SimplifyResult s = simplified_sphere(4, 0.1, 20261202, 3);
  const QualityReport before = compute_quality(s.map);
  ASSERT_GT(before.kappa_max, 10.0);
  for (const std::string& weights : weight_models) {
    SCOPED_TRACE(weights);
    SmoothOptions options;
    options.weights = weights;
    options.sweeps = 5;
    const SmoothResult r = smooth(s.map, options);
    ASSERT_TRUE(verified_parametrization(r.map));
    const QualityReport after = compute_quality(r.map);
    Index crossed = 0;
    for (const auto& sweep : r.report.sweeps) crossed += sweep.nodes_crossed;
    std::cout << weights << ": kappa max " << before.kappa_max << " -> " << after.kappa_max << ", mean "
              << before.kappa_mean << " -> " << after.kappa_mean << ", crossed " << crossed << "\n";
    EXPECT_LE(after.kappa_max, before.kappa_max);  // the κ guards, for every model
    if (weights != "uniform") {
      EXPECT_GT(crossed, 0);
      EXPECT_LT(after.kappa_max, 0.8 * before.kappa_max);
      EXPECT_LT(after.kappa_mean, before.kappa_mean);
    }
  }
}

// The quadrilaterals do what the element pass cannot: with mean-value weights, on the nearly
// isometric sphere where the element pass barely moves κ (2.24 -> 2.17), κ max drops below 2.
TEST(QuadSmoothing, QuadrilateralsBeatTheElementPass) {
  const SimplifyResult s = simplified_sphere(3, 0.1, 20261202, 12);
  SmoothOptions options;
  options.weights = "mean-value";
  options.sweeps = 5;
  options.quadrilaterals = false;
  const double elements_only = compute_quality(smooth(s.map, options).map).kappa_max;
  options.quadrilaterals = true;
  const double with_quads = compute_quality(smooth(s.map, options).map).kappa_max;
  EXPECT_LT(with_quads, elements_only);
  EXPECT_LT(with_quads, 2.0);
}

}  // namespace
}  // namespace plmap
