// White-box tests of the closure (core/src/element_closure.hpp). The O(k) simplicity shortcut:
// whenever convex_and_winding_once accepts a face, the pairwise test agrees it is simple, and it
// accepts the convex faces it is meant for. The fast path as a whole: the same closure as its
// plain reference.
#include "element_closure.hpp"
#include "reference_element_closure.hpp"

#include <plmap/core/predicates.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <numbers>
#include <numeric>
#include <random>

using namespace plmap;

namespace {

/// The O(k^2) test of close_by_faces: no two sides meet except consecutive ones at their vertex.
bool simple_by_pairs(const std::vector<LocalPoint<2>>& p) {
  const int k = static_cast<int>(p.size());
  for (int i = 0; i < k; ++i)
    for (int j = i + 1; j < k; ++j)
      if (segments_cross_properly(p[i], p[(i + 1) % k], p[j], p[(j + 1) % k])) return false;
  return true;
}

bool shortcut(const std::vector<LocalPoint<2>>& p) {
  std::vector<int> poly(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) poly[i] = static_cast<int>(i);
  return detail::convex_and_winding_once(p, poly);
}

/// Vertices at the given angles (in turns) on an ellipse, on a grid of 1/64 so that collinear
/// and axis-parallel sides occur.
std::vector<LocalPoint<2>> on_ellipse(const std::vector<double>& turns) {
  std::vector<LocalPoint<2>> p;
  for (double t : turns) {
    const double a = 2.0 * std::numbers::pi * t;
    p.emplace_back(std::round(32.0 * std::cos(a)) / 64.0 + 0.5, std::round(20.0 * std::sin(a)) / 64.0 + 0.5);
  }
  return p;
}

}  // namespace

