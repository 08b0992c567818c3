// Normal projection on copies renumbered in spatial order (construct/src/spatial_renumbering.hpp,
// ProjectionOptions::renumbering). The copies keep every element with its corners in their order;
// the order measure tells surfaces in rows from shuffled ones; and — the property — projecting
// the caller's surfaces with renumbering gives exactly the map of the renumbered copies (projected
// as given), read element by element through the permutations: every node, neighbour list, edge
// array, region, start region and report entry, compared here one element at a time, not by the
// gathers the library uses. The translated maps pass every check of plmap::verify on the caller's
// surfaces.
//
// Seed and number of cases come from RC_PARAMS (set by CTest, see tests/CMakeLists.txt).
#include "projection_fixtures.hpp"
#include "small_planar_recipe.hpp"
#include "spatial_renumbering.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

using namespace plmap;
using namespace plmap::test;
using plmap::projection::RenumberedSurface;
namespace gen = plmap::generators;

namespace {

/// The surface with its elements and vertices in a random order (corners kept in their order).
template <int d>
std::shared_ptr<const Surface<d>> shuffled(const Surface<d>& s, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Index> element(static_cast<std::size_t>(s.element_count())), vertex(static_cast<std::size_t>(s.vertex_count()));
  std::iota(element.begin(), element.end(), 0);
  std::iota(vertex.begin(), vertex.end(), 0);
  std::shuffle(element.begin(), element.end(), rng);
  std::shuffle(vertex.begin(), vertex.end(), rng);  // vertex[new] = old
  std::vector<Index> new_of_old(vertex.size());
  for (std::size_t v = 0; v < vertex.size(); ++v) new_of_old[static_cast<std::size_t>(vertex[v])] = static_cast<Index>(v);
  std::vector<WorldPoint<d>> points;
  for (Index old : vertex) points.push_back(s.vertex(old));
  std::vector<ElementCorners<d>> cells;
  for (Index old : element) {
    ElementCorners<d> c = s.element(old);
    for (Index& v : c) v = new_of_old[static_cast<std::size_t>(v)];
    cells.push_back(c);
  }
  return std::make_shared<const Surface<d>>(std::move(points), std::move(cells));
}

/// The copy's number of a caller's element (identity when the surface was kept).
template <int d>
std::vector<Index> copy_element_of(const RenumberedSurface<d>& r, Index elements) {
  std::vector<Index> out(static_cast<std::size_t>(elements));
  if (!r.renumbered()) {
    std::iota(out.begin(), out.end(), 0);
    return out;
  }
  for (std::size_t i = 0; i < r.original_element.size(); ++i) out[static_cast<std::size_t>(r.original_element[i])] = static_cast<Index>(i);
  return out;
}

template <int d>
Index original_element(const RenumberedSurface<d>& r, Index t) {
  return r.renumbered() && t >= 0 ? r.original_element[static_cast<std::size_t>(t)] : t;
}
template <int d>
Index original_vertex(const RenumberedSurface<d>& r, Index v) {
  return r.renumbered() && v >= 0 ? r.original_vertex[static_cast<std::size_t>(v)] : v;
}

/// The caller's S2 edge of edge e of the copy, found by its vertices, and whether it runs the
/// other way (edge parameters run from the smaller-numbered vertex).
template <int d>
std::pair<Index, bool> original_edge(const RenumberedSurface<d>& r2, const Surface<d>& original, Index e) {
  if (!r2.renumbered() || e < 0) return {e, false};
  if constexpr (d == 1) {
    return {original_element(r2, e), false};
  } else {
    const auto [a, b] = r2.surface->edge_vertices(e);
    const Index oa = original_vertex(r2, a), ob = original_vertex(r2, b);
    return {original.find_edge(oa, ob), oa > ob};
  }
}

/// Where `a` (the caller's surfaces, renumbered internally) differs from `b` (the copies,
/// projected as given) read through the permutations; empty if nowhere.
template <int d>
std::string translation_difference(const ProjectionResult<d>& a, const ProjectionResult<d>& b,
                                   const RenumberedSurface<d>& r1, const RenumberedSurface<d>& r2) {
  const PlMap<d>& ma = a.map;
  const PlMap<d>& mb = b.map;
  const MapData<d>& x = ma.data();
  const MapData<d>& y = mb.data();
  const Surface<d>& s2 = ma.target();
  if (ma.domain().element_count() != mb.domain().element_count()) return "element counts";
  if (x.orientation != y.orientation) return "orientation";
  if (ma.node_count() != mb.node_count() || ma.region_count() != mb.region_count()) return "node or region counts";
  const std::vector<Index> copy = copy_element_of(r1, ma.domain().element_count());
  for (Index t = 0; t < ma.domain().element_count(); ++t) {
    const Index i = copy[static_cast<std::size_t>(t)];
    const Index na = x.node_begin[t], nb = y.node_begin[i], ra = x.region_begin[t], rb = y.region_begin[i];
    const auto where = [&](const std::string& what) { return fmt::format("element {} (copy's {}): {}", t, i, what); };
    if (x.node_begin[t + 1] - na != y.node_begin[i + 1] - nb) return where("node count");
    if (x.region_begin[t + 1] - ra != y.region_begin[i + 1] - rb) return where("region count");
    const auto node_a = [&](Index n_b) { return n_b == invalid_index ? n_b : n_b - nb + na; };
    const auto region_a = [&](Index r_b) { return r_b == invalid_index ? r_b : r_b - rb + ra; };
    for (Index k = 0; k < x.node_begin[t + 1] - na; ++k) {
      const Index p = na + k, q = nb + k;
      if (x.node_type[p] != y.node_type[q] || x.node_location[p] != y.node_location[q]) return where("node type or place");
      if (x.node_position[p] != y.node_position[q] || x.node_image_local[p] != y.node_image_local[q])
        return where("node position or image");
      if (x.node_image_element[p] != original_element(r2, y.node_image_element[q])) return where("node image element");
      const NodeType type = y.node_type[q];
      const Index target = is_target_vertex_preimage(type) ? original_vertex(r2, y.node_target[q])
                           : type == NodeType::ghost      ? y.node_target[q]
                                                          : original_edge(r2, s2, y.node_target[q]).first;
      if (x.node_target[p] != target) return where(fmt::format("target of node {}", k));
      const auto la = ma.neighbors(p), lb = mb.neighbors(q);
      if (la.size() != lb.size()) return where("neighbour count");
      for (std::size_t j = 0; j < la.size(); ++j)
        if (la[j] != node_a(lb[j]) ||
            x.neighbor_edge_kind[static_cast<std::size_t>(x.neighbor_begin[p]) + j] !=
                y.neighbor_edge_kind[static_cast<std::size_t>(y.neighbor_begin[q]) + j])
          return where(fmt::format("neighbours of node {}", k));
    }
    if constexpr (d == 2)
      for (int side = 0; side < 3; ++side) {
        const auto ea = ma.edge_nodes(t, side), eb = mb.edge_nodes(i, side);
        if (ea.size() != eb.size()) return where("edge node count");
        for (std::size_t j = 0; j < ea.size(); ++j)
          if (ea[j] != node_a(eb[j])) return where("edge nodes");
      }
    const auto na_region = ma.region_neighbors(), nb_region = mb.region_neighbors();
    for (Index k = 0; k < x.region_begin[t + 1] - ra; ++k) {
      const Index p = ra + k, q = rb + k;
      for (int c = 0; c <= d; ++c) {
        if (x.region_corners[p][c] != node_a(y.region_corners[q][c])) return where("region corners");
        if (na_region[p][c] != region_a(nb_region[q][c])) return where("region neighbours");
      }
      if (x.region_target[p] != original_element(r2, y.region_target[q])) return where("region target");
      if (x.region_map[p] != y.region_map[q]) return where("region map");
    }
    if (x.start_region[t] != region_a(y.start_region[i])) return where("start region");
  }
  const auto& fa = a.report.edges_not_inserted;
  const auto& fb = b.report.edges_not_inserted;
  if (fa.size() != fb.size()) return "number of edges not inserted";
  for (std::size_t j = 0; j < fa.size(); ++j) {
    const auto [edge, reversed] = original_edge(r2, s2, fb[j].target_edge);
    const double parameter = reversed ? 1.0 - fb[j].target_parameter : fb[j].target_parameter;
    if (fa[j].target_edge != edge || fa[j].target_parameter != parameter || fa[j].reason != fb[j].reason ||
        fa[j].domain_element != original_element(r1, fb[j].domain_element) || fa[j].domain_point != fb[j].domain_point)
      return fmt::format("edge not inserted #{}", j);
  }
  if (a.measures.covered_domain != b.measures.covered_domain || a.measures.covered_target != b.measures.covered_target)
    return "covered measures";
  if (a.report.renumbered_domain != r1.renumbered() || a.report.renumbered_target != r2.renumbered())
    return "the report's renumbered flags";
  return {};
}

/// Projects (s1, s2) with `options` (renumbering as given) and the copies the rule makes as
/// given, and compares. (The rule `automatic` chooses between what `target` and `never` do; the
/// unit tests above check its choice.)
template <int d>
void check_projection_on_copies(const std::shared_ptr<const Surface<d>>& s1, const std::shared_ptr<const Surface<d>>& s2,
                                ProjectionOptions options, const std::string& what) {
  const auto choice = projection::renumbering_choice<d>(*s2, s1 == s2, options.renumbering);
  const auto r1 = projection::renumbered_or_kept<d>(s1, choice.domain);
  const auto r2 = projection::renumbered_or_kept<d>(s2, choice.target);
  RC_TAG(fmt::format("S1 {}, S2 {}", r1.renumbered() ? "renumbered" : "kept", r2.renumbered() ? "renumbered" : "kept"));
  const ProjectionResult<d> a = project<d>(s1, s2, options);
  ProjectionOptions as_given = projection::options_for_renumbered(options, r1);
  as_given.renumbering = SpatialRenumbering::never;
  const ProjectionResult<d> b = project<d>(r1.surface, r2.surface, as_given);
  const std::string difference = translation_difference(a, b, r1, r2);
  if (!difference.empty()) RC_FAIL(what + ": the translated map differs from the copies' in its " + difference);
  RC_ASSERT(&a.map.domain() == s1.get());
  RC_ASSERT(&a.map.target() == s2.get());
  const std::string violations = verify_violations(a.map);
  if (!violations.empty()) RC_FAIL(what + ": the translated map fails verify\n" + violations);
}


}  // namespace

