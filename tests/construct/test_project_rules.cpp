// project() records its acceptance rules in the map (core/projection_rules.hpp), on both of its
// return paths (with and without renumbered copies), and the ray check applies them by itself
// (apply_recorded_rules): a map with area behind S1 is checked without being told so.
#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/verify/ray_check_rules.hpp>

#include <gtest/gtest.h>

using namespace plmap;
using namespace plmap::test;

namespace {

/// The unit square, and above it a plane tilted about the line x = 0.5, so that its half
/// x < 0.5 lies behind S1 (z < 0).
std::shared_ptr<const Surface<2>> tilted_plane() {
  auto flat = grid(9, 9, -0.1, 1.1, -0.1, 1.1, 0.0, true, 0.2);
  std::vector<WorldPoint<2>> v = flat->vertices();
  for (auto& p : v) p.z() = 0.3 * (p.x() - 0.5);
  return std::make_shared<const Surface<2>>(std::move(v), flat->elements());
}

}  // namespace

TEST(ProjectRules, TheMapRecordsTheRulesItWasProjectedWith) {
  auto s1 = grid(6, 6, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  auto s2 = tilted_plane();
  for (const SpatialRenumbering renumbering : {SpatialRenumbering::never, SpatialRenumbering::always}) {
    ProjectionOptions o{.max_distance = 0.5,
                        .max_distance_is_relative = true,
                        .allow_negative_distance = true,
                        .normal_check = TargetNormalCheck::facing};
    o.renumbering = renumbering;
    const auto r = project<2>(s1, s2, o);
    const std::optional<ProjectionRules> recorded = recorded_projection_rules(r.map.provenance());
    ASSERT_TRUE(recorded.has_value()) << to_string(renumbering);
    EXPECT_EQ(*recorded, projection_rules(o, 2));
    EXPECT_EQ(recorded->max_distance, 0.5);
    EXPECT_TRUE(recorded->max_distance_is_relative && recorded->allow_negative_distance);
    EXPECT_EQ(recorded->normal_check, NormalCheck::facing);
    EXPECT_FALSE(recorded->directions_fingerprint.has_value());
    EXPECT_EQ(r.map.provenance().at("made_by"), "project");

    o.directions = constant_directions(*s1, WorldPoint<2>(0.1, 0, 1));
    const auto given = project<2>(s1, s2, o);
    const std::optional<ProjectionRules> along = recorded_projection_rules(given.map.provenance());
    ASSERT_TRUE(along.has_value() && along->directions_fingerprint.has_value());
    EXPECT_EQ(*along->directions_fingerprint, directions_fingerprint(o.directions, 3));
    EXPECT_NE(*along->directions_fingerprint,
              directions_fingerprint(constant_directions(*s1, WorldPoint<2>(0.1, 0, 1.5)), 3));
  }
}

TEST(ProjectRules, TheRayCheckAppliesTheRecordedRules) {
  auto s1 = grid(8, 8, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  const auto r = project<2>(s1, tilted_plane(), {.allow_negative_distance = true});
  ASSERT_GT(r.measures.covered_domain, 0.99);
  RayCheckOptions<2> o;
  o.directions = averaged_vertex_normals(*s1);
  o.samples = 4000;
  // under the default rules the half behind S1 is area the rays do not accept
  const RayCheckReport<2> strict = check_against_rays(r.map, o);
  EXPECT_GT(strict.extra_by_reason[static_cast<std::size_t>(ExtraReason::behind_domain)], 1000u);
  const std::optional<ProjectionRules> applied = apply_recorded_rules(r.map, o);
  ASSERT_TRUE(applied.has_value());
  EXPECT_TRUE(o.allow_negative_distance);
  const RayCheckReport<2> same = check_against_rays(r.map, o);
  EXPECT_EQ(same.extra, 0u);
  EXPECT_EQ(same.missed, 0u);

  // a map without recorded rules leaves the options as they are
  PlMap<2> plain = r.map;
  plain.set_provenance({});
  RayCheckOptions<2> untouched;
  EXPECT_FALSE(apply_recorded_rules(plain, untouched).has_value());
  EXPECT_FALSE(untouched.allow_negative_distance);
}

namespace {

RayRuleChoice allow_negative(bool allow) {
  RayRuleChoice choice;
  choice.allow_negative_distance = allow;
  return choice;
}

}  // namespace

TEST(ProjectRules, TheCallersRulesReplaceTheRecordedOnes) {
  auto s1 = grid(8, 8, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  const auto r = project<2>(s1, tilted_plane(), {.allow_negative_distance = true, .normal_check = NormalCheck::facing});
  const auto choose = [&](const RayRuleChoice& choice, std::span<const double> values = {}) {
    RayCheckOptions<2> o;
    o.directions = averaged_vertex_normals(*s1);
    o.samples = 2000;
    const ChosenRayRules chosen = choose_ray_rules(r.map, choice, values, o);
    return std::pair{chosen, o};
  };
  // nothing given: the map's rules, and the check passes
  auto [as_recorded, o1] = choose({});
  EXPECT_EQ(as_recorded.source, RayRulesSource::recorded);
  EXPECT_TRUE(o1.allow_negative_distance);
  EXPECT_EQ(o1.normal_check, NormalCheck::facing);
  EXPECT_FALSE(as_recorded.directions_missing || as_recorded.directions_differ);
  EXPECT_TRUE(ray_check_passes(check_against_rays(r.map, o1), 1e-4));
  // the recorded value given again is no change
  EXPECT_EQ(choose(allow_negative(true)).first.source, RayRulesSource::recorded);
  // a changed rule replaces the recorded one, the others stay
  auto [changed, o2] = choose(allow_negative(false));
  EXPECT_EQ(changed.source, RayRulesSource::recorded_with_changes);
  EXPECT_FALSE(o2.allow_negative_distance);
  EXPECT_EQ(o2.normal_check, NormalCheck::facing);
  EXPECT_FALSE(ray_check_passes(check_against_rays(r.map, o2), 1e-4));  // the half behind S1 is extra
  // the map's rules ignored: the defaults and what is given
  RayRuleChoice ignoring;
  ignoring.use_recorded = false;
  ignoring.normal_check = NormalCheck::aligned;
  auto [ignored, o3] = choose(ignoring);
  EXPECT_EQ(ignored.source, RayRulesSource::given);
  EXPECT_FALSE(ignored.recorded.has_value());
  EXPECT_FALSE(o3.allow_negative_distance);
  EXPECT_EQ(o3.normal_check, NormalCheck::aligned);
  // direction values given for a map projected along S1's averaged normals
  const std::vector<double> tilted = constant_directions(*s1, WorldPoint<2>(0.1, 0, 1));
  EXPECT_TRUE(choose({}, tilted).first.directions_differ);

  // a map projected along a given field: its values must come along, and other ones differ
  const auto along = project<2>(s1, tilted_plane(), {.directions = tilted, .allow_negative_distance = true});
  RayCheckOptions<2> o;
  o.directions = directions_from_values(*s1, tilted);
  const ChosenRayRules missing = choose_ray_rules(along.map, {}, {}, o);
  EXPECT_TRUE(missing.directions_missing);
  const ChosenRayRules same = choose_ray_rules(along.map, {}, tilted, o);
  EXPECT_FALSE(same.directions_missing || same.directions_differ);
  const std::vector<double> other = constant_directions(*s1, WorldPoint<2>(0.2, 0, 1));
  EXPECT_TRUE(choose_ray_rules(along.map, {}, other, o).directions_differ);

  // a map that records nothing
  PlMap<2> plain = r.map;
  plain.set_provenance({});
  RayCheckOptions<2> p;
  EXPECT_EQ(choose_ray_rules(plain, allow_negative(true), {}, p).source,
            RayRulesSource::given_none_recorded);
  EXPECT_TRUE(p.allow_negative_distance);
}
