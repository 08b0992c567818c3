#pragma once
/// \file
/// RapidCheck generators of random surfaces and valid maps, on top of the deterministic
/// functions of random_surfaces.hpp and random_maps.hpp.
///
/// Every generated value comes from a small "recipe" (shape, resolution, seed) that RapidCheck
/// draws and shrinks (smaller resolutions, simpler shapes); the recipe is in the value's
/// description, so a failing case can be rebuilt outside RapidCheck with make_*(recipe).
/// Sizes grow with RapidCheck's size parameter (0..100 by default): at size 100 a surface has
/// up to ~100 elements and a refinement a few hundred.

#include <plmap/verify/generators/random_maps.hpp>

#include <rapidcheck.h>

#include <cstdint>
#include <memory>
#include <ostream>
#include <string>

namespace plmap::generators {

// ---- recipes -----------------------------------------------------------------------------------

enum class PlanarBase { grid, delaunay };

/// A triangulation of the unit square (with the HoleBox hole when `with_hole`), z = 0.
struct PlanarRecipe {
  PlanarBase base = PlanarBase::grid;
  /// grid: cells per side (rounded up to a multiple of 4 with a hole); delaunay: interior
  /// points (boundary and dyadic grid points scale with it).
  int resolution = 2;
  bool with_hole = false;
  /// grid: jitter the vertices (no shared grid lines); delaunay: no effect.
  bool jitter = false;
  std::uint64_t seed = 0;
};

/// The shapes of random triangle surfaces beyond the flat square.
enum class SheetShape {
  planar,         ///< the planar triangulation itself
  height_field,   ///< lifted to a random height field
  fins,           ///< planar plus one or two fins (edges with three triangles)
  shared_corner,  ///< two sheets (one lifted) sharing one vertex
};

struct TriangleSurfaceRecipe {
  PlanarRecipe planar;
  SheetShape shape = SheetShape::planar;
};

enum class CurveShape { open, closed, star };

struct CurveRecipe {
  CurveShape shape = CurveShape::open;
  int segments = 3;  ///< open/closed: segments; star: segments per arm
  int arms = 3;      ///< star only
  std::uint64_t seed = 0;
};

std::string describe(const PlanarRecipe& r);
std::string describe(const TriangleSurfaceRecipe& r);
std::string describe(const CurveRecipe& r);

Surface<2> make_planar(const PlanarRecipe& r);
Surface<2> make_triangle_surface(const TriangleSurfaceRecipe& r);
Surface<1> make_curve(const CurveRecipe& r);

// ---- generators --------------------------------------------------------------------------------

rc::Gen<PlanarRecipe> planar_recipes();
rc::Gen<TriangleSurfaceRecipe> triangle_surface_recipes();
rc::Gen<CurveRecipe> curve_recipes();

/// Random triangle surfaces of every SheetShape (manifold or not, with or without boundary/hole).
rc::Gen<std::shared_ptr<const Surface<2>>> triangle_surfaces();
/// Random polylines: open, closed, stars.
rc::Gen<std::shared_ptr<const Surface<1>>> curves();

/// Identity maps S -> S over triangle_surfaces() (d = 2) or curves() (d = 1).
template <int d>
rc::Gen<MapCase<d>> identity_maps();
/// Inclusion maps of random refinements over the same surfaces.
template <int d>
rc::Gen<MapCase<d>> refinement_maps();
/// d = 2: overlays of two independent planar triangulations of the same domain (grid/grid with
/// shared grid lines, grid/Delaunay with shared dyadic points, Delaunay/Delaunay; with or
/// without the hole). d = 1: two subdivisions of the same random polyline (open, closed, star).
template <int d>
rc::Gen<MapCase<d>> overlay_maps();

/// Prints the description (RapidCheck shows it for a failing case).
template <int d>
std::ostream& operator<<(std::ostream& os, const MapCase<d>& c) {
  os << c.description << " (|S1| = " << c.domain->element_count()
     << ", |S2| = " << c.target->element_count() << ", regions = " << c.map->region_count() << ")";
  return os;
}

}  // namespace plmap::generators
