#pragma once
/// \file
/// An order of points along a Morton (Z-order) curve: points near each other in space come near
/// each other in the order. Normal projection renumbers surfaces in a poor order this way
/// (ProjectionOptions::renumbering), and the peers benchmark its inputs (--order spatial).

#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/parallel_sort.hpp>
#include <plmap/core/types.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace plmap {

namespace detail {

/// Bit i of the low 32 bits of x moved to bit 2i (the others cleared): each step moves the upper
/// half of every group of bits up by half the group's new spacing.
constexpr std::uint64_t spread_to_every_second_bit(std::uint64_t x) {
  x &= 0xffffffffu;
  x = (x | (x << 16)) & 0x0000ffff0000ffffu;
  x = (x | (x << 8)) & 0x00ff00ff00ff00ffu;
  x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0fu;
  x = (x | (x << 2)) & 0x3333333333333333u;
  x = (x | (x << 1)) & 0x5555555555555555u;
  return x;
}

/// Bit i of the low 21 bits of x moved to bit 3i (the others cleared), the same way.
constexpr std::uint64_t spread_to_every_third_bit(std::uint64_t x) {
  x &= 0x1fffffu;
  x = (x | (x << 32)) & 0x001f00000000ffffu;
  x = (x | (x << 16)) & 0x001f0000ff0000ffu;
  x = (x | (x << 8)) & 0x100f00f00f00f00fu;
  x = (x | (x << 4)) & 0x10c30c30c30c30c3u;
  x = (x | (x << 2)) & 0x1249249249249249u;
  return x;
}

}  // namespace detail

/// Interleaves the `bits` low bits of the cell coordinates, most significant first (x before y):
/// bit b of coordinate k becomes bit b n + (n - 1 - k) of the code (bits n <= 64).
///
/// For two and three coordinates the bits are spread apart by shifts and masks, a few operations
/// per coordinate instead of one loop step per bit (63 steps per point were a sixth of the
/// projection's renumbering of a CGAL mesh); the codes are the same (tests/core/test_morton_order.cpp
/// compares them with the bit loop).
template <std::size_t n>
std::uint64_t morton_code(const std::array<std::uint32_t, n>& cell, int bits) {
  if constexpr (n == 2) {
    const std::uint64_t low_bits = (std::uint64_t{1} << bits) - 1;  // bits <= 32
    return detail::spread_to_every_second_bit(cell[0] & low_bits) << 1 | detail::spread_to_every_second_bit(cell[1] & low_bits);
  } else if constexpr (n == 3) {
    const std::uint64_t low_bits = (std::uint64_t{1} << bits) - 1;  // bits <= 21
    return detail::spread_to_every_third_bit(cell[0] & low_bits) << 2 | detail::spread_to_every_third_bit(cell[1] & low_bits) << 1 |
           detail::spread_to_every_third_bit(cell[2] & low_bits);
  } else {
    std::uint64_t code = 0;
    for (int b = bits - 1; b >= 0; --b)
      for (std::size_t k = 0; k < n; ++k) code = (code << 1) | ((cell[k] >> b) & 1u);
    return code;
  }
}

/// The indices 0 .. count - 1 sorted by the Morton code of point(i)'s place in the box
/// [low, high] (63 / (d + 1) bits per coordinate); equal codes keep their index order, so the
/// order is deterministic and the same for every thread count. The codes are computed and sorted
/// on up to `threads` threads (0: all the process may run on). Taking the points as a function
/// spares the caller an array of them (the projection's centroids: fresh memory, which on the
/// benchmark machine costs more than computing them).
template <int d, class PointOf>
std::vector<Index> morton_order_of(std::size_t count, const PointOf& point, const WorldPoint<d>& low,
                                   const WorldPoint<d>& high, unsigned threads = 1) {
  constexpr std::size_t n = d + 1;
  constexpr int bits = 63 / static_cast<int>(n);
  const WorldPoint<d> extent = high - low;
  // the index in the key makes every key distinct, hence ties in index order and one sorted
  // result for every thread count (parallel_sort.hpp); left unwritten until the threads fill it,
  // so that each thread touches its own pages first
  struct Key {
    std::uint64_t code;
    Index index;
    bool operator<(const Key& o) const { return code != o.code ? code < o.code : index < o.index; }
  };
  const auto keyed = std::make_unique_for_overwrite<Key[]>(count);
  populate_in_parallel(keyed.get(), count * sizeof(Key), threads);  // backed in one call per thread
  parallel_ranges(count, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const WorldPoint<d> p = point(i);
      std::array<std::uint32_t, n> cell;
      for (std::size_t k = 0; k < n; ++k) {
        const auto axis = static_cast<Eigen::Index>(k);
        const double unit = extent(axis) > 0.0 ? (p(axis) - low(axis)) / extent(axis) : 0.0;
        cell[k] = static_cast<std::uint32_t>(std::clamp(unit, 0.0, 1.0) * double((std::uint32_t{1} << bits) - 1));
      }
      keyed[i] = {morton_code<n>(cell, bits), static_cast<Index>(i)};
    }
  });
  parallel_sort(keyed.get(), keyed.get() + count, threads);
  std::vector<Index> order;
  assign_on_huge_pages(order, count, Index{0}, threads);
  parallel_ranges(count, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) order[i] = keyed[i].index;
  });
  return order;
}

/// morton_order_of for points given in an array.
template <int d>
std::vector<Index> morton_order(std::span<const WorldPoint<d>> points, const WorldPoint<d>& low,
                                const WorldPoint<d>& high, unsigned threads = 1) {
  return morton_order_of<d>(points.size(), [&](std::size_t i) { return points[i]; }, low, high, threads);
}

}  // namespace plmap
