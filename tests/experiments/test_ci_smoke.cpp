// The shipped CI experiment runs end to end, its metrics equal the values that follow from its
// inputs (derived in this file, not read from an earlier run), and running it twice gives
// bit-identical non-timing results.

#include <plmap/experiment/config.hpp>
#include <plmap/experiment/plots.hpp>
#include <plmap/experiment/runner.hpp>
#include <plmap/experiment/schema.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace plmap::experiment {
namespace {

const std::filesystem::path experiments_dir = PLMAP_EXPERIMENTS_DIR;

std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::path(PLMAP_TEST_BINARY_DIR) / name;
  std::filesystem::remove_all(dir);
  return dir;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The metrics that follow from the inputs and the map kind alone, derived here and not from an
/// earlier run: a grid of n x n cells has (n+1)^2 vertices and 2 n^2 triangles; the Delaunay
/// triangulation of the unit square has its 4 corners, the boundary and the interior points as
/// vertices and, by Euler's formula for a disc with b boundary vertices, 2 V - b - 2 triangles; the
/// k x k subdivision map has k^2 regions (and S2 triangles) per S1 triangle and (k+1)(k+2)/2
/// nodes per triangle; it covers all of S1, so every query is in D; a valid map has no violation
/// and a condition number of at least 1.
void expect_derived_metrics(const nlohmann::json& config, const nlohmann::json& metrics, const std::string& where) {
  long vertices = 0, boundary = 0;
  if (config["input.kind"] == "grid") {
    const long n = config["input.cells"].get<long>();
    vertices = (n + 1) * (n + 1);
    boundary = 4 * n;
  } else {
    ASSERT_EQ(config["input.kind"], "delaunay") << where;
    boundary = 4 + config["input.boundary_points"].get<long>();
    vertices = boundary + config["input.interior_points"].get<long>();
  }
  const long triangles = 2 * vertices - boundary - 2;
  const long k = config["build.k"].get<long>();
  EXPECT_EQ(metrics["input.vertices"].get<long>(), vertices) << where;
  EXPECT_EQ(metrics["input.elements"].get<long>(), triangles) << where;
  EXPECT_EQ(metrics["build.regions"].get<long>(), triangles * k * k) << where;
  EXPECT_EQ(metrics["build.target_elements"].get<long>(), triangles * k * k) << where;
  EXPECT_EQ(metrics["build.nodes"].get<long>(), triangles * (k + 1) * (k + 2) / 2) << where;
  EXPECT_EQ(metrics["build.regions_per_element"].get<double>(), double(k * k)) << where;
  EXPECT_EQ(metrics["evaluate.in_domain"], config["evaluate.queries"]) << where;
  EXPECT_TRUE(metrics["check.ok"].get<bool>()) << where;
  EXPECT_EQ(metrics["check.violations"], 0) << where;
  EXPECT_GE(metrics["check.kappa_max"].get<double>(), metrics["check.kappa_mean"].get<double>()) << where;
  EXPECT_GE(metrics["check.kappa_mean"].get<double>(), 1.0) << where;
}

TEST(CiSmoke, MetricsFollowFromTheInputsAndTheSubdivision) {
  const auto config = parse_experiment_file(experiments_dir / "configs" / "ci_smoke.toml");
  const auto out = fresh_directory("ci_smoke");
  const auto outcome = run_experiment(config, out);

  const auto rows = read_jsonl(out / "results.jsonl");
  ASSERT_EQ(rows.size(), 12u);  // 2 inputs x 2 k x 3 locators
  std::map<std::string, nlohmann::json> checksum_by_input_and_k;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string where = "run " + std::to_string(i);
    EXPECT_EQ(rows[i]["run"], i);
    expect_derived_metrics(rows[i]["config"], rows[i]["metrics"], where);
    // the point locators find the same regions, so Xi of the same queries sums to the same value
    const std::string key = rows[i]["config"]["input.name"].get<std::string>() + " k " +
                            std::to_string(rows[i]["config"]["build.k"].get<long>());
    const auto [it, first] = checksum_by_input_and_k.emplace(key, rows[i]["metrics"]["evaluate.checksum"]);
    if (!first) {
      EXPECT_EQ(rows[i]["metrics"]["evaluate.checksum"], it->second) << where << ", " << key;
    }
    EXPECT_TRUE(rows[i]["notes"].empty()) << where << ": " << rows[i]["notes"];
    // Timings: repeated, median within the spread.
    for (const auto& [name, t] : rows[i]["timings"].items()) {
      EXPECT_EQ(t["samples"].size(), 2u) << name;
      EXPECT_LE(t["min"].get<double>(), t["median"].get<double>()) << name;
      EXPECT_LE(t["median"].get<double>(), t["max"].get<double>()) << name;
    }
    // Provenance is in every row.
    EXPECT_FALSE(rows[i]["provenance"]["plmap_version"].get<std::string>().empty());
    EXPECT_FALSE(rows[i]["provenance"]["compiler"].get<std::string>().empty());
  }
  EXPECT_EQ(checksum_by_input_and_k.size(), 4u);

