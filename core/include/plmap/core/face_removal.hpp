#pragma once
/// \file
/// Shrinking the domain of a finished map: remove_faces() takes faces of the graph out of D,
/// remove_regions() named regions.
///
/// A face is what the triangular closure cut into regions: the regions of one S1 element joined
/// across closure edges (d = 1: a region on its own). Removing a face removes its regions, and
/// with them the closure edges that no longer border a region (d = 1: the graph edge of the
/// region). Nodes, graph edges (preimages of S2 edges) and the edge arrays stay: the graph is
/// still the preimage of S2's edge graph; only D, and so the regions, shrink.
///
/// An element whose corners and boundary are all covered by regions is expected to be covered
/// entirely (the region_tiling invariant of verify/): what leaves D must reach the element
/// boundary, or take the whole element, but for holes bounded by S2's boundary or by the rim of
/// a projection (rim edges). So a removed face that lies strictly inside its element (no side
/// along the element boundary) takes all regions of that element with it.
///
/// remove_regions() takes out only the named regions where that leaves no hole strictly inside
/// an element: the named regions of a face joined across closure edges (a part of the face) go
/// alone when the part has a side on its element's boundary; D then ends along the closure edges
/// between the part and the rest of its face, and the rest keeps its regions and images. A part
/// strictly inside its element takes its whole face, as remove_faces() does (and the face, if it
/// too lies strictly inside, the element). Curves (d = 1): a region is a face.
///
/// Normal projection uses remove_regions() to leave out the farther of two sheets whose images
/// overlap on S2 and the regions whose rays pass a focal point (construct/, image overlaps,
/// folded regions): each names every region concerned, so the rest of a face is not.

#include <plmap/core/pl_map.hpp>

#include <span>

namespace plmap {

struct FaceRemovalReport {
  /// Faces named (through one of their regions) that were removed, whole or (remove_regions) in
  /// part; partial_faces of them in part.
  Index removed_faces = 0;
  Index partial_faces = 0;
  Index removed_regions = 0;  ///< regions removed in all, including whole cleared elements
  /// Elements whose regions were all removed because a removed face lay strictly inside them.
  Index cleared_elements = 0;
};

/// The map without the faces that contain the given regions (any order, repeats allowed).
/// Throws InvalidMapError if a region index is out of range. `threads`: up to that many threads
/// (0: all the process may use) re-decide which elements keep a stored graph; the map is the same
/// for every count.
template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_faces(const PlMap<d>& map, std::span<const Index> regions, FaceRemovalReport* report = nullptr,
                      unsigned threads = 1);

/// The same, reusing the map's arrays: the cost is one pass over the regions and (if entries
/// leave) the neighbour lists, and no copy (a sheet selection on a million-node map removes a
/// few dozen regions).
template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_faces(PlMap<d>&& map, std::span<const Index> regions, FaceRemovalReport* report = nullptr,
                      unsigned threads = 1);

/// The map without the named regions (any order, repeats allowed), except where a part of a face
/// lies strictly inside its element: then without that face (see above). Reuses the map's arrays
/// as remove_faces(PlMap&&) does. Throws InvalidMapError if a region index is out of range.
template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_regions(PlMap<d>&& map, std::span<const Index> regions, FaceRemovalReport* report = nullptr,
                        unsigned threads = 1);

extern template PlMap<1> remove_faces<1>(const PlMap<1>&, std::span<const Index>, FaceRemovalReport*, unsigned);
extern template PlMap<2> remove_faces<2>(const PlMap<2>&, std::span<const Index>, FaceRemovalReport*, unsigned);
extern template PlMap<1> remove_faces<1>(PlMap<1>&&, std::span<const Index>, FaceRemovalReport*, unsigned);
extern template PlMap<2> remove_faces<2>(PlMap<2>&&, std::span<const Index>, FaceRemovalReport*, unsigned);
extern template PlMap<1> remove_regions<1>(PlMap<1>&&, std::span<const Index>, FaceRemovalReport*, unsigned);
extern template PlMap<2> remove_regions<2>(PlMap<2>&&, std::span<const Index>, FaceRemovalReport*, unsigned);

}  // namespace plmap
