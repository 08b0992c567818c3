// Valid maps pass every check of plmap::verify, and the report's numbers are right.

#include "test_check_support.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/report_json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

namespace plmap {
namespace {

using namespace plmap::test;

template <int d>
void expect_valid(const PlMap<d>& map, VerifyOptions options = {}) {
  const VerificationReport report = verify(map, options);
  EXPECT_TRUE(report.ok()) << summary(report);
  EXPECT_EQ(report.checks.size(), 7u);
  for (const auto& c : report.checks) EXPECT_FALSE(c.skipped) << c.name;
}

VerifyOptions parametrization() {
  VerifyOptions o;
  o.expect_parametrization = true;
  return o;
}

TEST(VerifyValid, IdentityOfTwoTriangles) { expect_valid(identity_square(), parametrization()); }
TEST(VerifyValid, TouchingNodeOnSharedEdge) { expect_valid(centre_fan(), parametrization()); }
TEST(VerifyValid, MidpointRefinement) { expect_valid(midpoint_refinement(), parametrization()); }
TEST(VerifyValid, IntersectionNodeOnSharedEdge) { expect_valid(crossed_diagonals(), parametrization()); }
TEST(VerifyValid, CurveRefinement) { expect_valid(curve_refinement(), parametrization()); }
TEST(VerifyValid, CurveWithGhostNodes) { expect_valid(curve_with_ghost(), parametrization()); }

TEST(VerifyValid, ScaleInvariant) {
  for (double scale : {1e-6, 1e6}) {
    expect_valid(centre_fan(scale), parametrization());
    expect_valid(identity_square(scale), parametrization());
  }
}

/// `base` with its nodes moved by `move` (in S1) and every region's map made again through its
/// corners (affine_through, as the builder does); `change` then gets the data and the most
/// stretched region.
PlMap<2> remapped(const PlMap<2>& base, const std::function<void(MapData<2>&)>& move,
                  const std::function<void(MapData<2>&, std::size_t)>& change) {
  return modified<2>(base, [&](MapData<2>& m) {
    move(m);
    std::size_t most_stretched = 0;
    for (std::size_t r = 0; r < m.region_corners.size(); ++r) {
      std::array<LocalPoint<2>, 3> from, to;
      for (int i = 0; i < 3; ++i) {
        const Index n = m.region_corners[r][i];
        from[i] = m.node_position[n];
        to[i] = local_of(base.target(), m.region_target[r],
                         base.target().world_position(m.node_image_element[n], m.node_image_local[n]));
      }
      m.region_map[r] = affine_through<2>(from, to);
      if (m.region_map[r].leftCols<2>().norm() > m.region_map[most_stretched].leftCols<2>().norm()) most_stretched = r;
    }
    change(m, most_stretched);
  });
}

/// centre_fan with the preimage of S2's centre vertex moved along S1's diagonal to within f of
/// S1's corner (1, 1): the regions next to it become slivers of height ~f, far from their
/// elements' local origin, whose maps stretch ~0.5 / f.
PlMap<2> sliver_fan(double f, const std::function<void(MapData<2>&, std::size_t)>& change) {
  const PlMap<2> base = centre_fan();
  auto move = [&](MapData<2>& m) {
    for (Index t = 0; t < 2; ++t) {
      const Index n = node_with_target(base, t, 4, NodeType::touching);
      m.node_position[n] = t == 0 ? lp<2>(0.0, 1.0 - f) : lp<2>(1.0 - f, 0.0);
    }
  };
  return remapped(base, move, change);
}

/// crossed_diagonals with the preimage of S2's diagonal crossing moved along S1's diagonal to
/// within f of S1's corner (0, 0): the two regions on S2 triangle (0, 1, 3) become slivers whose
/// maps stretch ~0.5 / f, and their images meet along the half-diagonal from (0, 0) to the centre.
PlMap<2> crossed_slivers(double f, const std::function<void(MapData<2>&, std::size_t)>& change) {
  const PlMap<2> base = crossed_diagonals();
  const Index diagonal = base.target().find_edge(1, 3);
  auto move = [&](MapData<2>& m) {
    for (Index t = 0; t < 2; ++t) {
      const Index n = node_with_target(base, t, diagonal, NodeType::intersection);
      m.node_position[n] = t == 0 ? lp<2>(0.0, f) : lp<2>(f, 0.0);
    }
  };
  return remapped(base, move, change);
}

TEST(VerifyValid, SliverRegionsMayRoundOutsideTheirTriangleByTheirMapsRounding) {
  // A region whose preimage is a sliver has a map with huge entries, and evaluating it in doubles
  // at its own corners can land outside its S2 triangle by more than the plain tolerance (1e-9):
  // seen on CGAL's dino simplified with the aspect-ratio and long-edge oracles only (stretch
  // 1.25e6, a corner 2^-29 outside). The check allows for a few units in the last place of the
  // map's largest terms. Here the slivers of sliver_fan(1e-8) stretch ~5e7 and have offsets near
  // 5e7, whose last place is 7.45e-9; such a region's offset moved along one coordinate by
  // 7.5e-9, which rounds to two units in that place: its corners then map 1.49e-8 outside, which
  // the plain tolerance would reject.
  const double shift = 7.5e-9;
  const PlMap<2> sliver = sliver_fan(1e-8, [&](MapData<2>& m, std::size_t most_stretched) {
    ASSERT_GT(m.region_map[most_stretched].leftCols<2>().norm(), 1e7);
    m.region_map[most_stretched].col(2) -= LocalPoint<2>(shift, 0.0);
  });
  expect_valid(sliver, parametrization());
  // The same shift on a region that is not stretched is far above its rounding: caught.
  const PlMap<2> shifted =
      modified<2>(centre_fan(), [&](MapData<2>& m) { m.region_map[0].col(2) -= LocalPoint<2>(shift, 0.0); });
  EXPECT_GT(verify(shifted, parametrization()).violation_count("map", "region_corner_image"), 0u);
}

TEST(VerifyValid, SliverRegionsMayRoundTheirImagesAreaByTheirMapsRounding) {
  // The coverage check sums the areas of the regions' images on each S2 triangle; a sliver's
  // map rounds those too. Seen on CGAL's mpi_triang.off simplified to 18 triangles (plane-
  // projection flattening, min-max-aspect holes, estimate ranking, feature angle 113): one
  // region of local area 8e-9 covers a whole S2 triangle, and its image's area came out
  // 0.5 + 2^-24, above the measure tolerance (1e-8). Here: the slivers of sliver_fan(1e-8) with
  // one linear entry moved by eight units in its last place, in the direction that enlarges the
  // image.
  auto image_area = [](const PlMap<2>& map, Index r) {
    std::array<LocalPoint<2>, 3> q;
    for (int i = 0; i < 3; ++i) q[i] = apply<2>(map.data().region_map[r], map.data().node_position[map.data().region_corners[r][i]]);
    return 0.5 * std::abs((q[1] - q[0]).x() * (q[2] - q[0]).y() - (q[1] - q[0]).y() * (q[2] - q[0]).x());
  };
  bool shown = false;
  for (double sign : {1.0, -1.0}) {
    const PlMap<2> sliver = sliver_fan(1e-8, [&](MapData<2>& m, std::size_t most_stretched) {
      double& entry = m.region_map[most_stretched](0, 0);
      for (int k = 0; k < 8; ++k) entry = std::nextafter(entry, sign * std::numeric_limits<double>::infinity());
    });
    double largest = 0.0;
    for (Index r = 0; r < sliver.region_count(); ++r) largest = std::max(largest, image_area(sliver, r));
    if (!(largest > 0.5 * (1.0 + VerifyOptions{}.measure_tolerance))) continue;
    expect_valid(sliver, parametrization());
    shown = true;
  }
  EXPECT_TRUE(shown) << "no variant enlarges an image beyond the plain measure tolerance";
}

TEST(VerifyValid, SliverRegionsMayRoundIntoTheirNeighboursImagesByTheirMapsRounding) {
  // The pairwise test of the coverage check measures how far two images on one S2 triangle
  // overlap; a sliver's image, rounded by its map, may reach into its neighbour's by a strip as
  // wide as that rounding. Seen on CGAL's mpi_triang.off simplified to 18 triangles and smoothed
  // (Floater, one sweep): a region of local area 6.7e-8 whose exact corner images lie beside its
  // neighbour's overlapped it by 2.8e-9 through its map, above local_tolerance (1e-9) times its
  // boundary. Here: the slivers of crossed_slivers(1e-8), one of them with its offset moved by
  // 7.5e-9 in each of four directions; towards its neighbour that is a strip about 5e-9 wide
  // along their common side (length 0.71), about three times what local_tolerance explains.
  const double shift = 7.5e-9;
  const std::array<LocalPoint<2>, 4> directions = {lp<2>(1, 0), lp<2>(-1, 0), lp<2>(0, 1), lp<2>(0, -1)};
  for (const auto& direction : directions) {
    const PlMap<2> sliver = crossed_slivers(1e-8, [&](MapData<2>& m, std::size_t most_stretched) {
      ASSERT_GT(m.region_map[most_stretched].leftCols<2>().norm(), 1e7);
      m.region_map[most_stretched].col(2) += shift * direction;
    });
    SCOPED_TRACE(::testing::Message() << "direction " << direction.transpose());
    expect_valid(sliver, parametrization());
  }
  // The same shift of a region that is not stretched (the crossing at the centre) overlaps its
  // neighbour's image in some direction: caught.
  std::size_t caught = 0;
  for (const auto& direction : directions) {
    const PlMap<2> shifted = crossed_slivers(0.5, [&](MapData<2>& m, std::size_t most_stretched) {
      m.region_map[most_stretched].col(2) += shift * direction;
    });
    caught += verify(shifted, parametrization()).violation_count("coverage", "image_overlap");
  }
  EXPECT_GT(caught, 0u);
}

TEST(VerifyValid, PartialDomainIsNotAParametrization) {
  // Drop the regions of element 1: still a valid map on D = element 0, but not onto S2.
  const PlMap<2> full = identity_square();
  const PlMap<2> half = modified<2>(full, [](MapData<2>& m) {
    m.region_corners.resize(1);
    m.region_neighbors.resize(1);
    m.region_target.resize(1);
    m.region_map.resize(1);
    m.region_begin[2] = 1;
    m.start_region[1] = invalid_index;
  });
  expect_valid(half);
  const VerificationReport report = verify(half, parametrization());
  EXPECT_GT(report.violation_count("coverage", "not_a_parametrization"), 0u) << summary(report);
  // The report says where: element 1 of S1 has no region, and the S2 element it mapped onto no
  // image.
  bool names_s1_element = false, names_s2_element = false;
  const CheckResult* coverage = report.find("coverage");
  ASSERT_NE(coverage, nullptr);
  for (const auto& v : coverage->violations) {
    if (v.rule != "not_a_parametrization") continue;
    names_s1_element |= v.message.find("S1 elements short of it: 1 (0 of 0.5)") != std::string::npos;
    names_s2_element |= v.message.find("S2 elements short of it: 1 (0 of 0.5)") != std::string::npos;
  }
  EXPECT_TRUE(names_s1_element) << summary(report);
  EXPECT_TRUE(names_s2_element) << summary(report);
}

TEST(VerifyQuality, IdentityHasConditionOne) {
  const VerificationReport report = verify(centre_fan());
  ASSERT_TRUE(report.quality.has_value());
  EXPECT_NEAR(report.quality->kappa_max, 1.0, 1e-12);
  EXPECT_EQ(report.quality->region_count, 4);
  EXPECT_EQ(report.quality->degenerate_count, 0);
  EXPECT_EQ(report.quality->histogram.at(0), 4u);
}

TEST(VerifyQuality, StretchedTargetHasConditionTwo) {
  // Same local data, S2 stretched by 2 along x: every region's linear piece is diag(2, 1).
  const PlMap<2> base = identity_square();
  auto stretched = make_surface<2>({w2(0, 0), w2(2, 0), w2(2, 1), w2(0, 1)}, {{0, 1, 2}, {0, 2, 3}});
  const PlMap<2> map(base.domain_ptr(), stretched, base.data());
  const VerificationReport report = verify(map);
  EXPECT_TRUE(report.ok()) << summary(report);
  ASSERT_TRUE(report.quality.has_value());
  EXPECT_NEAR(report.quality->kappa_max, 2.0, 1e-12);
  EXPECT_NEAR(report.quality->stretch_max, 2.0, 1e-12);
  EXPECT_NEAR(report.quality->stretch_min, 1.0, 1e-12);
  for (double q : report.quality->quantiles) EXPECT_NEAR(q, 2.0, 1e-12);

  VerifyOptions strict;
  strict.max_condition = 1.5;
  const VerificationReport flagged = check_quality(map, strict);
  EXPECT_EQ(flagged.violation_count("quality", "condition"), 2u) << summary(flagged);
}

TEST(VerifyQuality, CurveConditionIsOneAndStretchIsTheLengthRatio) {
  const QualityReport q = compute_quality(curve_refinement());
  EXPECT_EQ(q.kappa_max, 1.0);
  EXPECT_NEAR(q.stretch_min, 1.0, 1e-12);
  EXPECT_NEAR(q.stretch_max, 1.0, 1e-12);
}

TEST(VerifyReport, JsonAndSummaryNameTheChecks) {
  const VerificationReport good = verify(identity_square());
  const nlohmann::json j = to_json(good);
  EXPECT_TRUE(j.at("ok").get<bool>());
  for (const char* name : {"structure", "plane_graph", "minimal_embedding", "map", "continuity",
                           "coverage", "quality"})
    EXPECT_TRUE(j.at("checks").contains(name)) << name;
  EXPECT_TRUE(j.contains("quality"));
  EXPECT_NE(summary(good).find("OK"), std::string::npos);

  const PlMap<2> bad = modified<2>(identity_square(), [](MapData<2>& m) { m.region_target[0] = 1; });
  const VerificationReport report = verify(bad);
  const nlohmann::json jb = to_json(report);
  EXPECT_FALSE(jb.at("ok").get<bool>());
  EXPECT_GT(jb.at("checks").at("map").at("violation_count").get<std::size_t>(), 0u);
  const auto& first = jb.at("checks").at("map").at("violations").at(0);
  EXPECT_EQ(first.at("check"), "map");
  EXPECT_FALSE(first.at("message").get<std::string>().empty());
  EXPECT_NE(summary(report).find("FAILED"), std::string::npos);
}

TEST(VerifyReport, StoredViolationsAreCappedButAllCounted) {
  VerifyOptions o;
  o.max_reported_per_rule = 1;
  // Every region maps to the wrong S2 element: several region_corner_image violations.
  const PlMap<2> bad = modified<2>(centre_fan(), [](MapData<2>& m) {
    for (auto& t : m.region_target) t = (t + 2) % 4;
  });
  const VerificationReport report = check_map(bad, o);
  const CheckResult* map = report.find("map");
  ASSERT_NE(map, nullptr);
  EXPECT_GT(map->rule_counts.at("region_corner_image"), 1u);
  EXPECT_EQ(std::count_if(map->violations.begin(), map->violations.end(),
                          [](const Violation& v) { return v.rule == "region_corner_image"; }),
            1);
}

// ---- maps made by MapBuilder ------------------------------------------------------------------

/// An n x n grid of the unit square (scaled), each cell split along its (i,j)-(i+1,j+1) diagonal.
std::shared_ptr<const Surface<2>> grid(int n, double scale = 1.0) {
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) v.push_back(w2(double(i) / n, double(j) / n) * scale);
  auto id = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      e.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      e.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return make_surface<2>(std::move(v), std::move(e));
}

TEST(VerifyBuilder, IdentityMapOfAGrid) {
  auto s = grid(4);
  MapBuilder<2> b(s, s);
  for (Index v = 0; v < s->vertex_count(); ++v) b.add_vertex_preimage_at_vertex(v, v);
  for (Index t = 0; t < s->element_count(); ++t) b.add_target_element(t);
  const PlMap<2> map = std::move(b).finalize();
  expect_valid(map, parametrization());
  EXPECT_NEAR(compute_quality(map).kappa_max, 1.0, 1e-9);
}

TEST(VerifyBuilder, RefinementOfTheSquare) {
  for (double scale : {1e-6, 1.0, 1e6}) {
    // S1: the square as two triangles; S2: a 4 x 4 grid whose diagonals lie along S1's.
    auto s1 = square(scale);
    auto s2 = grid(4, scale);
    MapBuilder<2> b(s1, s2);
    for (Index v = 0; v < s2->vertex_count(); ++v) {
      const WorldPoint<2> x = s2->vertex(v) / scale;
      // Element 0 = (0,0),(1,0),(1,1): local (x - y, y); element 1 = (0,0),(1,1),(0,1): (x, y - x).
      if (x.x() >= x.y())
        b.add_vertex_preimage(v, {0, lp<2>(x.x() - x.y(), x.y())});
      else
        b.add_vertex_preimage(v, {1, lp<2>(x.x(), x.y() - x.x())});
    }
    for (Index t = 0; t < s2->element_count(); ++t) b.add_target_element(t);
    const PlMap<2> map = std::move(b).finalize();
    expect_valid(map, parametrization());
  }
}

TEST(VerifyBuilder, CurveRefinement) {
  auto s1 = make_surface<1>({w1(0), w1(1), w1(1, 1)}, {{0, 1}, {1, 2}});
  auto s2 = make_surface<1>({w1(0), w1(0.25), w1(1), w1(1, 0.5), w1(1, 1)},
                            {{0, 1}, {1, 2}, {2, 3}, {3, 4}});
  MapBuilder<1> b(s1, s2);
  b.add_vertex_preimage_at_vertex(0, 0);
  b.add_vertex_preimage(1, {0, lp<1>(0.25)});
  b.add_vertex_preimage_at_vertex(2, 1);
  b.add_vertex_preimage(3, {1, lp<1>(0.5)});
  b.add_vertex_preimage_at_vertex(4, 2);
  for (Index t = 0; t < s2->element_count(); ++t) b.add_edge(t);
  const PlMap<1> map = std::move(b).finalize();
  expect_valid(map, parametrization());
}

}  // namespace
}  // namespace plmap

