// Sweep expansion: every combination, in a documented order, with every parameter resolved.

#include <plmap/experiment/config.hpp>
#include <plmap/experiment/sweep.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

namespace plmap::experiment {
namespace {

ExperimentConfig parse(const std::string& text) {
  return parse_experiment_text(text, "sweep.toml", std::filesystem::temp_directory_path());
}

const std::string header = "[experiment]\nname = \"s\"\nseed = 42\n";
const std::string two_inputs =
    "[[inputs]]\nname = \"a\"\nkind = \"grid\"\ncells = 4\n"
    "[[inputs]]\nname = \"b\"\nkind = \"delaunay\"\n";
const std::string pipeline =
    "[[pipeline]]\nstep = \"build\"\nmap = \"subdivision\"\n"
    "[[pipeline]]\nstep = \"evaluate\"\n";

TEST(Sweep, WithoutSweepEveryRunningInputRunsOnce) {
  const auto config = parse(header + two_inputs + "[[inputs]]\nname = \"t\"\nkind = \"grid\"\nrun = false\n" + pipeline);
  const auto runs = expand_runs(config);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(run_count(config), 2u);
  EXPECT_EQ(runs[0].columns["input.name"], "a");
  EXPECT_EQ(runs[1].columns["input.name"], "b");
}

TEST(Sweep, CartesianProductWithTheFirstAxisSlowest) {
  const auto config = parse(header + "[[inputs]]\nkind = \"grid\"\n" + pipeline +
                            "[sweep]\n\"build.k\" = [1, 2, 3]\n\"evaluate.threads\" = [1, 4]\n");
  const auto runs = expand_runs(config);
  ASSERT_EQ(runs.size(), 6u);
  const std::vector<std::pair<int, int>> expected = {{1, 1}, {1, 4}, {2, 1}, {2, 4}, {3, 1}, {3, 4}};
  for (std::size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(runs[i].index, int(i));
    EXPECT_EQ(runs[i].columns["build.k"], expected[i].first) << i;
    EXPECT_EQ(runs[i].columns["evaluate.threads"], expected[i].second) << i;
    EXPECT_EQ(runs[i].step_parameters[0].integer("k"), expected[i].first);
  }
}

TEST(Sweep, AnAxisOfOneInputOnlyMultipliesThatInput) {
  const auto config = parse(header + two_inputs + pipeline +
                            "[sweep]\n\"inputs.a.cells\" = [4, 8, 12]\n\"evaluate.threads\" = [1, 2]\n");
  const auto runs = expand_runs(config);
  ASSERT_EQ(runs.size(), 3u * 2u + 2u);
  std::set<std::int64_t> cells;
  for (const auto& r : runs) {
    if (r.columns["input.name"] == "a") cells.insert(r.columns["input.cells"].get<std::int64_t>());
    else EXPECT_FALSE(r.columns.contains("input.cells"));
  }
  EXPECT_EQ(cells, (std::set<std::int64_t>{4, 8, 12}));
}

TEST(Sweep, AnInputAxisAppliesToEveryInputThatHasTheParameter) {
  const auto config = parse(header + "[[inputs]]\nname = \"a\"\nkind = \"grid\"\n[[inputs]]\nname = \"b\"\nkind = "
                                     "\"bumpy-grid\"\n" + pipeline + "[sweep]\n\"input.cells\" = [2, 3]\n");
  const auto runs = expand_runs(config);
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_EQ(runs[3].columns["input.name"], "b");
  EXPECT_EQ(runs[3].columns["input.cells"], 3);
}

TEST(Sweep, DefaultsAndSeedsAreResolved) {
  const auto config = parse(header + "[[inputs]]\nkind = \"grid\"\n[[inputs]]\nkind = \"open-polyline\"\n" + pipeline);
  const auto runs = expand_runs(config);
  ASSERT_EQ(runs.size(), 2u);
  // Every parameter of the schema appears, defaults filled in; seeds inherit [experiment] seed.
  EXPECT_EQ(runs[0].columns["input.cells"], 8);
  EXPECT_EQ(runs[0].columns["input.seed"], 42);
  EXPECT_EQ(runs[0].columns["build.k"], 4);
  EXPECT_EQ(runs[0].columns["build.seed"], 42);
  EXPECT_EQ(runs[0].columns["evaluate.queries"], 100000);
  // The default locator depends on the dimension of the input.
  EXPECT_EQ(runs[0].columns["evaluate.locator"], "brown-faigle");
  EXPECT_EQ(runs[1].columns["evaluate.locator"], "bisection");
}

TEST(Sweep, ASweptMapKindChangesWhichParametersApply) {
  const auto config = parse(header + "[[inputs]]\nkind = \"grid\"\n[[pipeline]]\nstep = \"build\"\nmap = \"identity\"\n"
                                     "[sweep]\n\"build.map\" = [\"identity\", \"refinement\"]\n");
  const auto runs = expand_runs(config);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_FALSE(runs[0].columns.contains("build.max_points_per_edge"));
  EXPECT_EQ(runs[1].columns["build.max_points_per_edge"], 2);
}

TEST(Sweep, RealParametersAcceptIntegersAndStoreNumbers) {
  const auto config = parse(header + "[[inputs]]\nkind = \"grid\"\n" + pipeline + "[sweep]\n\"build.jitter\" = [0, 0.1]\n");
  const auto runs = expand_runs(config);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_TRUE(runs[0].columns["build.jitter"].is_number_float());
  EXPECT_EQ(runs[1].columns["build.jitter"].get<double>(), 0.1);
}

}  // namespace
}  // namespace plmap::experiment
