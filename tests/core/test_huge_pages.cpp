// The huge-page helpers (core/huge_page_allocator.hpp) and the parallel first touch
// (core/parallel_first_touch.hpp) change only where memory comes from and which thread backs it, never
// what it holds: large arrays keep every value, are aligned to 2 MiB, and marking a range that
// is small, unaligned or already written is harmless. (Whether the kernel then backs a range
// with huge pages depends on its settings, so that is measured by benchmarks, not asserted.)
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/surface.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

using namespace plmap;

TEST(HugePages, LargeArraysAreAlignedAndKeepTheirValues) {
  std::vector<std::uint32_t, HugePageAllocator<std::uint32_t>> big(3'000'000);
  std::iota(big.begin(), big.end(), 7u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(big.data()) % HugePageAllocator<char>::huge_page_bytes, 0u);
  big.push_back(1);  // grows into a new block: the values move with it
  for (std::size_t i = 0; i < 3'000'000; i += 99'991) ASSERT_EQ(big[i], 7u + i);
  EXPECT_EQ(big.back(), 1u);
  std::vector<int, HugePageAllocator<int>> small(10, 3);  // below a huge page: an ordinary block
  EXPECT_EQ(std::accumulate(small.begin(), small.end(), 0), 30);
}

TEST(HugePages, ReservingKeepsWhatIsWrittenAndMarkingAnyRangeIsHarmless) {
  std::vector<double> v = {1.5, 2.5, 3.5};
  reserve_on_huge_pages(v, 1'000'000);
  EXPECT_GE(v.capacity(), 1'000'000u);
  EXPECT_EQ(v, (std::vector<double>{1.5, 2.5, 3.5}));
  v.resize(1'000'000, 4.5);
  EXPECT_EQ(v[999'999], 4.5);
  reserve_on_huge_pages(v, 10);  // less than there is: nothing changes
  EXPECT_EQ(v.size(), 1'000'000u);
  advise_huge_pages(v.data() + 1, 17);                 // unaligned and small
  advise_huge_pages(v.data(), v.size() * sizeof(double));  // written already
  advise_huge_pages(nullptr, 0);
  EXPECT_EQ(v[0], 1.5);
  EXPECT_EQ(v[2], 3.5);
}

TEST(HugePages, AssigningOnHugePagesFillsLikeAssign) {
  std::vector<int> big;
  assign_on_huge_pages(big, 2'000'000, -1);  // several huge pages
  EXPECT_EQ(big, std::vector<int>(2'000'000, -1));
  std::vector<double> zeros;
  assign_on_huge_pages(zeros, 5);  // value-initialized, below a huge page
  EXPECT_EQ(zeros, std::vector<double>(5, 0.0));
  std::vector<int> refilled = {1, 2, 3};
  assign_on_huge_pages(refilled, 2, 9);  // replaces what was there, as assign does
  EXPECT_EQ(refilled, (std::vector<int>{9, 9}));
}

TEST(HugePages, BackingMemoryOnSeveralThreadsKeepsWhatItHolds) {
  // 12 MiB: several 2 MiB pieces, the range starting and ending inside pages
  std::vector<std::uint32_t> v(3'000'000);
  std::iota(v.begin(), v.end(), 11u);
  for (unsigned threads : {0u, 1u, 2u, 3u}) {
    populate_in_parallel(reinterpret_cast<char*>(v.data()) + 3, v.size() * sizeof(std::uint32_t) - 5, threads);
    for (std::size_t i = 0; i < v.size(); i += 7'919) ASSERT_EQ(v[i], 11u + i) << threads << " threads";
    EXPECT_EQ(v.back(), 11u + 2'999'999u);
  }
  populate_in_parallel(nullptr, 0, 2);
  populate_in_parallel(v.data(), 1, 2);  // less than a page
  EXPECT_EQ(v.front(), 11u);
  // fresh room, backed first: reads as what assign writes there
  for (unsigned threads : {1u, 2u, 3u}) {
    std::vector<std::int64_t> filled = {1, 2, 3};
    assign_on_huge_pages(filled, 2'500'000, std::int64_t{-4}, threads);
    EXPECT_EQ(filled, std::vector<std::int64_t>(2'500'000, -4)) << threads << " threads";
    assign_on_huge_pages(filled, 2, std::int64_t{9}, threads);  // fewer than there are, as assign does
    EXPECT_EQ(filled, (std::vector<std::int64_t>{9, 9}));
  }
}

TEST(HugePages, ASurfaceMovedOntoHugePagesKeepsItsVerticesAndElements) {
  // above one huge page of vertices: Surface copies them onto marked pages
  const int n = 400;
  std::vector<WorldPoint<2>> vertices;
  std::vector<ElementCorners<2>> elements;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) vertices.emplace_back(i, j, 0.5 * i - 0.25 * j);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      elements.push_back({a, b, d});
      elements.push_back({a, d, c});
    }
  ASSERT_GT(vertices.size() * sizeof(WorldPoint<2>), HugePageAllocator<char>::huge_page_bytes);
  const Surface<2> s(vertices, elements);
  EXPECT_EQ(s.vertices(), vertices);
  EXPECT_EQ(s.elements(), elements);
  EXPECT_EQ(s.edge_count(), 3 * n * n + 2 * n);
}
