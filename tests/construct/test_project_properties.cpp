// Property tests of normal projection (issue 4) over random surface pairs: random planar
// triangulations (grids with random diagonals, constrained Delaunay), lifted to random height
// fields, offset and remeshed; random rigid motions; random polylines and circles for d = 1.
// Properties: the map passes every check of plmap::verify; the covered measure equals the
// analytic overlap where it is known; S1 = S2 gives the identity; the covered measure does not
// change under a rigid motion of both surfaces; Newton and Ceres agree; the thread count does
// not change the map.
//
// Seed and number of cases come from RC_PARAMS (set by CTest, see tests/CMakeLists.txt). Every
// case is small (at most a few hundred triangles), so the whole executable stays fast.
#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/verify/generators/rc_generators.hpp>
#include <plmap/verify/ray_check.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

using namespace plmap;
using namespace plmap::test;
namespace gen = plmap::generators;

namespace {

/// A random planar triangulation of the unit square (grid or Delaunay, sometimes with the
/// HoleBox hole), small enough for hundreds of cases.
gen::PlanarRecipe small_planar_recipe(bool hole_allowed) {
  gen::PlanarRecipe r;
  r.base = *rc::gen::element(gen::PlanarBase::grid, gen::PlanarBase::delaunay);
  r.with_hole = hole_allowed && *rc::gen::inRange(0, 4) == 0;
  r.resolution = r.base == gen::PlanarBase::grid ? *rc::gen::inRange(1, 7) : *rc::gen::inRange(0, 16);
  r.jitter = *rc::gen::arbitrary<bool>();
  r.seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  return r;
}

Eigen::Matrix3d random_rotation() {
  const double angle = *rc::gen::inRange(0, 6283) / 1000.0;
  Eigen::Vector3d axis(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101), *rc::gen::inRange(1, 101));
  return Eigen::AngleAxisd(angle, axis.normalized()).matrix();
}

template <int d>
void assert_valid(const ProjectionResult<d>& r, const std::string& what) {
  const std::string violations = verify_violations(r.map);
  if (!violations.empty()) RC_FAIL(what + "\n" + violations);
  const double slack = 1e-9 * (r.measures.domain + r.measures.target);
  RC_ASSERT(r.measures.covered_domain <= r.measures.domain + slack);
  RC_ASSERT(r.measures.covered_target <= r.measures.target + slack);
  if constexpr (d == 2) {
    // what is left out of D, by why, and what D covers add up to S1
    const auto& out = r.report.left_out;
    double sum = r.measures.covered_domain;
    std::string parts;
    for (const auto& [name, measure] : out.fields()) {
      const double part = out.*measure;
      RC_ASSERT(part >= -slack);
      sum += part;
      parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", name, part);
    }
    if (!(std::abs(sum - r.measures.domain) <= 1e-9 * r.measures.domain))
      RC_FAIL(what + fmt::format(": covered {:.17g} and left out ({}) add up to {:.17g}, not S1's {:.17g}",
                                 r.measures.covered_domain, parts, sum, r.measures.domain));
  }
}

/// The measures agree to a relative 1e-9 (of the larger surface measure).
void assert_same_measure(double a, double b, double scale, const std::string& what) {
  if (!(std::abs(a - b) <= 1e-9 * scale)) RC_FAIL(what + fmt::format(": {:.17g} != {:.17g}", a, b));
}

/// Area of the part of S1 (a surface over the xy-plane) that lies over the rectangle
/// [x0, x1] x [y0, y1] = box: per triangle, its area times the fraction of its xy-footprint inside
/// the box (the footprint clipped to the box, Sutherland-Hodgman). The covered measure of a
/// projection along the vertical onto a surface over that box, computed without the projection.
double area_over_box(const Surface<2>& s1, const std::array<double, 4>& box) {
  double total = 0.0;
  for (Index t = 0; t < s1.element_count(); ++t) {
    std::vector<Eigen::Vector2d> polygon;
    for (int k = 0; k < 3; ++k) polygon.push_back(s1.corner(t, k).head<2>());
    // clip against x >= x0, x <= x1, y >= y0, y <= y1: inside(p) = sign * (p(axis) - bound) >= 0
    for (const auto& [axis, bound, sign] : {std::tuple{0, box[0], 1.0}, std::tuple{0, box[1], -1.0},
                                            std::tuple{1, box[2], 1.0}, std::tuple{1, box[3], -1.0}}) {
      std::vector<Eigen::Vector2d> out;
      for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Eigen::Vector2d& a = polygon[i];
        const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
        const double fa = sign * (a(axis) - bound), fb = sign * (b(axis) - bound);
        if (fa >= 0) out.push_back(a);
        if ((fa >= 0) != (fb >= 0)) out.push_back(a + fa / (fa - fb) * (b - a));
      }
      polygon = std::move(out);
      if (polygon.empty()) break;
    }
    double clipped = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector2d& a = polygon[i];
      const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
      clipped += 0.5 * (a.x() * b.y() - a.y() * b.x());
    }
    const Eigen::Vector2d e1 = (s1.corner(t, 1) - s1.corner(t, 0)).head<2>(), e2 = (s1.corner(t, 2) - s1.corner(t, 0)).head<2>();
    const double footprint = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    if (footprint > 0.0) total += s1.element_measure(t) * std::abs(clipped) / footprint;
  }
  return total;
}

