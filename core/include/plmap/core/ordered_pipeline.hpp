#pragma once
/// \file
/// Work whose results must be used in index order, while producing them is independent per item:
/// the blocks of [0, n) are produced on all threads and consumed one at a time, in block order,
/// on the calling thread, so consuming block k overlaps with producing the blocks after it. The
/// projection plans the walks of its S2 edges this way while the builder takes the edges planned
/// before, in index order. Built on the one parallel mechanism of plmap (oneTBB, see
/// parallel_ranges.hpp).
///
/// Results do not depend on the thread count when producing a block is deterministic: the blocks
/// are the same for every thread count, and they are consumed in order. An exception reaches the
/// caller: one thrown while producing a block is rethrown when that block's turn to be consumed
/// comes (so it is the exception of the first failing block, for every thread count), one thrown
/// by consume stops the work at once; in both cases after every producing thread has stopped.

#include <plmap/core/parallel_ranges.hpp>

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <vector>

namespace plmap {

namespace detail {

/// The shared state of produce_in_parallel_consume_in_order: which block is produced next, which
/// one the consumer waits for, and which block each slot holds.
class OrderedPipelineState {
 public:
  OrderedPipelineState(std::size_t blocks, std::size_t slots) : blocks_(blocks), slots_(slots), ready_(slots) {
    for (auto& r : ready_) r.store(0, std::memory_order_relaxed);
  }

  /// The next block nobody has started, if its slot is free; `none` when every block is taken
  /// (or the work stopped). Waits while the slot still holds an unconsumed block, unless
  /// `wait` is false (then returns `busy`).
  static constexpr std::size_t none = static_cast<std::size_t>(-1), busy = none - 1;
  std::size_t claim(bool wait) {
    for (;;) {
      const std::size_t consumed = consumed_.load(std::memory_order_acquire);
      if (stopped_.load(std::memory_order_acquire)) return none;  // (stop() sets it before consumed_)
      std::size_t b = next_.load(std::memory_order_relaxed);
      if (b >= blocks_) return none;
      if (b >= consumed + slots_) {  // its slot still holds block b - slots
        if (!wait) return busy;
        consumed_.wait(consumed, std::memory_order_acquire);
        continue;
      }
      if (next_.compare_exchange_weak(b, b + 1, std::memory_order_relaxed)) return b;
    }
  }

  /// Block b (in slot b % slots) is produced; its failure, if any, was stored first.
  void produced(std::size_t b) {
    auto& r = ready_[b % slots_];
    r.store(b + 1, std::memory_order_release);
    r.notify_all();
  }
  bool is_ready(std::size_t b) const { return ready_[b % slots_].load(std::memory_order_acquire) == b + 1; }
  /// Waits until block b is produced, if someone has started it (else returns at once).
  void wait_until_ready(std::size_t b) {
    auto& r = ready_[b % slots_];
    for (std::size_t seen = r.load(std::memory_order_acquire); seen != b + 1; seen = r.load(std::memory_order_acquire)) {
      if (next_.load(std::memory_order_relaxed) <= b) return;  // nobody has it: the caller takes it
      r.wait(seen, std::memory_order_acquire);
    }
  }

  /// Block b is consumed: its slot is free for block b + slots.
  void consumed(std::size_t b) {
    consumed_.store(b + 1, std::memory_order_release);
    consumed_.notify_all();
  }
  /// Stops the producers (after an exception); they finish the block they are on.
  void stop() {
    stopped_.store(true, std::memory_order_release);
    consumed_.store(blocks_ + slots_, std::memory_order_release);  // wakes producers waiting for a slot
    consumed_.notify_all();
  }

  std::vector<std::exception_ptr> failure;  // per slot: the exception of producing its block

 private:
  std::size_t blocks_, slots_;
  std::atomic<std::size_t> next_{0}, consumed_{0};
  std::atomic<bool> stopped_{false};
  std::vector<std::atomic<std::size_t>> ready_;  // per slot: 1 + the block produced into it
};

}  // namespace detail

/// Cuts [0, n) into blocks of `block` items and calls produce(slot, begin, end) for every block,
/// on up to `threads` threads (0: all hardware threads), and consume(slot, begin, end) for every
/// block, on the calling thread, in block order, each after its produce. Up to `slots` blocks are
/// produced ahead of the one consumed: a block's results go in the caller's buffers numbered
/// `slot` (in [0, slots)), which the next block in that slot reuses only after it is consumed.
/// The calling thread produces blocks too while the next one to consume is not ready. With one
/// thread, each block is produced and consumed before the next.
template <class Produce, class Consume>
void produce_in_parallel_consume_in_order(std::size_t n, std::size_t block, std::size_t slots, unsigned threads,
                                          Produce&& produce, Consume&& consume) {
  block = std::max<std::size_t>(1, block);
  slots = std::max<std::size_t>(1, slots);
  const std::size_t blocks = (n + block - 1) / block;
  auto begin_of = [&](std::size_t b) { return b * block; };
  auto end_of = [&](std::size_t b) { return std::min(n, (b + 1) * block); };
  threads = resolve_thread_count(threads);
  if (threads == 1 || blocks <= 1 || slots == 1) {
    for (std::size_t b = 0; b < blocks; ++b) {
      produce(b % slots, begin_of(b), end_of(b));
      consume(b % slots, begin_of(b), end_of(b));
    }
    return;
  }
  detail::OrderedPipelineState state(blocks, slots);
  state.failure.resize(slots);
  auto produce_block = [&](std::size_t b) {
    const std::size_t slot = b % slots;
    state.failure[slot] = nullptr;
    try {
      produce(slot, begin_of(b), end_of(b));
    } catch (...) {
      state.failure[slot] = std::current_exception();
    }
    state.produced(b);
  };
  auto producer = [&] {
    for (std::size_t b = state.claim(true); b != detail::OrderedPipelineState::none; b = state.claim(true))
      produce_block(b);
  };
  detail::execute_in_arena(threads, [&] {
    tbb::task_group producers;
    for (unsigned w = 1; w < threads; ++w) producers.run(producer);
    try {
      for (std::size_t b = 0; b < blocks; ++b) {
        // help while block b is not ready: produce it (or a later one) here
        while (!state.is_ready(b)) {
          const std::size_t mine = state.claim(false);
          if (mine == detail::OrderedPipelineState::none || mine == detail::OrderedPipelineState::busy)
            state.wait_until_ready(b);
          else
            produce_block(mine);
        }
        if (const auto failure = state.failure[b % slots]) std::rethrow_exception(failure);
        consume(b % slots, begin_of(b), end_of(b));
        state.consumed(b);
      }
    } catch (...) {
      state.stop();
      producers.wait();
      throw;
    }
    producers.wait();
  });
}

}  // namespace plmap
