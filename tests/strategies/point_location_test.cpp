// Point locators: every locator agrees with brute force, reports points outside D as outside,
// handles queries exactly on nodes and region sides, and evaluate_batch does not depend on the
// number of threads.

#include <plmap/verify/generators/subdivision_maps.hpp>

#include <plmap/core/evaluation.hpp>
#include <plmap/core/region_image.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/strategies/point_locator_registry.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace plmap {
namespace {

using point_location::Bisection;
using point_location::BrownFaigleWalk;
using point_location::BruteForce;
using point_location::CellGridLocator;
using point_location::CellGridOptions;
using point_location::StraightWalk;
using point_location::detail::region_contains;

// ---- the maps under test ---------------------------------------------------------------------

// Drops a scattered fifth of the sub-triangles: D ∩ T has holes and is not convex, so walks
// meet sides without neighbours in the middle of the element.
bool drop_some(Index element, int sub) { return (sub * 7 + element * 3) % 5 == 0; }
// Keeps only the sub-triangles of the lower left part of the first element of each pair.
bool drop_most(Index element, int sub) { return element % 2 == 1 || sub % 9 > 2; }

const std::vector<generators::SubdivisionMap<2>>& maps2() {
  static const std::vector<generators::SubdivisionMap<2>> maps = [] {
    std::vector<generators::SubdivisionMap<2>> m;
    m.push_back(generators::subdivision_map(generators::two_triangles(), 1, 0.0, 1));       // S1 itself
    m.push_back(generators::subdivision_map(generators::two_triangles(), 6, 0.2, 2));       // S2: refinement
    m.push_back(generators::subdivision_map(generators::bumpy_grid(3), 11, 0.2, 3));        // 121 per element
    m.push_back(generators::subdivision_map(generators::two_triangles(), 9, 0.15, 4, drop_some));  // holes
    m.push_back(generators::subdivision_map(generators::bumpy_grid(2), 7, 0.1, 5, drop_most));    // partial
    return m;
  }();
  return maps;
}

const std::vector<generators::SubdivisionMap<1>>& maps1() {
  static const std::vector<generators::SubdivisionMap<1>> maps = [] {
    std::vector<generators::SubdivisionMap<1>> m;
    m.push_back(generators::subdivision_map(generators::zigzag_curve(3), 1, 0.0, 1));
    m.push_back(generators::subdivision_map(generators::zigzag_curve(4), 13, 0.3, 2));
    m.push_back(generators::subdivision_map(generators::zigzag_curve(5), 40, 0.3, 3,
                                [](Index e, int s) { return (s + e) % 4 == 0 || s < 3; }));
    return m;
  }();
  return maps;
}

/// Random local coordinates on an element, a little beyond it so that some queries are outside.
LocalPoint<2> random_query(std::mt19937_64& rng, Index& element, Index elements) {
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  element = std::uniform_int_distribution<Index>(0, elements - 1)(rng);
  return {u(rng), u(rng)};
}

/// The locator's answer is right: found exactly when brute force finds a region, and then the
/// returned region belongs to the element and contains the point.
template <int d, class Locator>
::testing::AssertionResult agrees_with_brute_force(Locator& locator, const PlMap<d>& map,
                                                   Index element, const LocalPoint<d>& p) {
  const RegionLocation<d> got = locator.locate(map, element, p);
  const RegionLocation<d> reference = BruteForce<d>{}.locate(map, element, p);
  if (got.found() != reference.found())
    return ::testing::AssertionFailure()
           << "element " << element << " point (" << p.transpose() << "): found " << got.found()
           << ", brute force " << reference.found();
  if (!got.found()) return ::testing::AssertionSuccess();
  if (got.region < map.regions_begin(element) || got.region >= map.regions_end(element))
    return ::testing::AssertionFailure() << "region " << got.region << " not on element " << element;
  if (!region_contains(map.data(), got.region, p))
    return ::testing::AssertionFailure()
           << "region " << got.region << " does not contain (" << p.transpose() << ")";
  return ::testing::AssertionSuccess();
}

// ---- d = 2 -------------------------------------------------------------------------------------

TEST(PointLocation, TestMapsHaveTheExpectedRegions) {
  const auto& m = maps2();
  EXPECT_EQ(m[0].map->region_count(), 2);
  EXPECT_EQ(m[1].map->region_count(), 2 * 36);
  EXPECT_EQ(m[2].map->region_count(), 18 * 121);
  EXPECT_EQ(m[3].map->region_count(), 2 * 81 - Index(m[3].holes.size()));
  EXPECT_GT(m[3].holes.size(), 10u);
  EXPECT_GT(m[4].holes.size(), 100u);
}

/// Cell-grid locators with coarse, default and fine grids (the coarse ones certify few cells and
/// walk a lot; the fine ones answer almost everything from the table).
std::vector<CellGridLocator> cell_grid_variants() {
  return {CellGridLocator(CellGridOptions{0.5, 512}), CellGridLocator(),
          CellGridLocator(CellGridOptions{64, 512}), CellGridLocator(CellGridOptions{8, 3})};
}

/// The variants prepared for test map `which`, built once: property cases copy them (copies
/// share the tables), which keeps the sanitizer build fast.
const std::vector<CellGridLocator>& prepared_cell_grids(std::size_t which) {
  static std::vector<std::vector<CellGridLocator>> prepared(maps2().size());
  if (prepared[which].empty()) {
    prepared[which] = cell_grid_variants();
    for (CellGridLocator& locator : prepared[which]) locator.prepare(*maps2()[which].map);
  }
  return prepared[which];
}

RC_GTEST_PROP(PointLocation, WalksAgreeWithBruteForceOnRandomQueries, ()) {
  const auto which = *rc::gen::inRange<std::size_t>(0, maps2().size());
  const auto seed = *rc::gen::arbitrary<std::uint64_t>();
  const PlMap<2>& map = *maps2()[which].map;
  std::mt19937_64 rng(seed);
  BrownFaigleWalk brown_faigle(seed);
  StraightWalk straight;
  point_location::BucketWalk bucket(seed);
  CellGridLocator cell_grid = prepared_cell_grids(which)[1];
  for (int q = 0; q < 100; ++q) {
    Index element;
    const LocalPoint<2> p = random_query(rng, element, map.domain().element_count());
    RC_ASSERT(agrees_with_brute_force<2>(brown_faigle, map, element, p));
    RC_ASSERT(agrees_with_brute_force<2>(straight, map, element, p));
    RC_ASSERT(agrees_with_brute_force<2>(bucket, map, element, p));
    RC_ASSERT(agrees_with_brute_force<2>(cell_grid, map, element, p));
  }
}

// ---- cell-grid: certified cells answer without a test, so they get their own scrutiny --------


RC_GTEST_PROP(PointLocation, CellGridAgreesWithBruteForceOnRandomAndBoundaryQueries, ()) {
  const auto which = *rc::gen::inRange<std::size_t>(0, maps2().size());
  const PlMap<2>& map = *maps2()[which].map;
  const MapData<2>& m = map.data();
  std::mt19937_64 rng(*rc::gen::arbitrary<std::uint64_t>());
  const auto variant = *rc::gen::inRange<std::size_t>(0, cell_grid_variants().size());
  CellGridLocator locator = prepared_cell_grids(which)[variant];
  const Index elements = map.domain().element_count();
  for (int q = 0; q < 300; ++q) {
    Index element;
    LocalPoint<2> p = random_query(rng, element, elements);
    switch (q % 5) {
      case 0:  // anywhere around the element
        break;
      case 1: {  // on or a hair beside the grid lines of some grid size: cell rounding matters
        const int side = std::uniform_int_distribution<int>(1, 128)(rng);
        auto on_line = [&] {
          const double x = std::uniform_int_distribution<int>(0, side)(rng) / double(side);
          const int nudge = std::uniform_int_distribution<int>(-1, 1)(rng);
          return nudge == 0 ? x : std::nextafter(x, nudge * 2.0);
        };
        p.x() = on_line();
        if (q % 2 == 0) p.y() = on_line();
        break;
      }
      case 2: {  // on a node or a region side of the element
        if (map.regions_begin(element) == map.regions_end(element)) break;
        const Index r = std::uniform_int_distribution<Index>(map.regions_begin(element),
                                                             map.regions_end(element) - 1)(rng);
        const auto& a = m.node_position[m.region_corners[r][q % 3]];
        const auto& b = m.node_position[m.region_corners[r][(q + 1) % 3]];
        p = a + std::uniform_real_distribution<double>(0, 1)(rng) * (b - a);
        if (q % 2 == 0) p = a;
        break;
      }
      case 3:  // a hair off the element's edges
        p = {std::nextafter(0.0, -1.0), std::uniform_real_distribution<double>(0, 1)(rng)};
        if (q % 2 == 0) std::swap(p.x(), p.y());
        break;
      default:  // on the slanted edge
        p.y() = 1 - p.x();
    }
    RC_ASSERT(agrees_with_brute_force<2>(locator, map, element, p));
  }
}

TEST(PointLocation, CellGridReportsHolesAndFarPointsOutside) {
  for (std::size_t which : {3u, 4u}) {
    const auto& rm = maps2()[which];
    for (CellGridLocator locator : prepared_cell_grids(which))
      for (const auto& hole : rm.holes)
        EXPECT_FALSE(locator.locate(*rm.map, hole.element, hole.local).found());
  }
  const PlMap<2>& map = *maps2()[1].map;
  CellGridLocator locator;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const LocalPoint<2>& p :
       {LocalPoint<2>(-0.01, 0.3), LocalPoint<2>(0.3, -1e-300), LocalPoint<2>(0.5, 0.5000001),
        LocalPoint<2>(2, 2), LocalPoint<2>(-1e300, 1e300), LocalPoint<2>(nan, 0.2),
        LocalPoint<2>(0.2, nan)})
    EXPECT_FALSE(locator.locate(map, 0, p).found()) << p.transpose();
}

