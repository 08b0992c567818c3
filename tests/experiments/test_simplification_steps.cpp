// The simplify, smooth and refine steps of the experiment runner (in-process, sweeps over
// oracles), the peer_simplify step (experiments/peers' bench_simplification_peers in a child
// process), and the configs they reject.

#include "benchmark_tools.hpp"

#include <plmap/core/io/surface_writer.hpp>
#include <plmap/experiment/cgal_data.hpp>
#include <plmap/experiment/config.hpp>
#include <plmap/experiment/config_error.hpp>
#include <plmap/experiment/runner.hpp>
#include <plmap/experiment/schema.hpp>
#include <plmap/experiment/sweep.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace plmap::experiment {
namespace {

std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::path(PLMAP_TEST_BINARY_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

ExperimentConfig parse(const std::string& text, const std::filesystem::path& base = std::filesystem::temp_directory_path()) {
  return parse_experiment_text(text, "simp.toml", base);
}

const std::string kExperiment = "[experiment]\nname = \"simp\"\nrepetitions = 1\n";
const std::string kGrid = "[[inputs]]\nkind = \"grid\"\ncells = 8\nheight = 0.3\n";

struct BadCase {
  std::string name, text, key, mentions;
};

std::vector<BadCase> bad_cases() {
  std::vector<BadCase> cases;
  if (projection_available()) {
    cases.push_back({"simplify on a curve",
                     kExperiment + "[[inputs]]\nkind = \"open-polyline\"\n[[pipeline]]\nstep = \"simplify\"\ntarget_elements = 4\n",
                     "pipeline[0].step", "triangle surfaces"});
    cases.push_back({"unknown oracle",
                     kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\noracles = \"hausdorff:1,beauty:2\"\n",
                     "pipeline[0].oracles", "beauty"});
    cases.push_back({"malformed oracle weight",
                     kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\noracles = \"hausdorff:heavy\"\n",
                     "pipeline[0].oracles", "heavy"});
    cases.push_back({"no oracle", kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\noracles = \" , \"\n",
                     "pipeline[0].oracles", "at least one oracle"});
    cases.push_back({"smooth without a map", kExperiment + kGrid + "[[pipeline]]\nstep = \"smooth\"\n",
                     "pipeline[0].step", "needs a map"});
    cases.push_back({"unknown smoothing weights",
                     kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\n[[pipeline]]\nstep = \"smooth\"\nweights = \"cotan\"\n",
                     "pipeline[1].weights", "unknown smoothing weights"});
    cases.push_back({"refinement too deep",
                     kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\n[[pipeline]]\nstep = \"refine\"\nlevels = 9\n",
                     "pipeline[1].levels", "at most 8"});
    cases.push_back({"negative target",
                     kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\ntarget_elements = -5\n",
                     "pipeline[0].target_elements", "at least 0"});
    cases.push_back({"unknown hole triangulation",
                     kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\nhole_triangulation = \"ear\"\n",
                     "pipeline[0].hole_triangulation", "unknown hole triangulation"});
    cases.push_back({"unknown ranking",
                     kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\nranking = \"psychic\"\n",
                     "pipeline[0].ranking", "unknown ranking"});
    cases.push_back({"swept unknown oracle",
                     kExperiment + kGrid + "[[pipeline]]\nstep = \"simplify\"\n[sweep]\n\"simplify.oracles\" = [\"hausdorff\", \"nope\"]\n",
                     "sweep.\"simplify.oracles\"[1]", "nope"});
  }
  if (simplification_benchmark_available()) {
    cases.push_back({"peer_simplify on a grid input", kExperiment + kGrid + "[[pipeline]]\nstep = \"peer_simplify\"\ntool = \"plmap\"\n",
                     "inputs[0].kind", "file or cgal"});
  }
  if (simplification_benchmark_available() && !cgal_data_location().empty()) {
    cases.push_back({"unknown simplification tool",
                     kExperiment + "[[inputs]]\nkind = \"cgal\"\nmesh = \"femur\"\n[[pipeline]]\nstep = \"peer_simplify\"\ntool = \"meshlab\"\n",
                     "pipeline[0].tool", "unknown simplification tool"});
    cases.push_back({"peer_simplify without a tool",
                     kExperiment + "[[inputs]]\nkind = \"cgal\"\nmesh = \"femur\"\n[[pipeline]]\nstep = \"peer_simplify\"\n",
                     "pipeline[0].tool", "missing"});
    cases.push_back({"check after peer_simplify",
                     kExperiment + "[[inputs]]\nkind = \"cgal\"\nmesh = \"femur\"\n[[pipeline]]\nstep = \"peer_simplify\"\ntool = \"cgal\"\n"
                                   "[[pipeline]]\nstep = \"check\"\n",
                     "pipeline[1].step", "needs a map"});
    cases.push_back({"peer_simplify on a pre-simplified CGAL mesh",
                     kExperiment + "[[inputs]]\nkind = \"cgal\"\nmesh = \"femur\"\nsimplify_to = 1000\n[[pipeline]]\nstep = \"peer_simplify\"\ntool = \"cgal\"\n",
                     "inputs[0].simplify_to", "must be 0"});
  }
  return cases;
}

TEST(SimplificationSteps, EveryBadConfigIsRejectedNamingTheKey) {
  const auto cases = bad_cases();
  if (cases.empty()) GTEST_SKIP() << "built without plmap::construct";
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name + "\n" + c.text);
    try {
      parse(c.text);
      ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.key(), c.key) << e.what();
      const std::string message = e.what();
      EXPECT_NE(message.find(c.mentions), std::string::npos) << message;
      EXPECT_EQ(message.rfind("simp.toml", 0), 0u) << message;
    }
  }
}

