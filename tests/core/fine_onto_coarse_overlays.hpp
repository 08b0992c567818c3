#pragma once
// A RapidCheck generator shared by the inverse-evaluation tests: an overlay map of a fine planar
// triangulation onto a coarse grid (hundreds of regions per S2 element), the case where the
// inverse index builds per-element cell grids.

#include <plmap/core/errors.hpp>
#include <plmap/verify/generators/random_maps.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <rapidcheck.h>

#include <memory>

namespace plmap::test {

/// Draws the pair (fine: a 12-16 grid or a 100-199 point Delaunay triangulation, jittered or not;
/// coarse: an unjittered grid of 1..max_coarse_resolution cells per side) and overlays them. Pairs
/// the brute-force overlay generator refuses (edges through vertices it cannot order) are
/// discarded: they say nothing about inverse evaluation. The coarse grid is not jittered: overlays
/// onto a jittered 1x1 grid can place a touching node off its S2 vertex (a generator defect).
inline generators::MapCase<2> fine_onto_coarse_overlay(int max_coarse_resolution) {
  generators::PlanarRecipe fine, coarse;
  fine.base = *rc::gen::element(generators::PlanarBase::grid, generators::PlanarBase::delaunay);
  fine.resolution = fine.base == generators::PlanarBase::grid ? *rc::gen::inRange(12, 17) : *rc::gen::inRange(100, 200);
  fine.jitter = *rc::gen::arbitrary<bool>();
  fine.seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  coarse.base = generators::PlanarBase::grid;
  coarse.resolution = *rc::gen::inRange(1, max_coarse_resolution + 1);
  coarse.jitter = false;
  coarse.seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  RC_TAG(fine.base == generators::PlanarBase::grid ? "grid" : "delaunay");
  try {
    return generators::plane_overlay_map(std::make_shared<const Surface<2>>(generators::make_planar(fine)),
                                         std::make_shared<const Surface<2>>(generators::make_planar(coarse)),
                                         "fine " + generators::describe(fine) + " onto coarse " +
                                             generators::describe(coarse));
  } catch (const Error&) {
    RC_DISCARD("the overlay generator refused the pair");
  }
}

}  // namespace plmap::test
