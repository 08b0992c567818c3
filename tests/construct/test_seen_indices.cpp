// The set that the ring searches around a walk's stop keep of what they met
// (construct/src/seen_indices.hpp).

#include "seen_indices.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace plmap;
using namespace plmap::projection;

TEST(SeenIndices, TakesEachUnseenIndexOnceInTheOrderItComes) {
  SeenIndices seen;
  std::vector<Index> fresh;
  take_unseen_into(std::vector<Index>{7, 3, 7, 0, 3, 12}, seen, fresh);
  EXPECT_EQ(fresh, (std::vector<Index>{7, 3, 0, 12}));
  take_unseen_into(std::vector<Index>{12, 5, 0, 5, 8}, seen, fresh);
  EXPECT_EQ(fresh, (std::vector<Index>{5, 8}));
  take_unseen_into(std::vector<Index>{3, 7}, seen, fresh);
  EXPECT_TRUE(fresh.empty());
}

TEST(SeenIndices, KeepsWhatItHoldsWhenItGrows) {
  SeenIndices seen;
  // far more than the first table holds, with indices that share their low bits
  for (Index i = 0; i < 5000; ++i) EXPECT_TRUE(seen.insert(i * 1024)) << i;
  for (Index i = 0; i < 5000; ++i) EXPECT_FALSE(seen.insert(i * 1024)) << i;
  EXPECT_TRUE(seen.insert(1));
  EXPECT_TRUE(seen.insert(2147483646));
  EXPECT_FALSE(seen.insert(2147483646));
}
