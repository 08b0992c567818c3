#pragma once
/// \file
/// Closed triangle surfaces for tests of algorithms that need a surface without boundary
/// (simplification, smoothing): a subdivided icosahedron on the unit sphere, optionally with
/// every vertex moved radially by a random factor (a "bumpy sphere"), and a torus (genus one,
/// with saddle-shaped stars on its inner side). Triangles are oriented counter-clockwise seen
/// from outside.

#include <plmap/core/surface.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

namespace plmap::generators {

struct SphereOptions {
  int subdivisions = 2;      ///< 0: the icosahedron (20 triangles); each level multiplies by 4
  double radial_jitter = 0;  ///< radii drawn from [1 - jitter, 1 + jitter] (below 0.5)
};

Surface<2> icosphere(const SphereOptions& options, Rng& rng);

struct TorusOptions {
  int around = 16;           ///< vertices around the central axis (at least 3)
  int across = 6;            ///< vertices around the tube (at least 3)
  double major_radius = 1;   ///< distance of the tube's centre line from the axis
  double minor_radius = 0.25;  ///< the tube's radius (below major_radius)
};

/// The torus as a grid of around × across quadrilaterals, each split into two triangles.
Surface<2> torus(const TorusOptions& options);

}  // namespace plmap::generators
