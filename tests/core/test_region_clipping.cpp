// clip_regions (core/region_clipping.hpp): a region cut along a line keeps exactly its part on
// the kept side, with Xi unchanged there; the regions that share a cut side (in the element, or
// across an S1 edge) are split at the new node; the map stays valid.

#include <plmap/core/errors.hpp>
#include <plmap/core/region_clipping.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <Eigen/LU>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../verify_violations.hpp"

#include <optional>
#include <random>
#include <vector>

using namespace plmap;
using plmap::test::verify_violations;

namespace {

/// Xi at local point xi of element t, found by testing every region of t (no point locator).
std::optional<WorldPoint<2>> xi_at(const PlMap<2>& map, Index t, const LocalPoint<2>& xi) {
  const auto& m = map.data();
  for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) {
    const auto& c = m.region_corners[r];
    const LocalPoint<2> a = m.node_position[c[0]], b = m.node_position[c[1]], d = m.node_position[c[2]];
    Eigen::Matrix2d e;
    e << b - a, d - a;
    const LocalPoint<2> w = e.inverse() * (xi - a);
    if (w.x() >= -1e-12 && w.y() >= -1e-12 && w.x() + w.y() <= 1.0 + 1e-12)
      return map.target().world_position(m.region_target[r], apply<2>(m.region_map[r], xi));
  }
  return std::nullopt;
}

/// Area of the part of triangle (a, b, c) where n . x + o >= 0 (Sutherland-Hodgman, written
/// here independently of the library).
double kept_area(const std::array<LocalPoint<2>, 3>& tri, const LocalPoint<2>& n, double o) {
  std::vector<LocalPoint<2>> out;
  for (int i = 0; i < 3; ++i) {
    const LocalPoint<2> p = tri[i], q = tri[(i + 1) % 3];
    const double fp = n.dot(p) + o, fq = n.dot(q) + o;
    if (fp >= 0) out.push_back(p);
    if ((fp >= 0) != (fq >= 0)) out.push_back(p + fp / (fp - fq) * (q - p));
  }
  double area = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const LocalPoint<2> p = out[i], q = out[(i + 1) % out.size()];
    area += 0.5 * (p.x() * q.y() - p.y() * q.x());
  }
  return area;
}

double local_area(const std::array<LocalPoint<2>, 3>& t) {
  return 0.5 * ((t[1] - t[0]).x() * (t[2] - t[0]).y() - (t[1] - t[0]).y() * (t[2] - t[0]).x());
}

std::array<LocalPoint<2>, 3> corners_of(const PlMap<2>& map, Index r) {
  const auto& m = map.data();
  const auto& c = m.region_corners[r];
  return {m.node_position[c[0]], m.node_position[c[1]], m.node_position[c[2]]};
}

/// A line through the region at barycentric point w with normal n.
RegionClip line_through(const PlMap<2>& map, Index r, const Eigen::Vector3d& w, const LocalPoint<2>& n) {
  const auto c = corners_of(map, r);
  const LocalPoint<2> p = w(0) * c[0] + w(1) * c[1] + w(2) * c[2];
  return {r, n, -n.dot(p)};
}

}  // namespace

TEST(RegionClipping, ACutRegionKeepsItsSideWithXiUnchangedAndTheRestLeaves) {
  const auto sm = generators::subdivision_map(generators::two_triangles(), 3, 0.1, 7);
  const PlMap<2>& map = *sm.map;
  ASSERT_EQ(verify_violations(map), "");
  // region 0 lies at corner 0 of element 0: the line cuts it into a triangle and a quadrilateral
  const Index r = 0;
  const RegionClip clip = line_through(map, r, {0.3, 0.4, 0.3}, LocalPoint<2>(1.0, 0.35));
  const auto tri = corners_of(map, r);
  const double fraction = kept_area(tri, clip.normal, clip.offset) / local_area(tri);
  ASSERT_GT(fraction, 0.05);
  ASSERT_LT(fraction, 0.95);
  const double area = remote_intersection(map, r).domain_measure();
  RegionClipReport report;
  const PlMap<2> clipped = clip_regions(map, std::span<const RegionClip>(&clip, 1), &report);
  EXPECT_EQ(report.clipped_regions, 1);
  EXPECT_EQ(report.removed_regions, 0);
  EXPECT_EQ(report.new_nodes, 2);
  EXPECT_EQ(clipped.node_count(), map.node_count() + 2);
  EXPECT_NEAR(covered_measure(clipped).domain, covered_measure(map).domain - (1.0 - fraction) * area, 1e-14);
  EXPECT_EQ(verify_violations(clipped), "");
  // Xi on a grid of points of the old region: unchanged on the kept side, undefined beyond
  const Index t = 0;
  int kept = 0, gone = 0;
  // (inside the region only: its sides belong to its neighbours too)
  for (int i = 1; i < 20; ++i)
    for (int j = 1; i + j < 20; ++j) {
      const double u = i / 20.0, v = j / 20.0;
      const LocalPoint<2> x = (1 - u - v) * tri[0] + u * tri[1] + v * tri[2];
      const double f = clip.normal.dot(x) + clip.offset;
      if (std::abs(f) < 1e-9) continue;
      const auto before = xi_at(map, t, x), after = xi_at(clipped, t, x);
      ASSERT_TRUE(before);
      if (f > 0) {
        ASSERT_TRUE(after) << x.transpose();
        EXPECT_LT((*after - *before).norm(), 1e-14);
        ++kept;
      } else {
        EXPECT_FALSE(after) << x.transpose();
        ++gone;
      }
    }
  EXPECT_GT(kept, 10);
  EXPECT_GT(gone, 10);
}

