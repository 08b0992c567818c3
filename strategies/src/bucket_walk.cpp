#include <plmap/strategies/point_location/bucket_walk.hpp>

namespace plmap::point_location {

StartBuckets::StartBuckets(const PlMap<2>& map) : map_(&map), regions_(map.region_count()) {
  const MapData<2>& m = map.stored();
  const Index elements = map.domain().element_count();
  begin_.resize(elements);
  size_.resize(elements);
  for (Index t = 0; t < elements; ++t) {
    const Index n = m.region_begin[t + 1] - m.region_begin[t];
    // about two regions per bucket; at most 32 x 32
    const int g = std::clamp(static_cast<int>(std::lround(std::sqrt(n / 2.0))), 1, 32);
    size_[t] = static_cast<std::uint8_t>(g);
    begin_[t] = static_cast<Index>(cells_.size());
    cells_.resize(cells_.size() + static_cast<std::size_t>(g) * g, invalid_index);
    Index* cell = cells_.data() + begin_[t];
    if (n == 0) continue;
    // Each region claims the bucket of its centroid.
    for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r) {
      const auto& c = m.region_corners[r];
      const LocalPoint<2> centroid =
          (m.node_position[c[0]] + m.node_position[c[1]] + m.node_position[c[2]]) / 3.0;
      const int i = std::clamp(static_cast<int>(centroid(0) * g), 0, g - 1);
      const int j = std::clamp(static_cast<int>(centroid(1) * g), 0, g - 1);
      cell[i * g + j] = r;
    }
    // Empty buckets borrow from a neighbour in their row, else the element's start region: any
    // region is a correct start, a near one only makes the walk short.
    for (int i = 0; i < g; ++i) {
      Index last = invalid_index;
      for (int j = 0; j < g; ++j) {
        if (cell[i * g + j] == invalid_index)
          cell[i * g + j] = last;
        else
          last = cell[i * g + j];
      }
      last = invalid_index;
      for (int j = g - 1; j >= 0; --j) {
        if (cell[i * g + j] == invalid_index)
          cell[i * g + j] = last;
        else
          last = cell[i * g + j];
      }
      for (int j = 0; j < g; ++j)
        if (cell[i * g + j] == invalid_index) cell[i * g + j] = m.start_region[t];
    }
  }
}

}  // namespace plmap::point_location
