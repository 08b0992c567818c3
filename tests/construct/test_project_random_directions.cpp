// Normal projection with discontinuous direction fields (issue 12, defect 5): every S1 vertex
// gets its own random direction, unrelated to its neighbours'. The projection is then neither
// continuous nor injective in many places; it must still never return a map that verify
// rejects: what cannot be mapped is left out of D and reported. Before, about one field in seven
// gave a region whose image collapsed onto an S2 edge (fold_over), because the closure cut a
// face whose image has the face's orientation into triangles of which one had no image area.
//
// Seed and number of cases come from RC_PARAMS (set by CTest, see tests/CMakeLists.txt).
#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

using namespace plmap;
using namespace plmap::test;
namespace gen = plmap::generators;

namespace {

/// Directions at the S1 vertices: up to `tilt` (radians) away from +z, in random azimuths, or
/// (with `any_direction`) anywhere on the sphere.
std::vector<double> random_directions(Index vertices, double tilt, bool any_direction, gen::Rng& rng) {
  std::vector<double> out;
  for (Index v = 0; v < vertices; ++v) {
    const double z = any_direction ? gen::uniform_real(rng, -1.0, 1.0) : std::cos(tilt * gen::uniform_unit(rng));
    const double azimuth = gen::uniform_real(rng, 0.0, 2.0 * std::numbers::pi);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    out.insert(out.end(), {r * std::cos(azimuth), r * std::sin(azimuth), z});
  }
  return out;
}

}  // namespace

RC_GTEST_PROP(ProjectRandomDirections, DiscontinuousFieldsNeverGiveAnInvalidMap, ()) {
  gen::PlanarRecipe r1, r2;
  r1.base = *rc::gen::element(gen::PlanarBase::grid, gen::PlanarBase::delaunay);
  r2.base = *rc::gen::element(gen::PlanarBase::grid, gen::PlanarBase::delaunay);
  r1.resolution = r1.base == gen::PlanarBase::grid ? *rc::gen::inRange(1, 7) : *rc::gen::inRange(0, 16);
  r2.resolution = r2.base == gen::PlanarBase::grid ? *rc::gen::inRange(1, 7) : *rc::gen::inRange(0, 16);
  r1.jitter = *rc::gen::arbitrary<bool>();
  r2.jitter = *rc::gen::arbitrary<bool>();
  r1.seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  r2.seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  const double height = *rc::gen::inRange(5, 400) / 1000.0;
  const double tilt = *rc::gen::inRange(0, 90) * std::numbers::pi / 180.0;
  const bool any_direction = *rc::gen::inRange(0, 4) == 0;
  const bool negative = *rc::gen::arbitrary<bool>();
  const auto seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  const std::string what =
      fmt::format("S1 {} / S2 {} at height {}, tilt {} {}, seed {}{}", gen::describe(r1), gen::describe(r2), height,
                  tilt, any_direction ? "(any direction)" : "", seed, negative ? " negative allowed" : "");
  auto s1 = std::make_shared<const Surface<2>>(gen::make_planar(r1));
  auto s2 = transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    return WorldPoint<2>(-0.2 + 1.4 * p.x(), -0.2 + 1.4 * p.y(), height);
  });
  gen::Rng rng(seed);
  ProjectionOptions o;
  o.directions = random_directions(s1->vertex_count(), tilt, any_direction, rng);
  o.allow_negative_distance = negative;
  const auto r = project<2>(s1, s2, o);
  // Every invariant holds, image_overlap included: two regions of one element whose images
  // overlap on a partly covered S2 element are found by step 6 (docs/projection.md).
  const VerificationReport report = verify(r.map);
  std::string violations;
  for (const auto& check : report.checks)
    for (const auto& v : check.violations)
      violations += check.name + "/" + v.rule + " element " + std::to_string(v.element) + ": " + v.message + "\n";
  if (!violations.empty()) RC_FAIL(what + "\n" + violations);
}