TEST(PointLocation, CellGridOnNodesAndRegionSides) {
  for (std::size_t which = 0; which < maps2().size(); ++which) {
    const PlMap<2>& map = *maps2()[which].map;
    const MapData<2>& m = map.data();
    for (CellGridLocator locator : prepared_cell_grids(which))
      for (Index t = 0; t < map.domain().element_count(); ++t)
        for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r)
          for (int side = 0; side < 3; ++side) {
            const auto& a = m.node_position[m.region_corners[r][(side + 1) % 3]];
            const auto& b = m.node_position[m.region_corners[r][(side + 2) % 3]];
            for (double s : {0.0, 0.5, 0.25, 1.0 / 3.0})
              ASSERT_TRUE(agrees_with_brute_force<2>(locator, map, t, LocalPoint<2>(a + s * (b - a))));
          }
  }
}

TEST(PointLocation, CellGridCertifiesMostOfTheAreaAndReportsItsMemory) {
  const PlMap<2>& map = *maps2()[2].map;  // 121 regions per element
  CellGridLocator locator;
  EXPECT_EQ(locator.memory_bytes(), 0u);
  locator.prepare(map);
  ASSERT_NE(locator.grid(), nullptr);
  const auto memory = locator.grid()->memory();
  EXPECT_EQ(memory.region_record_bytes, 64u * std::size_t(map.region_count()));
  EXPECT_EQ(memory.region_image_bytes, 128u * std::size_t(map.region_count()));
  EXPECT_GE(memory.cells, 8u * std::size_t(map.region_count()));
  EXPECT_GT(memory.whole_cells, 0u);
  EXPECT_GT(memory.whole_cells + memory.split_cells, memory.cells / 2);
  EXPECT_GT(memory.whole_area + memory.split_area, 0.5);
  EXPECT_LE(memory.whole_area + memory.split_area, 1.0);
  EXPECT_EQ(locator.memory_bytes(), memory.total_bytes());
  // Every certified answer is checked against brute force on the cell centres and corners.
  for (Index t = 0; t < map.domain().element_count(); ++t)
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; i + j <= 40; ++j)
        ASSERT_TRUE(agrees_with_brute_force<2>(locator, map, t, LocalPoint<2>(i / 40.0, j / 40.0)));
}