TEST(ElementClosure, ShortcutAcceptsConvexFacesAndRejectsStarsAndSpikes) {
  EXPECT_TRUE(shortcut({{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  EXPECT_TRUE(shortcut({{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}}));  // a straight vertex
  EXPECT_FALSE(shortcut({{0, 0}, {0, 1}, {1, 1}, {1, 0}}));           // clockwise
  // a pentagram: left turns only, but it winds twice
  EXPECT_FALSE(shortcut(on_ellipse({0.0, 0.4, 0.8, 0.2, 0.6})));
  // doubling back along a line: (0,0) -> (1,0) -> (0.5,0) turns by exactly pi
  EXPECT_FALSE(shortcut({{0, 0}, {1, 0}, {0.5, 0}, {0.5, 1}}));
  // a reflex vertex
  EXPECT_FALSE(shortcut({{0, 0}, {1, 0}, {0.5, 0.2}, {1, 1}, {0, 1}}));
}

RC_GTEST_PROP(ElementClosure, ShortcutImpliesSimple, ()) {
  // random vertex sequences on an ellipse: sorted (convex), shuffled or wound several times
  const int k = *rc::gen::inRange(4, 12);
  auto turns = *rc::gen::container<std::vector<double>>(static_cast<std::size_t>(k), rc::gen::map(rc::gen::inRange(0, 1000), [](int i) {
    return i / 1000.0;
  }));
  const int mode = *rc::gen::inRange(0, 3);
  if (mode == 0) std::sort(turns.begin(), turns.end());
  if (mode == 1) {
    std::sort(turns.begin(), turns.end());
    for (std::size_t i = 0; i < turns.size(); i += 2) turns[i] += 1.0;  // every other vertex a turn later
    for (auto& t : turns) t *= 2.0;  // ... and wound twice
  }
  auto p = on_ellipse(turns);
  // distinct vertices, as close_by_faces guarantees before the test
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) RC_PRE(p[i] != p[j]);
  if (shortcut(p)) RC_ASSERT(simple_by_pairs(p));
  if (mode == 0 && simple_by_pairs(p)) {
    // sorted by angle on a convex curve and simple: convex unless rounding made a right turn
    bool left = true;
    for (int i = 0; i < k; ++i) left = left && orient2d(p[(i + k - 1) % k], p[i], p[(i + 1) % k]) >= 0;
    RC_ASSERT(shortcut(p) == left);
  }
}

// ---- the fast path against its reference --------------------------------------------------------
// close_by_faces pairs triangle sides while cutting ears, tests ears of convex faces against one
// side only, sorts edges around a vertex with a filtered turn test, and tells graph edges by flags
// carried through the flips; the reference (reference_element_closure.hpp) does each the plain
// way. On random element graphs both must decline alike or give the same triangles, in the same
// order, with the same neighbours, and the same rings.

namespace {

/// A random graph on the reference triangle: the lattice of spacing 1/n (moved off the lattice
/// inside when `jitter`, so that both cocircular ties and general position occur), triangulated
/// with random diagonals, of which a random part are graph edges.
struct RandomElementGraph {
  std::vector<LocalPoint<2>> points;
  std::vector<detail::ClosureSegment> segments;  // sorted by (a, b)
  std::array<int, 2> boundary_start{};
};

RandomElementGraph random_element_graph(std::mt19937_64& rng, int n, bool jitter, double keep) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RandomElementGraph g;
  std::vector<std::vector<int>> id(n + 1, std::vector<int>(n + 1, -1));
  const double h = 1.0 / n;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      LocalPoint<2> p(i * h, j * h);
      if (i + j == n) {  // on x + y = 1 exactly, as the builder places edge nodes
        const double s = j * h;
        p = s >= 0.5 ? LocalPoint<2>(1.0 - s, s) : LocalPoint<2>(1.0 - s, 1.0 - (1.0 - s));
      } else if (jitter && i > 0 && j > 0) {
        p += LocalPoint<2>((u(rng) - 0.5) * 0.4 * h, (u(rng) - 0.5) * 0.4 * h);
      }
      id[i][j] = static_cast<int>(g.points.size());
      g.points.push_back(p);
    }
  // a random relabelling, so that vertex order and geometry are unrelated
  std::vector<int> label(g.points.size());
  std::iota(label.begin(), label.end(), 0);
  std::shuffle(label.begin(), label.end(), rng);
  std::vector<LocalPoint<2>> relabelled(g.points.size());
  for (std::size_t v = 0; v < g.points.size(); ++v) relabelled[label[v]] = g.points[v];
  g.points = relabelled;
  auto at = [&](int i, int j) { return label[id[i][j]]; };
  std::vector<std::pair<std::array<int, 2>, bool>> edges;  // (a, b), on the boundary
  auto add = [&](int a, int b, bool boundary) { edges.push_back({{std::min(a, b), std::max(a, b)}, boundary}); };
  for (int i = 0; i < n; ++i) {
    add(at(i, 0), at(i + 1, 0), true);              // y = 0
    add(at(0, i), at(0, i + 1), true);              // x = 0
    add(at(n - i, i), at(n - i - 1, i + 1), true);  // x + y = 1
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      if (i + j + 1 < n) {  // a lattice square: its two inner sides and a random diagonal
        add(at(i + 1, j), at(i + 1, j + 1), false);
        add(at(i, j + 1), at(i + 1, j + 1), false);
        if (u(rng) < 0.5) add(at(i, j), at(i + 1, j + 1), false);
        else add(at(i + 1, j), at(i, j + 1), false);
      }
    }
  // the square sides on the lattice's outer rows were added twice or lie on the boundary
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end(),
                          [](const auto& x, const auto& y) { return x.first == y.first; }),
              edges.end());
  // the inner edges of the lattice triangles along x + y = 1 that the squares did not add
  for (int i = 0; i < n; ++i) {
    const int j = n - 1 - i;
    const std::array<int, 2> e1{std::min(at(i, j), at(i + 1, j)), std::max(at(i, j), at(i + 1, j))};
    const std::array<int, 2> e2{std::min(at(i, j), at(i, j + 1)), std::max(at(i, j), at(i, j + 1))};
    for (const auto& e : {e1, e2})
      if (std::none_of(edges.begin(), edges.end(), [&](const auto& x) { return x.first == e; }))
        edges.push_back({e, false});
  }
  std::sort(edges.begin(), edges.end());
  for (const auto& [e, boundary] : edges) {
    const bool graph = u(rng) < keep;
    if (boundary || graph) g.segments.push_back({e[0], e[1], graph});
  }
  g.boundary_start = {at(0, 0), at(1, 0)};
  return g;
}

}  // namespace

