// EditableMap's per-triangle lists in one pool (core/src/triangle_lists.hpp): lists written
// through open() + append() read back as written, replaced and cleared lists read as their
// replacement or empty, and the compaction that drops the garbage keeps every live list. Checked
// against a vector per slot over random sequences of operations used as EditableMap uses them
// (a batch of slots opened, then each filled to its size).
#include "triangle_lists.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <utility>
#include <vector>

using namespace plmap;

namespace {

void expect_same(const TriangleLists& lists, const std::vector<std::vector<Index>>& expected) {
  ASSERT_EQ(lists.slot_count(), expected.size());
  for (std::size_t t = 0; t < expected.size(); ++t) {
    const auto got = lists[static_cast<Index>(t)];
    EXPECT_EQ(std::vector<Index>(got.begin(), got.end()), expected[t]) << "slot " << t;
  }
}

}  // namespace

TEST(TriangleLists, ListsReadBackAfterReplacementClearingAndCompaction) {
  TriangleLists lists;
  lists.add_slots(3);
  std::vector<std::vector<Index>> expected(3);
  lists.open(std::vector<std::pair<Index, std::size_t>>{{0, 2}, {2, 3}});
  for (Index x : {7, 8}) lists.append(0, x);
  for (Index x : {1, 2, 3}) lists.append(2, x);
  expected[0] = {7, 8};
  expected[2] = {1, 2, 3};
  expect_same(lists, expected);
  // replacing slot 2 and then slot 0 three times makes more garbage than live entries: the pool
  // compacts before the last ranges are given
  for (int round = 0; round < 3; ++round) {
    lists.open(std::vector<std::pair<Index, std::size_t>>{{2, 1}, {0, 4}});
    lists.append(2, 40 + round);
    for (Index x : {10, 11, 12, 13}) lists.append(0, x + round);
    expected[2] = {40 + round};
    expected[0] = {10 + round, 11 + round, 12 + round, 13 + round};
    expect_same(lists, expected);
  }
  lists.clear(0);
  expected[0].clear();
  lists.add_slots(1);
  expected.emplace_back();
  lists.open(std::vector<std::pair<Index, std::size_t>>{{3, 2}});
  lists.append(3, 5);
  lists.append(3, 6);
  expected[3] = {5, 6};
  expect_same(lists, expected);
}

RC_GTEST_PROP(TriangleListsProperties, AgreeWithAVectorPerSlot, ()) {
  TriangleLists lists;
  std::vector<std::vector<Index>> expected;
  const int steps = *rc::gen::inRange(1, 60);
  for (int step = 0; step < steps; ++step) {
    const int what = *rc::gen::inRange(0, 4);
    if (what == 0 || expected.empty()) {
      const auto count = static_cast<std::size_t>(*rc::gen::inRange(1, 5));
      lists.add_slots(count);
      expected.resize(expected.size() + count);
    } else if (what == 1) {
      const auto t = *rc::gen::inRange<std::size_t>(0, expected.size());
      lists.clear(static_cast<Index>(t));
      expected[t].clear();
    } else {
      // a batch of distinct slots, each given a size and then filled to it
      std::vector<std::pair<Index, std::size_t>> batch;
      std::vector<bool> taken(expected.size(), false);
      const int n = *rc::gen::inRange(1, 4);
      for (int i = 0; i < n; ++i) {
        const auto t = *rc::gen::inRange<std::size_t>(0, expected.size());
        if (taken[t]) continue;
        taken[t] = true;
        batch.emplace_back(static_cast<Index>(t), static_cast<std::size_t>(*rc::gen::inRange(0, 7)));
      }
      lists.open(batch);
      for (const auto& [t, size] : batch) {
        expected[static_cast<std::size_t>(t)].clear();
        for (std::size_t i = 0; i < size; ++i) {
          const Index x = *rc::gen::inRange(0, 1000);
          lists.append(t, x);
          expected[static_cast<std::size_t>(t)].push_back(x);
        }
      }
    }
    RC_ASSERT(lists.slot_count() == expected.size());
  }
  for (std::size_t t = 0; t < expected.size(); ++t) {
    const auto got = lists[static_cast<Index>(t)];
    RC_ASSERT(std::vector<Index>(got.begin(), got.end()) == expected[t]);
  }
}
