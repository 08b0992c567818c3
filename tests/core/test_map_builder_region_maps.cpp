// The regions' affine maps that finalize() writes after the builder is freed, from the nodes'
// stored images and the omitted weights kept where 1 minus the stored two does not give them back
// (core/src/finalize_region_maps.hpp; crossing 0.3 needs one), against those finalize_reusing() writes
// with the regions from the closure's own corner images (reusing nothing, it closes every
// element that way). The images of intersection nodes are re-expressed from their image element
// onto the S2 element across their S2 edge; every rotation of the S2 elements' corners is tried,
// so that the weight node_image_local leaves out (corner 0's) is needed in some of them.

#include <plmap/core/map_builder.hpp>

#include <gtest/gtest.h>

#include <array>
#include <optional>

using namespace plmap;

namespace {

WorldPoint<2> P(double x, double y) { return {x, y, 0.0}; }

ElementCorners<2> rotated(ElementCorners<2> c, int by) {
  for (int i = 0; i < by; ++i) c = {c[1], c[2], c[0]};
  return c;
}

/// The nodes and edges of the square maps below: S1's and S2's corners on each other, S2's
/// diagonal 1-3 crossing S1's 0-2 at `crossing`.
void add_square_graph(MapBuilder<2>& b, const Surface<2>& s1, const Surface<2>& s2, double crossing) {
  for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
  const Index diagonal = s2.find_edge(1, 3);
  for (Index e = 0; e < s2.edge_count(); ++e) {
    if (e == diagonal) {
      const EdgeCrossing c{s1.find_edge(0, 2), crossing, crossing};
      b.add_edge(e, std::span(&c, 1));
    } else {
      b.add_edge(e);
    }
  }
}

/// S1: the unit square split along diagonal 0-2; S2: split along 1-3 (corners rotated by r0,
/// r1), its diagonal's preimage crossing S1's at the given parameter of both. With `previous`,
/// on its surfaces, every element closed again by finalize_reusing.
PlMap<2> square_map(int r0, int r1, double crossing, int orientation, const PlMap<2>* previous) {
  const std::vector<WorldPoint<2>> corners{P(0, 0), P(1, 0), P(1, 1), P(0, 1)};
  static std::shared_ptr<const Surface<2>> s1 = std::make_shared<const Surface<2>>(
      corners, std::vector<ElementCorners<2>>{{0, 1, 2}, {0, 2, 3}});
  auto s2 = previous != nullptr
                ? previous->target_ptr()
                : std::make_shared<const Surface<2>>(
                      corners, std::vector<ElementCorners<2>>{rotated({0, 1, 3}, r0), rotated({1, 2, 3}, r1)});
  BuilderOptions options;
  options.orientation = orientation;
  MapBuilder<2> b(s1, s2, options);
  add_square_graph(b, *s1, *s2, crossing);
  if (previous == nullptr) return std::move(b).finalize();
  const std::vector<char> none(2, 0);
  return std::move(b).finalize_reusing(*previous, none);
}

}  // namespace

TEST(MapBuilderRegionMaps, WrittenAfterTheBuilderEqualTheClosuresOwnForEveryCornerOrder) {
  for (int r0 = 0; r0 < 3; ++r0)
    for (int r1 = 0; r1 < 3; ++r1)
      for (const double crossing : {0.3, 0.5, 0.7}) {
        SCOPED_TRACE(testing::Message() << "rotations " << r0 << ", " << r1 << ", crossing " << crossing);
        const PlMap<2> deferred = square_map(r0, r1, crossing, 0, nullptr);
        ASSERT_EQ(deferred.region_count(), 4);
        const PlMap<2> closed = square_map(r0, r1, crossing, deferred.stored().orientation, &deferred);
        EXPECT_TRUE(closed.stored().region_map == deferred.stored().region_map);
        EXPECT_TRUE(closed.stored() == deferred.stored());
      }
}

TEST(MapBuilderRegionMaps, FinalizeMeasuresTheImagesAsTheFinishedMapGivesThem) {
  // BuilderOptions::measure_images: the image measures taken while the region maps are written
  // are image_measures() of the finished map (S1's side to the last bit, S2's side to rounding),
  // with the same bits on one thread (summed as the maps are written) and on two (each region's
  // term first, summed after).
  const std::vector<WorldPoint<2>> corners{P(0, 0), P(1, 0), P(1, 1), P(0, 1)};
  auto s1 = std::make_shared<const Surface<2>>(corners, std::vector<ElementCorners<2>>{{0, 1, 2}, {0, 2, 3}});
  for (int r0 = 0; r0 < 3; ++r0)
    for (const double crossing : {0.3, 0.5, 0.7}) {
      auto s2 = std::make_shared<const Surface<2>>(
          corners, std::vector<ElementCorners<2>>{rotated({0, 1, 3}, r0), rotated({1, 2, 3}, (r0 + 1) % 3)});
      std::array<FinalizeReport, 2> reports;
      std::array<std::optional<PlMap<2>>, 2> maps;
      for (unsigned threads : {1u, 2u}) {
        BuilderOptions options;
        options.threads = threads;
        options.measure_images = true;
        MapBuilder<2> b(s1, s2, options);
        add_square_graph(b, *s1, *s2, crossing);
        maps[threads - 1].emplace(std::move(b).finalize(&reports[threads - 1]));
      }
      for (int k = 0; k < 2; ++k) {
        ASSERT_TRUE(reports[k].images.has_value());
        const ImageMeasures& got = *reports[k].images;
        const ImageMeasures want = image_measures(*maps[k]);
        EXPECT_EQ(got.covered.domain, want.covered.domain);
        EXPECT_NEAR(got.covered.target, want.covered.target, 1e-14);
        EXPECT_NEAR(got.covered.target, 1.0, 1e-14);  // the unit square, covered once
        ASSERT_EQ(got.per_target.size(), want.per_target.size());
        for (std::size_t t2 = 0; t2 < got.per_target.size(); ++t2) EXPECT_NEAR(got.per_target[t2], want.per_target[t2], 1e-14);
      }
      EXPECT_EQ(reports[0].images->per_target, reports[1].images->per_target);
      EXPECT_EQ(reports[0].images->covered.target, reports[1].images->covered.target);
      // not asked for: not measured
      MapBuilder<2> plain(s1, s2);
      add_square_graph(plain, *s1, *s2, crossing);
      FinalizeReport report;
      (void)std::move(plain).finalize(&report);
      EXPECT_FALSE(report.images.has_value());
    }
}