// ---- the copies ---------------------------------------------------------------------------------

TEST(SpatialRenumbering, TheCopyKeepsEveryElementWithItsCornersInOrder) {
  const auto s = shuffled<2>(*sphere(3, 1.0), 7);
  const RenumberedSurface<2> r = projection::spatially_renumbered(*s);
  ASSERT_TRUE(r.renumbered());
  const Surface<2>& c = *r.surface;
  ASSERT_EQ(c.element_count(), s->element_count());
  ASSERT_EQ(c.vertex_count(), s->vertex_count());
  std::vector<Index> elements = r.original_element, vertices = r.original_vertex;
  std::sort(elements.begin(), elements.end());
  std::sort(vertices.begin(), vertices.end());
  for (Index i = 0; i < s->element_count(); ++i) ASSERT_EQ(elements[static_cast<std::size_t>(i)], i) << "not a permutation";
  for (Index v = 0; v < s->vertex_count(); ++v) ASSERT_EQ(vertices[static_cast<std::size_t>(v)], v) << "not a permutation";
  for (Index v = 0; v < c.vertex_count(); ++v) EXPECT_EQ(c.vertex(v), s->vertex(r.original_vertex[static_cast<std::size_t>(v)]));
  for (Index t = 0; t < c.element_count(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(r.original_vertex[static_cast<std::size_t>(c.element(t)[k])],
                s->element(r.original_element[static_cast<std::size_t>(t)])[k])
          << "element " << t << " corner " << k;
  EXPECT_DOUBLE_EQ(c.measure(), s->measure());
}

TEST(SpatialRenumbering, TheCopyIsTheSameOnEveryThreadCountAndTheConstructors) {
  // large enough that every thread computes codes, sorts and renames a share
  const auto s = shuffled<2>(*grid(90, 90, 0.0, 1.0, 0.0, 1.0, 0.0), 13);
  const RenumberedSurface<2> one = projection::spatially_renumbered(*s, 1);
  for (const unsigned threads : {2u, 3u}) {
    const RenumberedSurface<2> r = projection::spatially_renumbered(*s, threads);
    EXPECT_EQ(r.original_element, one.original_element) << threads;
    EXPECT_EQ(r.original_vertex, one.original_vertex) << threads;
    EXPECT_EQ(r.surface->vertices(), one.surface->vertices()) << threads;
    EXPECT_EQ(r.surface->elements(), one.surface->elements()) << threads;
  }
  // the copy's measure is the constructor's, summed in the copy's order, to the last bit
  // (tests/core/test_surface_renumbering.cpp compares every other array)
  const Surface<2> constructed(one.surface->vertices(), one.surface->elements());
  EXPECT_EQ(one.surface->measure(), constructed.measure());
  EXPECT_EQ(one.surface->edge_count(), constructed.edge_count());
}

TEST(SpatialRenumbering, VerticesNoElementUsesComeLastInTheirOrder) {
  // two isolated vertices (numbers 0 and 5) around a row of segments
  std::vector<WorldPoint<1>> v{{9, 9}, {0, 0}, {1, 0}, {2, 0}, {3, 0}, {8, 8}};
  const Surface<1> s(std::move(v), {{3, 4}, {1, 2}, {2, 3}});
  const RenumberedSurface<1> r = projection::spatially_renumbered(s);
  EXPECT_EQ(r.original_element, (std::vector<Index>{1, 2, 0}));
  EXPECT_EQ(r.original_vertex, (std::vector<Index>{1, 2, 3, 4, 0, 5}));
}

TEST(SpatialRenumbering, TheOrderMeasureTellsRowsFromShuffledElements) {
  const auto rows = grid(40, 40, 0.0, 1.0, 0.0, 1.0, 0.0);
  const auto subdivided = sphere(4, 1.0);
  const auto mixed = shuffled<2>(*rows, 3);
  EXPECT_LT(projection::consecutive_element_spacing(*rows), projection::poor_order_spacing);
  EXPECT_LT(projection::consecutive_element_spacing(*subdivided), projection::poor_order_spacing);
  EXPECT_GT(projection::consecutive_element_spacing(*mixed), projection::poor_order_spacing);
  // renumbered, the shuffled grid is in order again
  EXPECT_LT(projection::consecutive_element_spacing(*projection::spatially_renumbered(*mixed).surface),
            projection::poor_order_spacing);
  const auto ring = circle(2000, 1.0);
  EXPECT_LT(projection::consecutive_element_spacing(*ring), 1.5);
  EXPECT_GT(projection::consecutive_element_spacing(*shuffled<1>(*ring, 5)), projection::poor_order_spacing);
}

TEST(SpatialRenumbering, AutomaticRenumbersOnlyAShuffledTarget) {
  const auto rows = grid(20, 20, 0.0, 1.0, 0.0, 1.0, 0.0);
  const auto mixed = shuffled<2>(*grid(23, 21, -0.1, 1.1, -0.1, 1.1, 0.1, false, 0.2), 11);
  const auto automatic = project<2>(rows, mixed);
  EXPECT_FALSE(automatic.report.renumbered_domain);
  EXPECT_TRUE(automatic.report.renumbered_target);
  EXPECT_GT(automatic.report.seconds.renumbering, 0.0);
  ProjectionOptions never;
  never.renumbering = SpatialRenumbering::never;
  const auto kept = project<2>(rows, mixed, never);
  EXPECT_FALSE(kept.report.renumbered_target);
  EXPECT_EQ(kept.report.seconds.renumbering, 0.0);
  // the same surface, in rows: kept
  EXPECT_FALSE(project<2>(mixed, rows).report.renumbered_target);
  // the identity stays the identity: one object, not renumbered
  const auto identity = project<2>(mixed, mixed);
  EXPECT_FALSE(identity.report.renumbered_target);
  EXPECT_EQ(identity.map.region_count(), mixed->element_count());
  // both maps cover all of S1 and pass verify on the caller's surfaces
  EXPECT_NEAR(automatic.measures.covered_domain, rows->measure(), 1e-12);
  EXPECT_NEAR(kept.measures.covered_domain, rows->measure(), 1e-12);
  EXPECT_EQ(verify_violations(automatic.map), "");
}

TEST(SpatialRenumbering, DirectionsOfTheWrongCountAreStillTheProjectionsError) {
  const auto s1 = shuffled<2>(*grid(6, 6, 0.0, 1.0, 0.0, 1.0, 0.0), 1);
  const auto s2 = shuffled<2>(*grid(7, 7, 0.0, 1.0, 0.0, 1.0, 0.2), 2);
  ProjectionOptions o;
  o.renumbering = SpatialRenumbering::always;
  o.directions = {0.0, 0.0, 1.0};
  std::string renumbered, as_given;
  try {
    (void)project<2>(s1, s2, o);
  } catch (const Error& e) {
    renumbered = e.what();
  }
  o.renumbering = SpatialRenumbering::never;
  try {
    (void)project<2>(s1, s2, o);
  } catch (const Error& e) {
    as_given = e.what();
  }
  EXPECT_FALSE(as_given.empty());
  EXPECT_EQ(renumbered, as_given);
}

// ---- the translation back: exactly the copies' map ---------------------------------------------

RC_GTEST_PROP(SpatialRenumbering, RemeshedHeightFieldsTranslateExactly, ()) {
  // two triangulations of one random height field, S2 over a larger footprint and offset,
  // both in a random order; constant directions (permuted with S1's vertices) or averaged normals
  const auto r1 = small_planar_recipe(), r2 = small_planar_recipe();
  const auto field_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  const auto order_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  gen::Rng rng(field_seed);
  const gen::HeightField field = gen::random_height_field(rng);
  const double offset = *rc::gen::inRange(-300, 301) / 1000.0;
  auto s1 = shuffled<2>(gen::lift_to_height_field(gen::make_planar(r1), field), order_seed);
  auto s2 = shuffled<2>(*transformed<2>(gen::make_planar(r2),
                                        [&](const WorldPoint<2>& p) {
                                          const double x = -0.25 + 1.5 * p.x(), y = -0.25 + 1.5 * p.y();
                                          return WorldPoint<2>(x, y, field(x, y) + offset);
                                        }),
                        order_seed + 1);
  ProjectionOptions o;
  if (*rc::gen::arbitrary<bool>()) o.directions = constant_directions(*s1, WorldPoint<2>(0.0, 0.0, 1.0));
  o.allow_negative_distance = true;
  o.renumbering = *rc::gen::element(SpatialRenumbering::always, SpatialRenumbering::target);
  o.threads = *rc::gen::element(1u, 2u);
  check_projection_on_copies<2>(s1, s2, o,
                                fmt::format("S1 {} / S2 {} field seed {} offset {} order seed {}", gen::describe(r1),
                                            gen::describe(r2), field_seed, offset, order_seed));
}

RC_GTEST_PROP(SpatialRenumbering, SurfacesOntoLiftedCopiesTranslateExactly, ()) {
  // any generated surface (boundaries, non-manifold edges, several components) in a random order,
  // onto a lifted and shuffled copy of itself, with averaged normals
  const auto recipe = *gen::triangle_surface_recipes();
  const auto order_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  const auto s = shuffled<2>(gen::make_triangle_surface(recipe), order_seed);
  const auto lifted = shuffled<2>(
      *transformed<2>(*s, [](const WorldPoint<2>& p) { return WorldPoint<2>(p + WorldPoint<2>(0.01, -0.02, 0.05)); }),
      order_seed + 1);
  ProjectionOptions o;
  o.renumbering = *rc::gen::element(SpatialRenumbering::always, SpatialRenumbering::target);
  check_projection_on_copies<2>(s, lifted, o, fmt::format("{} order seed {}", gen::describe(recipe), order_seed));
}

RC_GTEST_PROP(SpatialRenumbering, CurvesTranslateExactly, ()) {
  const int n1 = *rc::gen::inRange(3, 60), n2 = *rc::gen::inRange(3, 60);
  const double phase = *rc::gen::inRange(0, 1000) / 1000.0;
  const auto order_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  const auto inner = shuffled<1>(*circle(n1, 1.0), order_seed);
  const auto outer = shuffled<1>(*circle(n2, 1.3, phase), order_seed + 1);
  ProjectionOptions o;
  o.renumbering = *rc::gen::element(SpatialRenumbering::always, SpatialRenumbering::target);
  check_projection_on_copies<1>(inner, outer, o,
                                fmt::format("circles {} / {} phase {} order seed {}", n1, n2, phase, order_seed));
}
