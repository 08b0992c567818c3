// Scale invariance (DESIGN §6, issue 12): the same surfaces scaled by a factor of magnitude 10^k,
// k in [-100, 100], give the same maps for the identity, refinement and overlay maps of
// verify/'s generators and for normal projection, and the scaled maps pass every check of
// plmap::verify. Scaled by the power of two nearest 10^k (exact), the maps agree in everything
// (nodes, types, targets, neighbours, region corners and targets; local positions and images to
// rounding). Scaled by 10^k itself, every coordinate is rounded once, which may decide exact ties
// of the input the other way (cocircular nodes of grid squares: the closure's diagonals); the
// preimage graphs must still agree (graph_difference), except for the overlay generator, whose
// exact predicates see the rounded input as a different one (there: valid maps). Plus the cases
// the issue reported: areas at 1e78 and 1e-150, and a clear error where the measures leave the
// range of doubles.
//
// Seed and number of cases come from RC_PARAMS (set by CTest, see tests/CMakeLists.txt).
#include "projection_fixtures.hpp"
#include "small_planar_recipe.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

using namespace plmap;
using namespace plmap::test;
namespace gen = plmap::generators;

namespace {

template <int d>
std::shared_ptr<const Surface<d>> scaled(const Surface<d>& s, double factor) {
  return transformed<d>(s, [factor](const WorldPoint<d>& p) { return WorldPoint<d>(factor * p); });
}

/// Where two maps of similar surface pairs differ combinatorially; empty if they do not. Local
/// coordinates (positions on S1, images on S2) are invariant under a similarity and compared to
/// rounding.
template <int d>
std::string graph_difference(const PlMap<d>& a, const PlMap<d>& b);

/// Everything: the graph, the closure's regions and their targets.
template <int d>
std::string combinatorial_difference(const PlMap<d>& a, const PlMap<d>& b) {
  const MapData<d>& x = a.data();
  const MapData<d>& y = b.data();
  if (auto g = graph_difference(a, b); !g.empty()) return g;
  if (x.neighbor_begin != y.neighbor_begin || x.neighbor != y.neighbor) return "neighbour lists";
  if (x.region_begin != y.region_begin) return fmt::format("regions per element ({} vs {} regions)", a.region_count(), b.region_count());
  if (x.region_corners != y.region_corners) return "region corners";
  if (x.region_target != y.region_target) return "region targets";
  return {};
}

/// The preimage of S2's edge graph: nodes (count per element, type, place, target, position,
/// image) and the graph edges that are pieces of S2 edges. Not the closure: where nodes are
/// cocircular (a square of a grid) its Delaunay diagonals are a tie that the rounding of 10^k
/// decides either way, and both are right.
template <int d>
std::string graph_difference(const PlMap<d>& a, const PlMap<d>& b) {
  const MapData<d>& x = a.data();
  const MapData<d>& y = b.data();
  if (x.node_begin != y.node_begin) return fmt::format("node counts per element ({} vs {} nodes)", a.node_count(), b.node_count());
  if (x.node_type != y.node_type) return "node types";
  if (x.node_location != y.node_location) return "node locations";
  if (x.node_target != y.node_target) return "node targets";
  if (x.orientation != y.orientation) return "orientation";
  for (Index n = 0; n < a.node_count(); ++n) {
    std::vector<Index> ea, eb;
    for (Index i = x.neighbor_begin[n]; i < x.neighbor_begin[n + 1]; ++i)
      if (x.neighbor_edge_kind[i] == GraphEdgeKind::target_edge) ea.push_back(x.neighbor[i]);
    for (Index i = y.neighbor_begin[n]; i < y.neighbor_begin[n + 1]; ++i)
      if (y.neighbor_edge_kind[i] == GraphEdgeKind::target_edge) eb.push_back(y.neighbor[i]);
    // as sets: where a node's ring of neighbours starts depends on the closure
    std::sort(ea.begin(), ea.end());
    std::sort(eb.begin(), eb.end());
    if (ea != eb) return fmt::format("graph edges at node {}", n);
  }
  // Images are compared as world points in units of S2's longest edge: the S2 element named for
  // an image on an S2 edge or vertex is any element containing it, which rounding may change.
  constexpr double rounding = 1e-9;
  const double unit_a = a.target().max_edge_length(), unit_b = b.target().max_edge_length();
  for (Index n = 0; n < a.node_count(); ++n) {
    if (!((x.node_position[n] - y.node_position[n]).cwiseAbs().maxCoeff() <= rounding))
      return fmt::format("position of node {}", n);
    const WorldPoint<d> image_a = a.node_target_world(n) / unit_a, image_b = b.node_target_world(n) / unit_b;
    if (!((image_a - image_b).cwiseAbs().maxCoeff() <= rounding)) return fmt::format("image of node {}", n);
  }
  return {};
}

/// With an exact factor (a power of two) the maps must agree in everything; with 10^k, which
/// rounds every input coordinate once, in their graphs (see graph_difference).
template <int d>
void assert_same_and_valid(const PlMap<d>& unit, const PlMap<d>& scaled_map, const std::string& what,
                           bool exact_factor) {
  const std::string difference =
      exact_factor ? combinatorial_difference(unit, scaled_map) : graph_difference(unit, scaled_map);
  if (!difference.empty()) RC_FAIL(what + ": the scaled map differs in its " + difference);
  const std::string violations = verify_violations(scaled_map);
  if (!violations.empty()) RC_FAIL(what + ": the scaled map fails verify\n" + violations);
}

/// A factor of magnitude 10^k, k in [-100, 100]: in half the cases 10^k itself, in the others
/// the power of two nearest to it, by which scaling is exact.
struct ScaleFactor {
  int k = 0;
  double f = 1.0;
  bool exact = false;
  std::string text() const { return fmt::format("{} (1e{})", f, k) + (exact ? " exactly" : ""); }
};

ScaleFactor scale_factor() {
  ScaleFactor s;
  s.k = *rc::gen::inRange(-100, 101);
  s.exact = *rc::gen::arbitrary<bool>();
  s.f = s.exact ? std::ldexp(1.0, static_cast<int>(std::lround(s.k * std::log2(10.0)))) : std::pow(10.0, s.k);
  RC_TAG(s.exact ? "power of two" : "power of ten");
  return s;
}


}  // namespace

