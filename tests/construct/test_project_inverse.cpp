// Inverse evaluation on maps made by normal projection (issue 15): Xi^{-1}(Xi(x)) = x and
// Xi(Xi^{-1}(y)) = y to rounding, and points of S2 outside Xi(D) reported as such. Random planar
// pairs as in test_project_properties.cpp: S1 a triangulation of the unit square (maybe with a
// hole) at z = 0, S2 another one scaled, shifted and lifted, facing S1 or not (orientation
// reversing or preserving). With vertical normals Xi is the vertical translation, so a point of
// S2 has a preimage iff it lies above S1, and the preimage is right below it. d = 1: concentric
// circles (round trips only).
#include <plmap/verify/deepest_region_locator.hpp>
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

using namespace plmap;
using namespace plmap::test;
namespace gen = plmap::generators;

namespace {

gen::PlanarRecipe small_planar_recipe(bool hole_allowed) {
  gen::PlanarRecipe r;
  r.base = *rc::gen::element(gen::PlanarBase::grid, gen::PlanarBase::delaunay);
  r.with_hole = hole_allowed && *rc::gen::inRange(0, 3) == 0;
  r.resolution = r.base == gen::PlanarBase::grid ? *rc::gen::inRange(1, 7) : *rc::gen::inRange(0, 16);
  r.jitter = *rc::gen::arbitrary<bool>();
  r.seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  return r;
}

/// The round trips on any map, at random points of both surfaces and at the map's nodes.
template <int d>
void check_round_trips(const PlMap<d>& map, const InverseIndex<d>& index, gen::Rng& rng, const std::string& what) {
  const double tolerance = 1e-9 * std::max(map.domain().max_edge_length(), map.target().max_edge_length());
  DeepestRegion<d> locator;
  std::vector<SurfacePoint<d>> xs;
  for (int k = 0; k < 40; ++k) xs.push_back({gen::uniform_index(rng, map.domain().element_count()), generators::uniform_local_point<d>(rng)});
  for (Index n = 0; n < map.node_count(); n += 3) xs.push_back({map.node_element(n), map.data().node_position[n]});
  for (const auto& x : xs) {
    const Evaluation<d> e = evaluate(map, x, locator);
    if (!e.in_domain) continue;
    const InverseEvaluation<d> inv = inverse_evaluate(index, e.image);
    if (!inv.in_image) RC_FAIL(what + fmt::format(": the image of a point of S1 element {} has no preimage", x.element));
    RC_ASSERT((inv.world - map.domain().world_position(x.element, x.local)).norm() <= tolerance);
  }
  for (int k = 0; k < 40; ++k) {
    const SurfacePoint<d> y{gen::uniform_index(rng, map.target().element_count()), generators::uniform_local_point<d>(rng)};
    const InverseEvaluation<d> inv = inverse_evaluate(index, y);
    if (!inv.in_image) continue;
    const Evaluation<d> back = evaluate_in_region(map, inv.region, inv.preimage.local);
    RC_ASSERT((back.world - map.target().world_position(y.element, y.local)).norm() <= tolerance);
  }
}

}  // namespace