  // CSV: a header and one line per run.
  std::istringstream csv(read_text(out / "results.csv"));
  std::size_t lines = 0;
  std::string header;
  for (std::string line; std::getline(csv, line);) lines += (lines == 0 ? (header = line, 1) : 1);
  EXPECT_EQ(lines, 1 + rows.size());
  EXPECT_NE(header.find("config.evaluate.locator"), std::string::npos);
  EXPECT_NE(header.find("timings.evaluate.ns_per_eval.median"), std::string::npos);
  EXPECT_NE(header.find("provenance.git_commit"), std::string::npos);

  const std::string summary = read_text(out / "summary.md");
  EXPECT_NE(summary.find("# ci_smoke"), std::string::npos);
  EXPECT_NE(summary.find("evaluate.locator"), std::string::npos);
  ASSERT_EQ(outcome.plots.size(), 1u);
  if (!find_executable("gnuplot").empty()) {
    EXPECT_TRUE(outcome.plots[0].warning.empty()) << outcome.plots[0].warning;
    EXPECT_TRUE(std::filesystem::exists(out / "plots" / "locate_time.svg"));
    EXPECT_NE(summary.find("plots/locate_time.svg"), std::string::npos);
  } else {
    EXPECT_FALSE(outcome.plots[0].warning.empty());
    EXPECT_NE(summary.find("gnuplot not found"), std::string::npos);
  }
  EXPECT_EQ(read_text(out / "config.toml"), config.text);
}

TEST(CiSmoke, RerunningReproducesEveryNonTimingNumberExactly) {
  const auto config = parse_experiment_file(experiments_dir / "configs" / "ci_smoke.toml");
  RunOptions options;
  options.repetitions_override = 1;
  const auto cache = fresh_directory("ci_smoke_cache");
  const auto first = run_all(config, cache, options);
  const auto second = run_all(config, cache, options);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].config, second[i].config);
    EXPECT_EQ(first[i].metrics, second[i].metrics) << first[i].metrics.dump() << "\n" << second[i].metrics.dump();
  }
}

TEST(CiSmoke, AMissingGnuplotIsAWarningNotAFailure) {
  auto config = parse_experiment_file(experiments_dir / "configs" / "ci_smoke.toml");
  RunOptions options;
  options.repetitions_override = 1;
  options.plots.gnuplot = "/nonexistent/gnuplot";
  const auto out = fresh_directory("ci_smoke_no_gnuplot");
  const auto outcome = run_experiment(config, out, options);
  ASSERT_EQ(outcome.plots.size(), 1u);
  EXPECT_NE(outcome.plots[0].warning.find("gnuplot not found"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out / "plots" / "locate_time.gp"));  // the script, to run later
  EXPECT_NE(read_text(out / "summary.md").find("| locate_time | gnuplot not found"), std::string::npos);
}

TEST(Experiment, OnlyTheSelectedMetricsAreRecorded) {
  const auto config = parse_experiment_text(
      "[experiment]\nname = \"m\"\nrepetitions = 1\nmetrics = [\"build.regions\", \"check.seconds\"]\n"
      "[[inputs]]\nkind = \"open-polyline\"\nsegments = 5\n"
      "[[pipeline]]\nstep = \"build\"\nmap = \"subdivision\"\nk = 3\n[[pipeline]]\nstep = \"check\"\n",
      "m.toml", std::filesystem::temp_directory_path());
  const auto rows = run_all(config, fresh_directory("metrics_cache"));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].metrics.size(), 1u);
  EXPECT_EQ(rows[0].metrics["build.regions"], 15);  // 5 segments x 3
  EXPECT_EQ(rows[0].timings.size(), 1u);
  EXPECT_TRUE(rows[0].timings.contains("check.seconds"));
}