TEST(SimplificationSteps, TwoOraclesOnTwoMeshesAreOneConfig) {
  if (!projection_available()) GTEST_SKIP() << "built without plmap::construct";
  const auto config = parse(kExperiment + kGrid +
                            "[[inputs]]\nname = \"bumpy\"\nkind = \"grid\"\ncells = 8\nheight = 0.5\nseed = 7\n"
                            "[[pipeline]]\nstep = \"simplify\"\ntarget_elements = 60\n"
                            "[[pipeline]]\nstep = \"smooth\"\n"
                            "[[pipeline]]\nstep = \"refine\"\nlevels = 2\n"
                            "[[pipeline]]\nstep = \"check\"\nparametrization = true\n"
                            "[sweep]\n\"simplify.oracles\" = [\"hausdorff:1\", \"hausdorff:1, aspect-ratio:0.5\"]\n");
  const auto rows = run_all(config, fresh_directory("simplification_steps_cache"));
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.config.dump());
    const auto& m = row.metrics;
    EXPECT_EQ(m["input.elements"], 128);
    EXPECT_LE(m["simplify.elements"].get<long>(), 60);
    EXPECT_TRUE(m["simplify.target_reached"].get<bool>());
    // refinement splits every coarse triangle into 4^levels
    EXPECT_EQ(m["refine.elements"].get<long>(), 16 * m["simplify.elements"].get<long>());
    EXPECT_GT(m["simplify.hausdorff"].get<double>(), 0.0);
    EXPECT_LT(m["simplify.hausdorff"].get<double>(), 0.5);
    EXPECT_GE(m["smooth.kappa_mean"].get<double>(), 1.0);
    EXPECT_EQ(m["smooth.kappa_max_before"], m["simplify.kappa_max"]);
    EXPECT_GE(m["refine.refined_aspect_max"].get<double>(), m["refine.refined_aspect_mean"].get<double>());
    EXPECT_EQ(m["refine.coarse_aspect_mean"], m["simplify.coarse_aspect_mean"]);
    EXPECT_TRUE(m["check.ok"].get<bool>()) << m.dump();
    EXPECT_TRUE(row.timings.contains("simplify.seconds"));
    EXPECT_TRUE(row.timings.contains("smooth.seconds"));
    EXPECT_TRUE(row.timings.contains("refine.seconds"));
    // simplification builds the editable form and the map: it needs memory
    ASSERT_TRUE(row.timings.contains("simplify.peak_mib"));
    EXPECT_GE(row.timings["simplify.peak_mib"]["median"].get<double>(), 0.0);
  }
  // the oracles are a column and change the result
  EXPECT_EQ(rows[0].config["simplify.oracles"], "hausdorff:1");
  EXPECT_EQ(rows[1].config["simplify.oracles"], "hausdorff:1, aspect-ratio:0.5");
  EXPECT_NE(rows[0].metrics["simplify.coarse_aspect_mean"], rows[1].metrics["simplify.coarse_aspect_mean"]);
}

// Smoothing inside each element only is one key, in the runner's own step and in the peer
// benchmark's: no quadrilateral is smoothed then, and with the default some are.
TEST(SimplificationSteps, SmoothingWithoutQuadrilateralsIsOneKey) {
  if (!projection_available()) GTEST_SKIP() << "built without plmap::construct";
  const auto config = parse(kExperiment + kGrid +
                            "[[inputs]]\nname = \"bumpy\"\nkind = \"grid\"\ncells = 8\nheight = 0.5\nseed = 7\n"
                            "[[pipeline]]\nstep = \"simplify\"\ntarget_elements = 40\n"
                            "[[pipeline]]\nstep = \"smooth\"\n"
                            "[[pipeline]]\nstep = \"check\"\nparametrization = true\n"
                            "[sweep]\n\"smooth.quadrilaterals\" = [true, false]\n");
  const auto rows = run_all(config, fresh_directory("smooth_quadrilaterals_cache"));
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.config.dump());
    const auto& m = row.metrics;
    EXPECT_TRUE(m["check.ok"].get<bool>()) << m.dump();
    if (row.config["smooth.quadrilaterals"].get<bool>())
      EXPECT_GT(m["smooth.quadrilaterals_smoothed"].get<long>(), 0);
    else
      EXPECT_EQ(m["smooth.quadrilaterals_smoothed"].get<long>(), 0);
  }
  if (!simplification_benchmark_available()) return;
  const auto dir = fresh_directory("peer_quadrilaterals_cache");
  generators::Rng rng(5);
  write_surface<2>(dir / "sphere.off", generators::icosphere({.subdivisions = 3, .radial_jitter = 0.05}, rng));
  const auto peers = parse(kExperiment + "[[inputs]]\nkind = \"file\"\npath = \"sphere.off\"\n"
                                         "[[pipeline]]\nstep = \"peer_simplify\"\ntool = \"plmap\"\ntarget_elements = 300\n"
                                         "[sweep]\n\"peer_simplify.quadrilaterals\" = [true, false]\n",
                           dir);
  const auto peer_rows = run_all(peers, dir);
  ASSERT_EQ(peer_rows.size(), 2u);
  for (const auto& row : peer_rows) {
    SCOPED_TRACE(row.config.dump());
    const auto& m = row.metrics;
    ASSERT_TRUE(m["peer_simplify.ok"].get<bool>()) << m.dump();
    if (row.config["peer_simplify.quadrilaterals"].get<bool>())
      EXPECT_GT(m["peer_simplify.quadrilaterals_smoothed"].get<long>(), 0);
    else
      EXPECT_EQ(m["peer_simplify.quadrilaterals_smoothed"].get<long>(), 0);
  }
}

