// The reasons the ray check (verify/ray_check.hpp) gives for missed samples that no region
// covers: another part of S1 between the sample and its hit, S2 crossing the ray twice within
// an edge length, S2 crossing itself within an edge length of the hit, a fold of the projection
// in or next to the sample's element. Each case projects with a distance limit far below the
// gap, so that the map covers nothing, and checks without the limit: every sample with a hit is
// missed, and its class is known from the geometry.
#include "offset_height_field_pair.hpp"
#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/verify/generators/rc_generators.hpp>
#include <plmap/verify/ray_check.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace plmap;
using namespace plmap::test;
namespace gen = plmap::generators;

namespace {

/// One surface made of the elements of a and b (two components).
std::shared_ptr<const Surface<2>> joined(const Surface<2>& a, const Surface<2>& b) {
  std::vector<WorldPoint<2>> v(a.vertices().begin(), a.vertices().end());
  v.insert(v.end(), b.vertices().begin(), b.vertices().end());
  auto e = a.elements();
  const auto offset = static_cast<Index>(a.vertex_count());
  for (auto t : b.elements()) {
    for (auto& c : t) c += offset;
    e.push_back(t);
  }
  return std::make_shared<const Surface<2>>(std::move(v), std::move(e));
}

/// The ray check, without a distance limit, of the map that projecting S2 onto S1 along
/// `directions` (empty: S1's averaged vertex normals) with a negligible distance limit and no
/// rim gives (a map that covers nothing; with the rim, D would be the thin strips where S2 lies
/// within the limit of S1).
RayCheckReport<2> check_of_empty_map(const std::shared_ptr<const Surface<2>>& s1,
                                     const std::shared_ptr<const Surface<2>>& s2, std::vector<double> directions) {
  ProjectionOptions po{.max_distance = 1e-9};
  po.end_on_rim = false;
  po.directions = std::move(directions);
  const auto r = project<2>(s1, s2, po);
  EXPECT_EQ(r.map.region_count(), 0);
  RayCheckOptions<2> o;
  o.directions = po.directions.empty() ? averaged_vertex_normals(*s1) : directions_from_values(*s1, po.directions);
  o.samples = 20000;
  o.max_listed = o.samples;
  return check_against_rays(r.map, o);
}

gen::PlanarRecipe recipe(gen::PlanarBase base, int resolution, bool with_hole, bool jitter, std::uint64_t seed) {
  gen::PlanarRecipe r;
  r.base = base;
  r.resolution = resolution;
  r.with_hole = with_hole;
  r.jitter = jitter;
  r.seed = seed;
  return r;
}

double fraction_of(const RayCheckReport<2>& r, MissedReason reason) {
  return r.fraction(r.missed_by_reason[static_cast<std::size_t>(reason)]);
}

}  // namespace

TEST(RayCheckReasons, AnotherPartOfS1BetweenTheSampleAndItsHit) {
  // S1: the unit square at z = 0 and, above its strip x < 0.4, a second sheet at z = 0.3; S2 a
  // plane at z = 1 facing them. The lower square's samples under the strip have the strip in
  // between (0.4 of 1.4); the rest, with nothing in between, stay unexplained.
  auto s1 = joined(*grid(10, 10, 0, 1, 0, 1, 0.0), *grid(4, 10, 0, 0.4, 0, 1, 0.3));
  auto s2 = grid(13, 13, -0.1, 1.1, -0.1, 1.1, 1.0, true);
  const auto r = check_of_empty_map(s1, s2, constant_directions(*s1, WorldPoint<2>(0, 0, 1)));
  EXPECT_EQ(r.missed, r.samples);
  EXPECT_NEAR(fraction_of(r, MissedReason::domain_in_between), 0.4 / 1.4, 0.02);
  EXPECT_NEAR(fraction_of(r, MissedReason::not_covered), 1.0 / 1.4, 0.02);
  for (const auto& s : r.missed_examples) {
    if (s.reason == MissedReason::domain_in_between) {
      EXPECT_LT(s.point.z(), 0.15);
      EXPECT_LT(s.point.x(), 0.4 + 1e-9);
    }
  }
  EXPECT_EQ(r.missed_defects(), r.missed_by_reason[static_cast<std::size_t>(MissedReason::not_covered)]);
}

