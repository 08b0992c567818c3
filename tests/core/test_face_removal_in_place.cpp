// remove_faces on a map it may take apart (core/face_removal.hpp): the in-place removal must give
// the map the header describes, checked against the rule by brute force (face_removal_rule.hpp).
// Projected maps, with closure edges everywhere: tests/construct/test_face_removal_projected.cpp.

#include "face_removal_rule.hpp"

#include <plmap/core/face_removal.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>

using namespace plmap;

using plmap::test::expect_rule_holds;
using plmap::test::entries_of;


TEST(FaceRemovalInPlace, KeepsWhatTheRuleKeepsOnSurfaces) {
  const auto sm = generators::subdivision_map(generators::two_triangles(), 6, 0.2, 5);
  const PlMap<2>& map = *sm.map;
  std::mt19937 random(11);
  for (int round = 0; round < 40; ++round) {
    std::vector<Index> named(1 + round % 5);
    for (Index& r : named) r = static_cast<Index>(random() % static_cast<unsigned>(map.region_count()));
    expect_rule_holds(map, named);
  }
}

TEST(FaceRemovalInPlace, KeepsWhatTheRuleKeepsOnCurves) {
  const auto sm = generators::subdivision_map(generators::zigzag_curve(6), 5, 0.2, 3);
  const PlMap<1>& map = *sm.map;
  std::mt19937 random(13);
  for (int round = 0; round < 40; ++round) {
    std::vector<Index> named(1 + round % 4);
    for (Index& r : named) r = static_cast<Index>(random() % static_cast<unsigned>(map.region_count()));
    expect_rule_holds(map, named);
  }
}

TEST(FaceRemovalInPlace, RemovingTwiceEqualsRemovingBoth) {
  // what project() does: the folded faces, then the farther sheet, each on the previous result
  const auto sm = generators::subdivision_map(generators::two_triangles(), 5, 0.1, 9);
  const PlMap<2>& map = *sm.map;
  const std::vector<Index> first = {0, 3}, both = {0, 3, map.region_count() - 1};
  const PlMap<2> once = remove_faces(map, std::span<const Index>(both));
  PlMap<2> twice = remove_faces(PlMap<2>(map), std::span<const Index>(first));
  // the last region keeps its place at the end
  const Index last = twice.region_count() - 1;
  twice = remove_faces(std::move(twice), std::span<const Index>(&last, 1));
  EXPECT_EQ(entries_of(twice), entries_of(once));
  EXPECT_EQ(twice.data().region_corners, once.data().region_corners);
  EXPECT_EQ(twice.data().region_neighbors, once.data().region_neighbors);
  EXPECT_EQ(twice.data().start_region, once.data().start_region);
}
