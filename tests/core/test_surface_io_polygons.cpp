// Polygon faces of OFF, OBJ and PLY files become triangles inside the polygon
// (core/src/io/polygon_triangulation.hpp): the fan from the first corner where it lies inside,
// ear clipping in the polygon's plane where it does not.
#include <plmap/core/io/surface_reader.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace plmap;

namespace {

/// The measure-weighted normal of each triangle (twice its area vector).
Eigen::Vector3d area_vector(const Surface<2>& s, Index t) {
  const auto& e = s.element(t);
  const WorldPoint<2>& a = s.vertex(e[0]);
  return (s.vertex(e[1]) - a).cross(s.vertex(e[2]) - a);
}

/// An OFF file of one polygon face over `points`, its corners listed from `start` on.
std::string one_polygon_off(const std::vector<Eigen::Vector3d>& points, std::size_t start) {
  std::ostringstream off;
  off.precision(17);
  off << "OFF\n" << points.size() << " 1 0\n";
  for (const auto& p : points) off << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  off << points.size();
  for (std::size_t k = 0; k < points.size(); ++k) off << ' ' << (start + k) % points.size();
  off << '\n';
  return off.str();
}

// The top face of CGAL's corner_poly.off: an L-shaped hexagon whose fan from its first corner
// puts a triangle over the notch.
const std::vector<Eigen::Vector3d> l_hexagon = {{0, 1, 1}, {1, 1, 1}, {1, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};

}  // namespace

TEST(SurfaceIoPolygons, AnLShapedHexagonIsCutInsideIt) {
  const std::string off = one_polygon_off(l_hexagon, 0);
  const Surface<2> s = parse_surface<2>(off, SurfaceFormat::off, "l.off");
  ASSERT_EQ(s.element_count(), 4);
  EXPECT_NEAR(s.measure(), 3.0, 1e-14);  // 2 x 2 less the unit notch
  for (Index t = 0; t < 4; ++t) EXPECT_GT(area_vector(s, t).z(), 0.0) << "triangle " << t << " folds";
  // the fan, asked for, folds over the notch: more measure than the polygon has
  SurfaceReadOptions fan;
  fan.polygons = PolygonPolicy::fan_triangulate;
  const Surface<2> folded = parse_surface<2>(off, SurfaceFormat::off, "l.off", fan);
  EXPECT_GT(folded.measure(), 3.5);
  // OBJ (vertices after the face: the triangulation waits for them) and PLY alike
  const std::string obj = "f 1 2 3 4 5 6\nv 0 1 1\nv 1 1 1\nv 1 0 1\nv 2 0 1\nv 2 2 1\nv 0 2 1\n";
  EXPECT_NEAR(parse_surface<2>(obj, SurfaceFormat::obj, "l.obj").measure(), 3.0, 1e-14);
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 1 1\n1 1 1\n1 0 1\n2 0 1\n2 2 1\n0 2 1\n6 0 1 2 3 4 5\n";
  EXPECT_NEAR(parse_surface<2>(ply, SurfaceFormat::ply, "l.ply").measure(), 3.0, 1e-14);
}

TEST(SurfaceIoPolygons, ConvexPolygonsKeepTheirFan) {
  const std::vector<Eigen::Vector3d> quad = {{0, 0, 0}, {1, 0, 0}, {1.2, 1, 0.1}, {0, 1, 0}};
  const Surface<2> s = parse_surface<2>(one_polygon_off(quad, 0), SurfaceFormat::off, "q.off");
  ASSERT_EQ(s.element_count(), 2);
  EXPECT_EQ(s.element(0), (ElementCorners<2>{0, 1, 2}));
  EXPECT_EQ(s.element(1), (ElementCorners<2>{0, 2, 3}));
}

TEST(SurfaceIoPolygons, AStraightCornerIsCutWithoutADegenerateTriangle) {
  // corner 1 lies on the segment from corner 0 to corner 2: the fan's first triangle would be
  // degenerate, the diagonal from the straight corner is not
  const std::vector<Eigen::Vector3d> quad = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
  const Surface<2> s = parse_surface<2>(one_polygon_off(quad, 0), SurfaceFormat::off, "s.off");
  ASSERT_EQ(s.element_count(), 2);
  EXPECT_NEAR(s.measure(), 1.0, 1e-15);
  for (Index t = 0; t < 2; ++t) EXPECT_GT(area_vector(s, t).z(), 0.0);
}

TEST(SurfaceIoPolygons, APolygonWithoutAnEarKeepsItsFanForSurfaceToJudge) {
  // a bow tie (self-intersecting in its plane): no triangulation inside it exists
  const std::vector<Eigen::Vector3d> bow_tie = {{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0}};
  const Surface<2> s = parse_surface<2>(one_polygon_off(bow_tie, 0), SurfaceFormat::off, "b.off");
  EXPECT_EQ(s.element(0), (ElementCorners<2>{0, 1, 2}));
  EXPECT_EQ(s.element(1), (ElementCorners<2>{0, 2, 3}));
}

RC_GTEST_PROP(SurfaceIoPolygons, StarShapedPolygonsInAnyPlaneAreCutInsideThem, ()) {
  // k corners at sorted random angles and random radii around a centre that is no corner, so
  // that the fan from a corner often leaves the polygon; turned into a random plane, far from
  // the origin, listed from a random corner. The triangles must tile the polygon: each turns
  // the polygon's way, and their measures add up to its area (the shoelace formula in 2-D).
  const int k = *rc::gen::inRange(4, 15);
  // corner i in its own sector of the circle, so that the corners are in order and no two
  // consecutive ones are more than half a turn apart (the polygon is simple around the centre)
  const double sector = 2.0 * std::numbers::pi / k;
  std::vector<double> angle(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i) angle[static_cast<std::size_t>(i)] = sector * (i + 0.05 + 0.9 * *rc::gen::inRange(0, 1001) / 1000.0);
  std::vector<Eigen::Vector2d> flat;
  for (double a : angle) {
    const double r = 0.2 + *rc::gen::inRange(0, 1000) * 0.0008;
    flat.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  double area = 0.0;
  for (std::size_t i = 0; i < flat.size(); ++i) {
    const auto& p = flat[i];
    const auto& q = flat[(i + 1) % flat.size()];
    area += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  const Eigen::Vector3d axis =
      Eigen::Vector3d(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101), *rc::gen::inRange(1, 101)).normalized();
  const Eigen::AngleAxisd turn(*rc::gen::inRange(0, 628) * 0.01, axis);
  const Eigen::Vector3d shift(*rc::gen::inRange(-1000, 1000), *rc::gen::inRange(-1000, 1000), 0.5);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : flat) points.push_back(turn * Eigen::Vector3d(p.x(), p.y(), 0.0) + shift);
  const std::size_t start = static_cast<std::size_t>(*rc::gen::inRange(0, k));
  const Surface<2> s = parse_surface<2>(one_polygon_off(points, start), SurfaceFormat::off, "star.off");
  RC_ASSERT(s.element_count() == k - 2);
  const Eigen::Vector3d normal = turn * Eigen::Vector3d::UnitZ();
  for (Index t = 0; t < s.element_count(); ++t) RC_ASSERT(area_vector(s, t).dot(normal) > 0.0);
  RC_ASSERT(std::abs(s.measure() - area) <= 1e-9 * area);
}

TEST(SurfaceIoPolygons, ALargeNonConvexPolygonIsCutInsideIt) {
  // A comb of 2,000 teeth (8,000 corners) whose fan from its fourth corner folds: ear clipping
  // cuts it into 7,998 triangles of the comb's area, each turning the comb's way.
  // counter-clockwise seen from +z: along the back, up the last tooth, then tooth by tooth
  // to the left (top, down into the gap, along its bottom, up the next tooth)
  const int teeth = 2000;
  std::vector<Eigen::Vector3d> comb = {{0.0, -1.0, 0.0}, {2.0 * teeth - 1.0, -1.0, 0.0}};
  for (int i = teeth - 1; i >= 0; --i) {
    comb.emplace_back(2.0 * i + 1.0, 5.0, 0.0);
    comb.emplace_back(2.0 * i, 5.0, 0.0);
    if (i > 0) {
      comb.emplace_back(2.0 * i, 0.0, 0.0);
      comb.emplace_back(2.0 * i - 1.0, 0.0, 0.0);
    }
  }
  const Surface<2> s = parse_surface<2>(one_polygon_off(comb, 3), SurfaceFormat::off, "comb.off");
  ASSERT_EQ(s.element_count(), static_cast<Index>(comb.size()) - 2);
  EXPECT_NEAR(s.measure(), teeth * 5.0 + (2.0 * teeth - 1.0) * 1.0, 1e-6);
  for (Index t = 0; t < s.element_count(); ++t) ASSERT_GT(area_vector(s, t).z(), 0.0) << t;
}
