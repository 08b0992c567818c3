#pragma once
/// \file
/// Which acceptance rules the ray check applies: those a map records (project() writes them into
/// its provenance), each replaced by a caller's where the caller gives one. `plmap check
/// --against-rays` and the Python `Map.check_against_rays` choose through here, so both treat a
/// map the same way.

#include <plmap/verify/ray_check.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace plmap {

/// What the caller says about the rules; an empty field keeps the recorded rule (or the default
/// of RayCheckOptions for a map that records none).
struct RayRuleChoice {
  /// false: ignore what the map records, check under the given rules and the defaults.
  bool use_recorded = true;
  // initialized, so that designated initializers may leave them out (-Wmissing-field-initializers)
  std::optional<double> max_distance = std::nullopt;
  std::optional<bool> max_distance_is_relative = std::nullopt;
  std::optional<bool> allow_negative_distance = std::nullopt;
  std::optional<NormalCheck> normal_check = std::nullopt;
};

/// Where the rules of a check came from.
enum class RayRulesSource {
  recorded,               ///< all as the map records them
  recorded_with_changes,  ///< the map's, with at least one rule changed by the caller
  given,                  ///< the caller's and the defaults; the map's were ignored (use_recorded = false)
  given_none_recorded,    ///< the caller's and the defaults; the map records none
};

/// What choose_ray_rules did, for the caller's report.
struct ChosenRayRules {
  RayRulesSource source = RayRulesSource::given_none_recorded;
  /// The rules the map records (nullopt: none, or ignored).
  std::optional<ProjectionRules> recorded = std::nullopt;
  /// The map was projected along a direction field given to project() (recorded as a
  /// fingerprint only), and no direction values were given here: the check would cast along
  /// other rays than the projection did. The caller should refuse.
  bool directions_missing = false;
  /// Direction values were given, but they are not those the map was projected along (another
  /// fingerprint, or the map was projected along S1's averaged normals). Worth a warning.
  bool directions_differ = false;
};

/// Sets the acceptance rules of `options` as `choice` says, from what `map` records (through
/// apply_recorded_rules). `direction_values` are the values the caller read for
/// options.directions (d+1 per S1 vertex, as given to project()), or empty if options.directions
/// is S1's averaged vertex normals; they are only compared with the recorded fingerprint.
/// Throws InvalidMapError if the recorded rules cannot be read.
template <int d>
ChosenRayRules choose_ray_rules(const PlMap<d>& map, const RayRuleChoice& choice,
                                std::span<const double> direction_values, RayCheckOptions<d>& options);

/// The rules `options` holds as a report gives them: {"from": from, "max_distance": a number or
/// "inf", "max_distance_is_relative", "allow_negative_distance", "normal_check": its name,
/// "directions": directions} (the CLI's and Python's "rules").
template <int d>
nlohmann::json ray_rules_json(const RayCheckOptions<d>& options, std::string_view from, std::string_view directions);

/// Whether a report passes at `tolerance` (a fraction of S1's measure): the missed defects, the
/// extra defects and the in-D defects are each at most that. `plmap check`'s verdict.
template <int d>
bool ray_check_passes(const RayCheckReport<d>& report, double tolerance);

}  // namespace plmap
