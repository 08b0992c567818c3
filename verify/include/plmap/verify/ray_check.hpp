#pragma once
/// \file
/// An independent check of a projection map by ray casting (`plmap check MAP --against-rays N`).
///
/// N points are sampled on S1, uniformly by measure (a fixed seed makes the sample
/// reproducible). From each point x, in S1 element T with local coordinates xi, the ray
/// x + mu nu(xi) is cast against S2, where nu(xi) is the direction field interpolated linearly
/// over T (not renormalised, as in the projection's equations). The ray cast uses CGAL's AABB
/// tree over S2's elements, not plmap's projection code. A hit is admissible under the
/// projection's acceptance rules, given here as RayCheckOptions with the same defaults as
/// ProjectionOptions:
/// - distance: mu >= 0 (or |mu| if negative distances are allowed) and |mu| <= the limit;
/// - normal check: <nu, n2> < 0 (facing) or > 0 (aligned), n2 the normal of the S2 element hit;
/// - no focal point: J(t) = det[dp/dxi_1 + t dnu/dxi_1, ..., nu] has no root with t strictly
///   between 0 and mu (the ray has not passed a focal point of the field; beyond one the
///   projection is folded). The polynomial is evaluated here, not taken from solvers/.
/// The admissible hit with the smallest mu (|mu|) is the ray's answer.
///
/// Each sample is then one of: in D with a hit (the image error |Xi(x) - hit| is measured
/// relative to the mean edge length of the S2 element hit), in D without a hit (**extra**),
/// outside D with a hit (**missed**), neither. The missed samples are classified by the
/// reason they may be outside D (MissedReason), the extra ones likewise (ExtraReason). Every count is also given as a fraction of the
/// samples, which estimates the fraction of S1's measure (standard error about
/// sqrt(f (1 - f) / N)).