TEST(PointLocation, CellGridCertifiesCellsAtTheElementBoundary) {
  // A cell at the reference triangle's edges reaches outside it, where no region is; it is
  // certified for its part inside (queries outside are left to the walk). S1 onto itself has one
  // region per element and one cell, half outside the triangle: it is whole.
  CellGridLocator identity;
  identity.prepare(*maps2()[0].map);
  EXPECT_EQ(identity.grid()->memory().whole_area, 1.0);
  EXPECT_EQ(identity.grid()->memory().whole_cells, identity.grid()->memory().cells);
  const LocalPoint<2> beyond_slanted_edge(0.5, std::nextafter(0.5, 1.0));
  EXPECT_FALSE(identity.locate(*maps2()[0].map, 0, beyond_slanted_edge).found());
  EXPECT_TRUE(identity.locate(*maps2()[0].map, 0, LocalPoint<2>(0.5, 0.5)).found());
  // Refinements: certifying no cell at the edges left 0.83 and 0.88 of the area certified
  // (about 1 - 5 / G less the cells around nodes); with them it is 0.93 and 0.94.
  for (std::size_t which : {1u, 2u}) {
    CellGridLocator locator;
    locator.prepare(*maps2()[which].map);
    const auto memory = locator.grid()->memory();
    EXPECT_GT(memory.whole_area + memory.split_area, 0.9) << "map " << which;
  }
}

