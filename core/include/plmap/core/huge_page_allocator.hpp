#pragma once
/// \file
/// An allocator for large arrays that are read at random (the inverse-evaluation index): blocks
/// of 2 MiB and more are aligned to 2 MiB and, on Linux, marked for transparent huge pages
/// (madvise MADV_HUGEPAGE; the system default "madvise" gives them only to memory so marked).
/// A random read into a 100 MB array with 4 KiB pages misses the TLB almost every time, and on a
/// virtual machine a page walk costs several memory accesses; with 2 MiB pages the walk is rare.
/// Elsewhere, or for small blocks, it allocates as std::allocator does. The contents are the same
/// either way: this changes only where the memory comes from.

#include <cstddef>
#include <cstdlib>
#include <memory>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace plmap {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t huge_page_bytes = std::size_t{2} << 20;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes < huge_page_bytes || alignof(T) > huge_page_bytes) return std::allocator<T>().allocate(n);
    const std::size_t rounded = (bytes + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes;
    void* p = std::aligned_alloc(huge_page_bytes, rounded);
    if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    ::madvise(p, rounded, MADV_HUGEPAGE);  // a hint: without huge pages the array still works
#endif
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < huge_page_bytes || alignof(T) > huge_page_bytes) {
      std::allocator<T>().deallocate(p, n);
      return;
    }
    std::free(p);
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace plmap
