#pragma once
/// \file
/// Shrinking the domain of a finished map: remove_faces() takes faces of the graph out of D.
///
/// A face is what the triangular closure cut into regions: the regions of one S1 element joined
/// across closure edges (d = 1: a region on its own). Removing a face removes its regions, and
/// with them the closure edges that no longer border a region (d = 1: the graph edge of the
/// region). Nodes, graph edges (preimages of S2 edges) and the edge arrays stay: the graph is
/// still the preimage of S2's edge graph; only D, and so the regions, shrink.
///
/// An element whose corners and boundary are all covered by regions is expected to be covered
/// entirely (the region_tiling invariant of verify/): D is a union of faces each of which
/// reaches the element boundary, or of whole elements, but for holes bounded by S2's boundary
/// or by the rim of a projection (rim edges). So a removed face that lies strictly inside its
/// element (no side along the element boundary) takes all regions of that element with it.
///
/// Normal projection uses this to keep only the nearer of two sheets whose images overlap on S2
/// (construct/, image overlaps).

#include <plmap/core/pl_map.hpp>

#include <span>

namespace plmap {

struct FaceRemovalReport {
  Index removed_faces = 0;    ///< faces named (through one of their regions) that were removed
  Index removed_regions = 0;  ///< regions removed in all, including whole cleared elements
  /// Elements whose regions were all removed because a removed face lay strictly inside them.
  Index cleared_elements = 0;
};

/// The map without the faces that contain the given regions (any order, repeats allowed).
/// Throws InvalidMapError if a region index is out of range.
template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_faces(const PlMap<d>& map, std::span<const Index> regions, FaceRemovalReport* report = nullptr);

/// The same, reusing the map's arrays: the cost is one pass over the regions and (if entries
/// leave) the neighbour lists, and no copy (a sheet selection on a million-node map removes a
/// few dozen regions).
template <int d>
  requires SurfaceDimension<d>
PlMap<d> remove_faces(PlMap<d>&& map, std::span<const Index> regions, FaceRemovalReport* report = nullptr);

extern template PlMap<1> remove_faces<1>(const PlMap<1>&, std::span<const Index>, FaceRemovalReport*);
extern template PlMap<2> remove_faces<2>(const PlMap<2>&, std::span<const Index>, FaceRemovalReport*);
extern template PlMap<1> remove_faces<1>(PlMap<1>&&, std::span<const Index>, FaceRemovalReport*);
extern template PlMap<2> remove_faces<2>(PlMap<2>&&, std::span<const Index>, FaceRemovalReport*);

}  // namespace plmap
