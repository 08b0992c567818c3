// The peer_project step: one tool's projection of a contact pair, run by experiments/peers'
// benchmark in a child process, recorded as a row like any other step's.

#include "benchmark_tools.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/experiment/config.hpp>
#include <plmap/experiment/runner.hpp>
#include <plmap/experiment/schema.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace plmap::experiment {
namespace {

std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::path(PLMAP_TEST_BINARY_DIR) / name;
  std::filesystem::remove_all(dir);
  return dir;
}

ExperimentConfig config_with(const std::string& inputs, const std::string& step, const std::string& sweep = "") {
  return parse_experiment_text("[experiment]\nname = \"peers\"\nrepetitions = 2\nseed = 3\n" + inputs +
                                   "[[pipeline]]\nstep = \"peer_project\"\n" + step + sweep,
                               "peers.toml", std::filesystem::temp_directory_path());
}

class PeerProject : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!peer_benchmark_available()) GTEST_SKIP() << "built without experiments/peers";
  }
};

TEST_F(PeerProject, PlmapOnAPlanePairAndACirclePairCoversTheExactOverlap) {
  const auto config = config_with(
      "[[inputs]]\nname = \"plane\"\nkind = \"contact-pair\"\ncase = \"plane\"\nsize = 300\n"
      "[[inputs]]\nname = \"circle\"\nkind = \"contact-circles\"\nsegments = 40\n",
      "tool = \"plmap\"\n");
  const auto rows = run_all(config, fresh_directory("peer_project_cache"));
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.config.dump());
    ASSERT_TRUE(row.metrics["peer_project.ok"].get<bool>()) << row.metrics.dump();
    EXPECT_EQ(row.metrics["peer_project.error"], "");
    EXPECT_GT(row.metrics["peer_project.pieces"].get<long>(), 0);
    EXPECT_GT(row.metrics["peer_project.target_elements"].get<long>(), row.metrics["input.elements"].get<long>());
    // plmap's coverage is complete up to S1's boundary (planes: 0.72 of S1; circles: all of it)
    EXPECT_LT(std::abs(row.metrics["peer_project.covered_error"].get<double>()), 1e-9);
    EXPECT_LT(std::abs(row.metrics["peer_project.covered_target_error"].get<double>()), 1e-9);
    ASSERT_TRUE(row.timings.contains("peer_project.seconds"));
    EXPECT_EQ(row.timings["peer_project.seconds"]["samples"].size(), 2u);
    EXPECT_GT(row.timings["peer_project.seconds"]["median"].get<double>(), 0.0);
    EXPECT_TRUE(row.timings.contains("peer_project.peak_mib"));
    EXPECT_TRUE(row.notes.empty()) << row.notes.front();
  }
  // the plane input's S1 is generated in-process from the same parameters as in the child
  EXPECT_GE(rows[0].metrics["input.elements"].get<long>(), 250);
  EXPECT_EQ(rows[1].metrics["input.elements"], 40);
}

TEST_F(PeerProject, TheInputOrderIsPassedOnAndKeepsTheGeometry) {
  // the same sphere pair as generated and renumbered along a Morton curve: the benchmark names the
  // order it ran, and plmap covers the same area either way
  const auto config = config_with("[[inputs]]\nkind = \"contact-pair\"\ncase = \"sphere\"\nsize = 2\n",
                                  "tool = \"plmap\"\n",
                                  "[sweep]\n\"peer_project.order\" = [\"as-generated\", \"spatial\"]\n");
  RunOptions options;
  options.repetitions_override = 1;
  const auto rows = run_all(config, fresh_directory("peer_project_order_cache"), options);
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) ASSERT_TRUE(row.metrics["peer_project.ok"].get<bool>()) << row.metrics.dump();
  EXPECT_NEAR(rows[0].metrics["peer_project.covered_error"].get<double>(),
              rows[1].metrics["peer_project.covered_error"].get<double>(), 1e-9);
  EXPECT_EQ(rows[0].metrics["peer_project.pieces"], rows[1].metrics["peer_project.pieces"]);
  const std::string as_generated = rows[0].metrics["peer_project.label"], spatial = rows[1].metrics["peer_project.label"];
  EXPECT_EQ(as_generated.find("spatial order"), std::string::npos) << as_generated;
  EXPECT_NE(spatial.find("(spatial order)"), std::string::npos) << spatial;
}

