// simplify_curve() on random curves (open, closed, stars with a junction) from verify's
// generators, stopped after any number of removal steps: the map passes every verify check as a
// parametrization, every S2 vertex has exactly one preimage, the region images tile S2 by length,
// and the feature corners (ends, junctions, sharp turns) stay S1 vertices.

#include <plmap/construct/simplify_curve.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <numbers>

namespace plmap {
namespace {

/// Feature corners of a curve by simplify_curve's rule.
std::vector<char> curve_corners(const Surface<1>& s, double feature_angle) {
  std::vector<char> corner(s.vertex_count(), 1);
  const double cos_limit = std::cos(feature_angle * std::numbers::pi / 180.0);
  for (Index v = 0; v < s.vertex_count(); ++v) {
    const auto segments = s.vertex_elements(v);
    if (segments.size() != 2) continue;
    const auto& a = s.element(segments[0]);
    const auto& b = s.element(segments[1]);
    const auto& in = a[1] == v ? a : b;
    const auto& out = a[0] == v ? a : b;
    if (in[1] != v || out[0] != v || &in == &out) continue;
    const Eigen::Vector2d d_in = (s.vertex(v) - s.vertex(in[0])).normalized();
    const Eigen::Vector2d d_out = (s.vertex(out[1]) - s.vertex(v)).normalized();
    corner[v] = feature_angle < 180.0 && d_in.dot(d_out) < cos_limit;
  }
  return corner;
}

void check_curve(std::shared_ptr<const Surface<1>> s2) {
  SimplifyOptions options;
  options.target_vertices = *rc::gen::inRange<Index>(1, std::max<Index>(2, s2->vertex_count()));
  RC_PRE(options.target_vertices < s2->vertex_count());
  options.feature_angle_degrees = *rc::gen::element(30.0, 60.0, 180.0);
  options.oracles.add(*rc::gen::element(std::string("hausdorff"), std::string("long-edge")), 1.0);
  const CurveSimplifyResult result = simplify_curve(s2, options);
  const PlMap<1>& map = result.map;

  VerifyOptions v;
  v.expect_parametrization = true;
  const VerificationReport report = verify(map, v);
  RC_ASSERT(report.ok());
  // Exactly one preimage per S2 vertex (copies of a node at one point count once).
  std::vector<std::vector<Eigen::Vector2d>> seen(s2->vertex_count());
  std::vector<char> at_corner(s2->vertex_count(), 0);
  const MapData<1>& m = map.data();
  for (Index n = 0; n < map.node_count(); ++n) {
    if (m.node_type[n] == NodeType::ghost || m.node_type[n] == NodeType::intersection) continue;
    const Eigen::Vector2d x = map.node_domain_world(n);
    auto& list = seen[m.node_target[n]];
    bool known = false;
    for (const auto& y : list) known = known || (x - y).norm() <= 1e-9 * map.domain().max_edge_length();
    if (!known) list.push_back(x);
    at_corner[m.node_target[n]] = at_corner[m.node_target[n]] || m.node_type[n] == NodeType::corner;
  }
  for (const auto& list : seen) RC_ASSERT(list.size() == 1u);
  // The region images tile S2 by length.
  double image_length = 0.0;
  for (Index r = 0; r < map.region_count(); ++r)
    image_length += (map.node_target_world(m.region_corners[r][1]) - map.node_target_world(m.region_corners[r][0])).norm();
  RC_ASSERT(std::abs(image_length - s2->measure()) <= 1e-9 * s2->measure());
  // Corners survive.
  const std::vector<char> corner = curve_corners(*s2, options.feature_angle_degrees);
  for (Index w = 0; w < s2->vertex_count(); ++w)
    if (corner[w]) RC_ASSERT(at_corner[w]);
  RC_ASSERT(map.domain().element_count() == result.report.elements_after);
  RC_CLASSIFY(result.report.removed_vertices > 0, "vertices removed");
  RC_CLASSIFY(result.report.target_reached, "target reached");
}

RC_GTEST_PROP(SimplifyCurveProperties, RandomCurvesStayValidParametrizations, ()) {
  check_curve(*generators::curves());
}

RC_GTEST_PROP(SimplifyCurveProperties, LongSmoothCurvesComeDownToTheirEnds, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  generators::Rng rng(seed);
  const bool closed = *rc::gen::arbitrary<bool>();
  const int segments = *rc::gen::inRange(3, 80);
  auto curve = std::make_shared<const Surface<1>>(closed ? generators::random_closed_polyline(segments, rng)
                                                         : generators::random_open_polyline(segments, rng));
  check_curve(curve);
}

TEST(SimplifyCurve, OpenCurveWithoutSharpTurnsComesDownToOneSegment) {
  // A quarter circle of 40 segments turns by 2.25 degrees per vertex: only its ends are corners.
  std::vector<WorldPoint<1>> v;
  std::vector<ElementCorners<1>> e;
  for (int i = 0; i <= 40; ++i) v.emplace_back(std::cos(i * std::numbers::pi / 80), std::sin(i * std::numbers::pi / 80));
  for (Index i = 0; i < 40; ++i) e.push_back({i, i + 1});
  auto arc = std::make_shared<const Surface<1>>(v, e);
  SimplifyOptions options;
  options.target_elements = 1;
  const CurveSimplifyResult r = simplify_curve(arc, options);
  EXPECT_TRUE(r.report.target_reached);
  EXPECT_EQ(r.map.domain().element_count(), 1);
  EXPECT_EQ(r.report.feature_corners, 2);
  // The chord of a quarter circle is 1 - cos(45°) away from its middle.
  EXPECT_NEAR(r.report.hausdorff_error, 1.0 - std::cos(std::numbers::pi / 4), 1e-3);
  VerifyOptions vo;
  vo.expect_parametrization = true;
  EXPECT_TRUE(verify(r.map, vo).ok());
}

TEST(SimplifyCurveBadInput, TargetsAndOraclesThatDoNotApplyAreClearErrors) {
  std::vector<WorldPoint<1>> v{{0, 0}, {1, 0}, {2, 0.1}};
  std::vector<ElementCorners<1>> e{{0, 1}, {1, 2}};
  auto curve = std::make_shared<const Surface<1>>(v, e);
  SimplifyOptions too_big;
  too_big.target_elements = 2;
  EXPECT_THROW(simplify_curve(curve, too_big), Error);
  SimplifyOptions triangles_only;
  triangles_only.target_elements = 1;
  triangles_only.oracles.add("normal-deviation");
  try {
    simplify_curve(curve, triangles_only);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("normal-deviation"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace plmap