TEST(RayCheckReasons, S2SeenTwiceWithinAnEdgeLength) {
  // S2: a plane at z = 1 facing S1 and, 0.03 above it (a third of its edge length), a second
  // one facing away: the ray meets S2 twice, from both sides. With the second sheet half a unit
  // above instead (several edge lengths), nothing explains the miss.
  auto s1 = grid(10, 10, 0, 1, 0, 1, 0.0);
  auto lower = grid(13, 13, -0.1, 1.1, -0.1, 1.1, 1.0, true);
  const auto close = check_of_empty_map(s1, joined(*lower, *grid(13, 13, -0.1, 1.1, -0.1, 1.1, 1.03)),
                                        constant_directions(*s1, WorldPoint<2>(0, 0, 1)));
  EXPECT_EQ(close.missed, close.samples);
  EXPECT_EQ(fraction_of(close, MissedReason::target_seen_twice), 1.0);
  EXPECT_EQ(close.missed_defects(), 0u);
  const auto far = check_of_empty_map(s1, joined(*lower, *grid(13, 13, -0.1, 1.1, -0.1, 1.1, 1.5)),
                                      constant_directions(*s1, WorldPoint<2>(0, 0, 1)));
  EXPECT_EQ(far.missed, far.samples);
  EXPECT_EQ(fraction_of(far, MissedReason::not_covered), 1.0);
}

TEST(RayCheckReasons, S2CrossingItselfWithinAnEdgeLength) {
  // S2: two sheets over the unit square, both facing S1, tilted against each other, z = 1 +- (x
  // - 0.5) / 2: they cross along x = 0.5, z = 1, in the middle of a column of cells. The rays go
  // straight up and meet both sheets from the same side (no second crossing from the other side,
  // so not target_seen_twice). A hit lies within one mean S2 edge length (about 0.111) of the
  // crossing line where |x - 0.5| < 0.111 / sqrt(1.25): 0.199 of S1. The rest stays unexplained.
  auto s1 = grid(10, 10, 0, 1, 0, 1, 0.0);
  auto sheet = [](double slope, int cells) {
    return transformed<2>(*grid(cells, cells, -0.1, 1.1, -0.1, 1.1, 0.0, true), [slope](const WorldPoint<2>& p) {
      return WorldPoint<2>(p.x(), p.y(), 1.0 + slope * (p.x() - 0.5));
    });
  };
  const auto up = constant_directions(*s1, WorldPoint<2>(0, 0, 1));
  const auto r = check_of_empty_map(s1, joined(*sheet(0.5, 13), *sheet(-0.5, 13)), up);
  EXPECT_EQ(r.missed, r.samples);
  const double band = std::sqrt(0.1032 * 0.1032 + 0.0923 * 0.0923);  // the longest edge: a diagonal
  EXPECT_NEAR(fraction_of(r, MissedReason::target_crosses_itself), 0.199, 0.015);
  EXPECT_EQ(fraction_of(r, MissedReason::target_seen_twice), 0.0);
  EXPECT_EQ(r.missed_examples.size(), r.missed);
  for (const auto& s : r.missed_examples) {
    const double from_crossing = std::abs(s.point.x() - 0.5);
    if (s.reason == MissedReason::target_crosses_itself) {
      EXPECT_LT(from_crossing, band);
    }
    if (from_crossing > band) {
      EXPECT_EQ(s.reason, MissedReason::not_covered);
    }
  }
  EXPECT_EQ(r.missed_defects(), r.missed_by_reason[static_cast<std::size_t>(MissedReason::not_covered)]);

  // One sheet bent along x = 0.5 (a ridge of its own elements, which meet only where they share
  // vertices) does not cross itself.
  auto ridge = transformed<2>(*grid(12, 12, -0.1, 1.1, -0.1, 1.1, 0.0, true), [](const WorldPoint<2>& p) {
    return WorldPoint<2>(p.x(), p.y(), 1.0 - 0.5 * std::abs(p.x() - 0.5));
  });
  const auto bent = check_of_empty_map(s1, ridge, up);
  EXPECT_EQ(bent.missed, bent.samples);
  EXPECT_EQ(fraction_of(bent, MissedReason::not_covered), 1.0);
}