TEST_F(PeerProject, PSurfaceAboveItsSizeLimitIsSkippedAndSaysSo) {
  const auto config = config_with("[[inputs]]\nkind = \"contact-pair\"\ncase = \"sphere\"\nsize = 1\n",
                                  "tool = \"psurface\"\npsurface_max_elements = 10\n");
  const auto rows = run_all(config, fresh_directory("peer_project_skip_cache"));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_FALSE(rows[0].metrics["peer_project.ok"].get<bool>());
  EXPECT_EQ(rows[0].metrics["peer_project.error"].get<std::string>().rfind("skipped: S1 has 80 elements", 0), 0u)
      << rows[0].metrics.dump();
  EXPECT_FALSE(rows[0].timings.contains("peer_project.seconds"));
}

TEST_F(PeerProject, AChildThatRunsTooLongIsKilledAndTheRunSaysSo) {
  // 200k triangles take several seconds to project; the limit is one.
  const auto config = config_with("[[inputs]]\nkind = \"contact-pair\"\ncase = \"plane\"\nsize = 200000\n",
                                  "tool = \"plmap\"\ntimeout_seconds = 1\n");
  RunOptions options;
  options.repetitions_override = 1;
  const auto rows = run_all(config, fresh_directory("peer_project_timeout_cache"), options);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_FALSE(rows[0].metrics["peer_project.ok"].get<bool>());
  EXPECT_EQ(rows[0].metrics["peer_project.error"], "timed out after 1 s");
}

TEST_F(PeerProject, AMissingBenchmarkIsAnErrorThatSaysWhatToBuild) {
  const auto config = config_with("[[inputs]]\nkind = \"contact-circles\"\nsegments = 10\n", "tool = \"plmap\"\n");
  ASSERT_EQ(setenv("PLMAP_PEER_BENCH", "/nonexistent/bench_projection_peers", 1), 0);
  try {
    (void)run_all(config, fresh_directory("peer_project_missing_cache"));
    ADD_FAILURE() << "ran without the benchmark";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/bench_projection_peers does not exist"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("PLMAP_PEER_BENCH"), std::string::npos) << e.what();
  }
  unsetenv("PLMAP_PEER_BENCH");
}

TEST_F(PeerProject, ContactMergeAgreesWithPlmapOnThePiecesOfAPlanePair) {
  if (!benchmark_has_tool(peer_benchmark_program(), "contactmerge")) GTEST_SKIP() << "built without dune-grid-glue";
  const auto config = config_with("[[inputs]]\nkind = \"contact-pair\"\ncase = \"plane\"\nsize = 300\n",
                                  "tool = \"plmap\"\n", "[sweep]\n\"peer_project.tool\" = [\"plmap\", \"contactmerge\"]\n");
  RunOptions options;
  options.repetitions_override = 1;
  const auto rows = run_all(config, fresh_directory("peer_project_cm_cache"), options);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].config["peer_project.tool"], "contactmerge");
  ASSERT_TRUE(rows[1].metrics["peer_project.ok"].get<bool>()) << rows[1].metrics.dump();
  // on planar facing patches both find every overlap: the same number of pieces, exact measure
  EXPECT_EQ(rows[0].metrics["peer_project.pieces"], rows[1].metrics["peer_project.pieces"]);
  EXPECT_LT(std::abs(rows[1].metrics["peer_project.covered_error"].get<double>()), 1e-9);
}

}  // namespace
}  // namespace plmap::experiment