// ---- maps with known correspondence (verify/'s generators) ------------------------------------------

RC_GTEST_PROP(ScaleInvariance, IdentityMaps, ()) {
  const auto recipe = *gen::triangle_surface_recipes();
  const ScaleFactor scale = scale_factor();
  const double f = scale.f;
  const auto s = std::make_shared<const Surface<2>>(gen::make_triangle_surface(recipe));
  const auto a = gen::identity_map<2>(s);
  const auto b = gen::identity_map<2>(scaled<2>(*s, f));
  assert_same_and_valid(*a.map, *b.map, fmt::format("{} scaled by {}", gen::describe(recipe), scale.text()), scale.exact);
  const auto curve = gen::make_curve(*gen::curve_recipes());
  assert_same_and_valid(*gen::identity_map<1>(std::make_shared<const Surface<1>>(curve)).map,
                        *gen::identity_map<1>(scaled<1>(curve, f)).map, "curve scaled by " + scale.text(), scale.exact);
}

RC_GTEST_PROP(ScaleInvariance, RefinementMaps, ()) {
  const auto recipe = *gen::triangle_surface_recipes();
  const ScaleFactor scale = scale_factor();
  const double f = scale.f;
  const auto seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  const std::string what = fmt::format("{} refined (seed {}) scaled by {}", gen::describe(recipe), seed, scale.text());
  const auto s = std::make_shared<const Surface<2>>(gen::make_triangle_surface(recipe));
  const auto big = scaled<2>(*s, f);
  const gen::RefinementOptions options{.max_points_per_edge = 2, .max_points_per_element = 3};
  gen::Rng rng_a(seed), rng_b(seed);
  const auto a = gen::refinement_map<2>(s, gen::random_refinement<2>(*s, options, rng_a));
  const auto b = gen::refinement_map<2>(big, gen::random_refinement<2>(*big, options, rng_b));
  assert_same_and_valid(*a.map, *b.map, what, scale.exact);
  // the uniform refinement of `plmap build refine --levels`
  const auto ua = gen::refinement_map<2>(s, gen::uniform_refinement<2>(*s, 1, 100000));
  const auto ub = gen::refinement_map<2>(big, gen::uniform_refinement<2>(*big, 1, 100000));
  assert_same_and_valid(*ua.map, *ub.map, what + " (uniform)", scale.exact);
}

