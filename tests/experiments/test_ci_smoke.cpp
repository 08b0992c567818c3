// The shipped CI experiment runs end to end and its non-timing results equal the stored ones;
// running it twice gives bit-identical non-timing results.

#include <plmap/experiment/config.hpp>
#include <plmap/experiment/plots.hpp>
#include <plmap/experiment/runner.hpp>
#include <plmap/experiment/schema.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
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

/// Equal, with a relative tolerance for floating-point numbers: the stored file may come from a
/// build with other optimisation flags, which may round the last bits differently.
void expect_same(const nlohmann::json& actual, const nlohmann::json& expected, const std::string& where) {
  if (expected.is_number_float() || actual.is_number_float()) {
    ASSERT_TRUE(actual.is_number()) << where << ": " << actual;
    const double a = actual.get<double>(), e = expected.get<double>();
    EXPECT_LE(std::abs(a - e), 1e-9 * std::max(1.0, std::abs(e))) << where << ": " << a << " vs " << e;
  } else if (expected.is_object()) {
    ASSERT_TRUE(actual.is_object()) << where;
    EXPECT_EQ(actual.size(), expected.size()) << where << ": " << actual.dump() << " vs " << expected.dump();
    for (const auto& [k, v] : expected.items()) {
      ASSERT_TRUE(actual.contains(k)) << where << ": missing " << k;
      expect_same(actual[k], v, where + "." + k);
    }
  } else {
    EXPECT_EQ(actual, expected) << where;
  }
}

TEST(CiSmoke, MatchesTheStoredExpectedResults) {
  const auto config = parse_experiment_file(experiments_dir / "configs" / "ci_smoke.toml");
  const auto out = fresh_directory("ci_smoke");
  const auto outcome = run_experiment(config, out);

  const auto rows = read_jsonl(out / "results.jsonl");
  const auto expected = read_jsonl(experiments_dir / "expected" / "ci_smoke.jsonl");
  ASSERT_EQ(rows.size(), expected.size());
  ASSERT_EQ(rows.size(), 12u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string where = "run " + std::to_string(i);
    EXPECT_EQ(rows[i]["run"], expected[i]["run"]);
    EXPECT_EQ(rows[i]["config"], expected[i]["config"]) << where;
    expect_same(rows[i]["metrics"], expected[i]["metrics"], where);
    EXPECT_TRUE(rows[i]["metrics"]["check.ok"].get<bool>()) << where;
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
  // The point locators agree on the answers (same queries, same map).
  EXPECT_EQ(rows[0]["metrics"]["evaluate.in_domain"], 2000);

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

TEST(Experiment, ProjectionOfAGridOntoALiftedCopyCoversIt) {
  if (!projection_available()) GTEST_SKIP() << "no plmap::construct in this build";
  const auto config = parse_experiment_text(
      "[experiment]\nname = \"p\"\nrepetitions = 1\n"
      "[[inputs]]\nname = \"s1\"\nkind = \"grid\"\ncells = 4\n"
      "[[inputs]]\nname = \"s2\"\nkind = \"grid\"\ncells = 4\njitter = 0.1\nseed = 3\nz_offset = 0.05\nrun = false\n"
      "[[pipeline]]\nstep = \"project\"\ntarget = \"s2\"\n[[pipeline]]\nstep = \"check\"\n",
      "p.toml", std::filesystem::temp_directory_path());
  const auto rows = run_all(config, fresh_directory("project_cache"));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows[0].metrics["project.covered_fraction"].get<double>(), 1.0, 1e-9) << rows[0].metrics.dump();
  EXPECT_EQ(rows[0].metrics["project.edges_not_inserted"], 0);
  EXPECT_TRUE(rows[0].metrics["check.ok"].get<bool>()) << rows[0].metrics.dump();
}

}  // namespace
}  // namespace plmap::experiment