TEST(RayCheckReasons, FoldsAtAValleyCrease) {
  // S1: a valley z = k(y) |x - 0.5| of 10 x 10 cells, k from 1 to 3 along y, with its averaged
  // normals. The normals of the two columns at the crease turn over one cell h, so their rays
  // meet at a height of about h (k + 1/k): 0.2 where k = 1, 0.33 where k = 3. S2, a plane at
  // z = 0.26, lies beyond those focal points at one end of the crease and before them at the
  // other: the crease elements where it passes through the focal line fold with admissible hits
  // on their unfolded side, and the elements around them are next to a fold.
  const double h = 0.1;
  auto s1 = transformed<2>(*grid(10, 10, 0, 1, 0, 1, 0.0), [](const WorldPoint<2>& p) {
    return WorldPoint<2>(p.x(), p.y(), (1.0 + 2.0 * p.y()) * std::abs(p.x() - 0.5));
  });
  auto s2 = grid(30, 10, -1, 2, -0.5, 1.5, 0.26, true);
  const auto r = check_of_empty_map(s1, s2, {});
  EXPECT_GT(fraction_of(r, MissedReason::in_folding_element), 0.005);
  EXPECT_GT(fraction_of(r, MissedReason::next_to_fold), 0.005);
  // Both are defects: each sample's own ray is admissible, so D could hold it (the empty map
  // holds nothing; the valley's walls put S1 between some samples and their hits, a stated
  // reason).
  const auto count = [&](MissedReason reason) { return r.missed_by_reason[static_cast<std::size_t>(reason)]; };
  EXPECT_EQ(r.missed_defects(), count(MissedReason::not_covered) + count(MissedReason::in_folding_element) +
                                    count(MissedReason::next_to_fold));
  EXPECT_EQ(r.missed_examples.size(), r.missed);
  for (const auto& s : r.missed_examples) {
    const double from_crease = std::abs(s.point.x() - 0.5);
    if (s.reason == MissedReason::in_folding_element) {
      EXPECT_LT(from_crease, h + 1e-9);
    }
    if (s.reason == MissedReason::next_to_fold) {
      EXPECT_LT(from_crease, 2 * h + 1e-9);
    }
  }
}

namespace {

double extra_fraction_of(const RayCheckReport<2>& r, ExtraReason reason) {
  return r.fraction(r.extra_by_reason[static_cast<std::size_t>(reason)]);
}

}  // namespace

TEST(RayCheckReasons, ExtraAreaWhereTheChecksOwnRulesRejectTheImage) {
  // The map file does not record the projection's options. A map projected with options the
  // check is not given covers S1 where the check's rays find no admissible hit; the check names
  // the rule that rejects Xi(x), and with the projection's own options finds no extra area.
  auto s1 = grid(10, 10, 0, 1, 0, 1, 0.0);
  RayCheckOptions<2> o;
  o.directions = averaged_vertex_normals(*s1);
  o.samples = 5000;

  // S2 below S1, projected with negative distances allowed.
  const auto below = project<2>(s1, grid(13, 13, -0.1, 1.1, -0.1, 1.1, -0.2), ProjectionOptions{.allow_negative_distance = true});
  ASSERT_GT(below.map.region_count(), 0);
  auto r = check_against_rays(below.map, o);
  EXPECT_EQ(r.extra, r.samples);
  EXPECT_EQ(extra_fraction_of(r, ExtraReason::behind_domain), 1.0);
  EXPECT_EQ(r.extra_rejected_by_rules(), r.samples);
  EXPECT_EQ(r.extra_defects(), r.samples);
  o.allow_negative_distance = true;
  r = check_against_rays(below.map, o);
  EXPECT_EQ(r.extra, 0u);
  EXPECT_EQ(r.in_domain_with_hit, r.samples);
  o.allow_negative_distance = false;

  // S2 0.3 above S1, its normals pointing up (aligned with the rays), projected with no limit
  // and no normal test: a check with a limit of 0.1 or with the facing test rejects every hit.
  const auto above = project<2>(s1, grid(13, 13, -0.1, 1.1, -0.1, 1.1, 0.3), ProjectionOptions{});
  o.max_distance = 0.1;
  r = check_against_rays(above.map, o);
  EXPECT_EQ(extra_fraction_of(r, ExtraReason::beyond_distance_limit), 1.0);
  o.max_distance = std::numeric_limits<double>::infinity();
  o.normal_check = RayNormalCheck::facing;
  r = check_against_rays(above.map, o);
  EXPECT_EQ(extra_fraction_of(r, ExtraReason::against_normal_check), 1.0);
  o.normal_check = RayNormalCheck::aligned;
  r = check_against_rays(above.map, o);
  EXPECT_EQ(r.extra, 0u);
}

