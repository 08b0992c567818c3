#pragma once
// Small surfaces and hand-written files shared by the surface I/O tests and the fuzz test.

#include <plmap/core/io/surface_reader.hpp>
#include <plmap/core/io/surface_writer.hpp>
#include <plmap/core/surface.hpp>

#include <string>
#include <vector>

namespace plmap::surface_io_test {

/// A closed tetrahedron; vertices are numbered in order of first appearance in the elements
/// (so STL, which renumbers that way, reads it back identically) and are exact floats.
inline Surface<2> tetrahedron() {
  return Surface<2>({{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}},
                    {{0, 1, 2}, {0, 2, 3}, {2, 1, 3}, {0, 3, 1}});
}

/// A non-manifold surface with boundary: three triangles sharing edge 0-1, with coordinates
/// that are not floats (to test exact decimal round trips).
inline Surface<2> fin() {
  return Surface<2>({{0.1, 0, 0}, {1.0 / 3.0, 0, 0}, {0.2, 1e-7, 1.5}, {0.2, 2.0 / 7.0, -2.5},
                     {0.2, -1.25, 0.0}},
                    {{0, 1, 2}, {0, 1, 3}, {1, 0, 4}});
}

/// An open polyline and a separate closed triangle in the plane.
inline Surface<1> polyline() {
  return Surface<1>({{0, 0}, {1.0 / 3.0, 0.5}, {1, 0}, {2, 2}, {3, 2}, {2.5, 3}},
                    {{0, 1}, {1, 2}, {3, 4}, {4, 5}, {5, 3}});
}

// ---- hand-written files ----

inline const char* off_quad_with_comments = R"(# a unit square as one quad plus a triangle
OFF
# counts: vertices faces edges
5 2 0
0 0 0
1 0 0
1 1 0   # trailing comment
0 1 0

0.5 2 0
4 0 1 2 3
3 3 2 4
)";

inline const char* obj_mixed_corners = R"(# OBJ with every corner form
mtllib none.mtl
o square
v 0 0 0
v 1 0 0
v 1 1 0 1.0
v 0 1 0
vt 0 0
vt 1 0
vn 0 0 1
g group
s off
f 1/1 2/2/1 3//1
f -4 -2 -1
l 1 2
)";

inline const char* stl_ascii_square = R"(solid square
  facet normal 0 0 1
    outer loop
      vertex 0 0 0
      vertex 1 0 0
      vertex 1 1 0
    endloop
  endfacet
  facet normal 0 0 1
    outer loop
      vertex 0 0 0
      vertex 1 1 0
      vertex 0 1 0
    endloop
  endfacet
endsolid square
)";

inline const char* ply_ascii_with_extras = R"(ply
format ascii 1.0
comment extra properties and elements that plmap skips
element vertex 4
property float x
property float y
property float z
property uchar red
property list uchar float extra
element face 1
property uchar flags
property list uchar int vertex_indices
element edge 1
property int vertex1
property int vertex2
end_header
0 0 0 255 0
1 0 0 255 1 0.5
1 1 0 0 2 0.5 0.25
0 1 0 0 0
7 4 0 1 2 3
0 2
)";

inline const char* gmsh_v2_mixed = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
1
2 1 "surface"
$EndPhysicalNames
$Nodes
5
10 0 0 0
20 1 0 0
30 1 1 0
40 0 1 0
50 9 9 9
$EndNodes
$Elements
5
1 15 2 0 1 10
2 1 2 0 1 10 20
3 2 2 1 1 10 20 30
4 2 3 1 1 7 10 30 40
5 4 2 0 1 10 20 30 50
$EndElements
)";

inline const char* gmsh_v41_blocks = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
0 0 1 0
1 0 0 0 1 1 0 0 0 0
$EndEntities
$Nodes
2 4 1 4
2 1 0 2
1
2
0 0 0
1 0 0
2 1 1 2
3
4
1 1 0 0.5 0.5
0 1 0 0 1
$EndNodes
$Elements
2 3 1 3
1 1 1 1
1 1 2
2 1 2 2
2 1 2 3
3 1 3 4
$EndElements
)";

inline const char* curve_text_triangle = R"(# a triangle in the plane
plmap-curve 1
vertices 3   # counts may carry comments
0 0
1 0
0 1
segments 3
0 1
1 2
2 0
)";

}  // namespace plmap::surface_io_test