namespace plmap {
namespace {

using namespace plmap::test;

TEST(VerifyBuilder, IntersectionNodesFromCrossings) {
  // S1 split along 0-2, S2 along 1-3: the S2 diagonal crosses the S1 diagonal at its middle.
  auto s1 = square();
  auto s2 = make_surface<2>({w2(0, 0), w2(1, 0), w2(1, 1), w2(0, 1)}, {{0, 1, 3}, {1, 2, 3}});
  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
  const EdgeCrossing crossing{s1->find_edge(0, 2), 0.5};
  for (Index e = 0; e < s2->edge_count(); ++e) {
    const auto ends = s2->edge_vertices(e);
    if (ends[0] == 1 && ends[1] == 3)
      b.add_edge(e, std::span<const EdgeCrossing>(&crossing, 1));
    else
      b.add_edge(e);
  }
  const PlMap<2> map = std::move(b).finalize();
  expect_valid(map, parametrization());
  Index intersections = 0;
  for (NodeType t : map.data().node_type) intersections += t == NodeType::intersection;
  EXPECT_EQ(intersections, 2);  // one copy per element
}

TEST(VerifyBuilder, GhostNodeAtAVertexInsideATargetEdge) {
  // S1: the square as a fan around its centre; S2: the square as two triangles. The centre of
  // S1 maps onto the S2 diagonal: a ghost node in each of the four S1 elements.
  auto s1 = make_surface<2>({w2(0, 0), w2(1, 0), w2(1, 1), w2(0, 1), w2(0.5, 0.5)},
                            {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  auto s2 = square();
  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
  b.add_ghost_node(4, {0, lp<2>(0.0, 0.5)});  // S2 element 0 = (0,0),(1,0),(1,1): centre at (0, 0.5)
  const std::array<EdgeCrossing, 1> through_centre{EdgeCrossing{s1->find_edge(0, 4), 1.0}};
  for (Index e = 0; e < s2->edge_count(); ++e) {
    const auto ends = s2->edge_vertices(e);
    if (ends[0] == 0 && ends[1] == 2)
      b.add_edge(e, through_centre);
    else
      b.add_edge(e);
  }
  const PlMap<2> map = std::move(b).finalize();
  expect_valid(map, parametrization());
  Index ghosts = 0;
  for (NodeType t : map.data().node_type) ghosts += t == NodeType::ghost;
  EXPECT_EQ(ghosts, 4);
}

}  // namespace
}  // namespace plmap