RC_GTEST_PROP(ScaleInvariance, PlaneOverlays, ()) {
  const auto c = *gen::overlay_maps<2>();
  const ScaleFactor scale = scale_factor();
  const double f = scale.f;
  const std::string what = c.description + " scaled by " + scale.text();
  if (scale.exact) {
    const auto b = gen::plane_overlay_map(scaled<2>(*c.domain, f), scaled<2>(*c.target, f));
    assert_same_and_valid(*c.map, *b.map, what, true);
  } else {
    // The overlay generator decides with exact predicates on the input doubles, and its inputs
    // share points and lines on purpose; rounding them by 10^k makes a different overlay. Where
    // the rounding leaves two such points or lines a few ulps apart, the crossings the generator
    // computes in floating point can coincide or change order, and the builder refuses the
    // edges with a BuilderError (in 1 of 12 runs of 1,000 cases: seeds 3 and 1355827423). That is
    // a limit of the generator's floating-point crossings on near-degenerate input, not of the
    // scale handling, so those cases are discarded; every map that is built must pass verify.
    std::optional<gen::MapCase<2>> b;
    try {
      b = gen::plane_overlay_map(scaled<2>(*c.domain, f), scaled<2>(*c.target, f));
    } catch (const BuilderError& e) {
      RC_DISCARD(what + ": rounded input too close to degenerate for the generator: " + e.what());
    }
    const std::string violations = verify_violations(*b->map);
    if (!violations.empty()) RC_FAIL(what + ": the scaled map fails verify\n" + violations);
  }
}

RC_GTEST_PROP(ScaleInvariance, PolylineOverlays, ()) {
  const auto recipe = *gen::curve_recipes();
  const ScaleFactor scale = scale_factor();
  const double f = scale.f;
  const auto seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  gen::Rng rng(seed);
  auto sub = gen::random_subdivisions(std::make_shared<const Surface<1>>(gen::make_curve(recipe)), 3, rng);
  const auto a = gen::polyline_overlay_map(sub);
  sub.base = scaled<1>(*sub.base, f);
  const auto b = gen::polyline_overlay_map(sub);
  assert_same_and_valid(*a.map, *b.map, fmt::format("{} (seed {}) scaled by {}", gen::describe(recipe), seed, scale.text()),
                        scale.exact);
}

// ---- normal projection ----------------------------------------------------------------------------

RC_GTEST_PROP(ScaleInvariance, ProjectionOfRemeshedHeightFields, ()) {
  // S1 and S2: two triangulations of one random height field, S2's over a larger footprint and
  // offset vertically; vertical directions (constant: a similarity keeps them).
  const auto r1 = small_planar_recipe(), r2 = small_planar_recipe();
  const auto field_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  gen::Rng rng(field_seed);
  const gen::HeightField field = gen::random_height_field(rng);
  const double offset = *rc::gen::inRange(-300, 301) / 1000.0;
  const ScaleFactor scale = scale_factor();
  const double f = scale.f;
  const std::string what = fmt::format("S1 {} / S2 {} field seed {} offset {} scaled by {}", gen::describe(r1),
                                       gen::describe(r2), field_seed, offset, scale.text());
  auto s1 = std::make_shared<const Surface<2>>(gen::lift_to_height_field(gen::make_planar(r1), field));
  auto s2 = transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    const double x = -0.25 + 1.5 * p.x(), y = -0.25 + 1.5 * p.y();
    return WorldPoint<2>(x, y, field(x, y) + offset);
  });
  ProjectionOptions o;
  o.directions = constant_directions(*s1, WorldPoint<2>(0.0, 0.0, 1.0));
  o.allow_negative_distance = true;
  const auto a = project<2>(s1, s2, o);
  const auto b = project<2>(scaled<2>(*s1, f), scaled<2>(*s2, f), o);
  assert_same_and_valid(a.map, b.map, what, scale.exact);
  RC_ASSERT(a.report.edges_not_inserted.size() == b.report.edges_not_inserted.size());
  // the measures are reported in the user's units
  const double area = f * f;
  RC_ASSERT(std::abs(b.measures.domain - a.measures.domain * area) <= 1e-12 * b.measures.domain);
  RC_ASSERT(std::abs(b.measures.covered_domain - a.measures.covered_domain * area) <= 1e-9 * b.measures.domain);
  RC_ASSERT(std::abs(b.measures.covered_target - a.measures.covered_target * area) <= 1e-9 * b.measures.target);
}

