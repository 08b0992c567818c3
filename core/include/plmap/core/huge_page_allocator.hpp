#pragma once
/// \file
/// Transparent huge pages for large arrays that are read at random (the inverse-evaluation
/// index, the builder's nodes and segments) or first written in bulk (the map's arrays, a
/// surface's adjacency, the projection's per-vertex results): an allocator whose blocks of 2 MiB
/// and more are aligned to 2 MiB and, on Linux, marked for transparent huge pages (madvise
/// MADV_HUGEPAGE; the system default "madvise" gives them only to memory so marked), helpers
/// that mark a std::vector's reserved room, and helpers that back memory about to be written in
/// one system call instead of one page fault per page (back_pages, reserve_for_writing,
/// PagesBackedAhead).
/// A random read into a 100 MB array with 4 KiB pages misses the TLB almost every time, and on a
/// virtual machine a page walk costs several memory accesses; with 2 MiB pages the walk is rare.
/// Elsewhere, or for small blocks, it allocates as std::allocator does. The contents are the same
/// either way: this changes only where the memory comes from.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace plmap {

/// Marks the 2 MiB-aligned part of [p, p + bytes) for transparent huge pages (Linux; a hint, and
/// a no-op elsewhere or for less than one huge page). Meant for an array that is allocated but
/// not yet written: its first writes then fault in 2 MiB pages instead of 4 KiB ones (512 times
/// fewer page faults, which also serialise threads on the process's page tables, and fewer TLB
/// misses in random reads). The contents are the same either way.
inline void advise_huge_pages([[maybe_unused]] const void* p, [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + huge - 1) & ~(huge - 1), last = (begin + bytes) & ~(huge - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
}

/// Marks the whole pages inside [p, p + bytes) for small pages (Linux: MADV_NOHUGEPAGE; a hint,
/// a no-op elsewhere): for a little memory about to be written first in room marked for huge
/// pages, where a first write would otherwise make a whole huge page resident. Pages already
/// resident stay as they are.
inline void advise_small_pages([[maybe_unused]] const void* p, [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_NOHUGEPAGE)
  const std::uintptr_t page = static_cast<std::uintptr_t>(std::max(4096L, sysconf(_SC_PAGESIZE)));
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + page - 1) & ~(page - 1), last = (begin + bytes + page - 1) & ~(page - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_NOHUGEPAGE);
#endif
}

/// Reserves room for n elements in vector v and marks it for huge pages before anything is
/// written there (a no-op for the part already written, and for small vectors).
template <class Vector>
void reserve_on_huge_pages(Vector& v, std::size_t n) {
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(typename Vector::value_type));
}

/// The system's page size (4 KiB on x86-64, 16 or 64 KiB on some ARM systems).
inline std::uintptr_t system_page_bytes() noexcept {
#if defined(__linux__)
  static const auto page = static_cast<std::uintptr_t>(std::max(4096L, sysconf(_SC_PAGESIZE)));
  return page;
#else
  return 4096;
#endif
}

/// Backs the whole pages inside [p, p + bytes) with memory now, in one system call (Linux 5.14
/// and later: MADV_POPULATE_WRITE; a no-op elsewhere, where the pages fault in at their first
/// write as usual), in huge pages where the range is marked for them. For memory that is about to
/// be written in full: each first write to a fresh 4 KiB page is a trap into the kernel, which
/// on the virtual machines of docs/benchmarks.md costs about 11 µs, against 0.6-1 µs per page
/// backed here (2.5 µs for a single page), so page faults were 12-20 % of a projection there.
/// The bytes are left as they are (fresh memory reads as zeros).
inline void back_pages([[maybe_unused]] void* p, [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  const std::uintptr_t page = system_page_bytes();  // madvise takes whole pages
  const auto begin = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (begin + page - 1) & ~(page - 1), last = (begin + bytes) & ~(page - 1);
  if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);  // EINVAL on older kernels: ignored
#endif
}