TEST(ElementClosure, FastPathMatchesItsReferenceOnRandomGraphs) {
  std::mt19937_64 rng(7341);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  detail::ElementClosure closure;
  detail::ClosureScratch scratch;
  reference::Closure expected;
  reference::Scratch reference_scratch;
  std::vector<int> ring_begin, incident, expected_begin, expected_ring;
  std::vector<detail::RingEntry> ring;
  int closed = 0, declined = 0, cut = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int n = 1 + static_cast<int>(rng() % 6);
    const auto g = random_element_graph(rng, n, trial % 2 == 1, 0.1 + 0.8 * u(rng));
    std::vector<std::array<int, 2>> pairs;
    for (const auto& s : g.segments) pairs.push_back({s.a, s.b});
    const bool ok = detail::close_by_faces(g.points, g.segments, g.boundary_start, closure, scratch);
    const bool expected_ok = reference::close_by_faces(g.points, pairs, g.boundary_start, expected, reference_scratch);
    ASSERT_EQ(ok, expected_ok) << "trial " << trial;
    if (!ok) {
      ++declined;
      continue;
    }
    ++closed;
    ASSERT_EQ(closure.triangles, expected.triangles) << "trial " << trial;
    ASSERT_EQ(closure.neighbors, expected.neighbors) << "trial " << trial;
    ASSERT_EQ(closure.face, expected.face) << "trial " << trial;
    ASSERT_EQ(closure.face_count, expected.face_count) << "trial " << trial;
    // graph flags: exactly the sides that are graph segments
    for (std::size_t t = 0; t < closure.triangles.size(); ++t)
      for (int i = 0; i < 3; ++i) {
        const int a = closure.triangles[t][(i + 1) % 3], b = closure.triangles[t][(i + 2) % 3];
        const bool graph = std::any_of(g.segments.begin(), g.segments.end(), [&](const auto& s) {
          return s.graph && s.a == std::min(a, b) && s.b == std::max(a, b);
        });
        ASSERT_EQ(((closure.graph_sides[t] >> i) & 1) != 0, graph) << "trial " << trial;
      }
    // some face had to be cut into several triangles (ears, and diagonals to flip)
    cut += closure.triangles.size() > static_cast<std::size_t>(closure.face_count);
    const int nv = static_cast<int>(g.points.size());
    detail::closure_rings(closure, nv, nv, ring_begin, ring, incident);
    reference::Closure as_closed{closure.triangles, closure.neighbors, closure.face, closure.face_count};
    reference::closure_rings(as_closed, nv, expected_begin, expected_ring);
    ASSERT_EQ(ring_begin, expected_begin) << "trial " << trial;
    auto is_graph_segment = [&](int a, int b) {
      return std::any_of(g.segments.begin(), g.segments.end(), [&](const auto& s) {
        return s.graph && s.a == std::min(a, b) && s.b == std::max(a, b);
      });
    };
    for (int v = 0; v < nv; ++v) {
      const int first = ring_begin[v], last = ring_begin[v + 1];
      for (int r = first; r < last; ++r) {
        ASSERT_EQ(ring[r].vertex, expected_ring[r]) << "trial " << trial;
        ASSERT_EQ(ring[r].graph, is_graph_segment(v, ring[r].vertex)) << "trial " << trial;
        // the triangle after an entry is the one before the next entry, and holds v and both
        const int following = r + 1 < last ? r + 1 : first;
        ASSERT_EQ(ring[r].after, r + 1 < last || ring[r].after >= 0 ? ring[following].before : -1)
            << "trial " << trial;
        if (ring[r].after >= 0) {
          const auto& tri = closure.triangles[ring[r].after];
          for (int x : {v, ring[r].vertex, ring[following].vertex})
            ASSERT_EQ(std::count(tri.begin(), tri.end(), x), 1) << "trial " << trial;
        }
      }
    }
  }
  EXPECT_GT(closed, 1000);
  EXPECT_GT(declined, 100);
  EXPECT_GT(cut, 500);
}

TEST(ElementClosure, RingsNameTheTrianglesBesideEachEdge) {
  // Unit square cut by its diagonal 0-2: around vertex 0 (a boundary vertex) the ring is 1, 2, 3
  // with the triangles (0, 1, 2) and (0, 2, 3) between them.
  detail::ElementClosure c;
  c.triangles = {{0, 1, 2}, {0, 2, 3}};
  c.neighbors = {{-1, 1, -1}, {-1, -1, 0}};
  c.graph_sides = {0b010, 0b100};  // side 0-2 is a graph edge (flagged in both triangles)
  c.face = {0, 0};
  c.face_count = 1;
  std::vector<int> begin, incident;
  std::vector<detail::RingEntry> ring;
  detail::closure_rings(c, 4, 4, begin, ring, incident);
  ASSERT_EQ(begin, (std::vector<int>{0, 3, 5, 8, 10}));
  EXPECT_EQ(ring[0].vertex, 1);
  EXPECT_EQ(ring[0].before, -1);
  EXPECT_EQ(ring[0].after, 0);
  EXPECT_EQ(ring[1].vertex, 2);
  EXPECT_EQ(ring[1].before, 0);
  EXPECT_EQ(ring[1].after, 1);
  EXPECT_TRUE(ring[1].graph);
  EXPECT_EQ(ring[2].vertex, 3);
  EXPECT_EQ(ring[2].before, 1);
  EXPECT_EQ(ring[2].after, -1);
  EXPECT_FALSE(ring[0].graph || ring[2].graph);
}
