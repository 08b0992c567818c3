#pragma once
// finalize(), phase 4: joining. The parts assembled per block of elements (each numbered from 0)
// become one map: arrays are concatenated and node, region and entry indices shifted by the
// sizes of the parts before. Private to the builder.

#include <plmap/core/pl_map.hpp>

#include <vector>

namespace plmap::detail {

/// Joins `parts` (blocks of consecutive elements, in element order, together covering `elements`
/// elements) into m, keeping m.orientation, on up to `threads` threads. One array at a time, with
/// the parts' copies of it released as soon as it is joined: the parts and the map are then
/// never held whole at once (with two blocks the peak of the 200k plane pair was the map twice
/// over).
void join_parts(std::vector<MapData<2>>& parts, Index elements, unsigned threads, MapData<2>& m);

}  // namespace plmap::detail
