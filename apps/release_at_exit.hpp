#pragma once
/// \file
/// Leaving a command's large results to the end of the process. A command that has printed its
/// summary is about to exit; freeing a map of several hundred megabytes block by block first
/// (destructors, then the allocator returning each block) is time the user waits for nothing,
/// since the operating system takes the whole address space back at once.
///
/// Under AddressSanitizer the object is destroyed normally, so that LeakSanitizer (which CI runs
/// on the command-line tests) sees nothing left over.

#include <new>
#include <type_traits>
#include <utility>

#if defined(__SANITIZE_ADDRESS__)
#define PLMAP_RELEASE_AT_EXIT_FREES 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PLMAP_RELEASE_AT_EXIT_FREES 1
#endif
#endif

namespace plmap::cli {

/// Takes `object` over; its memory is returned when the process exits, without running its
/// destructor (except under AddressSanitizer, where it is destroyed here).
template <class T>
void release_at_exit(T&& object) {
  using Value = std::remove_cvref_t<T>;
#if defined(PLMAP_RELEASE_AT_EXIT_FREES)
  [[maybe_unused]] Value destroyed_here(std::forward<T>(object));
#else
  // Deliberately never deleted: see the file comment.
  static_cast<void>(new Value(std::forward<T>(object)));
#endif
}

}  // namespace plmap::cli