TEST(RayCheckReasons, ImagesMoreThanAnEdgeFromTheHitAreCounted) {
  // Projected along a tilted constant field onto a plane 1 above, Xi(x) lies 0.5 to the side of
  // the hit of a vertical ray, five S2 edge lengths: checked along the vertical, every sample in
  // D counts as above one edge; checked along the projection's own field, none does.
  auto s1 = grid(10, 10, 0, 1, 0, 1, 0.0);
  auto s2 = grid(20, 20, -1, 2, -1, 2, 1.0, true);  // edge length 0.15
  ProjectionOptions po;
  po.directions = constant_directions(*s1, WorldPoint<2>(0.5, 0, 1));
  const auto map = project<2>(s1, s2, po).map;
  RayCheckOptions<2> o;
  o.samples = 4000;
  o.directions = directions_from_values(*s1, po.directions);
  auto r = check_against_rays(map, o);
  EXPECT_EQ(r.in_domain_with_hit, r.samples);
  EXPECT_EQ(r.error_above_one_edge, 0u);
  EXPECT_LT(r.error_max, 1e-9);
  o.directions = averaged_vertex_normals(*s1);
  r = check_against_rays(map, o);
  EXPECT_EQ(r.in_domain_with_hit, r.samples);
  EXPECT_EQ(r.error_above_one_edge, r.samples);
  EXPECT_GT(r.error_median, 2.0);
  // The vertical hit over x is the image of x - 0.5 (along the tilted field, a longer way than
  // x's): a farther part of S1 where that lies in S1, no part where it does not (x < 0.5).
  const auto by = [&](MissedReason reason) { return r.fraction(r.above_one_by_reason[static_cast<std::size_t>(reason)]); };
  EXPECT_EQ(by(MissedReason::nearer_sheet), 0.0);
  EXPECT_NEAR(by(MissedReason::farther_sheet), 0.5, 0.05);
  EXPECT_NEAR(by(MissedReason::not_covered), 0.5, 0.05);
  EXPECT_EQ(r.in_domain_defects(), r.samples);
  // The defects are listed (up to max_listed), each with Xi(x)'s element, which is not the one
  // hit, and its error: the tilt puts Xi(x) 0.5 from the hit, 2.93 times the mean edge length
  // (0.15, 0.15, 0.15 sqrt 2) of an S2 element.
  ASSERT_EQ(r.in_domain_defect_examples.size(), o.max_listed);
  for (const RaySample<2>& s : r.in_domain_defect_examples) {
    EXPECT_TRUE(s.reason == MissedReason::farther_sheet || s.reason == MissedReason::not_covered);
    EXPECT_NE(s.image_element, s.hit_element);
    EXPECT_NEAR(s.image_error, 0.5 / ((0.3 + 0.15 * std::sqrt(2.0)) / 3.0), 1e-6);
    EXPECT_LT(s.element, s1->element_count());
    EXPECT_EQ(s.point.z(), 0.0);  // on S1
  }
  const nlohmann::json listed = to_json(r)["image_error_relative_to_edge"]["examples"];
  ASSERT_EQ(listed.size(), o.max_listed);
  EXPECT_EQ(listed[0]["image_element"], r.in_domain_defect_examples[0].image_element);
  EXPECT_EQ(listed[0]["error"], r.in_domain_defect_examples[0].image_error);
  // none is listed where there is no defect
  o.directions = directions_from_values(*s1, po.directions);
  EXPECT_TRUE(check_against_rays(map, o).in_domain_defect_examples.empty());
}

// The next two are the interpolation error at S2's boundary, which the property
// OffsetHeightFieldsWithAveragedNormals once reported as a defect (seeds of 2026-12-03).

TEST(RayCheckReasons, ExtraAreaAtABoundaryCornerOfS2IsTheInterpolation) {
  // S2 (two triangles' worth of boundary) ends near a corner where two boundary edges of
  // different elements meet: rays from D there leave S2 across the neighbour's boundary edge
  // while Xi(x) lies on the element next to it. That is still the interpolation at S2's boundary.
  const auto p = offset_height_fields(recipe(gen::PlanarBase::delaunay, 0, true, false, 1),
                                      recipe(gen::PlanarBase::delaunay, 0, false, false, 7), 2, 0.02, -0.3, -0.3);
  const auto& r = p.rays;
  EXPECT_GT(r.extra_by_reason[static_cast<std::size_t>(ExtraReason::beyond_target_boundary)], 0u);
  EXPECT_EQ(r.extra_defects(), 0u);
  EXPECT_LT(r.error_max, 1.0);
}

