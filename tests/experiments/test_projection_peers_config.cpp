// experiments/configs/projection_peers.toml (issue 14): the shipped config is valid and runs what
// it says — every tool on one thread, the real-mesh contact pairs for plmap and ContactMerge, and
// plmap on two threads on the planes 200k, the spheres L7 and the real-mesh pairs — and a reduced
// copy of its real-mesh part runs end to end.

#include "benchmark_tools.hpp"

#include <plmap/experiment/cgal_data.hpp>
#include <plmap/experiment/config.hpp>
#include <plmap/experiment/runner.hpp>
#include <plmap/experiment/schema.hpp>
#include <plmap/experiment/sweep.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <set>
#include <string>

namespace plmap::experiment {
namespace {

const std::filesystem::path configs = std::filesystem::path(PLMAP_EXPERIMENTS_DIR) / "configs";

class ProjectionPeersConfig : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!peer_benchmark_available()) GTEST_SKIP() << "built without experiments/peers";
    if (cgal_data_location().empty()) GTEST_SKIP() << "libcgal-demo's data set is missing";
  }
};

/// The run's columns without the thread count: two runs that differ only in threads measure the
/// same projection.
std::string without_threads(nlohmann::ordered_json columns) {
  columns.erase("peer_project.threads");
  return columns.dump();
}

TEST_F(ProjectionPeersConfig, TheShippedConfigSweepsToolsRealMeshesAndPlmapsThreads) {
  const auto config = parse_experiment_file(configs / "projection_peers.toml");
  const auto runs = expand_runs(config);
  // sweep 1: planes 4 + spheres 3 + circles 4 + two femur pairs, three tools; sweep 2: two more
  // real-mesh pairs, two tools; sweep 3: five pairs, plmap on two threads; sweep 4: three
  // real-mesh pairs in spatial order, two tools
  EXPECT_EQ(runs.size(), (4u + 3u + 4u + 2u) * 3u + 2u * 2u + 5u + 3u * 2u);
  std::set<std::string> spatial;  // input and tool of the runs in spatial order
  for (const auto& r : runs)
    if (r.columns["peer_project.order"] == "spatial") {
      const std::string input = r.columns["input.name"], tool = r.columns["peer_project.tool"];
      spatial.insert(input + " " + tool);
      EXPECT_EQ(r.columns["peer_project.threads"], 1) << r.columns.dump();
    }
  EXPECT_EQ(spatial, (std::set<std::string>{"armadillo-remeshed contactmerge", "armadillo-remeshed plmap",
                                            "bones-remeshed contactmerge", "bones-remeshed plmap",
                                            "femur-remeshed contactmerge", "femur-remeshed plmap"}));
  std::map<std::string, std::set<std::string>> tools_of;  // input name -> tools
  std::set<std::string> single_thread_plmap, two_threads;
  for (const auto& r : runs) {
    const std::string input = r.columns["input.name"], tool = r.columns["peer_project.tool"];
    tools_of[input].insert(tool);
    const auto threads = r.columns["peer_project.threads"].get<int>();
    if (threads == 2) {
      EXPECT_EQ(tool, "plmap") << "the peers are single-threaded: " << r.columns.dump();
      two_threads.insert(without_threads(r.columns));
    } else {
      EXPECT_EQ(threads, 1) << r.columns.dump();
      if (tool == "plmap") single_thread_plmap.insert(without_threads(r.columns));
    }
  }
  for (const char* real_mesh : {"femur-remeshed", "bones-remeshed", "armadillo-remeshed"}) {
    EXPECT_TRUE(tools_of[real_mesh].contains("plmap")) << real_mesh;
    EXPECT_TRUE(tools_of[real_mesh].contains("contactmerge")) << real_mesh;
  }
  // every two-thread run has its single-thread partner (the speed-up is their ratio)
  EXPECT_EQ(two_threads.size(), 5u);
  for (const auto& r : two_threads) EXPECT_TRUE(single_thread_plmap.contains(r)) << r;
  std::set<std::string> two_thread_inputs;
  for (const auto& r : runs)
    if (r.columns["peer_project.threads"] == 2) {
      const std::string name = r.columns["input.name"];
      two_thread_inputs.insert(name);
      if (name == "plane") {
        EXPECT_EQ(r.columns["input.size"], 200000);
      }
      if (name == "sphere") {
        EXPECT_EQ(r.columns["input.size"], 7);
      }
    }
  EXPECT_EQ(two_thread_inputs,
            (std::set<std::string>{"plane", "sphere", "femur-remeshed", "bones-remeshed", "armadillo-remeshed"}));
  EXPECT_EQ(runs.back().columns["input.mesh"], "armadillo");
}

TEST_F(ProjectionPeersConfig, AReducedRealMeshPairRunsForBothToolsAndOnTwoThreads) {
  const bool contactmerge = benchmark_has_tool(peer_benchmark_program(), "contactmerge");
  const std::string tools = contactmerge ? "[\"plmap\", \"contactmerge\"]" : "[\"plmap\"]";
  const auto config = parse_experiment_text(
      "[experiment]\nname = \"bones\"\nrepetitions = 1\n"
      "[[inputs]]\nname = \"bones-remeshed\"\nkind = \"contact-pair\"\ncase = \"femur\"\nmesh = \"bones\"\n"
      "[[pipeline]]\nstep = \"peer_project\"\ntool = \"plmap\"\n"
      "[[sweep]]\n\"peer_project.tool\" = " + tools + "\n"
      "[[sweep]]\n\"peer_project.tool\" = [\"plmap\"]\n\"peer_project.threads\" = [2]\n",
      "bones.toml", std::filesystem::temp_directory_path());
  const auto dir = std::filesystem::path(PLMAP_TEST_BINARY_DIR) / "projection_peers_bones";
  std::filesystem::remove_all(dir);
  const auto rows = run_all(config, dir);
  ASSERT_EQ(rows.size(), contactmerge ? 3u : 2u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.config.dump());
    ASSERT_TRUE(row.metrics["peer_project.ok"].get<bool>()) << row.metrics.dump();
    // S1 is CGAL's bones mesh, not the femur (7,798 triangles); S2 its remeshed offset copy
    EXPECT_EQ(row.config["input.mesh"], "bones");
    EXPECT_EQ(row.metrics["input.elements"], 4204);
    EXPECT_GT(row.metrics["peer_project.target_elements"].get<long>(), 4204);
    EXPECT_TRUE(row.timings.contains("peer_project.seconds"));
  }
  const auto& one_thread = rows.front();
  const auto& two_threads = rows.back();
  ASSERT_EQ(two_threads.config["peer_project.threads"], 2);
  // the map does not depend on the thread count
  EXPECT_EQ(one_thread.metrics["peer_project.pieces"], two_threads.metrics["peer_project.pieces"]);
  EXPECT_EQ(one_thread.metrics["peer_project.covered_error"], two_threads.metrics["peer_project.covered_error"]);
}

}  // namespace
}  // namespace plmap::experiment