/// The map's coverage against an independent ray cast (verify/ray_check.hpp) along the same
/// field and rules: plmap claims no area whose ray misses S2 (but for the interpolation error at
/// S2's boundary) or lands elsewhere (image error below one S2 edge length), and where it reports
/// every S2 edge inserted and no face left out, it misses none either.
void assert_coverage_against_rays(const ProjectionResult<2>& r, const std::vector<WorldPoint<2>>& directions,
                                  const ProjectionOptions& o, const std::string& what) {
  RayCheckOptions<2> rays;
  rays.directions = directions;
  rays.samples = 2000;
  rays.allow_negative_distance = o.allow_negative_distance;
  rays.normal_check = o.normal_check == TargetNormalCheck::facing   ? RayNormalCheck::facing
                      : o.normal_check == TargetNormalCheck::aligned ? RayNormalCheck::aligned
                                                                     : RayNormalCheck::none;
  const auto report = check_against_rays(r.map, rays);
  if (report.extra_defects() != 0)
    RC_FAIL(what + fmt::format(": {} of {} ray samples in D miss S2", report.extra_defects(), report.samples));
  if (!(report.error_max < 1.0)) RC_FAIL(what + fmt::format(": image error {} S2 edge lengths", report.error_max));
  // complete: every S1 vertex has the image of its ray, every S2 edge is inserted, no face left
  // out. (A ghost ray that passes a focal point, or misses S2, costs the elements around its
  // vertex without an entry in edges_not_inserted; the ray check finds that area as missed.)
  const auto& p = r.report;
  const bool complete = p.edges_not_inserted.empty() && p.occluded_faces == 0 && p.reversed_faces == 0 &&
                        p.unmapped_faces == 0 &&
                        p.folded_faces == 0 &&
                        p.ghost_nodes + p.vertices_mapped_by_ray == p.domain_vertices;
  // (but for the interpolation error at S2's boundary, as for the extra samples)
  const std::size_t missed_inside_boundary =
      report.missed_by_reason[static_cast<std::size_t>(MissedReason::inside_target_boundary)];
  if (complete && report.missed != missed_inside_boundary)
    RC_FAIL(what + fmt::format(": every ray and edge inserted, but {} of {} ray samples outside D hit S2",
                               report.missed - missed_inside_boundary, report.samples));
  // Not asserted yet: that the rays find no more than plmap covers where it is incomplete. On
  // these pairs plmap can miss up to all of S1 where half of its rays hit S2 (e.g. S1 delaunay
  // resolution=2 hole seed=479153123641135 / S2 grid resolution=1 seed=472756763763325 height
  // field (seed 52607475947924) offset 0.161 shift (-0.3, -0.3)); that is the coverage work of
  // issue 14, and the classification below shows how often.
  RC_CLASSIFY(complete, "complete");
  RC_CLASSIFY(report.missed == 0, "no ray sample missed");
  RC_CLASSIFY(report.in_domain_with_hit == 0 && report.missed > 0, "D empty, rays hit S2");
}

}  // namespace

// ---- d = 2 ----------------------------------------------------------------------------------------

