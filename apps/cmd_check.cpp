// `plmap check MAP`: runs every invariant check of verify/ and exits 0 only if all pass; with
// --against-rays N it also compares a projection map with an independent ray cast
// (verify/ray_check.hpp).

#include "cli_common.hpp"
#include "directions_file.hpp"
#include "progress_bar.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/surface_fingerprint.hpp>
#include <plmap/verify/ray_check_rules.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/report_json.hpp>

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <span>
#include <utility>

namespace plmap::cli {

namespace {

struct CheckOptions {
  std::string file;
  bool json = false;
  ProgressMode progress = ProgressMode::automatic;
  bool parametrization = false;
  double max_condition = std::numeric_limits<double>::infinity();
  std::size_t max_reported = 20;
  // --against-rays: the sample and the projection's acceptance rules. The rules a map records
  // (`plmap project` records them) apply unless an option below says otherwise; without recorded
  // rules the defaults are `plmap project`'s.
  std::size_t ray_samples = 0;
  std::uint64_t ray_seed = 1;
  double ray_tolerance = 1e-4;
  double max_distance = std::numeric_limits<double>::infinity();
  bool relative_distance = false, allow_negative = false;
  std::string normal_check = "none";
  std::string directions_file;  // empty: S1's averaged vertex normals
  bool ignore_recorded_rules = false;
  // which rules the command line gave (they win over the recorded ones)
  bool max_distance_given = false, normal_check_given = false;
};

/// The rules of the ray check: those the map records (unless told to ignore them), each replaced
/// by the command line's where it gives one (verify/ray_check_rules.hpp). Returns where they came
/// from, for the report.
template <int d>
std::string choose_rules(const PlMap<d>& map, const CheckOptions& o, std::span<const double> given_directions,
                         RayCheckOptions<d>& options) {
  RayRuleChoice choice;
  choice.use_recorded = !o.ignore_recorded_rules;
  // The options' defaults are RayCheckOptions' (and `plmap project`'s): only what is given changes.
  if (o.max_distance_given) choice.max_distance = o.max_distance;
  if (o.relative_distance) choice.max_distance_is_relative = true;
  if (o.allow_negative) choice.allow_negative_distance = true;
  if (o.normal_check_given) choice.normal_check = normal_check_named(o.normal_check);
  const ChosenRayRules chosen = choose_ray_rules(map, choice, given_directions, options);
  if (chosen.directions_missing)
    throw UsageError(fmt::format(
        "{} was projected along directions given to `plmap project` (fingerprint {}); pass the same file with "
        "--directions, or check under other rules with --no-recorded-rules",
        o.file, fingerprint_hex(*chosen.recorded->directions_fingerprint)));
  if (chosen.directions_differ)
    std::cerr << "warning: the directions of " << o.directions_file << " are not those " << o.file
              << " was projected along (" << directions_description(*chosen.recorded) << ")\n";
  switch (chosen.source) {
    case RayRulesSource::recorded: return "map";
    case RayRulesSource::recorded_with_changes: return "map, with the command line's";
    case RayRulesSource::given: return "command line";
    case RayRulesSource::given_none_recorded: break;
  }
  return "command line (the map records none)";
}

/// The ray check under the rules choose_rules picks and along the directions given (default: S1's
/// averaged vertex normals, the projection's default field). Passes if the missed area that is not outside D on
/// purpose and the extra area that the interpolation at S2's boundary does not explain are each
/// at most ray_tolerance of S1's measure.
template <int d>
std::pair<Json, bool> ray_check(const PlMap<d>& map, const CheckOptions& o) {
  RayCheckOptions<d> options;
  // the values as read, as `plmap project` took them: the recorded fingerprint is theirs
  const std::vector<double> given_directions =
      o.directions_file.empty() ? std::vector<double>{}
                                : read_directions(o.directions_file, d, map.domain().vertex_count());
  options.directions = o.directions_file.empty()
                           ? averaged_vertex_normals(map.domain())
                           : directions_from_values(map.domain(), std::span<const double>(given_directions));
  options.samples = o.ray_samples;
  options.seed = o.ray_seed;
  const std::string rules_from = choose_rules(map, o, given_directions, options);
  options.max_listed = o.max_reported;
  const RayCheckReport<d> report = check_against_rays(map, options);
  const bool ok = ray_check_passes(report, o.ray_tolerance);
  Json j = to_json(report);
  j["rules"] = ray_rules_json(options, rules_from,
                              o.directions_file.empty() ? std::string("averaged-normals") : o.directions_file);
  j["tolerance"] = o.ray_tolerance;
  j["ok"] = ok;
  return {j, ok};
}

std::string ray_summary(const Json& j) {
  const auto& by = j["missed"]["by_reason"];
  const auto& e = j["image_error_relative_to_edge"];
  const auto f = [&](const char* reason) { return by[reason]["fraction"].get<double>(); };
  const auto x = [&](const char* reason) { return j["extra"]["by_reason"][reason]["fraction"].get<double>(); };
  const auto a = [&](const char* reason) {
    return j["image_error_relative_to_edge"]["above_one_by_reason"][reason]["fraction"].get<double>();
  };
  // A map checked under other rules than it was projected with (a map without recorded rules,
  // or rules changed on the command line) shows extra area on the ray, which this line points out.
  const bool rejected = x("behind_domain") + x("beyond_distance_limit") + x("against_normal_check") > 0.0;
  const std::string rules_hint =
      rejected ? "    note: the map puts parts of D where this check's rules reject the ray's hit; check with the "
                 "options the map was projected with (--allow-negative, --max-distance, --normal-check)\n"
               : "";
  const auto& rules = j["rules"];
  const std::string max_distance =
      rules["max_distance"].is_number() ? fmt::format("{}", rules["max_distance"].get<double>()) : "none";
  return fmt::format(
      "against rays ({} samples): {}\n"
      "  rules from the {}: distance limit {}{}, {}, normal check {}, directions {}\n"
      "  missed {:.3g} of S1, defects {:.3g}\n"
      "    outside D for a reason: nearer sheet {:.3g}, S1 in between {:.3g}, S2 seen twice {:.3g}, S2 crossing "
      "itself {:.3g}, just inside S2's boundary {:.3g}\n"
      "    defects: farther sheet {:.3g}, in a folding element {:.3g}, next to a fold {:.3g}, not covered {:.3g}\n"
      "  extra {:.3g} of S1 (beyond S2's boundary {:.3g}, past a focal point {:.3g}, a region across a fold {:.3g}, "
      "unexplained {:.3g}; rejected by "
      "this check's rules: "
      "behind S1 {:.3g}, beyond the distance limit {:.3g}, against the normal check {:.3g})\n"
      "{}"
      "  image error / S2 edge length: median {:.3g}, p99 {:.3g}, max {:.3g}; above 1 {:.3g} of S1 (the hit "
      "is the image of a nearer part of S1 {:.3g}; defects: of a farther part {:.3g}, of none {:.3g})\n",
      j["samples"].get<std::size_t>(), j["ok"].get<bool>() ? "ok" : "FAILED", rules["from"].get<std::string>(),
      max_distance, rules["max_distance_is_relative"].get<bool>() ? " (relative)" : "",
      rules["allow_negative_distance"].get<bool>() ? "hits behind S1 too" : "hits in front of S1 only",
      rules["normal_check"].get<std::string>(), rules["directions"].get<std::string>(),
      j["missed"]["fraction"].get<double>(),
      j["missed"]["defect_fraction"].get<double>(), f("nearer_sheet"), f("domain_in_between"),
      f("target_seen_twice"), f("target_crosses_itself"), f("inside_target_boundary"),
      f("farther_sheet"), f("in_folding_element"), f("next_to_fold"), f("not_covered"),
      j["extra"]["fraction"].get<double>(), j["extra"]["by_reason"]["beyond_target_boundary"]["fraction"].get<double>(), x("past_focal_point"),
      x("folded_region"),
      j["extra"]["by_reason"]["unexplained"]["fraction"].get<double>(), x("behind_domain"),
      x("beyond_distance_limit"), x("against_normal_check"), rules_hint, e["median"].get<double>(),
      e["p99"].get<double>(), e["max"].get<double>(), e["fraction_above_one"].get<double>(), a("nearer_sheet"),
      a("farther_sheet"), a("not_covered"));
}

int run_check(const CheckOptions& o) {
  require_readable_file(o.file);
  VerifyOptions options;
  options.expect_parametrization = o.parametrization;
  options.max_condition = o.max_condition;
  options.max_reported_per_rule = o.max_reported;
  if (o.ray_samples > 0) normal_check_named(o.normal_check);  // a bad name fails before the work
  const AnyPlMap any_map = load_map_showing_progress(o.file, o.progress);
  const VerificationReport report = std::visit([&](const auto& map) { return verify(map, options); }, any_map);
  std::optional<std::pair<Json, bool>> rays;
  if (o.ray_samples > 0) rays = std::visit([&](const auto& map) { return ray_check(map, o); }, any_map);
  const bool ok = report.ok() && (!rays || rays->second);
  if (o.json) {
    Json j = to_json(report);
    j["file"] = o.file;
    if (rays) {
      j["ok"] = ok;
      j["against_rays"] = rays->first;
    }
    print_json(j);
  } else {
    const std::string text = summary(report);
    std::cout << o.file << ": " << (report.ok() ? "valid" : "INVALID") << '\n' << text;
    if (!text.empty() && text.back() != '\n') std::cout << '\n';
    if (rays) std::cout << ray_summary(rays->first);
  }
  return ok ? exit_code::success : exit_code::check_failed;
}

}  // namespace

void register_check(CLI::App& app, Action& action) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Check every invariant of a map (structure, plane graph, minimal embedding, map, "
      "continuity, coverage, quality). Exit code 0 if the map is valid, 1 if not; every "
      "violation is named with its element, node or region.");
  cmd->add_option("MAP", o->file, "Map file (.plmap)")->required();
  cmd->add_flag("--json", o->json, "Print the full report as JSON");
  cmd->add_flag("--parametrization", o->parametrization,
                "Also require that the regions cover all of S1 and their images all of S2");
  cmd->add_option("--max-condition", o->max_condition,
                  "Report regions whose condition number kappa exceeds this as violations")
      ->check(positive_number);
  cmd->add_option("--max-reported", o->max_reported,
                  "Violations listed per rule, and examples per class of the ray check (further ones are only counted)")
      ->capture_default_str();
  CLI::Option* against_rays =
      cmd->add_option("--against-rays", o->ray_samples,
                      "Also cast N rays from points sampled uniformly on S1 along its averaged vertex normals "
                      "(the projection's default field; see --directions) against S2 and report the area missed "
                      "(the ray hits S2, the point is outside D), the extra area (in D, no hit) and the image error")
          ->check(positive_number);
  cmd->add_option("--directions", o->directions_file,
                  "Ray check: text file with one projection direction per S1 vertex (d+1 numbers a line), as "
                  "given to project")
      ->needs(against_rays);
  cmd->add_option("--ray-seed", o->ray_seed, "Seed of the ray sample")->capture_default_str();
  cmd->add_option("--ray-tolerance", o->ray_tolerance,
                  "The ray check fails if the missed area that has no stated reason to be outside D (farther "
                  "sheet, next to a fold, not covered) or "
                  "the extra area (not counting the interpolation at S2's boundary) exceeds this fraction of S1")
      ->capture_default_str()
      ->check(non_negative_number);
  CLI::Option* max_distance =
      cmd->add_option("--max-distance", o->max_distance,
                      "Ray check: largest projection distance |mu| (default: the map's recorded rule)")
          ->check(positive_number);
  cmd->add_flag("--relative-distance", o->relative_distance,
                "Ray check: --max-distance is a multiple of S1's bounding-box diagonal");
  cmd->add_flag("--allow-negative", o->allow_negative, "Ray check: also accept hits behind S1");
  CLI::Option* normal_check =
      cmd->add_option("--normal-check", o->normal_check,
                      "Ray check: none, facing or aligned (default: the map's recorded rule, else none)");
  cmd->add_flag("--no-recorded-rules", o->ignore_recorded_rules,
                "Ray check: ignore the acceptance rules that `plmap project` recorded in the map, and check under "
                "the options given here and project's defaults")
      ->needs(against_rays);
  add_progress_options(*cmd, o->progress);
  cmd->callback([o, max_distance, normal_check, &action] {
    o->max_distance_given = max_distance->count() > 0;
    o->normal_check_given = normal_check->count() > 0;
    action = [o] { return run_check(*o); };
  });
}

}  // namespace plmap::cli
