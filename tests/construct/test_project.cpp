// Normal projection (paper section 3.2): identity for S1 = S2, exact covered measures for
// planar and concentric configurations, boundary pieces, determinism under threading, and
// agreement of the two solver strategies.
#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/regions.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <numeric>
#include <random>

using namespace plmap;
using namespace plmap::test;

namespace {

/// Per S1 element, the sorted list of S2 elements its regions map into: the combinatorics of the
/// map independent of the order in which the triangulation lists the regions.
template <int d>
std::vector<std::vector<Index>> region_targets_per_element(const PlMap<d>& m) {
  std::vector<std::vector<Index>> out(m.domain().element_count());
  for (Index t = 0; t < m.domain().element_count(); ++t) {
    for (Index r = m.regions_begin(t); r < m.regions_end(t); ++r) out[t].push_back(m.data().region_target[r]);
    std::sort(out[t].begin(), out[t].end());
  }
  return out;
}

/// Area of a convex polygon clipped to the box [x0, x1] x [y0, y1] (Sutherland-Hodgman).
double clipped_area(std::vector<Eigen::Vector2d> poly, double x0, double x1, double y0, double y1) {
  auto clip = [&poly](int axis, double bound, bool keep_above) {
    std::vector<Eigen::Vector2d> out;
    auto inside = [&](const Eigen::Vector2d& p) { return keep_above ? p(axis) >= bound : p(axis) <= bound; };
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
      if (inside(a)) out.push_back(a);
      if (inside(a) != inside(b)) out.push_back(a + (bound - a(axis)) / (b(axis) - a(axis)) * (b - a));
    }
    poly = std::move(out);
  };
  clip(0, x0, true);
  clip(0, x1, false);
  clip(1, y0, true);
  clip(1, y1, false);
  double twice = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d a = poly[i], b = poly[(i + 1) % poly.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice);
}

std::string describe(const ProjectionReport<1>& r) {
  std::string s;
  for (const auto& f : r.edges_not_inserted)
    s += "segment " + std::to_string(f.target_edge) + ": " + std::string(to_string(f.reason)) + " " + f.detail + "\n";
  return s;
}
std::string describe(const ProjectionReport<2>& r) {
  std::string s;
  for (const auto& f : r.edges_not_inserted)
    s += "edge " + std::to_string(f.target_edge) + ": " + std::string(to_string(f.reason)) + " at element " +
         std::to_string(f.domain_element) + " eta " + std::to_string(f.target_parameter) + " " + f.detail + "\n";
  return s;
}

/// Every region is a whole S1 element mapped onto the same S2 element, corner to corner.
template <int d>
void expect_identity(const ProjectionResult<d>& r) {
  const auto& m = r.map;
  ASSERT_EQ(m.region_count(), m.domain().element_count());
  for (Index reg = 0; reg < m.region_count(); ++reg) {
    const auto ri = remote_intersection(m, reg);
    EXPECT_EQ(ri.domain_element, ri.target_element);
    for (int i = 0; i <= d; ++i) EXPECT_EQ(ri.domain_local[i], ri.target_local[i]) << "region " << reg;
  }
  for (NodeType t : m.data().node_type) EXPECT_EQ(t, NodeType::corner);
  EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
  EXPECT_EQ(r.report.vertex_preimages, m.target().vertex_count());
  EXPECT_EQ(r.report.ghost_nodes, 0);
  EXPECT_DOUBLE_EQ(r.measures.covered_domain, r.measures.domain);
}

}  // namespace

TEST(Project, IdentityCircle) {
  auto s = circle(24, 1.0);
  expect_identity(project<1>(s, s));
}

