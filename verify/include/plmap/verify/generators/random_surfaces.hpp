#pragma once
/// \file
/// Deterministic random surfaces for tests, examples and experiments: each function takes its
/// options and a random engine, so the same seed gives the same surface on every platform that
/// has the same std::mt19937_64 (all of them) and uses no distribution of the standard library
/// whose output is implementation-defined (we draw through uniform_unit / uniform_index below).
///
/// d = 2: triangulations of the unit square [0,1]^2 at z = 0 (a jittered grid with random
/// diagonals, or a constrained Delaunay triangulation of random points), optionally with a
/// rectangular hole, lifted to a height field, or made non-manifold (a fin: three triangles on
/// one edge; two sheets sharing one vertex).
/// d = 1: polylines in the plane: open, closed, or a star whose centre has three or more
/// segments (non-manifold).
///
/// The rc::Gen wrappers live in rc_generators.hpp; these functions do not need RapidCheck.

#include <plmap/core/surface.hpp>

#include <cstdint>
#include <random>

namespace plmap::generators {

using Rng = std::mt19937_64;

/// Uniform double in [0, 1), computed from the raw engine output (portable across libraries).
double uniform_unit(Rng& rng);
/// Uniform double in [lo, hi).
double uniform_real(Rng& rng, double lo, double hi);
/// Uniform integer in [0, n), n > 0.
int uniform_index(Rng& rng, int n);

/// A uniformly distributed point of the reference element: [0, 1) for d = 1; for d = 2 a point
/// of the unit square folded onto the triangle along its diagonal (x drawn before y).
template <int d>
LocalPoint<d> uniform_local_point(Rng& rng) {
  if constexpr (d == 1) {
    return LocalPoint<1>(uniform_unit(rng));
  } else {
    double x = uniform_unit(rng);
    double y = uniform_unit(rng);
    if (x + y > 1.0) {
      x = 1.0 - x;
      y = 1.0 - y;
    }
    return {x, y};
  }
}

/// The hole of the planar domains: [0.25, 0.5] x [0.5, 0.75], aligned with every grid whose cell
/// count is a multiple of 4, so two such triangulations cover exactly the same domain.
struct HoleBox {
  static constexpr double x0 = 0.25, x1 = 0.5, y0 = 0.5, y1 = 0.75;
  static bool contains_strictly(double x, double y) { return x > x0 && x < x1 && y > y0 && y < y1; }
};

// ---- d = 2 -------------------------------------------------------------------------------------

struct GridOptions {
  int cells = 2;  ///< cells per side of the unit square; a multiple of 4 when with_hole
  /// Interior vertices move by up to jitter * cell size in x and y, boundary vertices only along
  /// their side, corners and hole corners stay. At most 0.2 (keeps every triangle positive).
  /// Zero gives exact grid coordinates (dyadic when cells is a power of two), so that grid lines
  /// of two grids coincide exactly.
  double jitter = 0.0;
  bool with_hole = false;
};

/// The unit square (minus the hole) split into cells x cells squares, each cut along a random
/// diagonal. Triangles are counter-clockwise seen from +z.
Surface<2> grid_triangulation(const GridOptions& options, Rng& rng);

struct DelaunayOptions {
  int interior_points = 10;  ///< random points inside the domain
  int boundary_points = 4;   ///< random points on the sides of the square (and of the hole)
  /// Points taken from the dyadic grid of spacing 1/8 (inside or on the domain boundary); they
  /// coincide with vertices and lie on edges of grid triangulations, which exercises touching
  /// nodes, coinciding vertices and S2 edges through S1 vertices in overlays.
  int grid_points = 0;
  bool with_hole = false;
};

/// A constrained Delaunay triangulation (CGAL) of the square's corners, the hole's corners and
/// random points, with the domain boundary as constraints. Points keep a minimum separation, so
/// no triangle is a sliver. Triangles are counter-clockwise seen from +z.
Surface<2> delaunay_triangulation(const DelaunayOptions& options, Rng& rng);

/// A smooth height field z = amplitude * sin(kx x + px) * cos(ky y + py).
struct HeightField {
  double amplitude = 0.2;
  double kx = 3.0, ky = 2.0, px = 0.0, py = 0.0;
  double operator()(double x, double y) const;
};
HeightField random_height_field(Rng& rng);

/// The same triangulation with every vertex lifted to z = h(x, y).
Surface<2> lift_to_height_field(const Surface<2>& planar, const HeightField& h);

/// Adds `fins` fins: on random interior edges (two triangles each) a new triangle standing up in
/// z, so that those edges have three triangles. Needs a surface with interior edges.
Surface<2> add_fins(const Surface<2>& sheet, int fins, Rng& rng);

/// Two sheets that share exactly one vertex (non-manifold vertex): `second` is moved by
/// (x, y, z) -> (1 + x, 1 + y, (x + y) / 2) and its vertex at (0, 0) is identified with the vertex
/// of `first` at (1, 1). Both must contain these corners (all planar generators above do).
Surface<2> join_at_corner(const Surface<2>& first, const Surface<2>& second);

// ---- d = 1 -------------------------------------------------------------------------------------

/// An x-monotone polyline from x = 0 to x = 1 with `segments` segments (at least 1).
Surface<1> random_open_polyline(int segments, Rng& rng);
/// A closed star-shaped polygon around the origin with `segments` segments (at least 3),
/// oriented counter-clockwise.
Surface<1> random_closed_polyline(int segments, Rng& rng);
/// `arms` (at least 3) polylines leaving a common centre vertex, each of `segments_per_arm`
/// segments and staying inside its own angular sector, so they never cross. The centre is a
/// non-manifold vertex with `arms` segments. Segments point away from the centre.
Surface<1> random_star_polyline(int arms, int segments_per_arm, Rng& rng);

}  // namespace plmap::generators
