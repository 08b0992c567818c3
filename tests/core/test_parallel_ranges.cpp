// The one parallel mechanism (core/parallel_ranges.hpp): fixed pieces whatever the thread count,
// and a worker's exception reaches the caller instead of ending the process.

#include <plmap/core/errors.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace plmap {
namespace {

using Piece = std::tuple<std::size_t, std::size_t, std::size_t>;  // (piece, begin, end)

std::set<Piece> pieces_seen(std::size_t n, std::size_t pieces, unsigned threads) {
  std::mutex mutex;
  std::set<Piece> seen;
  parallel_for_pieces(n, pieces, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    const std::lock_guard lock(mutex);
    seen.insert({k, begin, end});
  });
  return seen;
}

TEST(ParallelRanges, PiecesDoNotDependOnTheThreadCount) {
  for (const std::size_t n : {0u, 1u, 7u, 1000u, 1001u}) {
    const auto one = pieces_seen(n, 8, 1);
    EXPECT_EQ(pieces_seen(n, 8, 2), one) << "n = " << n;
    EXPECT_EQ(pieces_seen(n, 8, 3), one) << "n = " << n;
    // the pieces cover [0, n) once, in order
    std::size_t covered = 0;
    for (const auto& [k, begin, end] : one) {
      EXPECT_EQ(begin, covered);
      EXPECT_LT(begin, end);
      covered = end;
    }
    EXPECT_EQ(covered, n);
  }
}

TEST(ParallelRanges, ChunksHaveTheGivenSize) {
  std::vector<std::atomic<int>> hits(1000);
  std::atomic<int> short_chunks{0};
  parallel_for_chunks(1000, 256, 2, [&](std::size_t begin, std::size_t end) {
    EXPECT_EQ(begin % 256, 0u);
    if (end - begin != 256) {
      ++short_chunks;
      EXPECT_EQ(end, 1000u);
    }
    for (std::size_t i = begin; i < end; ++i) ++hits[i];
  });
  EXPECT_EQ(short_chunks.load(), 1);
  for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
}

TEST(ParallelRanges, AWorkersExceptionReachesTheCaller) {
  for (const unsigned threads : {1u, 2u, 4u}) {
    std::vector<std::atomic<int>> ran(16);
    try {
      parallel_for_pieces(1600, 16, threads, [&](std::size_t k, std::size_t, std::size_t) {
        ++ran[k];
        if (k == 5) throw BuilderError("piece 5 failed");
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const BuilderError& e) {  // the type the worker threw, not a wrapper
      EXPECT_STREQ(e.what(), "piece 5 failed");
    }
    // the pieces before the failing one always run, each once
    for (std::size_t k = 0; k <= 5; ++k) EXPECT_EQ(ran[k].load(), 1) << "piece " << k << ", " << threads << " threads";
    for (std::size_t k = 6; k < 16; ++k) EXPECT_LE(ran[k].load(), 1);
  }
}

TEST(ParallelRanges, TheFirstFailingPieceDecidesWhatIsThrown) {
  for (const unsigned threads : {1u, 2u, 4u}) {
    for (int repeat = 0; repeat < 20; ++repeat) {
      try {
        parallel_for_chunks(100, 10, threads, [&](std::size_t begin, std::size_t) {
          if (begin == 70) throw Error("chunk 7");
          if (begin == 30) {
            // let the later chunk fail first where it can
            std::this_thread::sleep_for(std::chrono::microseconds(repeat * 50));
            throw Error("chunk 3");
          }
        });
        ADD_FAILURE() << "no exception";
      } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "chunk 3") << threads << " threads";
      }
    }
  }
}

TEST(ParallelRanges, ThrowingWorkersOfAProjectionSizedLoopDoNotEndTheProcess) {
  // many pieces, every one of them throwing: the caller gets one exception and can go on
  std::atomic<int> calls{0};
  EXPECT_THROW(parallel_ranges(100000, 2,
                               [&](std::size_t, std::size_t) {
                                 ++calls;
                                 throw Error("worker failed");
                               }),
               Error);
  EXPECT_GE(calls.load(), 1);
  std::atomic<std::size_t> sum{0};
  parallel_ranges(100, 2, [&](std::size_t begin, std::size_t end) { sum += end - begin; });
  EXPECT_EQ(sum.load(), 100u);
}

}  // namespace
}  // namespace plmap
