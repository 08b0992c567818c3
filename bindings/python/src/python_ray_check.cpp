// Map.check_against_rays: the independent ray check of a projection map (verify/ray_check.hpp),
// under the rules the map records unless the arguments change them, as `plmap check
// --against-rays` does (verify/ray_check_rules.hpp chooses for both).

#include "keyword_options.hpp"
#include "numpy_arrays.hpp"
#include "python_map.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/core/surface_fingerprint.hpp>
#include <plmap/verify/ray_check_rules.hpp>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace plmap::python {

namespace {

/// The arguments of check_against_rays beside the rules.
struct RayCall {
  std::size_t samples = 100000;
  std::uint64_t seed = 1;
  std::optional<py::array_t<double>> directions;
  double tolerance = 1e-4;
  std::size_t max_listed = 20;
  RayRuleChoice choice;
};

const char* source_name(RayRulesSource source) {
  switch (source) {
    case RayRulesSource::recorded: return "map";
    case RayRulesSource::recorded_with_changes: return "map, with the arguments'";
    case RayRulesSource::given: return "arguments";
    case RayRulesSource::given_none_recorded: break;
  }
  return "arguments (the map records none)";
}

template <int d>
py::object check_map(const PlMap<d>& map, const RayCall& call) {
  RayCheckOptions<d> options;
  std::vector<double> values;  // as given, for the recorded fingerprint
  if (call.directions) {
    const py::array_t<double>& a = *call.directions;
    if (a.shape(1) != d + 1 || a.shape(0) != map.domain().vertex_count())
      throw py::value_error("check_against_rays(): directions must have shape (" +
                            std::to_string(map.domain().vertex_count()) + ", " + std::to_string(d + 1) +
                            ") (one per S1 vertex), got (" + std::to_string(a.shape(0)) + ", " +
                            std::to_string(a.shape(1)) + ")");
    values.assign(a.data(), a.data() + a.size());
    options.directions = directions_from_values(map.domain(), std::span<const double>(values));
  } else {
    options.directions = averaged_vertex_normals(map.domain());
  }
  options.samples = call.samples;
  options.seed = call.seed;
  options.max_listed = call.max_listed;
  const ChosenRayRules chosen = choose_ray_rules(map, call.choice, values, options);
  if (chosen.directions_missing)
    throw py::value_error("check_against_rays(): the map was projected along directions given to project() "
                          "(fingerprint " +
                          fingerprint_hex(*chosen.recorded->directions_fingerprint) +
                          "); pass the same array as directions=, or check under other rules with "
                          "recorded_rules=False");
  if (chosen.directions_differ)
    py::module_::import("warnings").attr("warn")(
        "check_against_rays(): the directions given are not those the map was projected along (" +
        directions_description(*chosen.recorded) + ")");
  std::optional<RayCheckReport<d>> report;
  {
    py::gil_scoped_release unlocked;
    report.emplace(check_against_rays(map, options));
  }
  nlohmann::json j = to_json(*report);
  j["rules"] = ray_rules_json(options, source_name(chosen.source), call.directions ? "given" : "averaged-normals");
  j["tolerance"] = call.tolerance;
  j["ok"] = ray_check_passes(*report, call.tolerance);
  return json_to_python(j);
}

}  // namespace

void bind_ray_check(py::module_& m) {
  auto map_class = py::reinterpret_borrow<py::class_<PyMap>>(m.attr("Map"));
  map_class.def(
      "check_against_rays",
      [](const PyMap& pm, std::size_t samples, std::uint64_t seed, std::optional<py::handle> directions,
         bool recorded_rules, std::optional<double> max_distance, std::optional<bool> max_distance_is_relative,
         std::optional<bool> allow_negative_distance, std::optional<std::string> normal_check, double tolerance,
         std::size_t max_listed) {
        RayCall call;
        call.samples = samples;
        call.seed = seed;
        if (directions && !directions->is_none())
          call.directions = float_matrix(*directions, "check_against_rays(): directions", -1);
        if (max_distance && !(*max_distance >= 0.0))
          throw py::value_error("check_against_rays(): max_distance must be >= 0");
        if (!(tolerance >= 0.0)) throw py::value_error("check_against_rays(): tolerance must be >= 0");
        call.tolerance = tolerance;
        call.max_listed = max_listed;
        call.choice = {.use_recorded = recorded_rules,
                       .max_distance = max_distance,
                       .max_distance_is_relative = max_distance_is_relative,
                       .allow_negative_distance = allow_negative_distance,
                       .normal_check = normal_check ? std::optional(normal_check_argument("check_against_rays", *normal_check))
                                                    : std::nullopt};
        return visit_map(pm, [&](const auto& map) { return check_map(map, call); });
      },
      py::arg("samples") = 100000, py::kw_only(), py::arg("seed") = 1, py::arg("directions") = py::none(),
      py::arg("recorded_rules") = true, py::arg("max_distance") = py::none(),
      py::arg("max_distance_is_relative") = py::none(), py::arg("allow_negative_distance") = py::none(),
      py::arg("normal_check") = py::none(), py::arg("tolerance") = 1e-4, py::arg("max_listed") = 20,
      "Compares a projection map with an independent ray cast (CGAL's AABB tree), as `plmap check "
      "--against-rays`: samples points on S1, casts each along the direction field (S1's averaged "
      "vertex normals, or `directions`, an (n1, d+1) array) under the projection's acceptance rules, "
      "and returns a dict: 'missed' (hit but outside D), 'extra' (in D without a hit), each by "
      "reason with examples, 'image_error_relative_to_edge', 'rules' (which rules and from where) "
      "and 'ok' (the defects each at most `tolerance` of S1). The rules are those the map records "
      "(project() records them) unless an argument changes one (max_distance, "
      "max_distance_is_relative, allow_negative_distance, normal_check: 'none', 'facing', "
      "'aligned'), or recorded_rules=False ignores them all. A map projected along given directions "
      "needs the same array again (ValueError otherwise; a different array gives a warning).");
}

}  // namespace plmap::python
