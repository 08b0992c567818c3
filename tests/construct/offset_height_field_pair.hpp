#pragma once
// A pair of ProjectProperties.OffsetHeightFieldsWithAveragedNormals, rebuilt from its recipe for
// regression tests: S1 a planar triangulation lifted to a random height field, S2 another one
// over a footprint shifted by (dx, dy) and lifted to the same field plus `offset`, facing away;
// both seen from S1 along its averaged vertex normals, negative distances allowed, S2's normal
// aligned with the rays; the map checked against 20,000 rays cast along the same field.

#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/verify/generators/rc_generators.hpp>
#include <plmap/verify/ray_check.hpp>

#include <cstdint>
#include <memory>

namespace plmap::test {

/// The recipe of a Delaunay planar triangulation of the unit square, as the property tests print
/// it ("delaunay resolution=R [hole] seed=S").
inline generators::PlanarRecipe delaunay(int resolution, bool with_hole, std::uint64_t seed) {
  generators::PlanarRecipe r;
  r.base = generators::PlanarBase::delaunay;
  r.resolution = resolution;
  r.with_hole = with_hole;
  r.seed = seed;
  return r;
}

struct OffsetHeightFieldPair {
  std::shared_ptr<const Surface<2>> s1, s2;
  ProjectionResult<2> projected;
  RayCheckReport<2> rays;
};

inline OffsetHeightFieldPair offset_height_fields(const generators::PlanarRecipe& r1, const generators::PlanarRecipe& r2,
                                                  std::uint64_t field_seed, double offset, double dx, double dy) {
  namespace gen = plmap::generators;
  gen::Rng rng(field_seed);
  const gen::HeightField field = gen::random_height_field(rng);
  auto s1 = std::make_shared<const Surface<2>>(gen::lift_to_height_field(gen::make_planar(r1), field));
  auto s2 = transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    const double x = p.x() + dx, y = p.y() + dy;
    return WorldPoint<2>(x, y, field(x, y) + offset);
  });
  ProjectionOptions po{.allow_negative_distance = true, .normal_check = TargetNormalCheck::aligned};
  auto projected = project<2>(s1, s2, po);
  RayCheckOptions<2> o;
  o.directions = averaged_vertex_normals(*s1);
  o.samples = 20000;
  o.allow_negative_distance = true;
  o.normal_check = RayNormalCheck::aligned;
  auto rays = check_against_rays(projected.map, o);
  return {s1, s2, std::move(projected), std::move(rays)};
}

}  // namespace plmap::test