RC_GTEST_PROP(ProjectProperties, PlanarPairsCoverTheExactOverlap, ()) {
  // S1: a triangulation of the unit square (maybe with its hole) at z = 0; S2: another one,
  // scaled by s and shifted by (dx, dy), at height h, facing S1 or not. Vertical normals, so the
  // covered measure is the overlap of the two footprints, computed from rectangles.
  // S2 without a hole, so that the overlap is that of two rectangles (holes of S2 inside S1
  // elements are covered by ProjectEdgeCases.TargetHoleInsideADomainElementPassesVerify).
  const auto r1 = small_planar_recipe(true), r2 = small_planar_recipe(false);
  const double s = *rc::gen::inRange(50, 201) / 100.0;
  // shifts on a 1/8 grid half of the time: S2's boundary then runs exactly above S1 edges
  const bool dyadic = *rc::gen::arbitrary<bool>();
  const double dx = dyadic ? *rc::gen::inRange(-8, 9) / 8.0 : *rc::gen::inRange(-900, 901) / 1000.0;
  const double dy = dyadic ? *rc::gen::inRange(-8, 9) / 8.0 : *rc::gen::inRange(-900, 901) / 1000.0;
  const double h = *rc::gen::inRange(1, 500) / 1000.0;
  const bool facing = *rc::gen::arbitrary<bool>();
  RC_TAG(dyadic ? "dyadic shift" : "random shift");
  const std::string what = fmt::format("S1 {} / S2 {} scale {} shift ({}, {}) height {}{}", gen::describe(r1),
                                       gen::describe(r2), s, dx, dy, h, facing ? " facing" : "");
  auto s1 = std::make_shared<const Surface<2>>(gen::make_planar(r1));
  auto placed = transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    return WorldPoint<2>(dx + s * p.x(), dy + s * p.y(), h);
  });
  auto s2 = facing ? flipped(*placed) : placed;
  const auto r = project<2>(s1, s2);
  assert_valid(r, what);
  if (!r.report.edges_not_inserted.empty()) RC_FAIL(what + "\n" + describe_failures(r.report));

  const std::array<double, 4> square{0, 1, 0, 1}, target{dx, dx + s, dy, dy + s};
  const std::array<double, 4> hole{gen::HoleBox::x0, gen::HoleBox::x1, gen::HoleBox::y0, gen::HoleBox::y1};
  const std::array<double, 4> target_hole{dx + s * hole[0], dx + s * hole[1], dy + s * hole[2], dy + s * hole[3]};
  // inclusion-exclusion over the two holes (each inside its square)
  double overlap = rectangle_overlap(square, target);
  if (r1.with_hole) overlap -= rectangle_overlap(hole, target);
  if (r2.with_hole) overlap -= rectangle_overlap(square, target_hole);
  if (r1.with_hole && r2.with_hole) overlap += rectangle_overlap(hole, target_hole);
  assert_same_measure(r.measures.covered_domain, overlap, 1.0, what + " covered on S1");
  assert_same_measure(r.measures.covered_target, overlap, 1.0, what + " covered on S2");
}

RC_GTEST_PROP(ProjectProperties, AnySurfaceOntoItselfIsTheIdentity, ()) {
  // planar, height fields, fins (non-manifold edges), two sheets sharing a vertex
  const auto recipe = *gen::triangle_surface_recipes();
  const std::string what = gen::describe(recipe);
  auto s = std::make_shared<const Surface<2>>(gen::make_triangle_surface(recipe));
  const auto r = project<2>(s, s);
  assert_valid(r, what);
  if (!r.report.edges_not_inserted.empty()) RC_FAIL(what + "\n" + describe_failures(r.report));
  RC_ASSERT(r.map.region_count() == s->element_count());
  for (Index g = 0; g < r.map.region_count(); ++g) {
    const auto ri = remote_intersection(r.map, g);
    RC_ASSERT(ri.domain_element == ri.target_element);
    for (int k = 0; k < 3; ++k) RC_ASSERT(ri.domain_local[k] == ri.target_local[k]);
  }
  RC_ASSERT(r.measures.covered_domain == r.measures.domain);
}

