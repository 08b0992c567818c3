// `plmap check MAP`: runs every invariant check of verify/ and exits 0 only if all pass.

#include "cli_common.hpp"

#include <plmap/core/io/map_file.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/report_json.hpp>

#include <iostream>
#include <limits>

namespace plmap::cli {

namespace {

struct CheckOptions {
  std::string file;
  bool json = false;
  bool parametrization = false;
  double max_condition = std::numeric_limits<double>::infinity();
  std::size_t max_reported = 20;
};

int run_check(const CheckOptions& o) {
  require_readable_file(o.file);
  VerifyOptions options;
  options.expect_parametrization = o.parametrization;
  options.max_condition = o.max_condition;
  options.max_reported_per_rule = o.max_reported;
  const VerificationReport report =
      std::visit([&](const auto& map) { return verify(map, options); }, load_map(o.file));
  if (o.json) {
    Json j = to_json(report);
    j["file"] = o.file;
    print_json(j);
  } else {
    const std::string text = summary(report);
    std::cout << o.file << ": " << (report.ok() ? "valid" : "INVALID") << '\n' << text;
    if (!text.empty() && text.back() != '\n') std::cout << '\n';
  }
  return report.ok() ? exit_code::success : exit_code::check_failed;
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
                  "Violations listed per rule (further ones are only counted)")
      ->capture_default_str();
  cmd->callback([o, &action] { action = [o] { return run_check(*o); }; });
}

}  // namespace plmap::cli