RC_GTEST_PROP(ProjectInverse, PlanarPairsRoundTripAndReportPointsOutsideTheImage, (std::uint64_t sample_seed)) {
  const auto r1 = small_planar_recipe(true), r2 = small_planar_recipe(false);
  const double s = *rc::gen::inRange(50, 201) / 100.0;
  const double dx = *rc::gen::inRange(-8, 9) / 8.0, dy = *rc::gen::inRange(-900, 901) / 1000.0;
  const double h = *rc::gen::inRange(1, 500) / 1000.0;
  const bool facing = *rc::gen::arbitrary<bool>();
  RC_TAG(facing ? "orientation reversing" : "orientation preserving");
  const std::string what = fmt::format("S1 {} / S2 {} scale {} shift ({}, {}) height {}{}", gen::describe(r1),
                                       gen::describe(r2), s, dx, dy, h, facing ? " facing" : "");
  auto s1 = std::make_shared<const Surface<2>>(gen::make_planar(r1));
  auto placed = transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    return WorldPoint<2>(dx + s * p.x(), dy + s * p.y(), h);
  });
  auto s2 = facing ? flipped(*placed) : placed;
  const auto r = project<2>(s1, s2);
  const InverseIndex<2> index(r.map);
  gen::Rng rng(sample_seed);
  check_round_trips(r.map, index, rng, what);

  // Above S1 (away from its boundary by 1e-6): a preimage right below; elsewhere none.
  // Coverage is promised only when every S2 edge is inserted, and on these pairs (vertical
  // normals, parallel planes) every edge must be: a failure is a defect of its own, not a case
  // to skip (PlanarPairsCoverTheExactOverlap asserts the same on the same kind of pairs).
  if (!r.report.edges_not_inserted.empty()) RC_FAIL(what + "\n" + describe_failures(r.report));
  auto above_s1 = [&](double x, double y, double margin) {
    const bool in_square = x > margin && x < 1 - margin && y > margin && y < 1 - margin;
    const bool in_hole = r1.with_hole && x > gen::HoleBox::x0 - margin && x < gen::HoleBox::x1 + margin &&
                         y > gen::HoleBox::y0 - margin && y < gen::HoleBox::y1 + margin;
    return in_square && !in_hole;
  };
  for (int k = 0; k < 60; ++k) {
    const SurfacePoint<2> y{gen::uniform_index(rng, s2->element_count()), generators::uniform_local_point<2>(rng)};
    const WorldPoint<2> yw = s2->world_position(y.element, y.local);
    const InverseEvaluation<2> inv = inverse_evaluate(index, y);
    if (above_s1(yw.x(), yw.y(), 1e-6)) {
      if (!inv.in_image) RC_FAIL(what + fmt::format(": ({}, {}) is above S1 but has no preimage", yw.x(), yw.y()));
      RC_ASSERT((inv.world - WorldPoint<2>(yw.x(), yw.y(), 0.0)).norm() <= 1e-9);
    } else if (!above_s1(yw.x(), yw.y(), -1e-6)) {
      if (inv.in_image) RC_FAIL(what + fmt::format(": ({}, {}) is not above S1 but has a preimage", yw.x(), yw.y()));
    }
  }
}

RC_GTEST_PROP(ProjectInverse, ConcentricCirclesRoundTrip, (std::uint64_t sample_seed)) {
  const int n1 = *rc::gen::inRange(3, 60), n2 = *rc::gen::inRange(3, 60);
  const double phase = *rc::gen::inRange(0, 1000) / 1000.0, radius = *rc::gen::inRange(900, 1200) / 1000.0;
  auto s1 = circle(n1, 1.0), s2 = circle(n2, radius, phase);
  const auto r = project<1>(s1, s2);
  const InverseIndex<1> index(r.map);
  gen::Rng rng(sample_seed);
  check_round_trips(r.map, index, rng, fmt::format("circles {} / {} radius {} phase {}", n1, n2, radius, phase));
}

TEST(ProjectInverse, PointsOnS2EdgesAboveTheBoundaryOfS1AreFoundFromEitherSide) {
  // S2's 3 x 3 grid over [-1, 2]^2 has edges right above S1's boundary (the unit square), so D
  // ends exactly at S2 edges: a point on such an edge, given on the outer (uncovered) S2 element,
  // must be found through the inner one.
  const auto s1 = grid(2, 2, 0.0, 1.0, 0.0, 1.0, 0.0);
  const auto s2 = grid(3, 3, -1.0, 2.0, -1.0, 2.0, 0.1);
  const auto r = project<2>(s1, s2);
  ASSERT_TRUE(r.report.edges_not_inserted.empty());
  const InverseIndex<2> index(r.map);
  auto in_square = [](const WorldPoint<2>& w, bool closed) {
    return closed ? w.x() >= 0 && w.x() <= 1 && w.y() >= 0 && w.y() <= 1 : w.x() > 0 && w.x() < 1 && w.y() > 0 && w.y() < 1;
  };
  int given_on_outer_elements = 0;
  for (Index t = 0; t < s2->element_count(); ++t) {
    const bool outer_element = !in_square(s2->world_position(t, LocalPoint<2>(1.0 / 3, 1.0 / 3)), false);
    for (int k = 0; k < 3; ++k)
      for (const LocalPoint<2>& y : {reference_corner<2>(k), LocalPoint<2>(0.5 * (reference_corner<2>(k) + reference_corner<2>((k + 1) % 3)))}) {
        const WorldPoint<2> w = s2->world_position(t, y);
        const bool inside = in_square(w, true);
        const InverseEvaluation<2> inv = inverse_evaluate(index, {t, y});
        EXPECT_EQ(inv.in_image, inside) << "S2 element " << t << " point (" << w.x() << ", " << w.y() << ")";
        if (inside && inv.in_image) {
          EXPECT_NEAR((inv.world - WorldPoint<2>(w.x(), w.y(), 0.0)).norm(), 0.0, 1e-12);
        }
        given_on_outer_elements += inside && outer_element;
      }
  }
  EXPECT_GT(given_on_outer_elements, 8);  // the case this test is about did occur
}
