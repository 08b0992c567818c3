#pragma once
// The triangular closure of the plane graph on one S1 element (paper Remark 2.1), computed
// from the faces of the graph. Private to the builder.
//
// The graph on an element is a plane straight-line graph inside the reference triangle: the
// element boundary (split at the nodes on it) plus the pieces of S2 edge preimages. Its faces
// are the regions of the map before closure. This fast path finds the faces directly — sort
// the edges around each node with exact orientation predicates, trace the faces, cut each face
// into triangles by ear clipping — and checks, with exact predicates, that what it traced is a
// tiling of the element (every inner face a simple counter-clockwise polygon). Anything else
// (a disconnected graph, a face with a dangling edge, crossing or overlapping edges) makes it
// decline, and the caller falls back to a constrained Delaunay triangulation, which handles or
// diagnoses those cases.
//
// The diagonals chosen do matter: Xi is interpolated linearly on each closure triangle from its
// corners' images, so where the construction is not exactly piecewise linear on a face (normal
// projection) they decide the interpolation inside the face, and a sliver gets an affine map
// that amplifies the rounding of its corner images. The best-shaped ear goes first for that
// reason, then Lawson flips make each face's triangulation Delaunay.

#include <plmap/core/types.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace plmap::detail {

/// A triangulation of the reference triangle that contains every graph edge.
struct ElementClosure {
  std::vector<std::array<int, 3>> triangles;  ///< vertex ids, counter-clockwise
  /// Triangle across the side opposite corner i, or -1 (element boundary).
  std::vector<std::array<int, 3>> neighbors;
  std::vector<int> face;  ///< face of the graph each triangle belongs to
  int face_count = 0;

  void clear() {
    triangles.clear();
    neighbors.clear();
    face.clear();
    face_count = 0;
  }
};

/// Buffers reused from element to element, so the fast path does not allocate in steady state.
struct ClosureScratch {
  std::vector<int> out_begin, out_half_edge, position, next, half_edge_face, cycle, polygon;
  std::vector<char> visited;
  std::vector<int> order;
  std::vector<std::pair<std::uint64_t, int>> side_keys;
};

/// Tries the fast path. `points` are the element's vertices in local coordinates (all distinct
/// is checked), `segments` the constraint edges (element boundary pieces and graph edges, each
/// once), `boundary_start` a half-edge (a, b) of the element boundary taken counter-clockwise.
/// Returns false, leaving `out` unspecified, when the graph is not one it handles.
bool close_by_faces(std::span<const LocalPoint<2>> points, std::span<const std::array<int, 2>> segments,
                    std::array<int, 2> boundary_start, ElementClosure& out, ClosureScratch& scratch);

/// Whether the closed polygon `poly` (indices into `points`) turns left or goes straight at every
/// vertex, never doubles back, and winds exactly once: then it is convex and simple. Exact.
bool convex_and_winding_once(std::span<const LocalPoint<2>> points, const std::vector<int>& poly);

/// For each vertex, its neighbours in the closure in counter-clockwise order: boundary vertices
/// start right after the outside, interior vertices at their smallest neighbour. Written as
/// CSR arrays (ring_begin has points + 1 entries).
void closure_rings(const ElementClosure& closure, int vertex_count, std::vector<int>& ring_begin,
                   std::vector<int>& ring);

}  // namespace plmap::detail
