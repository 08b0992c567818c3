#pragma once
/// \file
/// An order of points along a Morton (Z-order) curve: points near each other in space come near
/// each other in the order. Normal projection renumbers surfaces in a poor order this way
/// (ProjectionOptions::renumbering), and the peers benchmark its inputs (--order spatial).

#include <plmap/core/types.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace plmap {

/// Interleaves the `bits` low bits of the cell coordinates, most significant first (x before y).
template <std::size_t n>
std::uint64_t morton_code(const std::array<std::uint32_t, n>& cell, int bits) {
  std::uint64_t code = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (std::size_t k = 0; k < n; ++k) code = (code << 1) | ((cell[k] >> b) & 1u);
  return code;
}

/// The indices of `points` sorted by the Morton code of their place in the box [low, high]
/// (63 / (d + 1) bits per coordinate); equal codes keep their index order, so the order is
/// deterministic.
template <int d>
std::vector<Index> morton_order(std::span<const WorldPoint<d>> points, const WorldPoint<d>& low,
                                const WorldPoint<d>& high) {
  constexpr std::size_t n = d + 1;
  constexpr int bits = 63 / static_cast<int>(n);
  const WorldPoint<d> extent = high - low;
  std::vector<std::pair<std::uint64_t, Index>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::array<std::uint32_t, n> cell;
    for (std::size_t k = 0; k < n; ++k) {
      const auto axis = static_cast<Eigen::Index>(k);
      const double unit = extent(axis) > 0.0 ? (points[i](axis) - low(axis)) / extent(axis) : 0.0;
      cell[k] = static_cast<std::uint32_t>(std::clamp(unit, 0.0, 1.0) * double((std::uint32_t{1} << bits) - 1));
    }
    keyed[i] = {morton_code<n>(cell, bits), static_cast<Index>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<Index> order(points.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace plmap