TEST(PointLocation, CellGridOnElementsWithMoreRegionsThanACellCanName) {
  // 91 x 91 = 8,281 regions per element: more than a 16-bit cell can address (8,191), so part of
  // each element's cells start walks from a substitute region.
  const auto rm = generators::subdivision_map(generators::two_triangles(), 91, 0.2, 9);
  const PlMap<2>& map = *rm.map;
  ASSERT_GT(map.regions_end(0) - map.regions_begin(0), 8191);
  CellGridLocator locator(CellGridOptions{2, 512});  // few cells: the map is the large part
  std::mt19937_64 rng(13);
  // Brute force scans 8,281 regions per query: a few hundred queries suffice.
  for (int q = 0; q < 400; ++q) {
    Index element;
    const LocalPoint<2> p = random_query(rng, element, map.domain().element_count());
    ASSERT_TRUE(agrees_with_brute_force<2>(locator, map, element, p));
  }
}

TEST(PointLocation, CellGridFollowsTheMapItIsUsedOn) {
  // One locator object used on two maps in turn rebuilds its tables for each.
  CellGridLocator locator;
  std::mt19937_64 rng(11);
  for (int round = 0; round < 2; ++round)
    for (std::size_t which : {1u, 2u, 3u}) {
      const PlMap<2>& map = *maps2()[which].map;
      for (int q = 0; q < 500; ++q) {
        Index element;
        const LocalPoint<2> p = random_query(rng, element, map.domain().element_count());
        ASSERT_TRUE(agrees_with_brute_force<2>(locator, map, element, p));
      }
      EXPECT_EQ(locator.grid()->memory().region_record_bytes, 64u * std::size_t(map.region_count()));
    }
  EXPECT_THROW(CellGridLocator(CellGridOptions{0, 8}).prepare(*maps2()[1].map), Error);
  EXPECT_THROW(CellGridLocator(CellGridOptions{8, 0}).prepare(*maps2()[1].map), Error);
}

RC_GTEST_PROP(PointLocation, PointsInsideTheElementAreInsideWhenCovered, ()) {
  // On fully covered elements (maps 0..2) every point of the closed reference triangle is in D.
  const auto which = *rc::gen::inRange<std::size_t>(0, 3);
  const PlMap<2>& map = *maps2()[which].map;
  const auto element = *rc::gen::inRange<Index>(0, map.domain().element_count());
  // Dyadic coordinates with x + y < 1 exactly: strictly below the slanted edge, whose nodes may
  // sit one ulp inside it (see QueriesOnRegionSidesFindARegionContainingThem).
  const int xi = *rc::gen::inRange(0, 1 << 20);
  const double x = xi / double(1 << 20);
  const double y = *rc::gen::inRange(0, (1 << 20) - xi) / double(1 << 20);
  BrownFaigleWalk brown_faigle;
  RC_ASSERT(brown_faigle.locate(map, element, {x, y}).found());
  RC_ASSERT(StraightWalk{}.locate(map, element, {x, y}).found());
}

TEST(PointLocation, PointsOutsideDAreReportedOutside) {
  for (std::size_t which : {3u, 4u}) {
    const auto& rm = maps2()[which];
    BrownFaigleWalk brown_faigle;
    for (const auto& hole : rm.holes) {
      EXPECT_FALSE(brown_faigle.locate(*rm.map, hole.element, hole.local).found());
      EXPECT_FALSE(StraightWalk{}.locate(*rm.map, hole.element, hole.local).found());
      EXPECT_FALSE(BruteForce<2>{}.locate(*rm.map, hole.element, hole.local).found());
    }
  }
  // Outside the element itself.
  const PlMap<2>& map = *maps2()[1].map;
  BrownFaigleWalk brown_faigle;
  for (const LocalPoint<2>& p : {LocalPoint<2>(-0.01, 0.3), LocalPoint<2>(0.3, -1e-300),
                                 LocalPoint<2>(0.5, 0.5000001), LocalPoint<2>(2, 2)}) {
    EXPECT_FALSE(brown_faigle.locate(map, 0, p).found()) << p.transpose();
    EXPECT_FALSE(StraightWalk{}.locate(map, 0, p).found()) << p.transpose();
  }
}

