// The huge-page helpers (core/huge_page_allocator.hpp) and the parallel first touch
// (core/parallel_first_touch.hpp) change only where memory comes from and which thread backs it, never
// what it holds: large arrays keep every value, are aligned to 2 MiB, and marking a range that
// is small, unaligned or already written is harmless. (Whether the kernel then backs a range
// with huge pages depends on its settings, so that is measured by benchmarks, not asserted.)
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/surface.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <new>
#include <numeric>
#include <type_traits>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

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

TEST(HugePages, ALargerThresholdTakesHugePagesOnlyFromThereOn) {
  constexpr std::size_t threshold = std::size_t{8} << 20;
  using Allocator = HugePageAllocator<std::uint64_t, threshold>;
  // rebinding keeps the threshold (std::vector and the node containers rebind)
  static_assert(std::is_same_v<std::allocator_traits<Allocator>::rebind_alloc<char>, HugePageAllocator<char, threshold>>);
  std::vector<std::uint64_t, Allocator> middle(500'000);  // 4 MiB: below the threshold, an ordinary block
  std::iota(middle.begin(), middle.end(), std::uint64_t{3});
  std::vector<std::uint64_t, Allocator> large(2'000'000);  // 16 MiB: on huge pages, aligned to them
  std::iota(large.begin(), large.end(), std::uint64_t{5});
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(large.data()) % Allocator::huge_page_bytes, 0u);
  middle.resize(1'500'000, 1);  // grows across the threshold: the values move with it
  large.resize(10);             // and back: the block stays until the vector goes
  large.shrink_to_fit();        // below the threshold again
  for (std::size_t i = 0; i < 500'000; i += 49'999) ASSERT_EQ(middle[i], 3u + i);
  EXPECT_EQ(middle.back(), 1u);
  EXPECT_EQ(large, (std::vector<std::uint64_t, Allocator>{5, 6, 7, 8, 9, 10, 11, 12, 13, 14}));
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

#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
/// How many of the whole pages in [p, p + bytes) are resident (mincore).
static std::size_t resident_pages(const void* p, std::size_t bytes, std::size_t& pages) {
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + page - 1) & ~(page - 1), last = (begin + bytes) & ~(page - 1);
  pages = (last - first) / page;
  std::vector<unsigned char> in_core(pages);
  if (mincore(reinterpret_cast<void*>(first), last - first, in_core.data()) != 0) return 0;
  return static_cast<std::size_t>(std::count_if(in_core.begin(), in_core.end(), [](unsigned char c) { return c & 1; }));
}

