#pragma once
/// \file
/// Closed triangle surfaces for tests of algorithms that need a surface without boundary
/// (simplification, smoothing): a subdivided icosahedron on the unit sphere, optionally with
/// every vertex moved radially by a random factor (a "bumpy sphere"). Triangles are oriented
/// counter-clockwise seen from outside.

#include <plmap/core/surface.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

namespace plmap::generators {

struct SphereOptions {
  int subdivisions = 2;      ///< 0: the icosahedron (20 triangles); each level multiplies by 4
  double radial_jitter = 0;  ///< radii drawn from [1 - jitter, 1 + jitter] (below 0.5)
};

Surface<2> icosphere(const SphereOptions& options, Rng& rng);

}  // namespace plmap::generators
