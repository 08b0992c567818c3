#pragma once
/// \file
/// Shrinking the domain of a finished triangle map along lines inside its elements:
/// clip_regions() keeps of each named region only the part on one side of a line.
///
/// remove_regions() (face_removal.hpp) takes regions out whole. Where only part of a region has
/// to leave D (the part of a region past the fold curve of a projection, or under the image of a
/// nearer sheet), that costs the rest as well. clip_regions() cuts the region instead: the line
/// meets two of its sides at new nodes whose images come from the region's own affine map, so Xi
/// does not change anywhere on what stays. The part on the kept side is re-triangulated into
/// regions with the region's S2 element and affine map; the part beyond leaves D, and D ends on
/// the segment between the two new nodes, a side between two rim nodes as where a projection's
/// S2 leaves the band of admissible distances (docs/data-model.md, "The rim of D").
///
/// A new node inside the element is a rim_inside node (node_target: the S2 edge its image lies
/// on when the cut side is the preimage of one, else none); one on the element's boundary is a
/// rim_on_edge node, with a copy in every other element at that S1 edge. Every other region
/// that has the cut side (across it in the same element, or along the S1 edge in the element
/// beyond) is split at the new node into two regions of its own S2 element and affine map, so
/// the regions still meet side to side. Graph edges are kept as remove_regions keeps them: the
/// pieces of S2 edges' preimages stay, closure edges that bordered only the part that left go.

#include <plmap/core/pl_map.hpp>

#include <span>
#include <vector>

namespace plmap {

/// Keep the part of `region` where normal · xi + offset >= 0, xi local coordinates on the
/// region's S1 element.
struct RegionClip {
  Index region = invalid_index;
  LocalPoint<2> normal = LocalPoint<2>::Zero();
  double offset = 0.0;
};

struct RegionClipReport {
  Index clipped_regions = 0;  ///< regions cut by their line (part kept)
  Index removed_regions = 0;  ///< regions wholly beyond their line
  Index split_regions = 0;    ///< other regions split at a new node on one of their sides
  Index new_nodes = 0;        ///< new nodes, copies on S1 edges counted once per element
  /// The S1 elements whose nodes or regions changed (sorted).
  std::vector<Index> changed_elements;
};

/// The map with each named region cut by its line (see above). A line that passes within
/// 1e-6 of a side's length of a corner passes through that corner; a region with no corner
/// strictly on the kept side leaves whole, one with no corner strictly beyond stays whole.
/// Throws InvalidMapError if a region is out of range or named twice, or if a normal is zero.
/// Works on the map's stored form: only the elements that change are looked at (their graph
/// taken from the stored graph or derived from their regions), the others are copied. `threads`:
/// up to that many threads (0: all the process may use) make the changed elements and move the
/// arrays; the map is the same for every count.
PlMap<2> clip_regions(PlMap<2>&& map, std::span<const RegionClip> clips, RegionClipReport* report = nullptr,
                      unsigned threads = 1);
/// The same on a copy of `map`.
PlMap<2> clip_regions(const PlMap<2>& map, std::span<const RegionClip> clips, RegionClipReport* report = nullptr,
                      unsigned threads = 1);

}  // namespace plmap
