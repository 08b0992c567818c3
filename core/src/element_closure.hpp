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

/// A constraint of the closure: an edge between vertices a < b, either a piece of the element
/// boundary, a graph edge (a piece of an S2 edge's preimage), or both.
struct ClosureSegment {
  int a, b;
  bool graph;
};

/// A triangulation of the reference triangle that contains every graph edge.
struct ElementClosure {
  std::vector<std::array<int, 3>> triangles;  ///< vertex ids, counter-clockwise
  /// Triangle across the side opposite corner i, or -1 (element boundary).
  std::vector<std::array<int, 3>> neighbors;
  /// Bit i set: the side opposite corner i is a graph edge.
  std::vector<std::uint8_t> graph_sides;
  std::vector<int> face;  ///< face of the graph each triangle belongs to
  int face_count = 0;

  void clear() {
    triangles.clear();
    neighbors.clear();
    graph_sides.clear();
    face.clear();
    face_count = 0;
  }
};

/// Buffers reused from element to element, so the fast path does not allocate in steady state.
struct ClosureScratch {
  struct HalfEdge {
    LocalPoint<2> direction;  // to - from, as computed in floating point
    int from, to;
    int next;      // the next half-edge of the face on its left
    int face;      // that face
    int position;  // index in the counter-clockwise order around `from`
    int side;      // the triangle side (3 t + i) it became, or -1 (outer face)
    bool upper;    // direction angle in [0, pi)
  };
  std::vector<HalfEdge> half_edges;
  std::vector<int> out_begin, out_half_edge, cursor, face_first, flips;
  std::vector<LocalPoint<2>> sorted_points;
};

/// Tries the fast path. `points` are the element's vertices in local coordinates (all distinct
/// is checked), `segments` the constraint edges, each once and sorted by (a, b) (the order
/// decides the order of the faces and so of the triangles), `boundary_start` a half-edge (a, b)
/// of the element boundary taken counter-clockwise. Returns false, leaving `out` unspecified,
/// when the graph is not one it handles.
bool close_by_faces(std::span<const LocalPoint<2>> points, std::span<const ClosureSegment> segments,
                    std::array<int, 2> boundary_start, ElementClosure& out, ClosureScratch& scratch);

/// Flips the side opposite corner i of triangle t (shared with the triangle across it) if the two
/// triangles form a strictly convex quadrilateral (exact): the new diagonal joins their far
/// corners, is no graph edge, and the outer sides keep theirs. Returns whether it flipped; t and
/// the triangle across keep their indices and faces.
bool flip_side(std::span<const LocalPoint<2>> points, ElementClosure& out, int t, int i);

/// Whether the closed polygon `poly` (indices into `points`) turns left or goes straight at every
/// vertex, never doubles back, and winds exactly once: then it is convex and simple. Exact.
bool convex_and_winding_once(std::span<const LocalPoint<2>> points, std::span<const int> poly);

/// A neighbour of a vertex in the closure, in counter-clockwise order around the vertex.
struct RingEntry {
  int vertex;
  /// The closure triangles on either side of the edge to `vertex`: `before` precedes it and
  /// `after` follows it counter-clockwise around the centre; -1 outside the element.
  int before, after;
  bool graph;  ///< the edge is a graph edge
};

/// Where each vertex's ring starts, as a corner 3 t + i (vertex = triangles[t][i]), -1 for a
/// vertex of no triangle: for a vertex on the boundary, the one triangle whose side v-a (a the
/// next corner) is on the boundary; for an interior vertex, any.
void ring_starts(const ElementClosure& closure, int vertex_count, std::vector<int>& start);

/// Calls visit(const RingEntry&) for the neighbours of vertex v in the closure in
/// counter-clockwise order: a boundary vertex's starting right after the outside, an interior
/// vertex's at its smallest neighbour. `start` is v's entry of ring_starts. Combinatorial: the
/// triangles around v are circulated, no angle is compared.
template <class Visit>
void visit_ring(const ElementClosure& closure, int v, int start, Visit&& visit) {
  if (start < 0) return;
  const auto* tri = closure.triangles.data();
  const auto* nb = closure.neighbors.data();
  const int nt = static_cast<int>(closure.triangles.size());
  auto corner_of = [&](int t) { return tri[t][0] == v ? 0 : (tri[t][1] == v ? 1 : 2); };
  auto graph = [&](int t, int i) { return ((closure.graph_sides[t] >> i) & 1u) != 0; };
  // Around v in triangle (v, a, b): a comes before b counter-clockwise; the next triangle shares
  // side v-b (opposite a), the previous one side v-a (opposite b).
  int t = start / 3, i = start % 3;
  if (nb[t][(i + 2) % 3] >= 0) {  // interior: go round once to find the smallest neighbour
    int u = t, j = i;
    for (int guard = 0; guard < nt; ++guard) {
      const int next = nb[u][(j + 1) % 3];
      if (next < 0 || next == start / 3) break;
      u = next;
      j = corner_of(u);
      if (tri[u][(j + 1) % 3] < tri[t][(i + 1) % 3]) {
        t = u;
        i = j;
      }
    }
  }
  const int first = t;
  visit(RingEntry{tri[t][(i + 1) % 3], nb[t][(i + 2) % 3], t, graph(t, (i + 2) % 3)});
  for (int guard = 0; guard < nt; ++guard) {
    const int next = nb[t][(i + 1) % 3];
    if (next < 0) {
      visit(RingEntry{tri[t][(i + 2) % 3], t, -1, graph(t, (i + 1) % 3)});
      return;
    }
    if (next == first) return;
    const int previous = t;
    t = next;
    i = corner_of(t);
    visit(RingEntry{tri[t][(i + 1) % 3], previous, t, graph(t, (i + 2) % 3)});
  }
}

/// The rings of the first `wanted` vertices as CSR arrays (ring_begin has wanted + 1 entries).
/// `start` is scratch.
void closure_rings(const ElementClosure& closure, int vertex_count, int wanted, std::vector<int>& ring_begin,
                   std::vector<RingEntry>& ring, std::vector<int>& start);

}  // namespace plmap::detail
