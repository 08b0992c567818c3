#pragma once
/// \file
/// The one way plmap's query batches use threads: [0, n) cut into `threads` contiguous ranges,
/// one std::jthread per range, no locking. Contiguous ranges keep each thread's queries in the
/// caller's order (good for caches when the points are sorted) and make the result independent
/// of the thread count for deterministic work. An exception thrown by a worker is rethrown in the
/// caller once every worker has stopped (the first one, by range order).

#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace plmap {

/// The thread count that `threads == 0` stands for: all hardware threads.
inline unsigned resolve_thread_count(unsigned threads) {
  return threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
}

/// Calls work(begin, end) on contiguous ranges covering [0, n), on up to `threads` threads
/// (0: all hardware threads). With one thread, or n <= 1, the caller's thread does all of it.
template <class Work>
void parallel_ranges(std::size_t n, unsigned threads, Work&& work) {
  threads = static_cast<unsigned>(std::min<std::size_t>(resolve_thread_count(threads), std::max<std::size_t>(n, 1)));
  if (threads <= 1) {
    work(std::size_t{0}, n);
    return;
  }
  std::vector<std::exception_ptr> failure(threads);
  {
    std::vector<std::jthread> pool;
    pool.reserve(threads);
    const std::size_t chunk = (n + threads - 1) / threads;
    for (unsigned k = 0; k < threads; ++k) {
      const std::size_t begin = std::min(n, k * chunk), end = std::min(n, begin + chunk);
      pool.emplace_back([&work, &failure, k, begin, end] {
        try {
          work(begin, end);
        } catch (...) {
          failure[k] = std::current_exception();
        }
      });
    }
  }  // the jthreads join here
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
}

}  // namespace plmap
