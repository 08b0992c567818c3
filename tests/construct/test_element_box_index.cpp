// ElementBoxIndex (construct/src/element_box_index.hpp) names the elements that may pass within a
// distance of a point, for the long elements the vertex preimage search adds as seeds. The
// search filters what it is given with its own exact tests, so the index may name more than
// needed (within a rounding margin of the distance) but never fewer: every element whose bounding
// box lies within the distance must be visited, once. Checked by brute force on meshes whose
// element sizes span orders of magnitude (the case the tree is built for) and at distances from
// zero to the whole mesh.
#include "../../construct/src/element_box_index.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace plmap;
using plmap::projection::ElementBoxIndex;

namespace {

template <int d>
double box_distance(const Surface<d>& s, Index t, const WorldPoint<d>& x) {
  WorldPoint<d> low = s.corner(t, 0), high = low;
  for (int k = 1; k <= d; ++k) {
    low = low.cwiseMin(s.corner(t, k));
    high = high.cwiseMax(s.corner(t, k));
  }
  return (x.cwiseMax(low).cwiseMin(high) - x).norm();
}

/// Visits from random points at random distances; returns how many (element, query) pairs the
/// index named beyond the exact answer (each within the margin of r).
template <int d>
std::size_t expect_superset(const Surface<d>& s, const WorldPoint<d>& low, const WorldPoint<d>& high, double largest,
                            std::uint32_t seed) {
  const ElementBoxIndex<d> index(s);
  EXPECT_TRUE(index.has_tree());  // uneven sizes: the tree is what is tested
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t extra = 0;
  std::vector<int> visits(static_cast<std::size_t>(s.element_count()));
  for (int q = 0; q < 300; ++q) {
    WorldPoint<d> x;
    for (int k = 0; k <= d; ++k) x(k) = low(k) + (high(k) - low(k)) * (1.4 * unit(random) - 0.2);
    // distances from 0 (a point on an element) to the whole extent, log-uniform
    const double r = q % 10 == 0 ? 0.0 : largest * std::pow(10.0, -5.0 * unit(random));
    std::fill(visits.begin(), visits.end(), 0);
    index.visit_near(x, r, [&](Index t) { ++visits[t]; });
    for (Index t = 0; t < s.element_count(); ++t) {
      EXPECT_LE(visits[t], 1) << "element " << t << " named twice";
      const bool near = box_distance(s, t, x) < r || (r == 0.0 && box_distance(s, t, x) == 0.0);
      if (near) {
        EXPECT_EQ(visits[t], 1) << "element " << t << " at box distance " << box_distance(s, t, x) << " < " << r
                                << " not named (query " << q << ")";
      } else if (visits[t] > 0) {
        // beyond r, only within the documented margin
        EXPECT_LE(box_distance(s, t, x), r * (1.0 + 1e-9)) << "element " << t << " named from far away (query " << q << ")";
        extra += static_cast<std::size_t>(visits[t]);
      }
    }
  }
  return extra;
}

}  // namespace

TEST(ElementBoxIndex, NamesEveryElementWhoseBoxIsNearOnAGradedZigzag) {
  // segment lengths from 1e-4 to about 1 (geometric), zigzagging up and down
  std::vector<WorldPoint<1>> v{{0.0, 0.0}};
  std::vector<ElementCorners<1>> e;
  double h = 1e-4;
  for (int i = 0; i < 600; ++i, h *= 1.016) {
    v.emplace_back(v.back()(0) + 0.3 * h, (i % 2 == 0 ? 1.0 : 0.0) * h);
    e.push_back({i, i + 1});
  }
  const Surface<1> s(v, e);
  const std::size_t extra = expect_superset<1>(s, s.bounding_box_min(), s.bounding_box_max(), 2.0, 3);
  EXPECT_LE(extra, 3u);  // at most a few, within rounding of the distance
}

TEST(ElementBoxIndex, NamesEveryElementWhoseBoxIsNearOnAGradedGrid) {
  // a 40 x 40 grid whose columns and rows shrink geometrically towards x = 0 and y = 0 (cells
  // from 1e-5 to 0.1 wide and high, slivers where a wide column meets a low row)
  const int n = 40;
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.emplace_back(std::pow(10.0, -5.0 + 4.0 * i / n) - 1e-5, std::pow(10.0, -5.0 + 4.0 * j / n) - 1e-5,
                     0.01 * std::sin(i + j));
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      e.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      e.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const Surface<2> s(v, e);
  expect_superset<2>(s, s.bounding_box_min(), s.bounding_box_max(), 1.5, 7);
}
