#pragma once
/// \file
/// First touches of large arrays spread over threads. The first write to a page of fresh memory
/// makes the kernel find and zero a page (on a virtual machine, often also the host: on the
/// 2-core machine of docs/benchmarks.md zeroing a 2 MiB huge page of never-used memory took
/// about 8 ms, some 250 MB/s). Done by one thread while the others wait, it is a serial phase
/// of its own: the 19 MB of the 200k plane pair's region maps took 73 ms of a 1.4 s two-thread
/// projection that way. Here the kernel backs the memory ahead of the writes, one piece of the
/// range per thread; the contents and the result do not change, only which thread pays the
/// page faults.

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace plmap {

/// Backs the whole pages of [p, p + bytes) with memory now (Linux 5.14 and later:
/// MADV_POPULATE_WRITE; a no-op elsewhere, where the pages fault in at their first write as
/// usual), in pieces of 2 MiB (one huge page each) spread over up to `threads` threads. The
/// bytes are left as they are (fresh memory reads as zeros).
inline void populate_in_parallel([[maybe_unused]] void* p, [[maybe_unused]] std::size_t bytes,
                                 [[maybe_unused]] unsigned threads) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  const std::uintptr_t page = system_page_bytes();  // madvise takes whole pages
  constexpr std::size_t piece = std::size_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + page - 1) & ~(page - 1), last = (begin + bytes) & ~(page - 1);
  if (last <= first) return;
  const std::size_t length = last - first;
  // pieces on 2 MiB boundaries (whole pages of any size up to 2 MiB), so that no huge page is
  // split between two threads
  const std::uintptr_t aligned_first = first & ~(std::uintptr_t{piece} - 1);
  const std::size_t pieces = (last - aligned_first + piece - 1) / piece;
  if (pieces <= 1 || resolve_thread_count(threads) <= 1) {
    back_pages(reinterpret_cast<void*>(first), length);
    return;
  }
  parallel_for_pieces_of_size(pieces, 1, threads, [&](std::size_t k, std::size_t, std::size_t) {
    const std::uintptr_t from = std::max(first, aligned_first + k * piece);
    const std::uintptr_t to = std::min(last, aligned_first + (k + 1) * piece);
    if (to > from) back_pages(reinterpret_cast<void*>(from), to - from);
  });
#endif
}

/// assign_on_huge_pages (huge_page_allocator.hpp) with the new memory backed on up to `threads`
/// threads first (populate_in_parallel), so that the calling thread's fill finds its pages there.
template <class Vector>
void assign_on_huge_pages(Vector& v, std::size_t n, const typename Vector::value_type& value, unsigned threads) {
  reserve_on_huge_pages(v, n);
  if (v.size() < n) populate_in_parallel(v.data() + v.size(), (n - v.size()) * sizeof(typename Vector::value_type), threads);
  v.assign(n, value);
}

}  // namespace plmap