TEST(SimplificationSteps, TheShippedConfigsAreValid) {
  if (!simplification_benchmark_available() || !projection_available()) GTEST_SKIP() << "built without the steps";
  if (cgal_data_location().empty()) GTEST_SKIP() << "libcgal-demo's data set is missing";
  const std::filesystem::path configs = std::filesystem::path(PLMAP_EXPERIMENTS_DIR) / "configs";
  const auto peers = parse_experiment_file(configs / "simplification_peers.toml");
  EXPECT_EQ(run_count(peers), 18u);  // three meshes, two targets, three tools
  const auto oracles = parse_experiment_file(configs / "simplification_oracles.toml");
  EXPECT_EQ(run_count(oracles), 10u);  // five meshes, two oracle combinations
}

TEST(SimplificationSteps, PeerSimplifyMeasuresEveryToolWithTheSameCode) {
  if (!simplification_benchmark_available()) GTEST_SKIP() << "built without experiments/peers";
  const auto dir = fresh_directory("peer_simplify_cache");
  generators::Rng rng(5);
  write_surface<2>(dir / "sphere.off", generators::icosphere({.subdivisions = 3, .radial_jitter = 0.05}, rng));
  std::string tools = "\"plmap\", \"cgal\"";
  const bool psurface = benchmark_has_tool(simplification_benchmark_program(), "psurface");
  if (psurface) tools += ", \"psurface\"";
  const auto config = parse(kExperiment + "[[inputs]]\nkind = \"file\"\npath = \"sphere.off\"\n"
                                          "[[pipeline]]\nstep = \"peer_simplify\"\ntool = \"plmap\"\ntarget_elements = 300\n"
                                          "[sweep]\n\"peer_simplify.tool\" = [" + tools + "]\n",
                            dir);
  const auto rows = run_all(config, dir);
  ASSERT_EQ(rows.size(), psurface ? 3u : 2u);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.config.dump());
    const auto& m = row.metrics;
    ASSERT_TRUE(m["peer_simplify.ok"].get<bool>()) << m.dump();
    EXPECT_EQ(m["input.elements"], 1280);
    const std::string tool = row.config["peer_simplify.tool"];
    // PSurface stops where every remaining vertex is blocked, the others at the target
    if (tool != "psurface") {
      EXPECT_LE(m["peer_simplify.elements"].get<long>(), 300);
      EXPECT_GE(m["peer_simplify.elements"].get<long>(), 296);
    } else {
      EXPECT_LT(m["peer_simplify.elements"].get<long>(), 1280);
    }
    EXPECT_GE(m["peer_simplify.coarse_aspect_mean"].get<double>(), 1.0);
    EXPECT_GE(m["peer_simplify.coarse_aspect_max"].get<double>(), m["peer_simplify.coarse_aspect_p90"].get<double>());
    EXPECT_GT(row.timings["peer_simplify.seconds"]["median"].get<double>(), 0.0);
    EXPECT_TRUE(row.timings.contains("peer_simplify.peak_mib"));
    EXPECT_GT(row.timings["peer_simplify.cpu_seconds"]["median"].get<double>(), 0.0);
    if (tool == "cgal") {
      // no map: no Hausdorff distance, no kappa
      EXPECT_TRUE(m["peer_simplify.hausdorff"].is_null());
      EXPECT_TRUE(m["peer_simplify.kappa_max"].is_null());
    } else {
      EXPECT_GT(m["peer_simplify.hausdorff"].get<double>(), 0.0);
      EXPECT_LT(m["peer_simplify.hausdorff"].get<double>(), 0.2);
      EXPECT_GE(m["peer_simplify.kappa_mean"].get<double>(), 1.0);
      EXPECT_GE(m["peer_simplify.kappa_max_before"].get<double>(), m["peer_simplify.kappa_mean_before"].get<double>());
      EXPECT_GE(m["peer_simplify.refined_aspect_mean"].get<double>(), 1.0);
    }
  }
}

}  // namespace
}  // namespace plmap::experiment
