#pragma once
/// \file
/// The one parallel mechanism of plmap: oneTBB tasks in a task arena whose concurrency is the
/// thread count asked for. Work over [0, n) is cut into contiguous pieces that depend only on n
/// and on what the caller asks (never on which thread is free), so work that is deterministic per
/// piece gives the same result for every thread count; the pieces are scheduled dynamically
/// (a thread that finishes early takes the next piece).
///
/// An exception thrown by the work reaches the caller: once a piece has thrown, the pieces after
/// it that have not started are skipped, the pieces before it still run, and the exception of
/// the first piece that threw (in piece order, hence the same for every thread count) is
/// rethrown in the caller after every running piece has stopped.

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

namespace plmap {

/// The CPUs this process may run on, as oneTBB reads them (its affinity mask: `taskset -c 0`, a
/// batch job given one core: 1; newer oneTBB versions also read cgroup CPU limits), not the
/// machine's hardware threads.
inline unsigned available_threads() {
  static const unsigned available = static_cast<unsigned>(std::max(1, tbb::info::default_concurrency()));
  return available;
}

namespace detail {

/// How deep the calling thread is in plmap's arenas (0: outside every one of them).
inline thread_local unsigned arena_depth = 0;

/// The arena of the calling thread for `threads` threads at its current depth, created on first
/// use and then kept for the life of the process.
///
/// Why kept: an arena created and destroyed per call (as plmap did first) leaves oneTBB's worker
/// threads behind on a loaded machine. After a few hundred short-lived arenas, a new arena's
/// work waited seconds for a worker, so the second thread did nothing (measured: a 2-thread
/// arena on the 2-core machine with six busy processes, after 300 create-use-destroy cycles,
/// got no worker within 5 s; with one arena reused, within a millisecond). Why per thread and
/// depth: a thread never shares an arena's caller slot with another thread (so nobody waits for
/// a slot), and work started inside a piece runs in an arena of its own, isolated from the
/// enclosing one as before (the thread cannot pick up an unrelated outer piece while it waits).
/// The arenas live in one registry that is never destroyed, keyed by thread id (a thread that
/// starts after another ended may reuse its arenas): there are at most a few per thread, and
/// destroying them at a worker thread's exit would race with oneTBB's own shutdown.
inline tbb::task_arena& reusable_arena(unsigned threads) {
  struct Key {
    std::thread::id thread;
    unsigned threads, depth;
    bool operator<(const Key& o) const {
      return std::tie(thread, threads, depth) < std::tie(o.thread, o.threads, o.depth);
    }
  };
  static std::mutex mutex;
  static auto* const arenas = new std::map<Key, std::unique_ptr<tbb::task_arena>>();
  const std::lock_guard<std::mutex> lock(mutex);
  auto& arena = (*arenas)[Key{std::this_thread::get_id(), threads, arena_depth}];
  // More threads than the process may run would only be asked of oneTBB in vain (it prints a
  // warning and runs them on the CPUs it has): the arena gets what can run. The work is cut by
  // the count asked for, so the results stay those of that count.
  if (!arena) arena = std::make_unique<tbb::task_arena>(static_cast<int>(std::min(threads, available_threads())));
  return *arena;
}

/// Runs f in the calling thread's arena for `threads` threads (see reusable_arena).
template <class F>
void execute_in_arena(unsigned threads, F&& f) {
  reusable_arena(threads).execute([&] {
    struct Depth {
      Depth() { ++arena_depth; }
      ~Depth() { --arena_depth; }
    } depth;
    f();
  });
}

}  // namespace detail

/// The thread count that `threads == 0` stands for: all hardware threads the process may run on
/// (available_threads).
inline unsigned resolve_thread_count(unsigned threads) { return threads != 0 ? threads : available_threads(); }

/// Calls work(piece, begin, end) for [0, n) cut into contiguous pieces of `size` items (piece k
/// covers [k size, (k + 1) size) within [0, n)), on up to `threads` threads (0: all hardware
/// threads). With one thread or one piece, the caller's thread does all of it, in piece order.
template <class Work>
void parallel_for_pieces_of_size(std::size_t n, std::size_t size, unsigned threads, Work&& work) {
  size = std::max<std::size_t>(1, size);
  const std::size_t pieces = (n + size - 1) / size;
  threads = resolve_thread_count(threads);
  if (threads == 1 || pieces <= 1) {
    for (std::size_t k = 0; k < pieces; ++k) work(k, k * size, std::min(n, (k + 1) * size));
    return;
  }
  std::vector<std::exception_ptr> failure(pieces);
  std::atomic<std::size_t> first_failed{pieces};
  auto run_piece = [&](std::size_t k) {
    if (k > first_failed.load(std::memory_order_relaxed)) return;  // a piece before it failed
    try {
      work(k, k * size, std::min(n, (k + 1) * size));
    } catch (...) {
      failure[k] = std::current_exception();
      std::size_t seen = first_failed.load();
      while (k < seen && !first_failed.compare_exchange_weak(seen, k)) {
      }
    }
  };
  detail::execute_in_arena(static_cast<unsigned>(std::min<std::size_t>(threads, pieces)), [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, pieces, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t k = r.begin(); k != r.end(); ++k) run_piece(k);
        },
        tbb::simple_partitioner());
  });
  for (const auto& f : failure)
    if (f) std::rethrow_exception(f);
}

/// Calls work(piece, begin, end) for [0, n) cut into up to `pieces` contiguous pieces of
/// ceil(n / pieces) items (the last ones shorter or absent), as parallel_for_pieces_of_size.
template <class Work>
void parallel_for_pieces(std::size_t n, std::size_t pieces, unsigned threads, Work&& work) {
  pieces = std::max<std::size_t>(1, std::min(pieces, n));
  parallel_for_pieces_of_size(n, (n + pieces - 1) / pieces, threads, std::forward<Work>(work));
}

/// Calls work(begin, end) on `threads` contiguous ranges covering [0, n) (0: all hardware
/// threads). Contiguous ranges keep each thread's items in the caller's order (good for caches
/// when the points are sorted); the ranges depend on the thread count, so use this for work that
/// is independent per item (query batches).
template <class Work>
void parallel_ranges(std::size_t n, unsigned threads, Work&& work) {
  parallel_for_pieces(n, resolve_thread_count(threads), threads,
                              [&work](std::size_t, std::size_t begin, std::size_t end) { work(begin, end); });
}

/// Calls work(begin, end) on [0, n) cut into chunks of `chunk` items, the chunks spread over
/// `threads` threads. Work inside a chunk is sequential, so a chunk may carry state from one item
/// to the next (a search hint) and the result still does not depend on the thread count: the
/// chunks are the same whatever it is.
template <class Work>
void parallel_for_chunks(std::size_t n, std::size_t chunk, unsigned threads, Work&& work) {
  parallel_for_pieces_of_size(n, chunk, threads,
                              [&work](std::size_t, std::size_t begin, std::size_t end) { work(begin, end); });
}

}  // namespace plmap
