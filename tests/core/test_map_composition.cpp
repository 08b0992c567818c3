// Composition of maps (core/map_composition.hpp) on generated maps of every kind, which are all
// the identity of space: a chain Xi_2 ∘ Xi_1 (a random map, then a random refinement of its
// target) maps every point to itself, composing with the identity map on either side changes
// nothing, and the inverse of the composition undoes it. Chains whose surfaces do not fit are
// refused.
#include <plmap/verify/deepest_region_locator.hpp>

#include <plmap/core/map_composition.hpp>
#include <plmap/verify/generators/rc_generators.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

using namespace plmap;

namespace {

template <int d>
void check_composition(const generators::MapCase<d>& first, std::uint64_t seed) {
  generators::Rng rng(seed);
  // Xi_2: a random refinement of Xi_1's target (its surface object, so the chain fits).
  const auto refinement = generators::random_refinement<d>(*first.target, {}, rng);
  const auto second = generators::refinement_map<d>(first.target, refinement);
  const auto identity_after = generators::identity_map<d>(first.target);
  const auto identity_before = generators::identity_map<d>(first.domain);

  const MapComposition<d> chain({first.map, second.map});
  const MapComposition<d> with_identity_after({first.map, identity_after.map});
  const MapComposition<d> with_identity_before({identity_before.map, first.map});
  const DeepestRegion<d> prototype;
  CompositionEvaluator<d, DeepestRegion<d>> eval_chain(chain, prototype), eval_after(with_identity_after, prototype),
      eval_before(with_identity_before, prototype);
  const InverseComposition<d> inverse_chain(chain);
  DeepestRegion<d> locator;

  const Surface<d>& s1 = *first.domain;
  const double tolerance = 1e-9 * std::max({s1.max_edge_length(), first.target->max_edge_length()});
  std::vector<SurfacePoint<d>> xs;
  for (int k = 0; k < 30; ++k) xs.push_back({generators::uniform_index(rng, s1.element_count()), generators::uniform_local_point<d>(rng)});
  for (Index n = 0; n < first.map->node_count(); n += 2) xs.push_back({first.map->node_element(n), first.map->data().node_position[n]});
  for (const auto& x : xs) {
    const WorldPoint<d> x_world = s1.world_position(x.element, x.local);
    const Evaluation<d> direct = evaluate(*first.map, x, locator);
    RC_ASSERT(direct.in_domain);
    const ComposedEvaluation<d> c = eval_chain(x), after = eval_after(x), before = eval_before(x);
    RC_ASSERT(c.defined);
    RC_ASSERT(after.defined);
    RC_ASSERT(before.defined);
    // every map is the identity of space, so is their composition
    RC_ASSERT((c.world - x_world).norm() <= tolerance);
    RC_ASSERT((chain.target().world_position(c.point.element, c.point.local) - c.world).norm() <= tolerance);
    // identity on either side: Xi_1 itself
    RC_ASSERT((after.world - direct.world).norm() <= tolerance);
    RC_ASSERT((before.world - direct.world).norm() <= tolerance);
    // the inverse of the composition undoes it
    const ComposedEvaluation<d> back = inverse_chain(c.point);
    RC_ASSERT(back.defined);
    RC_ASSERT((back.world - x_world).norm() <= tolerance);
    RC_ASSERT((s1.world_position(back.point.element, back.point.local) - x_world).norm() <= tolerance);
  }
}

}  // namespace

RC_GTEST_PROP(MapComposition, RefinementChains2, (std::uint64_t seed)) { check_composition(*generators::refinement_maps<2>(), seed); }
RC_GTEST_PROP(MapComposition, RefinementChains1, (std::uint64_t seed)) { check_composition(*generators::refinement_maps<1>(), seed); }
RC_GTEST_PROP(MapComposition, OverlayChains2, (std::uint64_t seed)) { check_composition(*generators::overlay_maps<2>(), seed); }
RC_GTEST_PROP(MapComposition, OverlayChains1, (std::uint64_t seed)) { check_composition(*generators::overlay_maps<1>(), seed); }
RC_GTEST_PROP(MapComposition, IdentityChains2, (std::uint64_t seed)) { check_composition(*generators::identity_maps<2>(), seed); }

TEST(MapComposition, ChainsWhoseSurfacesDoNotFitAreRefused) {
  const auto a = generators::subdivision_map(generators::bumpy_grid(3), 2, 0.1, 1);
  const auto b = generators::subdivision_map(generators::bumpy_grid(3), 2, 0.1, 2);
  // b's domain is an equal but separate surface object: accepted (same vertices and elements)
  const auto a_target_as_domain = generators::identity_map<2>(a.target);
  EXPECT_NO_THROW(MapComposition<2>({a.map, a_target_as_domain.map}));
  EXPECT_NO_THROW(MapComposition<2>({a.map, generators::identity_map<2>(std::make_shared<const Surface<2>>(*a.target)).map}));
  // a's target is a refinement of the grid, b's domain the grid itself
  EXPECT_THROW(MapComposition<2>({a.map, b.map}), Error);
  EXPECT_THROW(MapComposition<2>({}), Error);
  // the same map with itself: S2 (refined) is not S1
  EXPECT_THROW(MapComposition<2>({a.map, a.map}), Error);
}

TEST(MapComposition, BatchAgreesWithTheEvaluatorAndReportsWhereAChainStops) {
  // Xi_1 from a subdivision with dropped sub-elements: points there are outside D of map 0.
  const auto a = generators::subdivision_map(generators::bumpy_grid(4), 3, 0.1, 7, [](Index t, int s) { return (t + s) % 4 == 0; });
  const auto id = generators::identity_map<2>(a.target);
  const MapComposition<2> chain({a.map, id.map});
  std::vector<SurfacePoint<2>> points = a.holes;
  generators::Rng rng(3);
  for (int k = 0; k < 200; ++k) points.push_back({generators::uniform_index(rng, a.domain->element_count()), generators::uniform_local_point<2>(rng)});
  std::vector<ComposedEvaluation<2>> out(points.size());
  evaluate_composition_batch<2>(chain, points, out, DeepestRegion<2>{}, 2);
  CompositionEvaluator<2, DeepestRegion<2>> single(chain, {});
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto s = single(points[i]);
    EXPECT_EQ(s.defined, out[i].defined);
    EXPECT_EQ(s.point, out[i].point);
  }
  for (std::size_t i = 0; i < a.holes.size(); ++i) {
    EXPECT_FALSE(out[i].defined);
    EXPECT_EQ(out[i].stopped_at, 0);
  }
  std::vector<SurfacePoint<2>> bad{{a.domain->element_count(), LocalPoint<2>(0.1, 0.1)}};
  std::vector<ComposedEvaluation<2>> bad_out(1);
  EXPECT_THROW(evaluate_composition_batch<2>(chain, bad, bad_out, DeepestRegion<2>{}), Error);
}
