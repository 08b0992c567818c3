// Property tests over randomly generated valid maps (identity, refinement, overlay; d = 1 and 2;
// manifold, with boundary and holes, non-manifold). In all of them Xi is the identity of the
// ambient space, D = S1 and Xi(D) = S2, which gives exact oracles:
// - the map passes every check of plmap::verify as a parametrization;
// - the preimage of each S2 vertex evaluates to that vertex;
// - the regions' measures sum to |S1| on S1 and to |S2| (= |S1|) on S2;
// - any point of S1 evaluates to itself;
// - for the identity, the regions are the elements.
//
// Seed and number of cases come from RC_PARAMS (set by CTest, see tests/CMakeLists.txt).

#include <plmap/core/evaluation.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/deepest_region_locator.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace plmap {
namespace {

using generators::MapCase;

std::string show(const auto& c) {
  std::ostringstream os;
  os << c;
  return os.str();
}

/// Everything that holds for every generated map (Xi = identity of space, parametrization).
template <int d>
void check_generated_map(const MapCase<d>& c, std::uint64_t sample_seed, VerifyOptions options = {}) {
  RC_TAG(c.domain->element_count() < 20 ? "small" : c.domain->element_count() < 80 ? "medium" : "large");
  const PlMap<d>& map = *c.map;
  const Surface<d>& s1 = *c.domain;
  const Surface<d>& s2 = *c.target;

  // 1. The invariant checks.
  options.expect_parametrization = true;
  const VerificationReport report = verify(map, options);
  if (!report.ok()) RC_FAIL(show(c) + "\n" + summary(report));

  // 2. Preimages of S2 vertices evaluate to the vertices.
  DeepestRegion<d> locator;
  const double world_tolerance = 1e-9 * std::max(s1.max_edge_length(), s2.max_edge_length());
  RC_ASSERT(c.target_vertex_preimage.size() == static_cast<std::size_t>(s2.vertex_count()));
  for (Index v = 0; v < s2.vertex_count(); ++v) {
    const Evaluation<d> e = evaluate(map, c.target_vertex_preimage[v], locator);
    RC_ASSERT(e.in_domain);
    const double error = (e.world - s2.vertex(v)).norm();
    if (!(error <= world_tolerance))
      RC_FAIL(show(c) + ": S2 vertex " + std::to_string(v) + " evaluates " + std::to_string(error) + " away");
  }

  // 3. Both sides are covered exactly.
  const CoveredMeasure covered = covered_measure(map);
  const double measure_tolerance = 1e-9 * s1.measure();
  RC_ASSERT(std::abs(covered.domain - s1.measure()) <= measure_tolerance);
  RC_ASSERT(std::abs(covered.target - s2.measure()) <= measure_tolerance);
  RC_ASSERT(std::abs(s1.measure() - s2.measure()) <= measure_tolerance);

  // 4. Xi is the identity of space: random points of S1 evaluate to themselves.
  generators::Rng rng(sample_seed);
  for (int k = 0; k < 20; ++k) {
    const SurfacePoint<d> p{generators::uniform_index(rng, s1.element_count()), generators::uniform_local_point<d>(rng)};
    const Evaluation<d> e = evaluate(map, p, locator);
    RC_ASSERT(e.in_domain);
    const double error = (e.world - s1.world_position(p.element, p.local)).norm();
    if (!(error <= world_tolerance))
      RC_FAIL(show(c) + ": a point of S1 element " + std::to_string(p.element) + " moved by " +
              std::to_string(error));
  }
}

/// The identity map's regions are exactly the elements, corner for corner.
template <int d>
void check_identity_regions(const MapCase<d>& c) {
  const PlMap<d>& map = *c.map;
  RC_ASSERT(map.region_count() == c.domain->element_count());
  for (Index t = 0; t < c.domain->element_count(); ++t) {
    RC_ASSERT(map.regions_end(t) - map.regions_begin(t) == 1);
    const RemoteIntersection<d> ri = remote_intersection(map, map.regions_begin(t));
    RC_ASSERT(ri.domain_element == t);
    RC_ASSERT(ri.target_element == t);
    std::vector<std::array<double, d>> corners;
    for (int i = 0; i <= d; ++i) {
      RC_ASSERT(ri.domain_local[i] == ri.target_local[i]);
      std::array<double, d> a{};
      for (int k = 0; k < d; ++k) a[k] = ri.domain_local[i](k);
      corners.push_back(a);
    }
    std::sort(corners.begin(), corners.end());
    std::vector<std::array<double, d>> reference;
    for (int k = 0; k <= d; ++k) {
      std::array<double, d> a{};
      for (int i = 0; i < d; ++i) a[i] = reference_corner<d>(k)(i);
      reference.push_back(a);
    }
    std::sort(reference.begin(), reference.end());
    RC_ASSERT(corners == reference);
  }
}

rc::Gen<std::uint64_t> sample_seeds() { return rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>()); }

RC_GTEST_PROP(GeneratedMaps, IdentityOfTriangleSurfacesIsValidAndExact, ()) {
  const auto c = *generators::identity_maps<2>();
  check_generated_map<2>(c, *sample_seeds());
  check_identity_regions<2>(c);
}

RC_GTEST_PROP(GeneratedMaps, IdentityOfCurvesIsValidAndExact, ()) {
  const auto c = *generators::identity_maps<1>();
  check_generated_map<1>(c, *sample_seeds());
  check_identity_regions<1>(c);
}

RC_GTEST_PROP(GeneratedMaps, RefinementOfTriangleSurfacesIsValid, ()) {
  // Scaled down to keep the property within a few seconds in Debug builds.
  const auto c = *rc::gen::scale(0.6, generators::refinement_maps<2>());
  check_generated_map<2>(c, *sample_seeds());
  // Every S2 triangle lies in one S1 triangle: the regions are exactly the S2 triangles.
  RC_ASSERT(c.map->region_count() == c.target->element_count());
}

RC_GTEST_PROP(GeneratedMaps, RefinementOfCurvesIsValid, ()) {
  const auto c = *generators::refinement_maps<1>();
  check_generated_map<1>(c, *sample_seeds());
  RC_ASSERT(c.map->region_count() == c.target->element_count());
}

RC_GTEST_PROP(GeneratedMaps, OverlayOfPlanarTriangulationsIsValid, ()) {
  const auto c = *rc::gen::scale(0.6, generators::overlay_maps<2>());
  // Overlays of unrelated triangulations contain sliver regions (measure ~1e-7 of their S2
  // element); the default tolerances must accept their rounded corner images.
  check_generated_map<2>(c, *sample_seeds(), VerifyOptions{});
  // Each region is one piece of an S1 x S2 intersection: at least one per element of either side.
  RC_ASSERT(c.map->region_count() >= std::max(c.domain->element_count(), c.target->element_count()));
  RC_CLASSIFY(std::count(c.map->data().node_type.begin(), c.map->data().node_type.end(),
                         NodeType::intersection) > 0,
              "with intersection nodes");
  RC_CLASSIFY(std::count(c.map->data().node_type.begin(), c.map->data().node_type.end(), NodeType::ghost) > 0,
              "with ghost nodes");
}

RC_GTEST_PROP(GeneratedMaps, OverlayOfPolylineSubdivisionsIsValid, ()) {
  const auto c = *generators::overlay_maps<1>();
  check_generated_map<1>(c, *sample_seeds());
  RC_ASSERT(c.map->region_count() >= std::max(c.domain->element_count(), c.target->element_count()));
}

}  // namespace
}  // namespace plmap