TEST(Experiment, EveryMapKindBuildsAValidMapInBothDimensions) {
  const auto config = parse_experiment_text(
      "[experiment]\nname = \"maps\"\nrepetitions = 1\n"
      "[[inputs]]\nkind = \"grid\"\ncells = 4\n[[inputs]]\nkind = \"open-polyline\"\nsegments = 6\n"
      "[[pipeline]]\nstep = \"build\"\nmap = \"identity\"\n[[pipeline]]\nstep = \"evaluate\"\nqueries = 500\n"
      "[[pipeline]]\nstep = \"check\"\n"
      "[sweep]\n\"build.map\" = [\"identity\", \"subdivision\", \"refinement\", \"overlay\"]\n",
      "maps.toml", std::filesystem::temp_directory_path());
  const auto rows = run_all(config, fresh_directory("maps_cache"));
  ASSERT_EQ(rows.size(), 8u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.config.dump());
    EXPECT_TRUE(row.metrics["check.ok"].get<bool>());
    EXPECT_EQ(row.metrics["evaluate.in_domain"], 500);  // all four kinds cover S1
    EXPECT_GE(row.metrics["build.regions"].get<int>(), row.metrics["input.elements"].get<int>());
  }
}

/// A 4 x 4 grid projected onto a jittered, lifted copy, then checked; `options` are more keys of
/// the project step.
std::vector<RunResult> project_grid_onto_lifted_copy(const std::string& options, const std::string& cache) {
  const auto config = parse_experiment_text(
      "[experiment]\nname = \"p\"\nrepetitions = 1\n"
      "[[inputs]]\nname = \"s1\"\nkind = \"grid\"\ncells = 4\n"
      "[[inputs]]\nname = \"s2\"\nkind = \"grid\"\ncells = 4\njitter = 0.1\nseed = 3\nz_offset = 0.05\nrun = false\n"
      "[[pipeline]]\nstep = \"project\"\ntarget = \"s2\"\n" + options + "[[pipeline]]\nstep = \"check\"\n",
      "p.toml", std::filesystem::temp_directory_path());
  return run_all(config, fresh_directory(cache));
}

TEST(Experiment, ProjectionOfAGridOntoALiftedCopyCoversIt) {
  if (!projection_available()) GTEST_SKIP() << "no plmap::construct in this build";
  const auto rows = project_grid_onto_lifted_copy("", "project_cache");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0].metrics["project.covered_fraction"].get<double>(), 1.0, 1e-9) << rows[0].metrics.dump();
  EXPECT_EQ(rows[0].metrics["project.edges_not_inserted"], 0);
  EXPECT_TRUE(rows[0].metrics["check.ok"].get<bool>()) << rows[0].metrics.dump();
  // generated grids come in rows: the default keeps them
  EXPECT_FALSE(rows[0].metrics["project.renumbered_target"].get<bool>());
}

TEST(Experiment, ProjectionOnRenumberedCopiesCoversTheSame) {
  if (!projection_available()) GTEST_SKIP() << "no plmap::construct in this build";
  const auto rows = project_grid_onto_lifted_copy("renumbering = \"always\"\n", "project_renumbered_cache");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_TRUE(rows[0].metrics["project.renumbered_domain"].get<bool>()) << rows[0].metrics.dump();
  EXPECT_TRUE(rows[0].metrics["project.renumbered_target"].get<bool>()) << rows[0].metrics.dump();
  EXPECT_NEAR(rows[0].metrics["project.covered_fraction"].get<double>(), 1.0, 1e-9) << rows[0].metrics.dump();
  EXPECT_TRUE(rows[0].metrics["check.ok"].get<bool>()) << rows[0].metrics.dump();
}

}  // namespace
}  // namespace plmap::experiment
