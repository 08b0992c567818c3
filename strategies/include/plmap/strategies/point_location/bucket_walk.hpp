#pragma once
/// \file
/// BucketWalk: jump-and-walk. Each element's reference square is cut into a G x G grid of
/// buckets (G grows like the square root of the element's region count); every bucket remembers a
/// region near it, and the Brown–Faigle walk starts from the query's bucket instead of the
/// element's single start region. Expected walk length drops from O(sqrt n) to O(1) on
/// well-shaped graphs, for about 2 bytes per region.
///
/// The bucket table is derived from the map on first use (and rebuilt if the locator is used on
/// another map); copies share it. Correctness is the walk's: exact containment, brute-force
/// fallback.

#include <plmap/strategies/point_location/brown_faigle_walk.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace plmap::point_location {

/// Per-element bucket grids of start regions for one map.
class StartBuckets {
 public:
  explicit StartBuckets(const PlMap<2>& map);
  bool built_for(const PlMap<2>& map) const {
    return map_ == &map && regions_ == map.region_count() &&
           static_cast<std::size_t>(map.domain().element_count()) == begin_.size();
  }

  Index start(Index element, const LocalPoint<2>& p) const {
    const int g = size_[element];
    const auto cell = [g](double x) {
      return std::clamp(static_cast<int>(x * g), 0, g - 1);  // NaN-free: x is finite
    };
    return cells_[begin_[element] + cell(p(0)) * g + cell(p(1))];
  }

  std::size_t memory_bytes() const {
    return begin_.capacity() * sizeof(Index) + size_.capacity() + cells_.capacity() * sizeof(Index);
  }

 private:
  const PlMap<2>* map_;
  Index regions_;
  std::vector<Index> begin_;
  std::vector<std::uint8_t> size_;
  std::vector<Index> cells_;
};

class BucketWalk {
 public:
  explicit BucketWalk(std::uint64_t seed = BrownFaigleWalk::default_seed) : walk_(seed) {}

  RegionLocation<2> locate(const PlMap<2>& map, Index element, const LocalPoint<2>& p) {
    prepare(map);
    Index start = buckets_->start(element, p);
    // A table outlived by its map (another map at the same address) must never index out of
    // range: starts are checked against the element's regions.
    if (start < map.regions_begin(element) || start >= map.regions_end(element))
      start = map.stored().start_region[element];
    return walk_.walk_from(map, element, p, start);
  }

  /// Builds the bucket table now (evaluate_batch copies the locator per thread; preparing it
  /// first lets the copies share one table).
  void prepare(const PlMap<2>& map) {
    if (!buckets_ || !buckets_->built_for(map)) buckets_ = std::make_shared<const StartBuckets>(map);
  }

  /// Bytes of the bucket table (0 before prepare); not part of the map's compact form.
  std::size_t memory_bytes() const { return buckets_ ? buckets_->memory_bytes() : 0; }

 private:
  BrownFaigleWalk walk_;
  std::shared_ptr<const StartBuckets> buckets_;
};

static_assert(PointLocator<BucketWalk, 2>);

}  // namespace plmap::point_location
