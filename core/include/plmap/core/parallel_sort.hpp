#pragma once
/// \file
/// A sort on up to `threads` threads, in plmap's arenas (parallel_ranges.hpp): oneTBB's
/// parallel_sort, or std::sort for one thread. Its result is the same for every thread count only
/// when no two items compare equal (a key that ends with the item's index, for instance): then
/// the sorted sequence is unique, whichever algorithm and split produced it.

#include <plmap/core/parallel_ranges.hpp>

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <iterator>

namespace plmap {

/// Sorts [begin, end) by `less` (a strict total order on its items, see above) on up to
/// `threads` threads (0: all the process may run on).
template <class RandomIt, class Less = std::less<>>
void parallel_sort(RandomIt begin, RandomIt end, unsigned threads, Less less = {}) {
  threads = resolve_thread_count(threads);
  // below some ten thousand items the tasks cost more than they save (oneTBB sorts such ranges
  // serially anyway)
  if (threads == 1 || end - begin < 10000) {
    std::sort(begin, end, less);
    return;
  }
  detail::execute_in_arena(threads, [&] { tbb::parallel_sort(begin, end, less); });
}

}  // namespace plmap