RC_GTEST_PROP(ScaleInvariance, ProjectionWithAveragedNormalsAndTheIdentity, ()) {
  // averaged vertex normals (computed from the scaled elements) on a surface and a lifted copy;
  // and S1 = S2, which must stay the identity at every scale
  const auto recipe = *gen::triangle_surface_recipes();
  const ScaleFactor scale = scale_factor();
  const double f = scale.f;
  const std::string what = fmt::format("{} scaled by {}", gen::describe(recipe), scale.text());
  auto s = std::make_shared<const Surface<2>>(gen::make_triangle_surface(recipe));
  auto lifted = transformed<2>(*s, [](const WorldPoint<2>& p) { return WorldPoint<2>(p + WorldPoint<2>(0.0, 0.0, 0.05)); });
  const auto big = scaled<2>(*s, f);
  assert_same_and_valid(project<2>(s, lifted).map,
                        project<2>(big, scaled<2>(*lifted, f)).map, what + " onto its lifted copy", scale.exact);
  const auto identity = project<2>(big, big);
  RC_ASSERT(identity.map.region_count() == s->element_count());
  assert_same_and_valid(project<2>(s, s).map, identity.map, what + " onto itself", true);
}

RC_GTEST_PROP(ScaleInvariance, ProjectionOfCurves, ()) {
  const int n1 = *rc::gen::inRange(3, 40), n2 = *rc::gen::inRange(3, 40);
  const double phase = *rc::gen::inRange(0, 1000) / 1000.0;
  const ScaleFactor scale = scale_factor();
  const double f = scale.f;
  auto inner = circle(n1, 1.0), outer = circle(n2, 1.3, phase);
  const auto a = project<1>(inner, outer);
  const auto b = project<1>(scaled<1>(*inner, f), scaled<1>(*outer, f));
  assert_same_and_valid(a.map, b.map, fmt::format("circles {} / {} phase {} scaled by {}", n1, n2, phase, scale.text()),
                        scale.exact);
}

// ---- the cases of issue 12 --------------------------------------------------------------------------

TEST(ScaleInvariance, AreasAt1e78AreFiniteAndProjectionMapsAll) {
  // Before: the squared norm of a cross product overflowed, the measure was infinite ("measure:
  // null") and the projection of two such surfaces returned an empty map.
  auto s1 = grid(4, 4, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.1);
  auto s2 = grid(5, 3, 0.0, 1.0, 0.0, 1.0, 0.2, false, 0.1);
  const double f = 1e78;
  auto b1 = scaled<2>(*s1, f), b2 = scaled<2>(*s2, f);
  EXPECT_TRUE(std::isfinite(b1->measure()));
  EXPECT_NEAR(b1->measure() / (f * f), 1.0, 1e-12);
  EXPECT_NEAR(b1->element_normal(0).z(), 1.0, 1e-15);
  const auto a = project<2>(s1, s2);
  const auto b = project<2>(b1, b2);
  EXPECT_GT(b.map.region_count(), 0);
  EXPECT_EQ(combinatorial_difference(a.map, b.map), "");
  EXPECT_NEAR(b.measures.covered_domain / (f * f), 1.0, 1e-9);
  EXPECT_EQ(verify_violations(b.map), "");
}