/// Backs the pages of a vector that grows by appends into reserved room, a stretch at a time ahead
/// of the appends (back_pages): for room reserved for more than the vector usually holds, which
/// cannot be backed at once without making all of it resident. At most one stretch (256 KiB) is
/// backed beyond what is appended. One object per vector.
class PagesBackedAhead {
 public:
  /// To be called before `count` items are appended to v.
  template <class Vector>
  void before_append(Vector& v, std::size_t count = 1) noexcept {
    using T = typename Vector::value_type;
    char* base = reinterpret_cast<char*>(v.data());
    const std::size_t end = (v.size() + count) * sizeof(T), room = v.capacity() * sizeof(T);
    if (base == base_ && end <= backed_) return;
    if (base != base_) {  // a new block (the vector grew): backed up to what it holds
      base_ = base;
      backed_ = v.size() * sizeof(T);
    }
    if (end > room) return;  // this append moves the vector to a new block
    // up to a page boundary, so that the next stretch starts on one (back_pages takes whole pages)
    const auto page_end = [&](std::size_t offset) {
      const auto address = reinterpret_cast<std::uintptr_t>(base) + offset;
      return static_cast<std::size_t>((address & ~(system_page_bytes() - 1)) - reinterpret_cast<std::uintptr_t>(base));
    };
    const std::size_t to = std::max(page_end(std::min(room, std::max(end, backed_) + stretch_bytes)), backed_);
    back_pages(base + backed_, to - backed_);
    backed_ = to;
  }

 private:
  static constexpr std::size_t stretch_bytes = std::size_t{256} << 10;
  char* base_ = nullptr;
  std::size_t backed_ = 0;  // bytes from base_ that are backed (or were written)
};

/// reserve_on_huge_pages for n elements that are written next (the array filled to n, or
/// appended to n): the room beyond the current size is backed now (back_pages) instead of
/// faulting in page by page. Only for arrays that do reach n: backed memory is resident.
template <class Vector>
void reserve_for_writing(Vector& v, std::size_t n) {
  reserve_on_huge_pages(v, n);
  using T = typename Vector::value_type;
  if (n > v.size()) back_pages(v.data() + v.size(), (n - v.size()) * sizeof(T));
}

/// `v.assign(n, value)` on memory marked for huge pages before its first write (room reserved
/// first): for the per-vertex and per-element arrays of a large surface that the projection fills
/// right away (on the 1M circles they were a third of the run's page faults).
template <class Vector>
void assign_on_huge_pages(Vector& v, std::size_t n, const typename Vector::value_type& value = {}) {
  reserve_for_writing(v, n);
  v.assign(n, value);
}

/// Blocks of min_bytes and more come on huge pages (at least one huge page: below, there is no
/// aligned huge page inside the block). A larger min_bytes suits arrays reserved for more than
/// they usually hold: a huge page is resident as soon as one byte of it is written, so the
/// partly written last one (up to 2 MiB) is resident in full, which a small array pays dearly.
template <class T, std::size_t min_bytes = std::size_t{2} << 20>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t huge_page_bytes = std::size_t{2} << 20;
  static_assert(min_bytes >= huge_page_bytes, "a block below one huge page has no huge page to mark");
  template <class U>
  struct rebind {
    using other = HugePageAllocator<U, min_bytes>;
  };

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U, min_bytes>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < min_bytes || alignof(T) > huge_page_bytes) return std::allocator<T>().allocate(n);
    const std::size_t rounded = (bytes + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes;
    void* p = std::aligned_alloc(huge_page_bytes, rounded);
    if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    ::madvise(p, rounded, MADV_HUGEPAGE);  // a hint: without huge pages the array still works
#endif
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < min_bytes || alignof(T) > huge_page_bytes) {
      std::allocator<T>().deallocate(p, n);
      return;
    }
    std::free(p);
  }

  template <class U>
  bool operator==(const HugePageAllocator<U, min_bytes>&) const noexcept {
    return true;
  }
};

}  // namespace plmap
