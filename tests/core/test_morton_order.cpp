// plmap::morton_order (core/spatial_order.hpp): points sorted along the Z-order curve of their
// box, x's bit before y's at every level, equal codes in index order; the codes computed by
// spreading bits equal their bit-by-bit definition, and the order is the same on every thread count.
#include <plmap/core/spatial_order.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

using namespace plmap;

TEST(MortonOrder, TheCornersOfASquareComeInZOrder) {
  // the four corners of the unit square, listed in reverse Z order
  const std::vector<WorldPoint<1>> p{{1.0, 1.0}, {1.0, 0.0}, {0.0, 1.0}, {0.0, 0.0}};
  const auto order = morton_order<1>(std::span<const WorldPoint<1>>(p), WorldPoint<1>(0.0, 0.0), WorldPoint<1>(1.0, 1.0));
  // (0,0), (0,1), (1,0), (1,1): the x bit is the more significant of each pair
  EXPECT_EQ(order, (std::vector<Index>{3, 2, 1, 0}));
}

TEST(MortonOrder, QuadrantsComeOneAfterTheOtherAndTiesKeepTheirOrder) {
  // a 4 x 4 x 4 lattice (d = 2 points) listed backwards, and a duplicate of the first point
  std::vector<WorldPoint<2>> p;
  for (int i = 63; i >= 0; --i) p.emplace_back(i % 4, (i / 4) % 4, i / 16);
  p.push_back(p.front());
  const auto order = morton_order<2>(std::span<const WorldPoint<2>>(p), WorldPoint<2>(0, 0, 0), WorldPoint<2>(3, 3, 3));
  ASSERT_EQ(order.size(), p.size());
  // the first eight are the octant nearest the origin: coordinates 0 or 1 only
  for (int i = 0; i < 8; ++i) EXPECT_LE(p[static_cast<std::size_t>(order[i])].maxCoeff(), 1.0) << i;
  // the last two are the corner (3, 3, 3) and its duplicate, in index order
  EXPECT_EQ(order[63], 0);
  EXPECT_EQ(order[64], 64);
}

namespace {

/// The definition of the code: bit b of coordinate k at place b n + (n - 1 - k), one bit at a
/// time, most significant first (what morton_code computed before it spread bits with masks).
template <std::size_t n>
std::uint64_t morton_code_bit_by_bit(const std::array<std::uint32_t, n>& cell, int bits) {
  std::uint64_t code = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (std::size_t k = 0; k < n; ++k) code = (code << 1) | ((cell[k] >> b) & 1u);
  return code;
}

template <std::size_t n>
void expect_codes_as_defined(int bits, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (int i = 0; i < 20000; ++i) {
    std::array<std::uint32_t, n> cell;
    // full 32-bit words: bits above `bits` must be ignored; every tenth cell at the box's corners
    for (auto& c : cell) c = i % 10 == 0 ? (i % 20 == 0 ? 0u : ~0u) : static_cast<std::uint32_t>(rng());
    ASSERT_EQ(morton_code<n>(cell, bits), morton_code_bit_by_bit<n>(cell, bits)) << "bits " << bits << ", cell " << i;
  }
}

}  // namespace

TEST(MortonCode, SpreadBitsGiveTheCodesOfTheBitByBitDefinition) {
  for (int bits : {1, 5, 16, 20, 21}) expect_codes_as_defined<3>(bits, 7 + static_cast<std::uint64_t>(bits));
  for (int bits : {1, 7, 16, 31, 32}) expect_codes_as_defined<2>(bits, 11 + static_cast<std::uint64_t>(bits));
  expect_codes_as_defined<4>(15, 3);  // other counts keep the loop
}

TEST(MortonOrder, TheOrderIsTheSameOnEveryThreadCountAndTiesKeepTheirIndexOrder) {
  // 60,000 points (more than one thread's share, so the keys are computed and sorted on
  // several), many of them in the same cell, some outside the box
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> coordinate(-0.1, 1.1);
  std::vector<WorldPoint<2>> p;
  for (int i = 0; i < 60000; ++i) {
    if (i % 7 == 3) p.push_back(p[static_cast<std::size_t>(i / 2)]);
    else p.emplace_back(coordinate(rng), coordinate(rng), i % 5 == 0 ? 0.5 : coordinate(rng));
  }
  const WorldPoint<2> low(0, 0, 0), high(1, 1, 1);
  const auto one = morton_order<2>(std::span<const WorldPoint<2>>(p), low, high, 1);
  // the definition: stable sort of the indices by code
  std::vector<std::pair<std::uint64_t, Index>> keyed;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::array<std::uint32_t, 3> cell;
    for (int k = 0; k < 3; ++k)
      cell[static_cast<std::size_t>(k)] =
          static_cast<std::uint32_t>(std::clamp(p[i](k), 0.0, 1.0) * double((std::uint32_t{1} << 21) - 1));
    keyed.emplace_back(morton_code_bit_by_bit<3>(cell, 21), static_cast<Index>(i));
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Index> expected;
  for (const auto& k : keyed) expected.push_back(k.second);
  EXPECT_EQ(one, expected);
  for (unsigned threads : {2u, 3u, 8u}) EXPECT_EQ(morton_order<2>(std::span<const WorldPoint<2>>(p), low, high, threads), one) << threads;
}