TEST(ScaleInvariance, MeshesAt1eMinus150AreAcceptedAndProjected) {
  // Before: "element 0 is degenerate: its area is 0" (the area underflowed).
  auto s1 = grid(3, 3, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.1);
  auto s2 = grid(4, 4, 0.0, 1.0, 0.0, 1.0, 0.3, true, 0.1);
  const double f = 1e-150;
  std::shared_ptr<const Surface<2>> b1, b2;
  ASSERT_NO_THROW(b1 = scaled<2>(*s1, f));
  ASSERT_NO_THROW(b2 = scaled<2>(*s2, f));
  EXPECT_NEAR(b1->measure() / (f * 1e-150), 1.0, 1e-12);
  const auto a = project<2>(s1, s2);
  const auto b = project<2>(b1, b2);
  EXPECT_EQ(combinatorial_difference(a.map, b.map), "");
  EXPECT_NEAR(b.measures.covered_domain / a.measures.covered_domain / (f * 1e-150), 1.0, 1e-9);
  EXPECT_EQ(verify_violations(b.map), "");
}

TEST(ScaleInvariance, PowersOfTwoGiveBitForBitTheSameMap) {
  // Very large or small surfaces are projected as copies scaled by a power of two to unit size,
  // the others as they are, with relative tolerances only: scaling the input by 2^j (exact)
  // changes nothing at all, inside the band without copies (j = 5, 30) and outside it.
  auto s1 = grid(4, 4, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.15);
  auto lifted = transformed<2>(*s1, [](const WorldPoint<2>& p) { return WorldPoint<2>(p.x(), p.y(), 0.1 + 0.2 * p.x() * p.y()); });
  const auto a = project<2>(s1, lifted);
  for (int j : {-300, -77, 5, 30, 77, 300}) {
    const double f = std::ldexp(1.0, j);
    const auto b = project<2>(scaled<2>(*s1, f), scaled<2>(*lifted, f));
    EXPECT_TRUE(a.map.data() == b.map.data()) << "2^" << j;
  }
}

TEST(ScaleInvariance, SurfacesOutsideTheRangeOfDoublesAreRefusedWithAClearError) {
  auto s = grid(2, 2, 0.0, 1.0, 0.0, 1.0, 0.0);
  for (double f : {1e-160, 1e-200, 1e160, 1e200}) {
    try {
      scaled<2>(*s, f);
      ADD_FAILURE() << "scale " << f << " accepted";
    } catch (const InvalidSurfaceError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("element 0"), std::string::npos) << message;
      EXPECT_NE(message.find("outside the range of doubles"), std::string::npos) << message;
      EXPECT_NE(message.find("1e-150 to 1e150"), std::string::npos) << message;
    }
  }
  // coordinates whose differences overflow
  const std::vector<ElementCorners<2>> one_triangle{ElementCorners<2>{0, 1, 2}};
  std::vector<WorldPoint<2>> v{{-1e308, 0.0, 0.0}, {1e308, 0.0, 0.0}, {0.0, 1e308, 0.0}};
  EXPECT_THROW(Surface<2>(v, one_triangle), InvalidSurfaceError);
  // the degeneracy test is relative: the same sliver is degenerate at every scale
  for (double f : {1e-100, 1.0, 1e100}) {
    std::vector<WorldPoint<2>> sliver{{0.0, 0.0, 0.0}, {f, 0.0, 0.0}, {0.5 * f, 1e-15 * f, 0.0}};
    EXPECT_THROW(Surface<2>(sliver, one_triangle), InvalidSurfaceError) << f;
    std::vector<WorldPoint<2>> fine{{0.0, 0.0, 0.0}, {f, 0.0, 0.0}, {0.5 * f, 1e-13 * f, 0.0}};
    EXPECT_NO_THROW(Surface<2>(fine, one_triangle)) << f;
  }
}