RC_GTEST_PROP(ProjectProperties, RemeshedHeightFieldOverALargerFootprintCoversAllOfS1, ()) {
  // S1 and S2: two triangulations of the same random height field, S2's over [-0.25, 1.25]^2 and
  // lifted by a random offset (up or down). Vertical directions and negative distances allowed:
  // every vertical line through S1 meets S2 exactly once, so all of S1 is covered.
  const auto r1 = small_planar_recipe(true), r2 = small_planar_recipe(false);
  const auto field_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  gen::Rng rng(field_seed);
  const gen::HeightField field = gen::random_height_field(rng);
  const double offset = *rc::gen::inRange(-300, 301) / 1000.0;
  const std::string what = fmt::format("S1 {} / S2 {} height field (seed {}) amplitude {} k ({}, {}) offset {}",
                                       gen::describe(r1), gen::describe(r2), field_seed, field.amplitude, field.kx,
                                       field.ky, offset);
  auto s1 = std::make_shared<const Surface<2>>(gen::lift_to_height_field(gen::make_planar(r1), field));
  auto s2 = transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    const double x = -0.25 + 1.5 * p.x(), y = -0.25 + 1.5 * p.y();
    return WorldPoint<2>(x, y, field(x, y) + offset);
  });
  ProjectionOptions o;
  o.directions = constant_directions(*s1, WorldPoint<2>(0.0, 0.0, 1.0));
  o.allow_negative_distance = true;
  const auto r = project<2>(s1, s2, o);
  assert_valid(r, what);
  if (!r.report.edges_not_inserted.empty()) RC_FAIL(what + "\n" + describe_failures(r.report));
  assert_same_measure(r.measures.covered_domain, r.measures.domain, r.measures.domain, what);
}

RC_GTEST_PROP(ProjectProperties, RemeshedTiltedHeightFieldsWithADistanceLimitStayInsideTheBand, ()) {
  // S1 and S2: two triangulations of a random height field, S2's over [-0.25, 1.25]^2, lifted by
  // an offset and tilted, so that the gap between them runs through a random distance limit
  // (and, with negative distances, through -limit, or through 0 without). Vertical directions:
  // no focal points. D ends on the curves where the gap reaches a bound of the band (the rim),
  // and never beyond: the ray cast under the same rules (CGAL's AABB tree, verify/ray_check.hpp)
  // finds no point of D whose ray misses S2 within the band. How much of the band D misses is
  // classified, not asserted: on these coarse random meshes the rim is not always traced
  // through every element (docs/projection.md, Limitations; at seed 7, 1000 cases: none missed
  // in 83 %, more than 1 % of S1 in 13 %).
  const auto r1 = small_planar_recipe(true), r2 = small_planar_recipe(false);
  const auto field_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  gen::Rng rng(field_seed);
  const gen::HeightField field = gen::random_height_field(rng);
  const double offset = *rc::gen::inRange(-100, 201) / 1000.0;
  const double tilt = *rc::gen::inRange(-300, 301) / 1000.0;
  const double limit = *rc::gen::inRange(20, 201) / 1000.0;
  const bool negative = *rc::gen::arbitrary<bool>();
  const std::string what = fmt::format(
      "S1 {} / S2 {} height field (seed {}) amplitude {} k ({}, {}) offset {} tilt {} limit {}{}", gen::describe(r1),
      gen::describe(r2), field_seed, field.amplitude, field.kx, field.ky, offset, tilt, limit,
      negative ? " negative distances" : "");
  auto s1 = std::make_shared<const Surface<2>>(gen::lift_to_height_field(gen::make_planar(r1), field));
  auto s2 = transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    const double x = -0.25 + 1.5 * p.x(), y = -0.25 + 1.5 * p.y();
    return WorldPoint<2>(x, y, field(x, y) + offset + tilt * (x - 0.5));
  });
  ProjectionOptions o;
  o.directions = constant_directions(*s1, WorldPoint<2>(0.0, 0.0, 1.0));
  o.max_distance = limit;
  o.allow_negative_distance = negative;
  const auto r = project<2>(s1, s2, o);
  assert_valid(r, what);
  RayCheckOptions<2> rays;
  rays.directions.assign(static_cast<std::size_t>(s1->vertex_count()), WorldPoint<2>(0.0, 0.0, 1.0));
  rays.samples = 2000;
  rays.max_distance = limit;
  rays.allow_negative_distance = negative;
  const auto report = check_against_rays(r.map, rays);
  if (report.extra_defects() != 0)
    RC_FAIL(what + fmt::format(": {} of {} ray samples in D miss S2 within the band", report.extra_defects(),
                               report.samples));
  RC_CLASSIFY(report.missed_defects() == 0, "missed 0");
  RC_CLASSIFY(report.missed_defects() > 0 && report.missed_defects() <= 2, "missed 1-2");
  RC_CLASSIFY(report.missed_defects() > 2 && report.missed_defects() <= 20, "missed 3-20");
  RC_CLASSIFY(report.missed_defects() > 20, "missed >20");
  RC_CLASSIFY(report.in_domain_with_hit > 0 && report.in_domain_with_hit < report.samples, "D ends inside S1");
  RC_CLASSIFY(r.report.rim_edges > 0, "rim");
  // the thread count does not change the map
  ProjectionOptions threaded = o;
  threaded.threads = 2;
  RC_ASSERT(project<2>(s1, s2, threaded).map.data() == r.map.data());
}

