// produce_in_parallel_consume_in_order (core/ordered_pipeline.hpp): blocks consumed in order on
// the calling thread, a slot never reused before its block is consumed, producing overlapping
// with consuming, and exceptions reaching the caller in block order.

#include <plmap/core/errors.hpp>
#include <plmap/core/ordered_pipeline.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace plmap {
namespace {

using Block = std::tuple<std::size_t, std::size_t>;  // (begin, end)

/// Runs the pipeline with produce writing each item's square into its slot's buffer (after a
/// pause that varies by block, so blocks finish out of order) and consume checking and
/// recording it. Returns what was consumed, in consumption order.
std::vector<std::size_t> consumed_values(std::size_t n, std::size_t block, std::size_t slots, unsigned threads,
                                         std::vector<Block>* blocks = nullptr) {
  std::vector<std::vector<std::size_t>> buffer(slots);
  std::vector<std::size_t> out;
  const auto caller = std::this_thread::get_id();
  produce_in_parallel_consume_in_order(
      n, block, slots, threads,
      [&](std::size_t slot, std::size_t begin, std::size_t end) {
        EXPECT_LT(slot, slots);
        buffer[slot].clear();
        if ((begin / block) % 3 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
        for (std::size_t i = begin; i < end; ++i) buffer[slot].push_back(i * i);
      },
      [&](std::size_t slot, std::size_t begin, std::size_t end) {
        EXPECT_EQ(std::this_thread::get_id(), caller) << "consume runs on the calling thread";
        // the slot still holds this block's values: not overwritten by a later block
        EXPECT_EQ(buffer[slot].size(), end - begin);
        for (std::size_t i = begin; i < end; ++i) out.push_back(buffer[slot][i - begin]);
        if (blocks) blocks->emplace_back(begin, end);
      });
  return out;
}

TEST(OrderedPipeline, ConsumesEveryBlockOnceInOrderWhateverTheThreadCount) {
  for (const std::size_t n : {0u, 1u, 5u, 1000u, 1001u}) {
    std::vector<std::size_t> expected;
    for (std::size_t i = 0; i < n; ++i) expected.push_back(i * i);
    for (const unsigned threads : {1u, 2u, 4u})
      for (const std::size_t slots : {1u, 2u, 8u}) {
        std::vector<Block> blocks;
        EXPECT_EQ(consumed_values(n, 16, slots, threads, &blocks), expected)
            << "n " << n << ", threads " << threads << ", slots " << slots;
        // the blocks are [16 k, 16 (k + 1)) cut at n, whatever the thread count
        for (std::size_t k = 0; k < blocks.size(); ++k)
          EXPECT_EQ(blocks[k], Block(16 * k, std::min(n, 16 * (k + 1))));
        EXPECT_EQ(blocks.size(), (n + 15) / 16);
      }
  }
}

TEST(OrderedPipeline, ProducingOverlapsWithConsuming) {
  // Consuming block 0 waits until block 1 is being produced: only possible if another thread
  // produces while the caller consumes (the generous limit keeps a loaded machine from failing
  // it; a sequential pipeline would wait the whole limit and fail).
  std::atomic<bool> second_started{false};
  bool overlapped = false;
  produce_in_parallel_consume_in_order(
      4, 1, 4, 2,
      [&](std::size_t, std::size_t begin, std::size_t) {
        if (begin == 1) second_started = true;
      },
      [&](std::size_t, std::size_t begin, std::size_t) {
        if (begin != 0) return;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (!second_started && std::chrono::steady_clock::now() < deadline)
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        overlapped = second_started;
      });
  EXPECT_TRUE(overlapped);
}

TEST(OrderedPipeline, AProducersExceptionReachesTheCallerWhenItsBlockIsDue) {
  for (const unsigned threads : {1u, 2u, 4u}) {
    std::vector<std::size_t> consumed;
    try {
      produce_in_parallel_consume_in_order(
          100, 10, 4, threads,
          [&](std::size_t, std::size_t begin, std::size_t) {
            // blocks 3 and 7 fail; block 7 usually fails first in time with several threads
            if (begin == 30) std::this_thread::sleep_for(std::chrono::milliseconds(5));
            if (begin == 30 || begin == 70) throw BuilderError("block " + std::to_string(begin / 10) + " failed");
          },
          [&](std::size_t, std::size_t begin, std::size_t) { consumed.push_back(begin / 10); });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const BuilderError& e) {  // the type the producer threw, not a wrapper
      EXPECT_STREQ(e.what(), "block 3 failed") << threads << " threads";
    }
    EXPECT_EQ(consumed, (std::vector<std::size_t>{0, 1, 2})) << threads << " threads";
  }
}

TEST(OrderedPipeline, AConsumersExceptionStopsTheWork) {
  for (const unsigned threads : {1u, 2u, 4u}) {
    std::atomic<int> produced{0};
    std::vector<std::size_t> consumed;
    try {
      produce_in_parallel_consume_in_order(
          1000, 10, 4, threads, [&](std::size_t, std::size_t, std::size_t) { ++produced; },
          [&](std::size_t, std::size_t begin, std::size_t) {
            consumed.push_back(begin / 10);
            if (begin == 20) throw BuilderError("cancelled");
          });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const BuilderError& e) {
      EXPECT_STREQ(e.what(), "cancelled");
    }
    EXPECT_EQ(consumed, (std::vector<std::size_t>{0, 1, 2})) << threads << " threads";
    // at most the slots ahead of the consumer were produced, not the 100 blocks
    EXPECT_LE(produced.load(), 3 + 4) << threads << " threads";
  }
}

}  // namespace
}  // namespace plmap