TEST(PointLocation, QueriesOnNodesFindARegionAndEvaluateToTheNodeImage) {
  for (const auto& rm : maps2()) {
    const PlMap<2>& map = *rm.map;
    BrownFaigleWalk brown_faigle;
    StraightWalk straight;
    for (Index t = 0; t < map.domain().element_count(); ++t)
      for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n) {
        const LocalPoint<2>& p = map.data().node_position[n];
        if (!BruteForce<2>{}.locate(map, t, p).found()) continue;  // isolated ghost node
        ASSERT_TRUE(agrees_with_brute_force<2>(brown_faigle, map, t, p));
        ASSERT_TRUE(agrees_with_brute_force<2>(straight, map, t, p));
        const Evaluation<2> e = evaluate(map, SurfacePoint<2>{t, p}, brown_faigle);
        ASSERT_TRUE(e.in_domain);
        const double scale = map.target().max_edge_length();
        EXPECT_LE((e.world - map.node_target_world(n)).norm(), 1e-12 * scale)
            << "node " << n << " on element " << t;
      }
  }
}

TEST(PointLocation, QueriesOnRegionSidesFindARegionContainingThem) {
  for (const auto& rm : maps2()) {
    const PlMap<2>& map = *rm.map;
    const MapData<2>& m = map.data();
    BrownFaigleWalk brown_faigle;
    StraightWalk straight;
    for (Index t = 0; t < map.domain().element_count(); ++t)
      for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r)
        for (int side = 0; side < 3; ++side) {
          const auto& a = m.node_position[m.region_corners[r][(side + 1) % 3]];
          const auto& b = m.node_position[m.region_corners[r][(side + 2) % 3]];
          for (double s : {0.5, 0.25, 1.0 / 3.0}) {
            const LocalPoint<2> p = a + s * (b - a);
            ASSERT_TRUE(agrees_with_brute_force<2>(brown_faigle, map, t, p));
            ASSERT_TRUE(agrees_with_brute_force<2>(straight, map, t, p));
            // On an interior side the rounded point is in one of the two regions sharing it.
            if (m.region_neighbors[r][side] != invalid_index) {
              ASSERT_TRUE(BruteForce<2>{}.locate(map, t, p).found());
            }
          }
        }
    // Points exactly on the element's edges in fully covered elements. On the axis-aligned
    // local edges the nodes lie exactly on the edge, so these points are in D. On the slanted
    // edge x + y = 1 the builder may store a node one ulp off the line, so a point exactly on
    // the edge can be (exactly) outside every region: only agreement is required there.
    if (&rm - maps2().data() <= 2)
      for (double s : {0.0, 0.125, 0.25, 0.5, 0.75, 1.0}) {
        for (const LocalPoint<2>& p : {LocalPoint<2>(s, 0), LocalPoint<2>(0, s)}) {
          ASSERT_TRUE(brown_faigle.locate(map, 0, p).found()) << p.transpose();
          ASSERT_TRUE(straight.locate(map, 0, p).found()) << p.transpose();
        }
        ASSERT_TRUE(agrees_with_brute_force<2>(brown_faigle, map, 0, LocalPoint<2>(s, 1 - s)));
        ASSERT_TRUE(agrees_with_brute_force<2>(straight, map, 0, LocalPoint<2>(s, 1 - s)));
      }
  }
}

/// Exactly the same evaluation (== on every component): the locator's records must not change a single rounding.
template <int d>
::testing::AssertionResult same_evaluation(const Evaluation<d>& got, const Evaluation<d>& expected) {
  if (got.in_domain != expected.in_domain) return ::testing::AssertionFailure() << "in_domain differs";
  if (!got.in_domain) return ::testing::AssertionSuccess();
  if (got.region != expected.region || !(got.image == expected.image) || got.world != expected.world)
    return ::testing::AssertionFailure()
           << "region " << got.region << " / " << expected.region << ", image " << got.image.element
           << " (" << got.image.local.transpose() << ") / " << expected.image.element << " ("
           << expected.image.local.transpose() << "), world (" << got.world.transpose() << ") / ("
           << expected.world.transpose() << ")";
  return ::testing::AssertionSuccess();
}

