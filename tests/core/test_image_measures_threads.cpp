// image_measures computes its per-region and per-element terms on all threads and sums them in
// one fixed order, so the measures are the same to the last bit for every thread count (the
// projection's covered measures, and the sheets it keeps, must not depend on it).
#include <plmap/core/face_removal.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

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

// covered_domain_measure gives image_measures' covered domain measure to the last bit without
// measuring the images, for every thread count, before and after faces are removed (the
// projection takes the measure of what its fold removals leave out as the difference).
namespace {

template <int d>
void expect_domain_measure_of_image_measures(const PlMap<d>& original, Index every) {
  PlMap<d> map(original);
  for (int round = 0; round < 3; ++round) {
    const double expected = image_measures(map, 1).covered.domain;
    ASSERT_GT(expected, 0.0);
    for (unsigned threads : {1u, 2u, 3u})
      EXPECT_EQ(std::bit_cast<std::uint64_t>(covered_domain_measure(map, threads)),
                std::bit_cast<std::uint64_t>(expected))
          << "round " << round << ", " << threads << " threads";
    std::vector<Index> named;
    for (Index r = round; r < map.region_count(); r += every) named.push_back(r);
    const Index before = map.region_count();
    map = remove_faces(std::move(map), std::span<const Index>(named));
    ASSERT_LT(map.region_count(), before);
  }
}

}  // namespace

TEST(CoveredDomainMeasure, TrianglesGiveImageMeasuresBits) {
  const auto sub = generators::subdivision_map(generators::bumpy_grid(40), 3, 0.15, 7,
                                               [](Index element, int sub_element) { return (element + sub_element) % 5 == 0; });
  expect_domain_measure_of_image_measures<2>(*sub.map, 211);
}

TEST(CoveredDomainMeasure, CurvesGiveImageMeasuresBits) {
  const auto sub = generators::subdivision_map(generators::zigzag_curve(5000), 4, 0.15, 11,
                                               [](Index element, int sub_element) { return (element * 3 + sub_element) % 7 == 0; });
  expect_domain_measure_of_image_measures<1>(*sub.map, 97);
}
