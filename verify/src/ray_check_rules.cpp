// The ray check's acceptance rules taken from the map (ray_check.hpp: apply_recorded_rules).

#include <plmap/verify/ray_check.hpp>

namespace plmap {

std::string_view to_string(RayNormalCheck check) {
  switch (check) {
    case RayNormalCheck::none: return "none";
    case RayNormalCheck::facing: return "facing";
    case RayNormalCheck::aligned: return "aligned";
  }
  return "none";
}

std::optional<RayNormalCheck> ray_normal_check_from_name(std::string_view name) {
  for (const RayNormalCheck check : {RayNormalCheck::none, RayNormalCheck::facing, RayNormalCheck::aligned})
    if (to_string(check) == name) return check;
  return std::nullopt;
}

template <int d>
std::optional<ProjectionRules> apply_recorded_rules(const PlMap<d>& map, RayCheckOptions<d>& options) {
  std::optional<ProjectionRules> rules = recorded_projection_rules(map.provenance());
  if (!rules) return std::nullopt;
  options.max_distance = rules->max_distance;
  options.max_distance_is_relative = rules->max_distance_is_relative;
  options.allow_negative_distance = rules->allow_negative_distance;
  options.normal_check = *ray_normal_check_from_name(rules->normal_check);  // validated when read
  return rules;
}

template std::optional<ProjectionRules> apply_recorded_rules<1>(const PlMap<1>&, RayCheckOptions<1>&);
template std::optional<ProjectionRules> apply_recorded_rules<2>(const PlMap<2>&, RayCheckOptions<2>&);

}  // namespace plmap
