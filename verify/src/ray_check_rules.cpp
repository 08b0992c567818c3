// The ray check's acceptance rules taken from the map (ray_check.hpp: apply_recorded_rules) and
// chosen between the map's and a caller's (ray_check_rules.hpp).

#include <plmap/verify/ray_check_rules.hpp>

#include <cmath>

namespace plmap {

template <int d>
std::optional<ProjectionRules> apply_recorded_rules(const PlMap<d>& map, RayCheckOptions<d>& options) {
  std::optional<ProjectionRules> rules = recorded_projection_rules(map.provenance());
  if (!rules) return std::nullopt;
  options.max_distance = rules->max_distance;
  options.max_distance_is_relative = rules->max_distance_is_relative;
  options.allow_negative_distance = rules->allow_negative_distance;
  options.normal_check = rules->normal_check;
  return rules;
}

template <int d>
ChosenRayRules choose_ray_rules(const PlMap<d>& map, const RayRuleChoice& choice,
                                std::span<const double> direction_values, RayCheckOptions<d>& options) {
  ChosenRayRules chosen;
  if (choice.use_recorded) chosen.recorded = apply_recorded_rules(map, options);
  const RayCheckOptions<d> before = options;
  if (choice.max_distance) options.max_distance = *choice.max_distance;
  if (choice.max_distance_is_relative) options.max_distance_is_relative = *choice.max_distance_is_relative;
  if (choice.allow_negative_distance) options.allow_negative_distance = *choice.allow_negative_distance;
  if (choice.normal_check) options.normal_check = *choice.normal_check;
  if (!chosen.recorded) {
    chosen.source = choice.use_recorded ? RayRulesSource::given_none_recorded : RayRulesSource::given;
    return chosen;
  }
  // Only a rule that changes counts: repeating the recorded value is no change.
  const bool changed = options.max_distance != before.max_distance ||
                       options.max_distance_is_relative != before.max_distance_is_relative ||
                       options.allow_negative_distance != before.allow_negative_distance ||
                       options.normal_check != before.normal_check;
  chosen.source = changed ? RayRulesSource::recorded_with_changes : RayRulesSource::recorded;
  // The field is not in the map, only its fingerprint: a given field must be given again.
  const std::optional<std::uint64_t>& fingerprint = chosen.recorded->directions_fingerprint;
  if (direction_values.empty()) {
    chosen.directions_missing = fingerprint.has_value();
  } else {
    chosen.directions_differ = !fingerprint || *fingerprint != directions_fingerprint(direction_values, d + 1);
  }
  return chosen;
}

template <int d>
nlohmann::json ray_rules_json(const RayCheckOptions<d>& options, std::string_view from, std::string_view directions) {
  return {{"from", from},
          {"max_distance", std::isfinite(options.max_distance) ? nlohmann::json(options.max_distance) : "inf"},
          {"max_distance_is_relative", options.max_distance_is_relative},
          {"allow_negative_distance", options.allow_negative_distance},
          {"normal_check", to_string(options.normal_check)},
          {"directions", directions}};
}

template <int d>
bool ray_check_passes(const RayCheckReport<d>& report, double tolerance) {
  return report.fraction(report.missed_defects()) <= tolerance && report.fraction(report.extra_defects()) <= tolerance &&
         report.fraction(report.in_domain_defects()) <= tolerance;
}

template std::optional<ProjectionRules> apply_recorded_rules<1>(const PlMap<1>&, RayCheckOptions<1>&);
template std::optional<ProjectionRules> apply_recorded_rules<2>(const PlMap<2>&, RayCheckOptions<2>&);
template ChosenRayRules choose_ray_rules<1>(const PlMap<1>&, const RayRuleChoice&, std::span<const double>,
                                            RayCheckOptions<1>&);
template ChosenRayRules choose_ray_rules<2>(const PlMap<2>&, const RayRuleChoice&, std::span<const double>,
                                            RayCheckOptions<2>&);
template nlohmann::json ray_rules_json<1>(const RayCheckOptions<1>&, std::string_view, std::string_view);
template nlohmann::json ray_rules_json<2>(const RayCheckOptions<2>&, std::string_view, std::string_view);
template bool ray_check_passes<1>(const RayCheckReport<1>&, double);
template bool ray_check_passes<2>(const RayCheckReport<2>&, double);

}  // namespace plmap