/// Whether this kernel knows MADV_POPULATE_WRITE, which backing pages needs.
static bool kernel_backs_pages() {
  void* probe = mmap(nullptr, 1 << 16, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (probe == MAP_FAILED) return false;
  const bool known = madvise(probe, 1 << 16, MADV_POPULATE_WRITE) == 0;
  munmap(probe, 1 << 16);
  return known;
}

TEST(HugePages, BackingMemoryOnSeveralThreadsMakesItResident) {
  // the kernel must know MADV_POPULATE_WRITE (Linux 5.14); elsewhere backing is a no-op
  if (!kernel_backs_pages()) GTEST_SKIP() << "this kernel has no MADV_POPULATE_WRITE";
  for (unsigned threads : {1u, 2u, 3u}) {
    // a fresh mapping of 24 MB, never written: none of it resident yet (a mapping of its own, so
    // that no allocator hands back memory touched before)
    const std::size_t mapped = std::size_t{24} << 20;
    void* region = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(region, MAP_FAILED);
    char* p = static_cast<char*>(region) + 100;  // starting and ending inside a page
    const std::size_t bytes = mapped - 1000;
    std::size_t pages = 0;
    const std::size_t before = resident_pages(p, bytes, pages);
    ASSERT_GT(pages, 5000u);
    EXPECT_LT(before, pages / 10) << "fresh room should not be resident";
    populate_in_parallel(p, bytes, threads);
    const std::size_t after = resident_pages(p, bytes, pages);
    EXPECT_EQ(after, pages) << threads << " threads";
    EXPECT_EQ(p[0], 0);  // fresh memory reads as zeros, populated or not
    EXPECT_EQ(p[bytes - 1], 0);
    munmap(region, mapped);
  }
}
/// An allocator that maps every block freshly (never memory the process touched before), in
/// 4 KiB pages, so that what is resident in it is what the code under test made resident.
template <class T>
struct FreshMappingAllocator {
  using value_type = T;
  FreshMappingAllocator() = default;
  template <class U>
  FreshMappingAllocator(const FreshMappingAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    void* p = mmap(nullptr, n * sizeof(T), PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    madvise(p, n * sizeof(T), MADV_NOHUGEPAGE);  // 4 KiB pages whatever the system's default
    return static_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t n) noexcept { munmap(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const FreshMappingAllocator<U>&) const noexcept {
    return true;
  }
};

TEST(HugePages, BackedPagesAreResidentAndKeepWhatTheyHold) {
  // the kernel must know MADV_POPULATE_WRITE (Linux 5.14); elsewhere backing is a no-op
  if (!kernel_backs_pages()) GTEST_SKIP() << "this kernel has no MADV_POPULATE_WRITE";
  // reserve_for_writing backs the room up to n beyond what the vector holds, and no further
  std::vector<std::uint32_t, FreshMappingAllocator<std::uint32_t>> v = {5, 6, 7};
  reserve_for_writing(v, 1'000'000);  // 4 MB
  ASSERT_GE(v.capacity(), 1'000'000u);
  EXPECT_EQ(v, (std::vector<std::uint32_t, FreshMappingAllocator<std::uint32_t>>{5, 6, 7}));
  std::size_t pages = 0;
  EXPECT_EQ(resident_pages(v.data(), 1'000'000 * sizeof(std::uint32_t), pages), pages);
  // back_pages on part of a fresh mapping: whole pages inside the range only
  const std::size_t mapped = std::size_t{4} << 20;
  auto* region = static_cast<char*>(mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0));
  ASSERT_NE(region, MAP_FAILED);
  madvise(region, mapped, MADV_NOHUGEPAGE);
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  back_pages(region + page + 1, 10 * page);  // pages 2 to 10 whole, page 1 and 11 in part
  std::size_t one = 0;
  EXPECT_EQ(resident_pages(region + page, page, one), 0u);
  EXPECT_EQ(resident_pages(region + 2 * page, 9 * page, pages), 9u);
  EXPECT_EQ(resident_pages(region + 11 * page, page, one), 0u);
  back_pages(nullptr, 0);
  back_pages(region, 1);  // less than a page: nothing
  EXPECT_EQ(resident_pages(region, page, one), 0u);
  EXPECT_EQ(region[5 * page], 0);  // fresh memory reads as zeros, backed or not
  munmap(region, mapped);
}

TEST(HugePages, PagesBackedAheadStayAStretchAheadOfTheAppends) {
  // the kernel must know MADV_POPULATE_WRITE (Linux 5.14); elsewhere backing is a no-op
  if (!kernel_backs_pages()) GTEST_SKIP() << "this kernel has no MADV_POPULATE_WRITE";
  using Vector = std::vector<std::uint64_t, FreshMappingAllocator<std::uint64_t>>;
  constexpr std::size_t room = 2'000'000;  // 16 MB reserved, far more than is appended
  Vector v;
  v.reserve(room);
  PagesBackedAhead ahead;
  std::size_t pages = 0;
  const auto bytes = [](std::size_t items) { return items * sizeof(std::uint64_t); };
  for (std::size_t i = 0; i < 100'000; ++i) {  // 800 kB appended
    ahead.before_append(v);
    v.push_back(3 * i);
  }
  // everything appended is resident, and no more than a stretch (256 KiB) and a page beyond it
  EXPECT_EQ(resident_pages(v.data(), bytes(v.size()) - 4096, pages), pages);
  EXPECT_GT(resident_pages(v.data() + v.size(), 128 << 10, pages), 0u) << "backed ahead of the appends";
  const std::size_t beyond = bytes(v.size()) + (256 << 10) + 8192;
  EXPECT_EQ(resident_pages(reinterpret_cast<const char*>(v.data()) + beyond, bytes(room) - beyond, pages), 0u);
  // appends of several items at once, and a vector that outgrows its room: the values stay
  for (std::size_t i = 100'000; i < room + 50'000; i += 5) {
    ahead.before_append(v, 5);
    for (std::size_t k = 0; k < 5; ++k) v.push_back(3 * (i + k));
  }
  ASSERT_EQ(v.size(), room + 50'000);
  for (std::size_t i = 0; i < v.size(); i += 9'973) ASSERT_EQ(v[i], 3 * i);
  EXPECT_EQ(v.back(), 3 * (room + 49'999));
}

#endif

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
