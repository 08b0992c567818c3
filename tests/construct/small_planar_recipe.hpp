#pragma once
// A small random planar triangulation (grid or Delaunay, with or without jitter) for the
// projection properties that lift two of them onto one height field: small enough for thousands
// of cases, varied enough to give intersection and ghost nodes, rims and failed edges.

#include <plmap/verify/generators/rc_generators.hpp>

#include <rapidcheck.h>

namespace plmap::test {

inline generators::PlanarRecipe small_planar_recipe() {
  generators::PlanarRecipe r;
  r.base = *rc::gen::element(generators::PlanarBase::grid, generators::PlanarBase::delaunay);
  r.resolution = r.base == generators::PlanarBase::grid ? *rc::gen::inRange(1, 7) : *rc::gen::inRange(0, 16);
  r.jitter = *rc::gen::arbitrary<bool>();
  r.seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  return r;
}

}  // namespace plmap::test