namespace {
/// One case checks four properties on the same pair: a valid map; the same map for 1 and 2
/// threads; the same covered measures after a rigid motion of both surfaces (and of the
/// directions); the same covered measures with Ceres as with Newton.
void check_offset_height_fields(bool averaged_normals) {
  // S2: a remeshed copy of S1's height field, offset along z, over a footprint shifted a little;
  // averaged normals of S1 or vertical directions.
  // S2 without a hole, as in PlanarPairsCoverTheExactOverlap
  const auto r1 = small_planar_recipe(true), r2 = small_planar_recipe(false);
  const auto field_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  gen::Rng rng(field_seed);
  const gen::HeightField field = gen::random_height_field(rng);
  const double offset = *rc::gen::inRange(20, 301) / 1000.0;
  const double dx = *rc::gen::inRange(-300, 301) / 1000.0, dy = *rc::gen::inRange(-300, 301) / 1000.0;
  const bool facing = *rc::gen::arbitrary<bool>();
  const std::string what0 = fmt::format("S1 {} / S2 {} height field (seed {}) amplitude {} k ({}, {}) offset {} shift ({}, {}){}",
                                       gen::describe(r1), gen::describe(r2), field_seed, field.amplitude, field.kx, field.ky,
                                       offset, dx, dy, facing ? " facing" : "");
  auto s1 = std::make_shared<const Surface<2>>(gen::lift_to_height_field(gen::make_planar(r1), field));
  auto placed = transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    const double x = p.x() + dx, y = p.y() + dy;
    return WorldPoint<2>(x, y, field(x, y) + offset);
  });
  auto s2 = facing ? flipped(*placed) : placed;
  const std::string what = what0 + (averaged_normals ? " averaged normals" : " vertical directions");
  // negative distances allowed: the coarser interpolant of the field may dip below S1
  ProjectionOptions base{.allow_negative_distance = true,
                         .normal_check = facing ? TargetNormalCheck::facing : TargetNormalCheck::aligned};
  if (!averaged_normals) base.directions = constant_directions(*s1, WorldPoint<2>(0.0, 0.0, 1.0));
  const auto r = project<2>(s1, s2, base);
  assert_valid(r, what);
  if (averaged_normals) {
    assert_coverage_against_rays(r, averaged_vertex_normals(*s1), base, what);
  } else {
    // every vertical line through both footprints meets S2 once: D is the part of S1 over
    // S2's footprint (S1's hole lies inside S1's footprint and holds no triangle)
    const double expected = area_over_box(*s1, {dx, dx + 1.0, dy, dy + 1.0});
    assert_same_measure(r.measures.covered_domain, expected, r.measures.domain, what + " covered on S1");
  }

  // the thread count does not change the map
  ProjectionOptions threaded = base;
  threaded.threads = 2;
  RC_ASSERT(project<2>(s1, s2, threaded).map.data() == r.map.data());

  // a rigid motion of both surfaces does not change the covered measures
  const Eigen::Matrix3d rotation = random_rotation();
  const Eigen::Vector3d shift(*rc::gen::inRange(-5, 6), *rc::gen::inRange(-5, 6), *rc::gen::inRange(-5, 6));
  auto move = [&](const WorldPoint<2>& p) -> WorldPoint<2> { return rotation * p + shift; };
  ProjectionOptions moved_options = base;
  if (!averaged_normals) moved_options.directions = constant_directions(*s1, WorldPoint<2>(rotation.col(2)));
  const auto moved = project<2>(transformed<2>(*s1, move), transformed<2>(*s2, move), moved_options);
  assert_valid(moved, what + " (moved)");
  assert_same_measure(moved.measures.covered_domain, r.measures.covered_domain, r.measures.domain, what + " moved, S1");
  assert_same_measure(moved.measures.covered_target, r.measures.covered_target, r.measures.target, what + " moved, S2");

  // Newton and Ceres agree, unless a face leaves D by a decision on the rays' geometry (a fold, an
  // occluded sheet, a face whose nodes share no S2 element): there the last bits of the two
  // solvers' answers can tip a face either way (seed 112, case 7949 of 10,000: one occluded face
  // more with Newton, 0.4 % of S1), and each map is checked against the rays instead.
  ProjectionOptions ceres = base;
  ceres.solver = "ceres";
  const auto c = project<2>(s1, s2, ceres);
  assert_valid(c, what + " (ceres)");
  const auto decided_near_folds = [](const ProjectionReport<2>& p) {
    return p.folded_faces + p.folded_regions_cut + p.occluded_faces + p.unmapped_faces > 0;
  };
  const bool against_rays = averaged_normals && (decided_near_folds(r.report) || decided_near_folds(c.report));
  RC_CLASSIFY(against_rays, "Ceres checked against the rays, not against Newton");
  if (against_rays) {
    assert_coverage_against_rays(c, averaged_vertex_normals(*s1), ceres, what + " (ceres)");
    return;
  }
  assert_same_measure(c.measures.covered_domain, r.measures.covered_domain, r.measures.domain, what + " ceres, S1");
  assert_same_measure(c.measures.covered_target, r.measures.covered_target, r.measures.target, what + " ceres, S2");
}
}  // namespace