TEST(Project, IdentityJitteredPlane) {
  auto s = grid(6, 5, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  expect_identity(project<2>(s, s));
}

TEST(Project, IdentitySphereWithEitherSolver) {
  auto s = sphere(2, 1.0);
  expect_identity(project<2>(s, s));
  expect_identity(project<2>(s, s, {.solver = "ceres"}));
}

TEST(Project, FacingPlanesCoverTheExactOverlap) {
  // S1 = unit square at z = 0 (normals up); S2 = shifted, jittered grid at z = 0.1 facing down.
  // The overlap is [0.3, 1] x [0.2, 1]: S2 edges leave S1 through its boundary and S1 boundary
  // edges are crossed by S2 edges whose vertices are all outside S1.
  auto s1 = grid(6, 6, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  auto s2 = grid(7, 5, 0.3, 1.3, 0.2, 1.2, 0.1, true, 0.2);
  const auto r = project<2>(s1, s2, {.normal_check = TargetNormalCheck::facing});
  EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
  EXPECT_NEAR(r.measures.covered_domain, 0.7 * 0.8, 1e-9);
  EXPECT_NEAR(r.measures.covered_target, 0.7 * 0.8, 1e-9);
  EXPECT_GT(r.report.edge_pieces, 0);
  EXPECT_GT(r.report.boundary_entries, 0);
  EXPECT_EQ(r.map.data().orientation, -1);  // facing normals: orientation reversing
  // element by element: the regions of each S1 triangle tile its part inside S2's footprint
  for (Index t = 0; t < s1->element_count(); ++t) {
    double covered = 0.0;
    for (Index g = r.map.regions_begin(t); g < r.map.regions_end(t); ++g)
      covered += remote_intersection(r.map, g).domain_measure();
    std::vector<Eigen::Vector2d> triangle;
    for (int k = 0; k < 3; ++k) triangle.push_back(s1->corner(t, k).head<2>());
    EXPECT_NEAR(covered, clipped_area(triangle, 0.3, 1.3, 0.2, 1.2), 1e-12) << "S1 element " << t;
  }
}

TEST(Project, TargetLargerOrSmallerThanDomain) {
  auto small = grid(4, 4, 0.25, 0.75, 0.25, 0.75, -0.05, false, 0.1);
  auto large = grid(9, 7, -0.5, 1.5, -0.5, 1.5, 0.0, false, 0.1);
  {
    const auto r = project<2>(small, large);  // S2 larger: all of S1 covered
    EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
    EXPECT_NEAR(r.measures.covered_domain, 0.25, 1e-9);
    EXPECT_EQ(r.report.ghost_nodes, small->vertex_count());
  }
  {
    // S2 smaller and below S1 (mu < 0, as for penetrating bodies): covered = S2's area
    const auto r = project<2>(large, small, {.allow_negative_distance = true});
    EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
    EXPECT_NEAR(r.measures.covered_domain, 0.25, 1e-9);
    EXPECT_NEAR(r.measures.covered_target, 0.25, 1e-9);
    EXPECT_EQ(r.report.vertex_preimages, small->vertex_count());
    // without negative distances nothing projects
    EXPECT_EQ(project<2>(large, small).map.region_count(), 0);
  }
}

TEST(Project, VerticesExactlyAboveVerticesAndEdges) {
  auto s1 = grid(4, 4, 0.0, 1.0, 0.0, 1.0, 0.0);
  {
    // same grid lifted: every S2 vertex above an S1 vertex, every S2 edge above an S1 edge
    auto s2 = grid(4, 4, 0.0, 1.0, 0.0, 1.0, 0.3);
    const auto r = project<2>(s1, s2);
    EXPECT_EQ(r.map.region_count(), s1->element_count());
    EXPECT_EQ(r.report.ghost_nodes, 0);
    EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
    EXPECT_NEAR(r.measures.covered_domain, 1.0, 1e-12);
  }
  {
    // S2 vertices above the midpoints of S1's horizontal edges (shift by half a cell in x)
    auto s2 = grid(4, 4, 0.125, 1.125, 0.0, 1.0, 0.3);
    const auto r = project<2>(s1, s2);
    EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
    EXPECT_NEAR(r.measures.covered_domain, 0.875, 1e-12);
    int touching = 0;
    for (NodeType t : r.map.data().node_type) touching += t == NodeType::touching;
    EXPECT_GT(touching, 0);
  }
}

TEST(Project, ConcentricCirclesCoverBoth) {
  auto inner = circle(40, 1.0);
  auto outer = circle(57, 1.5, 0.01);
  const auto r = project<1>(inner, outer);
  EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
  EXPECT_NEAR(r.measures.covered_domain, r.measures.domain, 1e-9 * r.measures.domain);
  EXPECT_NEAR(r.measures.covered_target, r.measures.target, 1e-9 * r.measures.target);
  EXPECT_EQ(r.report.vertex_preimages, 57);
  EXPECT_EQ(r.report.ghost_nodes, 40);
}

TEST(Project, OpenLinesCoverTheOverlap) {
  auto s1 = line(7, 0.0, 1.0, 0.0);
  auto s2 = line(5, 0.35, 1.6, 0.2, true);
  const auto r = project<1>(s1, s2, {.normal_check = TargetNormalCheck::facing});
  EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
  EXPECT_NEAR(r.measures.covered_domain, 0.65, 1e-12);
  EXPECT_EQ(r.report.edge_pieces, 1);
  // S2 segments entering through S1's left end with no vertex inside
  auto s3 = line(2, -0.5, 0.5, 0.2, true);
  const auto r3 = project<1>(s1, s3);
  EXPECT_NEAR(r3.measures.covered_domain, 0.5, 1e-12);
}

TEST(Project, ConcentricSpheresCoverBoth) {
  auto inner = sphere(1, 1.0);
  auto outer = sphere(2, 1.25, false, 0.3);
  const auto r = project<2>(inner, outer, {.normal_check = TargetNormalCheck::aligned});
  EXPECT_TRUE(r.report.edges_not_inserted.empty()) << describe(r.report);
  EXPECT_NEAR(r.measures.covered_domain, r.measures.domain, 1e-9 * r.measures.domain);
  EXPECT_NEAR(r.measures.covered_target, r.measures.target, 1e-9 * r.measures.target);
}

TEST(Project, ThreadCountDoesNotChangeTheMap) {
  auto s1 = grid(9, 8, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  auto s2 = grid(11, 10, 0.1, 1.1, -0.1, 0.9, 0.05, true, 0.25);
  const auto a = project<2>(s1, s2, {.threads = 1});
  const auto b = project<2>(s1, s2, {.threads = 3});
  EXPECT_TRUE(a.map.data() == b.map.data());
  EXPECT_GT(a.map.region_count(), s1->element_count());
}

TEST(Project, NewtonAndCeresGiveTheSameCombinatorics) {
  auto inner = sphere(1, 1.0, false, 0.1);
  auto outer = sphere(2, 1.1, true, 0.7);
  const auto a = project<2>(inner, outer, {.solver = "newton"});
  const auto b = project<2>(inner, outer, {.solver = "ceres"});
  ASSERT_EQ(a.map.region_count(), b.map.region_count());
  EXPECT_EQ(region_targets_per_element(a.map), region_targets_per_element(b.map));
  EXPECT_EQ(a.map.data().node_type, b.map.data().node_type);
  EXPECT_NEAR(a.measures.covered_domain, b.measures.covered_domain, 1e-9);
}

TEST(Project, DistanceLimitLeavesFarSurfacesUnmapped) {
  auto s1 = grid(3, 3, 0.0, 1.0, 0.0, 1.0, 0.0);
  auto s2 = grid(4, 4, 0.0, 1.0, 0.0, 1.0, 0.5, true);
  const auto r = project<2>(s1, s2, {.max_distance = 0.2});
  EXPECT_EQ(r.map.region_count(), 0);
  EXPECT_EQ(r.report.vertex_preimages, 0);
  EXPECT_EQ(r.report.edges_outside, s2->edge_count());
  const auto relative = project<2>(s1, s2, {.max_distance = 0.4, .max_distance_is_relative = true});
  EXPECT_NEAR(relative.measures.covered_domain, 1.0, 1e-12);  // 0.4 x diagonal sqrt(2) > 0.5
}

TEST(Project, ScaledInputGivesTheSameCombinatorics) {
  auto s1 = grid(5, 5, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  auto s2 = grid(6, 4, 0.2, 1.2, 0.1, 1.1, 0.1, true, 0.2);
  auto scaled = [](const Surface<2>& s, double f) {
    std::vector<WorldPoint<2>> v;
    for (const auto& p : s.vertices()) v.push_back(f * p);
    return std::make_shared<const Surface<2>>(std::move(v), s.elements());
  };
  const auto a = project<2>(s1, s2);
  const auto b = project<2>(scaled(*s1, 1e-6), scaled(*s2, 1e-6));
  EXPECT_EQ(a.map.data().node_type, b.map.data().node_type);
  EXPECT_EQ(region_targets_per_element(a.map), region_targets_per_element(b.map));
}

TEST(Project, UserDirectionsAndBadOptions) {
  auto s1 = grid(3, 3, 0.0, 1.0, 0.0, 1.0, 0.0);
  auto s2 = grid(3, 3, 0.0, 1.0, 0.0, 1.0, 0.2, true);
  ProjectionOptions o;
  // oblique directions (1, 0, 2): the image is shifted by 0.1 in x
  for (Index v = 0; v < s1->vertex_count(); ++v) o.directions.insert(o.directions.end(), {1.0, 0.0, 2.0});
  const auto r = project<2>(s1, s2, o);
  EXPECT_NEAR(r.measures.covered_domain, 0.9, 1e-12);
  o.directions.pop_back();
  EXPECT_THROW(project<2>(s1, s2, o), Error);
  EXPECT_THROW(project<2>(s1, s2, {.solver = "bisection"}), Error);
}

TEST(DirectionField, AveragedNormalsOfACircleAreRadial) {
  auto c = circle(12, 2.0);
  const auto n = averaged_vertex_normals(*c);
  for (Index v = 0; v < c->vertex_count(); ++v)
    EXPECT_NEAR((n[v] - c->vertex(v) / 2.0).norm(), 0.0, 1e-12);
}

TEST(Project, CurvesAreIndependentOfThreadsAndSolver) {
  auto inner = circle(120, 1.0);
  auto outer = circle(170, 1.05, 0.002);
  const auto a = project<1>(inner, outer, {.threads = 1});
  const auto b = project<1>(inner, outer, {.solver = "ceres", .threads = 3});
  EXPECT_TRUE(a.map.data() == b.map.data() || region_targets_per_element(a.map) == region_targets_per_element(b.map));
  EXPECT_TRUE(a.map.data() == project<1>(inner, outer, {.threads = 3}).map.data());
  EXPECT_NEAR(a.measures.covered_domain, a.measures.domain, 1e-9 * a.measures.domain);
}

TEST(Project, RigidMotionKeepsTheCoveredMeasure) {
  auto s1 = grid(5, 4, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  auto s2 = grid(6, 5, 0.25, 1.25, 0.15, 1.15, 0.1, true, 0.2);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).matrix();
  const Eigen::Vector3d shift(3.0, -1.0, 2.0);
  auto moved = [&](const Surface<2>& s) {
    std::vector<WorldPoint<2>> v;
    for (const auto& p : s.vertices()) v.push_back(rotation * p + shift);
    return std::make_shared<const Surface<2>>(std::move(v), s.elements());
  };
  const auto a = project<2>(s1, s2);
  const auto b = project<2>(moved(*s1), moved(*s2));
  EXPECT_NEAR(a.measures.covered_domain, 0.75 * 0.85, 1e-9);
  EXPECT_NEAR(b.measures.covered_domain, a.measures.covered_domain, 1e-9);
  EXPECT_EQ(region_targets_per_element(a.map), region_targets_per_element(b.map));
}

// The searches of phases 1 and 2 seed each vertex from the offset found for the previous one in
// its chunk (project.cpp, search_chunk), so they see many chunks here, a gap of 240 segment
// lengths, and S2 once in order and once with its vertices shuffled (useless offsets, so every
// search falls back to the vertex itself): same map for every thread count, same measures and
// regions for either vertex order.
TEST(Project, LargeGapCirclesIndependentOfThreadsAndVertexOrder) {
  auto inner = circle(3000, 1.0);
  auto outer = circle(3900, 1.5, 0.0003);
  std::vector<Index> order(static_cast<std::size_t>(outer->vertex_count()));
  std::iota(order.begin(), order.end(), Index{0});
  std::mt19937 rng(7);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<WorldPoint<1>> vertices(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) vertices[static_cast<std::size_t>(order[i])] = outer->vertex(static_cast<Index>(i));
  auto elements = outer->elements();
  for (auto& e : elements)
    for (auto& v : e) v = order[static_cast<std::size_t>(v)];
  auto shuffled = std::make_shared<const Surface<1>>(std::move(vertices), std::move(elements));

  const auto a = project<1>(inner, outer, {.threads = 1});
  EXPECT_TRUE(a.report.edges_not_inserted.empty()) << describe(a.report);
  EXPECT_NEAR(a.measures.covered_domain, a.measures.domain, 1e-9 * a.measures.domain);
  EXPECT_NEAR(a.measures.covered_target, a.measures.target, 1e-9 * a.measures.target);
  EXPECT_EQ(a.report.vertex_preimages, 3900);
  EXPECT_EQ(a.report.ghost_nodes, 3000);
  EXPECT_TRUE(a.map.data() == project<1>(inner, outer, {.threads = 3}).map.data());

  const auto b = project<1>(inner, shuffled, {.threads = 2});
  EXPECT_EQ(b.report.vertex_preimages, 3900);
  EXPECT_EQ(b.report.ghost_nodes, 3000);
  EXPECT_EQ(b.map.region_count(), a.map.region_count());
  EXPECT_NEAR(b.measures.covered_domain, a.measures.covered_domain, 1e-12 * a.measures.domain);
  EXPECT_NEAR(b.measures.covered_target, a.measures.covered_target, 1e-12 * a.measures.target);
}