TEST(RegionClipping, ACutEndingOnASharedS1EdgeSplitsTheRegionAcrossIt) {
  const auto sm = generators::subdivision_map(generators::two_triangles(), 3, 0.1, 7);
  const PlMap<2>& map = *sm.map;
  const auto& m = map.data();
  // a region of element 0 with a side on the S1 edge it shares with element 1
  const Surface<2>& s1 = map.domain();
  Index shared_edge_local = -1;
  for (int k = 0; k < 3; ++k)
    if (s1.edge_elements(s1.element_edge(0, k)).size() == 2) shared_edge_local = k;
  ASSERT_GE(shared_edge_local, 0);
  Index r = invalid_index;
  int side = -1;
  for (Index q = map.regions_begin(0); q < map.regions_end(0) && r == invalid_index; ++q) {
    const auto& c = m.region_corners[q];
    for (int i = 0; i < 3 && r == invalid_index; ++i) {
      const auto list = map.edge_nodes(0, static_cast<int>(shared_edge_local));
      const bool a_on = std::find(list.begin(), list.end(), c[i]) != list.end();
      const bool b_on = std::find(list.begin(), list.end(), c[(i + 1) % 3]) != list.end();
      if (a_on && b_on) {
        r = q;
        side = i;
      }
    }
  }
  ASSERT_NE(r, invalid_index);
  // a line through the middle of that side and the opposite corner's neighbourhood
  const auto tri = corners_of(map, r);
  const LocalPoint<2> mid = 0.5 * (tri[side] + tri[(side + 1) % 3]);
  const LocalPoint<2> along = tri[(side + 2) % 3] - mid;
  const LocalPoint<2> normal(-along.y(), along.x());
  const LocalPoint<2> through = mid + 0.1 * (tri[(side + 1) % 3] - mid);
  const RegionClip clip{r, normal, -normal.dot(through)};
  const Index regions_of_1 = map.regions_end(1) - map.regions_begin(1);
  RegionClipReport report;
  const PlMap<2> clipped = clip_regions(map, std::span<const RegionClip>(&clip, 1), &report);
  EXPECT_EQ(report.clipped_regions, 1);
  EXPECT_EQ(report.new_nodes, 3);  // one inside, one on the S1 edge with its copy in element 1
  EXPECT_GE(report.split_regions, 1);
  EXPECT_EQ(clipped.regions_end(1) - clipped.regions_begin(1), regions_of_1 + 1);
  EXPECT_NEAR(covered_measure(clipped).domain,
              covered_measure(map).domain -
                  (1.0 - kept_area(tri, clip.normal, clip.offset) / local_area(tri)) * remote_intersection(map, r).domain_measure(),
              1e-14);
  EXPECT_EQ(verify_violations(clipped), "");
}

TEST(RegionClipping, ALineOutsideTheRegionChangesNothingAndOneBeyondItRemovesIt) {
  const auto sm = generators::subdivision_map(generators::two_triangles(), 3, 0.1, 7);
  const PlMap<2>& map = *sm.map;
  const Index r = 4;
  const auto tri = corners_of(map, r);
  // keeps the whole triangle: the line lies beyond its corners
  const LocalPoint<2> n(0.3, 1.0);
  double lowest = 1e300, highest = -1e300;
  for (const auto& p : tri) {
    lowest = std::min(lowest, n.dot(p));
    highest = std::max(highest, n.dot(p));
  }
  const RegionClip keep_all{r, n, -lowest + 0.01};
  const PlMap<2> same = clip_regions(map, std::span<const RegionClip>(&keep_all, 1));
  EXPECT_EQ(same.data(), map.data());
  RegionClipReport report;
  const RegionClip keep_none{r, n, -highest - 0.01};
  const PlMap<2> smaller = clip_regions(map, std::span<const RegionClip>(&keep_none, 1), &report);
  EXPECT_EQ(report.removed_regions, 1);
  EXPECT_EQ(smaller.region_count(), map.region_count() - 1);
  EXPECT_NEAR(covered_measure(smaller).domain, covered_measure(map).domain - remote_intersection(map, r).domain_measure(), 1e-14);
}