TEST(PointLocation, CellGridEvaluatesBitForBitAsTheMapsArrays) {
  // The cell grid answers whole evaluations from its own per-region records (RegionImage):
  // evaluate(), the unchecked evaluate_prepared() of evaluate_batch, and the batch itself must
  // give exactly locate() followed by evaluate_in_region on the map, inside and outside D. One
  // locator goes through all maps in turn, so evaluate() must also follow the map.
  CellGridLocator travelling;
  for (int round = 0; round < 2; ++round)
    for (std::size_t which = 0; which < maps2().size(); ++which) {
      const PlMap<2>& map = *maps2()[which].map;
      CellGridLocator prepared;
      prepared.prepare(map);
      std::mt19937_64 rng(40 + which);
      std::vector<SurfacePoint<2>> points(3000);
      for (auto& p : points) p.local = random_query(rng, p.element, map.domain().element_count());
      std::vector<Evaluation<2>> batch(points.size());
      evaluate_batch<2>(map, points, batch, CellGridLocator{}, 2);
      std::size_t inside = 0;
      for (std::size_t i = 0; i < points.size(); ++i) {
        const RegionLocation<2> located = prepared.locate(map, points[i].element, points[i].local);
        const Evaluation<2> expected =
            located.found() ? evaluate_in_region(map, located.region, points[i].local) : Evaluation<2>{};
        inside += expected.in_domain;
        ASSERT_TRUE(same_evaluation(evaluate(map, points[i], travelling), expected)) << which << " " << i;
        ASSERT_TRUE(same_evaluation(prepared.evaluate_prepared(points[i]), expected)) << which << " " << i;
        ASSERT_TRUE(same_evaluation(batch[i], expected)) << which << " " << i;
      }
      EXPECT_GT(inside, points.size() / 20) << which;  // map 4 covers a small corner
    }
}

TEST(PointLocation, RegionImagesEvaluateBitForBitAsTheMapsArrays) {
  // At every node of every region (the corners, where the affine maps are exact) and at random
  // points of the regions, for triangle and curve maps.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  for (const auto& sm : maps2()) {
    const PlMap<2>& map = *sm.map;
    const auto images = region_images(map);
    ASSERT_EQ(images.size(), std::size_t(map.region_count()));
    const MapData<2>& m = map.stored();
    for (Index r = 0; r < map.region_count(); ++r) {
      const auto& c = m.region_corners[r];
      const double a = u(rng), b = u(rng) * (1 - a);
      const LocalPoint<2> inside = m.node_position[c[0]] + a * (m.node_position[c[1]] - m.node_position[c[0]]) +
                                   b * (m.node_position[c[2]] - m.node_position[c[0]]);
      for (const LocalPoint<2>& p : {m.node_position[c[0]], m.node_position[c[1]], m.node_position[c[2]], inside})
        ASSERT_TRUE(same_evaluation(evaluate_in_region(images[std::size_t(r)], r, p), evaluate_in_region(map, r, p)))
            << r;
    }
  }
  for (const auto& sm : maps1()) {
    const PlMap<1>& map = *sm.map;
    const auto images = region_images(map);
    const MapData<1>& m = map.stored();
    for (Index r = 0; r < map.region_count(); ++r) {
      const auto& c = m.region_corners[r];
      const LocalPoint<1> inside = m.node_position[c[0]] + u(rng) * (m.node_position[c[1]] - m.node_position[c[0]]);
      for (const LocalPoint<1>& p : {m.node_position[c[0]], m.node_position[c[1]], inside})
        ASSERT_TRUE(same_evaluation(evaluate_in_region(images[std::size_t(r)], r, p), evaluate_in_region(map, r, p)))
            << r;
    }
  }
}

TEST(PointLocation, EvaluationInsideARegionMatchesTheInterpolatedCorners) {
  // The image of a region's centroid is the mean of its corners' images (the map is affine).
  const PlMap<2>& map = *maps2()[2].map;
  const MapData<2>& m = map.data();
  BrownFaigleWalk locator;
  for (Index r = 0; r < map.region_count(); r += 7) {
    const auto& c = m.region_corners[r];
    const LocalPoint<2> centroid =
        (m.node_position[c[0]] + m.node_position[c[1]] + m.node_position[c[2]]) / 3.0;
    const Index t = map.node_element(c[0]);
    const Evaluation<2> e = evaluate(map, SurfacePoint<2>{t, centroid}, locator);
    ASSERT_TRUE(e.in_domain);
    EXPECT_EQ(e.region, r);
    const WorldPoint<2> expected =
        (map.node_target_world(c[0]) + map.node_target_world(c[1]) + map.node_target_world(c[2])) /
        3.0;
    EXPECT_LE((e.world - expected).norm(), 1e-12);
  }
}