#include <plmap/core/pl_map.hpp>
#include <plmap/core/projection_rules.hpp>

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace plmap {

/// The projection's normal check (core/projection_rules.hpp), under the name the ray check's
/// options have always used.
using RayNormalCheck = NormalCheck;

/// The acceptance rules of the projection that produced the map, and the sample; the defaults
/// are ProjectionOptions' defaults. A map made by project() records its rules
/// (core/projection_rules.hpp): apply_recorded_rules sets them here.
template <int d>
struct RayCheckOptions {
  /// Direction per S1 vertex (e.g. averaged_vertex_normals of S1, the projection's default).
  /// Required: one per S1 vertex.
  std::vector<WorldPoint<d>> directions;
  std::size_t samples = 100000;
  std::uint64_t seed = 1;
  double max_distance = std::numeric_limits<double>::infinity();
  /// max_distance is a multiple of the diagonal of S1's bounding box.
  bool max_distance_is_relative = false;
  bool allow_negative_distance = false;
  RayNormalCheck normal_check = RayNormalCheck::none;
  /// Examples of missed and extra samples, and of in-D defects, listed in the report (the rest
  /// are counted).
  std::size_t max_listed = 20;
};

/// Why a sample whose ray hits S2 lies outside D. The first three say what covers the hit on
/// S2; a sample that no region covers is then put in the first of the later classes that applies
/// (in the order listed); not_covered is what none of them explains. nearer_sheet,
/// domain_in_between, target_seen_twice, target_crosses_itself and inside_target_boundary are
/// outside D for a stated reason; farther_sheet, not_covered, in_folding_element and
/// next_to_fold are defects of the construction.
enum class MissedReason {
  /// The hit lies in the image of a region whose preimage is nearer to it along the ray's
  /// measure than x: a nearer sheet of S1 claims that part of S2 (the projection keeps the
  /// nearer sheet, docs/projection.md step 6). Outside D on purpose.
  nearer_sheet,
  /// The hit lies in the image of a region whose preimage is farther than x: the map took a
  /// farther sheet there. A defect.
  farther_sheet,
  /// No region maps onto the hit, and none of the reasons below applies. A defect.
  not_covered,
  /// Not covered, and another part of S1 lies on the segment between x and its hit: that
  /// nearer sheet of S1 projects onto the hit first (its own ray may still miss it, or be
  /// folded there). Outside D on purpose.
  domain_in_between,
  /// Not covered, and S2 crosses the ray a second time, seen from its other side, within one
  /// edge length of the S2 element hit: S2 folds back over itself (or two of its sheets face
  /// each other) closer than its edges, so the preimages of its edges there cross or reverse.
  target_seen_twice,
  /// Not covered, and S2 intersects itself within one edge length of the hit: an S2 element there
  /// meets another with which it shares no vertex (overlapping bodies, such as CGAL's bones,
  /// whose components interpenetrate, and offset copies of them). Across the preimage of that
  /// intersection the nearest hit jumps from one sheet of S2 to the other, so Xi cannot be
  /// continuous there, and D, bounded by S1 edges and preimages of S2 edges, ends beside it.
  target_crosses_itself,
  /// Not covered, and the projection folds in x's S1 element: the ray from one of its corners
  /// passes a focal point before the hit's distance (x's own ray does not: its hit is
  /// admissible). The walks of the S2 edges that reach the fold stop at their last crossing of
  /// an S1 edge, so the unfolded part of the element between those crossings and the fold curve
  /// stays out of D. A defect: the data model can end D inside an element (rim nodes and rim
  /// edges, as on the rim where S2 passes behind S1), the projection does not do it at folds.
  /// (Until 2026-12-07 this class was named past_focal_point and counted as outside D for a
  /// stated reason.)
  in_folding_element,
  /// Not covered, x's element does not fold, but one sharing a vertex with it does (the test of
  /// in_folding_element): the construction lost the fold-free elements around a fold. A defect.
  next_to_fold,
  /// The hit lies on an S2 element at S2's boundary, in the image of a region whose preimage
  /// lies within one edge length of x: x lies just outside D's boundary there, the
  /// piecewise-linear preimage of S2's boundary, which differs from the true (curved) one by the
  /// interpolation error (the counterpart of ExtraReason::beyond_target_boundary). Taken instead
  /// of nearer_sheet or farther_sheet, which compare two distances that are then nearly equal.
  /// Outside D for a stated reason.
  inside_target_boundary,
};
constexpr std::size_t missed_reason_count = 9;
std::string_view to_string(MissedReason reason);

/// Why a sample in D has no admissible ray hit.
enum class ExtraReason {
  /// Xi(x) lies on an S2 element at the boundary of the part of S2 the rays may hit (S2's own
  /// boundary, or its silhouette along the rays, where the elements across fail the normal
  /// test), and the ray meets that element's plane (or a neighbour's around a boundary vertex)
  /// just across that boundary: D's boundary there is the piecewise-linear preimage of a curve,
  /// which differs from the true one by the interpolation error. The distance between Xi(x) and
  /// that point counts in the image error.
  beyond_target_boundary,
  /// Anything else. A defect.
  unexplained,
  /// Xi(x) lies on the ray (within half an edge length of the S2 element it is on), but behind
  /// S1 (mu < 0) while the check does not allow negative distances: a map projected with
  /// --allow-negative shows this when it is checked under other rules than those it records
  /// (apply_recorded_rules). Counted as a defect: the check cannot tell a wrong map from wrong
  /// options.
  behind_domain,
  /// Xi(x) lies on the ray, beyond the check's distance limit (as behind_domain, for
  /// --max-distance).
  beyond_distance_limit,
  /// Xi(x) lies on the ray, on an S2 element that the check's normal test rejects (as
  /// behind_domain, for --normal-check).
  against_normal_check,
  /// Xi(x) lies on the ray and passes the rules the projection applies (distance, normal), but
  /// the ray passes a focal point of x's element before reaching it, which the check (and not
  /// the projection's acceptance rules) excludes. The projection judges folds at the nodes: a
  /// region is the linear interpolation between nodes whose own rays are unfolded, and the fold
  /// curve of the field may cut a sliver off it (the interpolation at a fold, the counterpart of
  /// MissedReason::in_folding_element, the unfolded part of the element that D leaves out). Not a defect; Xi(x) is within half an edge of the ray.
  /// Where S2 crosses the focal surface, Xi(x) (off the ray by the interpolation error) can lie
  /// just before the focal point while the ray's own hit lies just past it: then that hit, if it
  /// is within half an edge of Xi(x), decides. Only where every corner of x's region is
  /// unfolded (see folded_region).
  past_focal_point,
  /// As past_focal_point, but the ray of a corner of x's region, from the corner's point to its
  /// image along the element's field, passes a focal point too: the region is not cut by the
  /// fold curve near its edge but lies across it, so the map interpolates over a fold of the
  /// projection (a projection that kept the regions its own fold test names, folded_regions.hpp,
  /// shows this). A defect.
  folded_region,
};
constexpr std::size_t extra_reason_count = 7;
std::string_view to_string(ExtraReason reason);

/// One sample listed in the report.
template <int d>
struct RaySample {
  Index element = invalid_index;  ///< S1 element of the sample
  WorldPoint<d> point = WorldPoint<d>::Zero();
  Index hit_element = invalid_index;  ///< S2 element hit (invalid for extra samples)
  double mu = 0.0;                    ///< ray parameter of the hit
  MissedReason reason = MissedReason::not_covered;  ///< for missed samples and in-D defects
  ExtraReason extra_reason = ExtraReason::unexplained;  ///< for extra samples
  /// For in-D defects: the S2 element Xi(x) lies on, and |Xi(x) - hit| relative to the mean
  /// edge length of the element hit.
  Index image_element = invalid_index;
  double image_error = 0.0;
};

template <int d>
struct RayCheckReport {
  std::size_t samples = 0;
  double domain_measure = 0.0;
  std::size_t in_domain_with_hit = 0;
  std::size_t extra = 0;   ///< in D, but no admissible hit
  std::size_t missed = 0;  ///< admissible hit, but outside D
  std::size_t neither = 0;
  /// missed samples by MissedReason (index = enum value)
  std::array<std::size_t, missed_reason_count> missed_by_reason{};
  /// extra samples by ExtraReason (index = enum value)
  std::array<std::size_t, extra_reason_count> extra_by_reason{};
  /// Image error |Xi(x) - hit| / mean edge length of the S2 element hit, over the samples in D
  /// with a hit and the extra samples beyond S2's boundary (0 if there are none).
  double error_median = 0.0, error_p99 = 0.0, error_max = 0.0;
  /// Of the samples in D with a hit, those whose image lies more than one edge length from the
  /// hit: Xi(x) lies on another part of S2 than the ray's nearest admissible hit (another
  /// sheet), or the projection stretches so much there (next to a focal point) that the
  /// piecewise-linear interpolation is off by more than an edge. 0 on the contact pairs of
  /// experiments/. By what maps onto the hit (the first three MissedReasons):
  /// - nearer_sheet: a part of S1 nearer to the hit. The map is injective, so x cannot have that
  ///   part of S2 as well and takes a farther one: the counterpart of a missed sample's
  ///   nearer_sheet, not a defect;
  /// - farther_sheet: a part of S1 farther from the hit than x. A defect;
  /// - not_covered: nothing (the stretched interpolation, or a part of S2 left out). A defect.
  std::size_t error_above_one_edge = 0;
  std::array<std::size_t, 3> above_one_by_reason{};
  std::vector<RaySample<d>> missed_examples, extra_examples;
  /// Examples of the in-D defects (image more than an edge from the hit, reason farther_sheet
  /// or not_covered), so that a user can find where the map takes another part of S2.
  std::vector<RaySample<d>> in_domain_defect_examples;

  double fraction(std::size_t count) const { return samples ? double(count) / double(samples) : 0.0; }
  /// Missed samples that are not outside D for a stated reason: farther_sheet, not_covered,
  /// in_folding_element and next_to_fold (inside_target_boundary is the interpolation error, as
  /// beyond_target_boundary for the extra samples).
  std::size_t missed_defects() const {
    return missed_by_reason[static_cast<std::size_t>(MissedReason::farther_sheet)] +
           missed_by_reason[static_cast<std::size_t>(MissedReason::not_covered)] +
           missed_by_reason[static_cast<std::size_t>(MissedReason::in_folding_element)] +
           missed_by_reason[static_cast<std::size_t>(MissedReason::next_to_fold)];
  }
  /// Extra samples not explained by the interpolation at S2's boundary or at a fold.
  std::size_t extra_defects() const {
    return extra - extra_by_reason[static_cast<std::size_t>(ExtraReason::beyond_target_boundary)] -
           extra_by_reason[static_cast<std::size_t>(ExtraReason::past_focal_point)];
  }
  /// Samples in D whose image lies more than an edge from the hit, and not because a nearer
  /// part of S1 maps onto the hit.
  std::size_t in_domain_defects() const {
    return above_one_by_reason[static_cast<std::size_t>(MissedReason::farther_sheet)] +
           above_one_by_reason[static_cast<std::size_t>(MissedReason::not_covered)];
  }
  /// Extra samples that the map puts where the check's own acceptance rules reject the hit
  /// (behind_domain, beyond_distance_limit, against_normal_check): a sign that the map was
  /// projected with other options than the check was given.
  std::size_t extra_rejected_by_rules() const {
    return extra_by_reason[static_cast<std::size_t>(ExtraReason::behind_domain)] +
           extra_by_reason[static_cast<std::size_t>(ExtraReason::beyond_distance_limit)] +
           extra_by_reason[static_cast<std::size_t>(ExtraReason::against_normal_check)];
  }
};

/// Sets the acceptance rules of `options` (max_distance, max_distance_is_relative,
/// allow_negative_distance, normal_check) to those `map` records (project() records them in
/// PlMap::provenance) and returns them; for a map without recorded rules leaves `options` as it
/// is and returns nullopt. The directions stay the caller's: where the returned rules have a
/// directions_fingerprint, the projection ran along directions given to it, and the same ones
/// belong in options.directions (core's directions_fingerprint of the values given to project()
/// tells them apart). Throws InvalidMapError if the recorded
/// rules cannot be read.
template <int d>
std::optional<ProjectionRules> apply_recorded_rules(const PlMap<d>& map, RayCheckOptions<d>& options);

/// Runs the ray check. Throws plmap::Error if the directions do not fit S1 or max_distance is
/// negative.
template <int d>
RayCheckReport<d> check_against_rays(const PlMap<d>& map, const RayCheckOptions<d>& options);

/// {"samples", "domain_measure", "missed": {"samples", "fraction", "by_reason": {reason:
/// {"samples", "fraction"}}, "defect_fraction", "examples": [...]}, "extra": {...},
/// "in_domain_with_hit", "neither", "image_error_relative_to_edge": {"median", "p99", "max",
/// "samples_above_one", "fraction_above_one", "above_one_by_reason", "defect_fraction",
/// "examples": in-D defects with "image_element" and "error"}}
template <int d>
nlohmann::json to_json(const RayCheckReport<d>& report);

}  // namespace plmap