RC_GTEST_PROP(ProjectProperties, OffsetHeightFieldsWithVerticalDirections, ()) { check_offset_height_fields(false); }

// With averaged normals the direction field converges near S1's boundary and hole and in the
// valleys of the field: preimages beyond a focal point are rejected, so the map stays valid. Eq.
// (4) is quadratic there, and both solvers start from its root on the edges (closed form), so
// they find the same crossings.
RC_GTEST_PROP(ProjectProperties, OffsetHeightFieldsWithAveragedNormals, ()) { check_offset_height_fields(true); }

// ---- d = 1 ----------------------------------------------------------------------------------------

RC_GTEST_PROP(ProjectProperties, ConcentricCirclesCoverEachOther, ()) {
  // at least 12 sides: the inner polygon then lies inside the outer one for every ratio below
  const int n = *rc::gen::inRange(12, 80), m = *rc::gen::inRange(12, 80);
  const double r1 = *rc::gen::inRange(500, 2001) / 1000.0;
  const double ratio = *rc::gen::element(0.7, 0.9, 1.05, 1.3, 2.0);
  const double phase = *rc::gen::inRange(0, 6283) / 1000.0;
  const std::string what = fmt::format("circles n {} r {} / m {} ratio {} phase {}", n, r1, m, ratio, phase);
  auto s1 = circle(n, r1), s2 = circle(m, r1 * ratio, phase);
  const auto r = project<1>(s1, s2, {.allow_negative_distance = true});
  assert_valid(r, what);
  if (!r.report.edges_not_inserted.empty()) RC_FAIL(what + "\n" + describe_failures(r.report));
  assert_same_measure(r.measures.covered_domain, r.measures.domain, r.measures.domain, what + " S1");
  assert_same_measure(r.measures.covered_target, r.measures.target, r.measures.target, what + " S2");
  // Newton, Ceres and threads
  const auto c = project<1>(s1, s2, {.solver = "ceres", .allow_negative_distance = true, .threads = 2});
  assert_same_measure(c.measures.covered_domain, r.measures.covered_domain, r.measures.domain, what + " ceres");
  RC_ASSERT(project<1>(s1, s2, {.allow_negative_distance = true, .threads = 2}).map.data() == r.map.data());
}

