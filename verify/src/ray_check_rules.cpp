// The ray check's acceptance rules taken from the map (ray_check.hpp: apply_recorded_rules).

#include <plmap/verify/ray_check.hpp>

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

template std::optional<ProjectionRules> apply_recorded_rules<1>(const PlMap<1>&, RayCheckOptions<1>&);
template std::optional<ProjectionRules> apply_recorded_rules<2>(const PlMap<2>&, RayCheckOptions<2>&);

}  // namespace plmap