TEST(RayCheckReasons, MissedJustInsideS2sBoundaryIsTheInterpolation) {
  // Every S2 edge inserted and every S1 vertex mapped, yet a sliver of S1 next to D's boundary,
  // the piecewise-linear preimage of S2's boundary, has rays that hit S2 just inside its
  // boundary: not a farther sheet (the preimage of the hit lies right next to the sample).
  const auto p = offset_height_fields(recipe(gen::PlanarBase::delaunay, 1, true, false, 199454027113),
                                      recipe(gen::PlanarBase::grid, 4, false, true, 53329283703), 68753429640, 0.167,
                                      -0.029, -0.004);
  const auto& q = p.projected.report;
  ASSERT_TRUE(q.edges_not_inserted.empty());
  ASSERT_EQ(q.ghost_nodes + q.vertices_mapped_by_ray, q.domain_vertices);
  const auto& r = p.rays;
  EXPECT_GT(r.missed_by_reason[static_cast<std::size_t>(MissedReason::inside_target_boundary)], 0u);
  EXPECT_EQ(r.missed, r.missed_by_reason[static_cast<std::size_t>(MissedReason::inside_target_boundary)]);
  EXPECT_EQ(r.missed_defects(), 0u);
  for (const auto& sample : r.missed_examples)
    EXPECT_GT(sample.point.x(), 0.95) << "the sliver lies at S2's boundary x = 0.971 (and S1's, x = 1)";
}

TEST(RayCheckReasons, ExtraAreaPastAFocalPointInsideARegionIsTheInterpolation) {
  // Averaged normals converge over a hill next to S2's boundary: the fold curve of the field
  // cuts slivers off regions whose nodes' rays are all unfolded. Where Xi(x) still lies on the
  // ray, only the check's own focal-point rule rejects the hit: past_focal_point, not a defect.
  // (12 of the 20000 samples were unexplained while the foot of Xi(x) on the ray, not the ray's
  // own hit, decided: see ExtraAreaWhereS2CrossesTheFocalSurfaceIsTheInterpolation.)
  const auto p = offset_height_fields(recipe(gen::PlanarBase::delaunay, 12, true, false, 165955196268940560),
                                      recipe(gen::PlanarBase::delaunay, 7, false, false, 268596341725630515),
                                      67107314507471909, 0.083, -0.087, -0.249);
  const auto& r = p.rays;
  const std::size_t past = r.extra_by_reason[static_cast<std::size_t>(ExtraReason::past_focal_point)];
  EXPECT_GT(past, 0u);
  EXPECT_EQ(r.extra_defects(), 0u);
}

TEST(RayCheckReasons, ExtraAreaWhereS2CrossesTheFocalSurfaceIsTheInterpolation) {
  // S2 crosses the focal surface of one S1 element's field: along a strip next to one of its
  // edges the rays reach S2 a hair (below 1e-3 of the distance) past their focal point. Xi(x)
  // lies off the ray by the interpolation error and its foot on the ray falls just before the
  // focal point, so only the ray's own hit shows the ray passes it. (Found by the property test
  // at seed 11, case 3734 of 10,000, when the foot decided: 1 of 2000 samples unexplained.)
  const auto p = offset_height_fields(recipe(gen::PlanarBase::delaunay, 8, false, false, 1519117415066863009),
                                      recipe(gen::PlanarBase::grid, 1, false, false, 4058713263496963672),
                                      4289197785344421940, 0.252, -0.059, -0.131);
  const auto& r = p.rays;
  EXPECT_GT(r.extra_by_reason[static_cast<std::size_t>(ExtraReason::past_focal_point)], 0u);
  EXPECT_EQ(r.extra_by_reason[static_cast<std::size_t>(ExtraReason::unexplained)], 0u);
  EXPECT_EQ(r.extra_defects(), 0u);
}

TEST(RayCheckReasons, ExtraAreaAtS2sSilhouetteIsTheInterpolation) {
  // Next to an S2 vertex where S2 turns nearly parallel to the rays, the element across an edge
  // fails the normal test: the part of S2 the rays may hit ends there (its silhouette along the
  // rays). A grazing ray passes just outside it while Xi(x) lies on the element next to it: the
  // interpolation at that boundary, as at S2's own boundary. (The faces at the S1 vertices whose
  // rays fail the test are split by S2 element; the triangles split off there between nodes on
  // both sides of the silhouette mapped points whose rays meet S2 up to 5.9 edges away, until the
  // projection left such unbacked regions out: split_region_rays.hpp.)
  const auto p = offset_height_fields(recipe(gen::PlanarBase::delaunay, 13, false, false, 5830993296404447939),
                                      recipe(gen::PlanarBase::delaunay, 12, false, false, 1073081101460284097),
                                      2168897717131573493, 0.054, -0.183, -0.295);
  EXPECT_GT(p.projected.report.unbacked_regions, 0);
  const auto& r = p.rays;
  EXPECT_GT(r.extra_by_reason[static_cast<std::size_t>(ExtraReason::beyond_target_boundary)], 0u);
  EXPECT_EQ(r.extra_defects(), 0u);
  EXPECT_LT(r.error_max, 1.0);
}
