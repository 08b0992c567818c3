#pragma once
/// \file
/// Polygon faces of OFF, OBJ and PLY files split into triangles that lie inside the polygon.
///
/// The parsers add a polygon as the fan (0, k, k+1) from its first corner (add_polygon), which
/// is right for every convex polygon and folds for a non-convex one: CGAL's corner_poly.off has
/// an L-shaped hexagon whose fan puts a triangle over the notch, and a surface read that way
/// projects onto a copy of itself with 42 % of it left out. Once every vertex is read, each
/// polygon whose fan is not inside it (a fan triangle turned against the polygon, seen along its
/// Newell normal) is cut again by ear clipping in its plane: the same n - 2 triangles' slots,
/// so element numbers and the file offsets of the messages stay as they were.
///
/// Private to core (the readers).

#include "surface_parse_support.hpp"

namespace plmap::surface_io_detail {

/// Re-triangulates, in place, the polygons of `mesh` (RawMesh::polygons) whose fan leaves the
/// polygon. A polygon without an ear in its plane (it is not simple there, or has collinear
/// corners that every triangulation makes degenerate) keeps its fan, which Surface then judges.
void triangulate_polygons_in_their_planes(RawMesh<2>& mesh);

}  // namespace plmap::surface_io_detail
