// image_measures computes its per-region and per-element terms on all threads and sums them in
// one fixed order, so the measures are the same to the last bit for every thread count (the
// projection's covered measures, and the sheets it keeps, must not depend on it).
#include <plmap/core/regions.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

using namespace plmap;

namespace {

template <int d>
void expect_same_measures_for_every_thread_count(const PlMap<d>& map) {
  const ImageMeasures one = image_measures(map, 1);
  ASSERT_GT(one.covered.domain, 0.0);
  for (unsigned threads : {2u, 3u, 4u}) {
    const ImageMeasures many = image_measures(map, threads);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(many.covered.domain), std::bit_cast<std::uint64_t>(one.covered.domain))
        << threads << " threads";
    EXPECT_EQ(std::bit_cast<std::uint64_t>(many.covered.target), std::bit_cast<std::uint64_t>(one.covered.target))
        << threads << " threads";
    ASSERT_EQ(many.per_target.size(), one.per_target.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < one.per_target.size(); ++i) {
      if (std::bit_cast<std::uint64_t>(many.per_target[i]) != std::bit_cast<std::uint64_t>(one.per_target[i])) ++differing;
    }
    EXPECT_EQ(differing, 0u) << threads << " threads";
  }
}

}  // namespace

// 80 x 80 x 2 triangles cut into 9 regions each, with holes: more elements and regions than one
// chunk of the parallel loops, and elements without regions.
TEST(ImageMeasuresThreads, TrianglesAreTheSameForEveryThreadCount) {
  const auto sub = generators::subdivision_map(generators::bumpy_grid(80), 3, 0.15, 7,
                                               [](Index element, int sub_element) { return (element + sub_element) % 5 == 0; });
  ASSERT_GT(sub.map->region_count(), 50000);
  expect_same_measures_for_every_thread_count(*sub.map);
}

TEST(ImageMeasuresThreads, CurvesAreTheSameForEveryThreadCount) {
  const auto sub = generators::subdivision_map(generators::zigzag_curve(20000), 4, 0.15, 11,
                                               [](Index element, int sub_element) { return (element * 3 + sub_element) % 7 == 0; });
  ASSERT_GT(sub.map->region_count(), 50000);
  expect_same_measures_for_every_thread_count(*sub.map);
}