RC_GTEST_PROP(ProjectProperties, StraightLinesCoverTheExactOverlap, ()) {
  // S1: [0, 1] on the x-axis split at random points; S2: [a, b] at height h, split at other
  // points, facing S1. Normals are vertical, so the covered length is |[0, 1] ∩ [a, b]|.
  gen::Rng rng(*rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>()));
  const bool dyadic = *rc::gen::arbitrary<bool>();
  const double a = dyadic ? *rc::gen::inRange(-8, 8) / 8.0 : *rc::gen::inRange(-900, 900) / 1000.0;
  const double b = a + (dyadic ? *rc::gen::inRange(1, 16) / 8.0 : *rc::gen::inRange(1, 2000) / 1000.0);
  const double h = *rc::gen::inRange(1, 500) / 1000.0;
  auto base = std::make_shared<const Surface<1>>(std::vector<WorldPoint<1>>{{1.0, 0.0}, {0.0, 0.0}},
                                                 std::vector<ElementCorners<1>>{{0, 1}});
  const auto splits = gen::random_subdivisions(base, *rc::gen::inRange(0, 12), rng);
  auto s1 = std::make_shared<const Surface<1>>(gen::subdivide_polyline(*base, splits.s1_splits));
  auto s2 = transformed<1>(gen::subdivide_polyline(*flipped(*base), splits.s2_splits),
                           [&](const WorldPoint<1>& p) { return WorldPoint<1>(a + (b - a) * p.x(), h); });
  const std::string what = fmt::format("lines S1 {} segments, S2 [{}, {}] {} segments at {}", s1->element_count(), a,
                                       b, s2->element_count(), h);
  const auto r = project<1>(s1, s2, {.normal_check = TargetNormalCheck::facing});
  assert_valid(r, what);
  if (!r.report.edges_not_inserted.empty()) RC_FAIL(what + "\n" + describe_failures(r.report));
  const double overlap = std::max(0.0, std::min(1.0, b) - std::max(0.0, a));
  assert_same_measure(r.measures.covered_domain, overlap, 1.0, what + " S1");
  assert_same_measure(r.measures.covered_target, overlap, 1.0, what + " S2");
}

RC_GTEST_PROP(ProjectProperties, RemeshedPolylinesMapOntoEachOtherAndKeepTheirMeasureUnderMotion, ()) {
  // Two subdivisions of the same random polyline (open or closed): the map is the identity of
  // the plane (mu = 0), D = S1, Xi(D) = S2; a rigid motion of both keeps that.
  const auto seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  gen::Rng rng(seed);
  const bool closed = *rc::gen::arbitrary<bool>();
  const int segments = *rc::gen::inRange(closed ? 3 : 1, 12);
  auto base = std::make_shared<const Surface<1>>(closed ? gen::random_closed_polyline(segments, rng)
                                                        : gen::random_open_polyline(segments, rng));
  const auto splits = gen::random_subdivisions(base, *rc::gen::inRange(0, 4), rng);
  auto s1 = std::make_shared<const Surface<1>>(gen::subdivide_polyline(*base, splits.s1_splits));
  auto s2 = std::make_shared<const Surface<1>>(gen::subdivide_polyline(*base, splits.s2_splits));
  const std::string what = fmt::format("{} polyline of {} segments (seed {}), S1 {} / S2 {} segments",
                                       closed ? "closed" : "open", segments, seed, s1->element_count(),
                                       s2->element_count());
  const auto r = project<1>(s1, s2);
  assert_valid(r, what);
  if (!r.report.edges_not_inserted.empty()) RC_FAIL(what + "\n" + describe_failures(r.report));
  assert_same_measure(r.measures.covered_domain, r.measures.domain, r.measures.domain, what + " S1");
  assert_same_measure(r.measures.covered_target, r.measures.target, r.measures.target, what + " S2");

  const double angle = *rc::gen::inRange(0, 6283) / 1000.0;
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(angle).toRotationMatrix();
  const Eigen::Vector2d shift(*rc::gen::inRange(-5, 6), *rc::gen::inRange(-5, 6));
  auto move = [&](const WorldPoint<1>& p) -> WorldPoint<1> { return rotation * p + shift; };
  const auto moved = project<1>(transformed<1>(*s1, move), transformed<1>(*s2, move));
  assert_valid(moved, what + " (moved)");
  assert_same_measure(moved.measures.covered_domain, r.measures.covered_domain, r.measures.domain, what + " moved");
}

RC_GTEST_PROP(ProjectProperties, AnyCurveOntoItselfIsTheIdentity, ()) {
  // open, closed and star polylines (a non-manifold centre)
  const auto recipe = *gen::curve_recipes();
  const std::string what = gen::describe(recipe);
  auto s = std::make_shared<const Surface<1>>(gen::make_curve(recipe));
  const auto r = project<1>(s, s);
  assert_valid(r, what);
  if (!r.report.edges_not_inserted.empty()) RC_FAIL(what + "\n" + describe_failures(r.report));
  RC_ASSERT(r.map.region_count() == s->element_count());
  RC_ASSERT(r.measures.covered_domain == r.measures.domain);
}
