#pragma once
// finalize(), phase 2: closure. Per S1 element, the plane graph of the map (its nodes as slots,
// the element boundary split at them, the graph edges) closed into triangles by the face-based
// fast path (element_closure.hpp) or, where it declines, a constrained Delaunay triangulation;
// then each face of the graph is given the S2 element its nodes map into and the orientation of
// its image there. Private to the builder.

#include "builder_nodes.hpp"
#include "element_closure.hpp"
#include "finalize_buckets.hpp"

#include <plmap/core/types.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace plmap::detail {

/// Per S1 element, the outcome of the closure, which the assembly writes into the flat arrays
/// right away (one per thread, reused from element to element).
struct ElementTriangulation {
  Index element = invalid_index;          // the S1 element
  std::vector<Index> slots;               // builder node of each slot (node order of the element)
  std::vector<LocalPoint<2>> positions;   // of the slots, then of the virtual corners
  std::vector<std::int8_t> location;      // of the slots: corner, local edge, or -1 (inside)
  // The closure itself (triangles, neighbours, faces; triangles touching a virtual corner lie
  // outside D) and the rings stay in the workspace that computed them; per face of the graph:
  struct Component {
    Index target = invalid_index;
    int sign = 0;
    bool outside = false;  // touches a virtual corner
  };
  std::vector<Component> components;
  // Per closure triangle of a face with a target: its corners' images on the target element
  // (computed when the target is chosen, used again for the region's affine map).
  std::vector<std::array<LocalPoint<2>, 3>> corner_images;
  // Per closure triangle of a face with a target: the affine map through those images (computed
  // when the face's triangles are judged, used again as the region's map; only where
  // ClosureWorkspace::corner_maps_wanted, or where the judgement needed it).
  std::vector<AffineMap<2>> corner_maps;
  // Per closure triangle, where some face has no target (an unmapped face: its nodes share no S2
  // element): the S2 element the triangle's own three corners map into, with the sign of its image
  // there (invalid / 0 where it has none); empty if the element has no unmapped face.
  std::vector<Index> split_target;
  std::vector<signed char> split_sign;
  std::vector<int> edge_slots;                // along local edges 0, 1, 2, corners included
  std::array<int, 4> edge_slots_begin{};
  int corner_count = 0;                       // slots at corners of the element
  int centroid_triangle = -1;                 // a closure triangle inside D, or -1

  /// Empties it for the next element, keeping the buffers.
  void clear() {
    slots.clear();
    positions.clear();
    location.clear();
    components.clear();
    split_target.clear();
    split_sign.clear();
    edge_slots.clear();
    edge_slots_begin = {};
    corner_count = 0;
    centroid_triangle = -1;
  }
};

struct DelaunayFallback;  // the constrained Delaunay triangulation, kept from element to element

/// What closing one element needs besides its result: the result (et, closure, rings) and the
/// buffers reused from element to element. One per thread.
struct ClosureWorkspace {
  ClosureWorkspace();
  ~ClosureWorkspace();
  ClosureWorkspace(ClosureWorkspace&&) noexcept;
  ClosureWorkspace& operator=(ClosureWorkspace&&) noexcept;

  ElementTriangulation et;  // the element being closed, assembled right after
  ElementClosure closure;
  std::vector<int> ring_start;  // per vertex, see ring_starts
  long long votes = 0;          // closure triangles of faces along the map's orientation minus against

  // ---- buffers -------------------------------------------------------------------------------
  std::unique_ptr<DelaunayFallback> delaunay;
  ClosureScratch scratch;
  std::vector<ClosureSegment> segments;
  // Constraints as (a, b, graph) packed into one integer each, a < b: sorting integers is
  // cheaper than comparing pairs, and the order is the order of (a, b).
  std::vector<std::uint64_t> segment_keys;
  // Slot of each builder node on the element being closed, -1 elsewhere: the graph edges
  // name builder nodes, and elements may carry thousands of them. Entries of the previous
  // element are reset when the next one starts (also after an exception).
  std::vector<int> slot_of_node;
  std::array<std::vector<int>, 3> edge_inner;
  std::vector<int> face_order, face_begin, comp_nodes, vertex_stamp;
  std::vector<LocalPoint<2>> on_candidate;  // per vertex: its image on a candidate S2 element
  std::vector<int> collapsed_faces;  // faces with a triangle whose image collapses (finalize_closure.cpp)
  std::vector<double> kept_measure;  // per closure triangle of an unmapped face (flip_towards_split)
  // Whether the assembly takes the closure triangles' affine maps as the regions' maps
  // (ElementTriangulation::corner_maps). Where the region maps are written after the closing
  // pass instead (finalize_region_maps.hpp), a triangle's map is computed only when its image
  // is too thin for the orientation test to do without it (judge_face_orientation).
  bool corner_maps_wanted = true;
};

/// Closes S1 element t into w (throws BuilderError where the graph cannot be closed: crossing
/// edges, an edge through a node, coinciding nodes). `orientation` is the map's (+1 or -1), or 0
/// where it is not known yet (the faces then only vote): unmapped faces are re-triangulated
/// towards it before they are split (BuilderOptions::split_unmapped_faces).
void close_element(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                   ClosureWorkspace& w, int orientation);

/// The first half of close_element: the graph of S1 element t closed into triangles in w, its
/// faces neither given their S2 elements nor judged. It throws exactly where close_element does
/// (nothing after it throws), at half the cost of closing and assembling: enough where finalize
/// only asks which elements cannot be closed.
/// Returns false if nothing of the map lies on t.
bool close_graph(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, Index t,
                 ClosureWorkspace& w);

/// Local position of the point at parameter s along local edge k (from corner k). Points lie
/// exactly on their edge line, or exact predicates would see them a rounding step off it.
LocalPoint<2> on_local_edge(int k, double s);

/// Local position of a builder node on S1 element t, which contains it.
LocalPoint<2> node_local(const BuilderContents<2>& in, Index node, Index t);

}  // namespace plmap::detail
