#pragma once
// remove_faces (face_removal.hpp) on a triangle map's stored form. A triangle map stores its
// nodes and regions and derives its graph (PlMap, docs/data-model.md); removing faces through
// the full arrays derived the whole graph, and the smaller map, handed its full arrays, compared
// every element's graph with the derivation again: on the armadillo projection, which removes a
// few dozen regions twice, that was most of the two removals. Here only the elements that lose
// regions are looked at: their graph (stored, or derived from their regions) loses the entries
// that leave, and after the regions are compacted each of them keeps its graph in the stored
// graph exactly when its regions no longer give it back, which is what the full-array
// constructor would keep. Every other element's graph follows from its regions as before.

#include "face_removal_rules.hpp"

#include <plmap/core/face_removal.hpp>

#include <optional>
#include <span>
#include <vector>

namespace plmap::detail {

/// The map without the faces of the named regions, or with RemovalExtent::named_regions without
/// the named regions (face_removal_rules.hpp; indices already checked to be in range), built from
/// its stored form; `map` is consumed. Nothing (and `map` untouched) where an element that loses
/// regions has regions that do not give its graph back and no stored graph (a damaged map): the
/// caller then takes the full-array path. The graphs are derived and compared on up to `threads`
/// threads, in pieces of elements joined in element order: the same map for every count.
std::optional<PlMap<2>> remove_faces_in_stored_form(PlMap<2>& map, std::span<const Index> regions,
                                                    RemovalExtent extent, FaceRemovalReport& report,
                                                    unsigned threads);

/// Drops the removed regions from m's region arrays in place, keeping the order of the rest,
/// and renumbers the region neighbours (when m holds them) and start regions; renumbered[r] is
/// r's new index or invalid_index. Returns how many regions are kept.
template <int d>
Index compact_regions(MapData<d>& m, Index element_count, const std::vector<char>& removed,
                      std::vector<Index>& renumbered);

}  // namespace plmap::detail