template <int d, class Locator>
void expect_batch_independent_of_threads(const PlMap<d>& map, const Locator& locator,
                                         const std::vector<SurfacePoint<d>>& points) {
  std::vector<Evaluation<d>> one(points.size()), two(points.size());
  evaluate_batch<d>(map, points, one, locator, 1);
  evaluate_batch<d>(map, points, two, locator, 2);
  std::size_t inside = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    ASSERT_EQ(one[i].in_domain, two[i].in_domain) << i;
    if (!one[i].in_domain) continue;
    ++inside;
    ASSERT_EQ(one[i].region, two[i].region) << i;
    ASSERT_EQ(one[i].image, two[i].image) << i;
    ASSERT_EQ(one[i].world, two[i].world) << i;
  }
  EXPECT_GT(inside, points.size() / 5);
}

TEST(PointLocation, BatchEvaluationDoesNotDependOnTheThreadCount) {
  for (std::size_t which : {2u, 3u}) {
    const PlMap<2>& map = *maps2()[which].map;
    std::mt19937_64 rng(17);
    std::vector<SurfacePoint<2>> points(5000);
    for (auto& p : points) p.local = random_query(rng, p.element, map.domain().element_count());
    expect_batch_independent_of_threads<2>(map, BrownFaigleWalk{}, points);
    expect_batch_independent_of_threads<2>(map, StraightWalk{}, points);
    expect_batch_independent_of_threads<2>(map, BruteForce<2>{}, points);
    expect_batch_independent_of_threads<2>(map, CellGridLocator{}, points);
    CellGridLocator prepared;
    prepared.prepare(map);
    expect_batch_independent_of_threads<2>(map, prepared, points);
  }
  const PlMap<1>& curve = *maps1()[2].map;
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<SurfacePoint<1>> points(3000);
  for (auto& p : points) {
    p.element = std::uniform_int_distribution<Index>(0, curve.domain().element_count() - 1)(rng);
    p.local(0) = u(rng);
  }
  expect_batch_independent_of_threads<1>(curve, Bisection{}, points);
}

TEST(PointLocation, DifferentSeedsGiveTheSameRegionsForInteriorPoints) {
  const PlMap<2>& map = *maps2()[2].map;
  std::mt19937_64 rng(5);
  BrownFaigleWalk a(1), b(2);
  for (int q = 0; q < 2000; ++q) {
    Index element;
    const LocalPoint<2> p = random_query(rng, element, map.domain().element_count());
    EXPECT_EQ(a.locate(map, element, p).region, b.locate(map, element, p).region);
  }
}

// ---- d = 1 -------------------------------------------------------------------------------------

TEST(PointLocation, CurveRegionsAreSortedByPosition) {
  // Bisection relies on this ordering of the builder's output.
  for (const auto& rm : maps1()) {
    const MapData<1>& m = rm.map->data();
    for (Index t = 0; t < rm.map->domain().element_count(); ++t)
      for (Index r = m.region_begin[t]; r + 1 < m.region_begin[t + 1]; ++r)
        ASSERT_LE(m.node_position[m.region_corners[r][1]](0),
                  m.node_position[m.region_corners[r + 1][0]](0));
  }
}

RC_GTEST_PROP(PointLocation, BisectionAgreesWithBruteForce, ()) {
  const auto which = *rc::gen::inRange<std::size_t>(0, maps1().size());
  const PlMap<1>& map = *maps1()[which].map;
  std::mt19937_64 rng(*rc::gen::arbitrary<std::uint64_t>());
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  Bisection bisection;
  for (int q = 0; q < 100; ++q) {
    const Index element =
        std::uniform_int_distribution<Index>(0, map.domain().element_count() - 1)(rng);
    RC_ASSERT(agrees_with_brute_force<1>(bisection, map, element, LocalPoint<1>(u(rng))));
  }
}