TEST(RegionClipping, BadClipsAreRefused) {
  const auto sm = generators::subdivision_map(generators::two_triangles(), 2, 0.1, 7);
  const PlMap<2>& map = *sm.map;
  const RegionClip out_of_range{map.region_count(), LocalPoint<2>(1, 0), 0};
  EXPECT_THROW(clip_regions(map, std::span<const RegionClip>(&out_of_range, 1)), InvalidMapError);
  const std::array<RegionClip, 2> twice{RegionClip{0, LocalPoint<2>(1, 0), 0}, RegionClip{0, LocalPoint<2>(0, 1), 0}};
  EXPECT_THROW(clip_regions(map, std::span<const RegionClip>(twice)), InvalidMapError);
  const RegionClip no_direction{0, LocalPoint<2>(0, 0), 0};
  EXPECT_THROW(clip_regions(map, std::span<const RegionClip>(&no_direction, 1)), InvalidMapError);
}

TEST(RegionClipping, RandomCutsOfManyRegionsKeepAValidMapAndExactlyTheirKeptParts) {
  // Up to a dozen regions of a jittered subdivision map cut at once by random lines (neighbours
  // cut too, so that one side can carry the nodes of two cuts): the map stays valid, and the
  // covered measure falls by exactly the parts beyond the lines, computed here independently.
  std::mt19937_64 random(20261207);
  for (int round = 0; round < 300; ++round) {
    const auto sm = generators::subdivision_map(generators::bumpy_grid(2), 3, 0.2, 100 + round);
    const PlMap<2>& map = *sm.map;
    std::uniform_int_distribution<Index> region(0, map.region_count() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<RegionClip> clips;
    std::vector<char> named(static_cast<std::size_t>(map.region_count()), 0);
    double removed = 0.0;
    const int count = 1 + round % 12;
    for (int i = 0; i < count; ++i) {
      const Index r = region(random);
      if (named[static_cast<std::size_t>(r)]++) continue;
      const double angle = 2 * 3.141592653589793 * unit(random);
      double w1 = unit(random), w2 = unit(random);
      if (w1 + w2 > 1) {
        w1 = 1 - w1;
        w2 = 1 - w2;
      }
      const RegionClip clip = line_through(map, r, {1 - w1 - w2, w1, w2}, LocalPoint<2>(std::cos(angle), std::sin(angle)));
      const auto tri = corners_of(map, r);
      const double fraction = kept_area(tri, clip.normal, clip.offset) / local_area(tri);
      // (a cut within the snapping distance of a corner is made through the corner: those are
      // left out here, so that the expected measure is exact)
      if (fraction < 1e-4 || fraction > 1 - 1e-4) continue;
      removed += (1.0 - fraction) * remote_intersection(map, r).domain_measure();
      clips.push_back(clip);
    }
    RegionClipReport report;
    const PlMap<2> clipped = clip_regions(map, std::span<const RegionClip>(clips), &report);
    EXPECT_EQ(report.clipped_regions + report.removed_regions, static_cast<Index>(clips.size())) << "round " << round;
    EXPECT_NEAR(covered_measure(clipped).domain, covered_measure(map).domain - removed, 1e-12) << "round " << round;
    std::string lines;
    for (const RegionClip& c : clips)
      lines += fmt::format(" region {} normal ({}, {}) offset {};", c.region, c.normal.x(), c.normal.y(), c.offset);
    ASSERT_EQ(verify_violations(clipped), "") << "round " << round << ":" << lines;
    // made on three threads (the changed elements in pieces, the arrays side by side): the same
    // map and report
    RegionClipReport report3;
    const PlMap<2> clipped3 = clip_regions(map, std::span<const RegionClip>(clips), &report3, 3);
    // (the neighbour lists and edge arrays are compared through the stored graph: verify has
    // derived the full ones on `clipped` by now, not on `clipped3`)
    const MapData<2>& x = clipped3.stored();
    const MapData<2>& y = clipped.stored();
    EXPECT_TRUE(x.node_begin == y.node_begin && x.node_position == y.node_position && x.node_type == y.node_type &&
                x.node_location == y.node_location && x.node_image_element == y.node_image_element &&
                x.node_image_local == y.node_image_local && x.node_target == y.node_target &&
                x.region_begin == y.region_begin && x.region_corners == y.region_corners &&
                x.region_target == y.region_target && x.region_map == y.region_map && x.start_region == y.start_region &&
                clipped3.stored_graph() == clipped.stored_graph())
        << "round " << round;
    EXPECT_EQ(report3.clipped_regions, report.clipped_regions) << "round " << round;
    EXPECT_EQ(report3.removed_regions, report.removed_regions) << "round " << round;
    EXPECT_EQ(report3.split_regions, report.split_regions) << "round " << round;
    EXPECT_EQ(report3.new_nodes, report.new_nodes) << "round " << round;
    EXPECT_EQ(report3.changed_elements, report.changed_elements) << "round " << round;
  }
}
