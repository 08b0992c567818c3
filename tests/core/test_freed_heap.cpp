// give_freed_heap_back (core/freed_heap.hpp): freed heap memory leaves the process's resident set.
#include <plmap/core/freed_heap.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <vector>

#include <unistd.h>

// AddressSanitizer brings its own malloc (GCC says so by __SANITIZE_ADDRESS__, clang by
// __has_feature)
#if defined(__SANITIZE_ADDRESS__)
#define PLMAP_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PLMAP_TEST_UNDER_ASAN 1
#endif
#endif

namespace {

/// Resident memory of this process in MiB (Linux), or a negative number where it cannot be read.
[[maybe_unused]] double resident_mib() {
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = -1;
  statm >> size >> resident;
  const long page = sysconf(_SC_PAGESIZE);  // statm counts pages, which are not 4 KiB everywhere
  return resident < 0 || page <= 0 ? -1.0 : double(resident) * double(page) / 1048576.0;
}

}  // namespace

TEST(FreedHeap, FreedBlocksInTheMiddleOfTheHeapLeaveTheResidentSet) {
#if defined(PLMAP_TEST_UNDER_ASAN)
  GTEST_SKIP() << "under AddressSanitizer, malloc is the sanitizer's, not glibc's";
#elif !defined(__GLIBC__)
  GTEST_SKIP() << "give_freed_heap_back trims glibc's heap only";
#else
  if (resident_mib() < 0.0) GTEST_SKIP() << "no /proc/self/statm";
  // 48 MiB in 64 KiB blocks (below malloc's mmap threshold, so they come from the heap), each
  // written; all but the last freed, which keeps the freed ones in the middle of the heap
  constexpr std::size_t block = 64 * 1024, count = 768;
  std::vector<std::unique_ptr<char[]>> blocks;
  for (std::size_t i = 0; i < count; ++i) {
    blocks.emplace_back(new char[block]);
    for (std::size_t j = 0; j < block; j += 4096) blocks.back()[j] = static_cast<char>(i + j);
  }
  for (std::size_t i = 0; i + 1 < count; ++i) blocks[i].reset();
  const double before = resident_mib();
  plmap::give_freed_heap_back();
  const double after = resident_mib();
  EXPECT_GT(before - after, 32.0) << "resident " << before << " MiB before, " << after << " MiB after";
#endif
}