TEST(PointLocation, BisectionOnNodesGapsAndOutside) {
  for (const auto& rm : maps1()) {
    const PlMap<1>& map = *rm.map;
    Bisection bisection;
    for (Index t = 0; t < map.domain().element_count(); ++t) {
      for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n) {
        const LocalPoint<1>& p = map.data().node_position[n];
        ASSERT_TRUE(agrees_with_brute_force<1>(bisection, map, t, p));
        if (bisection.locate(map, t, p).found()) {
          const Evaluation<1> e = evaluate(map, SurfacePoint<1>{t, p}, bisection);
          EXPECT_LE((e.world - map.node_target_world(n)).norm(), 1e-12);
        }
      }
      EXPECT_FALSE(bisection.locate(map, t, LocalPoint<1>(-1e-9)).found());
      EXPECT_FALSE(bisection.locate(map, t, LocalPoint<1>(1.5)).found());
      EXPECT_FALSE(
          bisection.locate(map, t, LocalPoint<1>(std::numeric_limits<double>::quiet_NaN())).found());
    }
    for (const auto& hole : rm.holes) {
      EXPECT_FALSE(bisection.locate(map, hole.element, hole.local).found());
      EXPECT_FALSE(BruteForce<1>{}.locate(map, hole.element, hole.local).found());
    }
  }
  EXPECT_GT(maps1()[2].holes.size(), 20u);
}

// ---- registry ----------------------------------------------------------------------------------

TEST(PointLocatorRegistry, NamesDispatchToTheirTypes) {
  auto type_of2 = [](std::string_view name) {
    return with_point_locator<2>(name, [](auto& locator) -> std::string {
      using L = std::decay_t<decltype(locator)>;
      if constexpr (std::is_same_v<L, BrownFaigleWalk>) return "BrownFaigleWalk";
      if constexpr (std::is_same_v<L, StraightWalk>) return "StraightWalk";
      if constexpr (std::is_same_v<L, point_location::BucketWalk>) return "BucketWalk";
      if constexpr (std::is_same_v<L, CellGridLocator>) return "CellGridLocator";
      if constexpr (std::is_same_v<L, BruteForce<2>>) return "BruteForce";
      return "other";
    });
  };
  EXPECT_EQ(type_of2("brown-faigle"), "BrownFaigleWalk");
  EXPECT_EQ(type_of2("straight-walk"), "StraightWalk");
  EXPECT_EQ(type_of2("bucket-walk"), "BucketWalk");
  EXPECT_EQ(type_of2("cell-grid"), "CellGridLocator");
  EXPECT_EQ(type_of2("brute-force"), "BruteForce");
  auto type_of1 = [](std::string_view name) {
    return with_point_locator<1>(name, [](auto& locator) -> std::string {
      using L = std::decay_t<decltype(locator)>;
      if constexpr (std::is_same_v<L, Bisection>) return "Bisection";
      if constexpr (std::is_same_v<L, BruteForce<1>>) return "BruteForce";
      return "other";
    });
  };
  EXPECT_EQ(type_of1("bisection"), "Bisection");
  EXPECT_EQ(type_of1("brute-force"), "BruteForce");
  EXPECT_EQ(default_point_locator_name<2>(), "brown-faigle");
  EXPECT_EQ(default_point_locator_name<1>(), "bisection");
  EXPECT_EQ(point_locator_names<2>().size(), 5u);
  EXPECT_EQ(point_locator_names<1>().size(), 2u);
}

TEST(PointLocatorRegistry, EveryRegisteredLocatorEvaluatesCorrectly) {
  const PlMap<2>& map = *maps2()[3].map;
  std::mt19937_64 rng(3);
  std::vector<SurfacePoint<2>> points(2000);
  for (auto& p : points) p.local = random_query(rng, p.element, map.domain().element_count());
  std::vector<Evaluation<2>> reference(points.size());
  evaluate_batch<2>(map, points, reference, BruteForce<2>{}, 1);
  for (const auto name : point_locator_names<2>()) {
    std::vector<Evaluation<2>> out(points.size());
    with_point_locator<2>(name, [&](auto& locator) { evaluate_batch<2>(map, points, out, locator, 2); });
    for (std::size_t i = 0; i < points.size(); ++i) {
      ASSERT_EQ(out[i].in_domain, reference[i].in_domain) << name << " query " << i;
      if (out[i].in_domain) {
        ASSERT_LE((out[i].world - reference[i].world).norm(), 1e-12) << name;
      }
    }
  }
}

TEST(PointLocatorRegistry, UnknownNamesListTheValidOnes) {
  try {
    with_point_locator<2>("kirkpatrick", [](auto&) {});
    FAIL() << "no exception";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("kirkpatrick"), std::string::npos) << what;
    for (const auto name : point_locator_names<2>())
      EXPECT_NE(what.find(name), std::string::npos) << what;
  }
  EXPECT_THROW(with_point_locator<1>("brown-faigle", [](auto&) {}), Error);
  EXPECT_NO_THROW(with_point_locator<1>("bisection", [](auto&) {}));
}

}  // namespace
}  // namespace plmap
