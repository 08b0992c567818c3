// Several sweeps in one config ([[sweep]] tables): each is its own cartesian product over the
// inputs it names, their runs follow each other, and a run two of them make is an error. This is
// what lets projection_peers.toml run plmap on two threads without running the single-threaded
// peers twice.

#include <plmap/experiment/config.hpp>
#include <plmap/experiment/config_error.hpp>
#include <plmap/experiment/sweep.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace plmap::experiment {
namespace {

ExperimentConfig parse(const std::string& text) {
  return parse_experiment_text(text, "groups.toml", std::filesystem::temp_directory_path());
}

const std::string header = "[experiment]\nname = \"g\"\nseed = 7\n";
const std::string inputs =
    "[[inputs]]\nname = \"a\"\nkind = \"grid\"\ncells = 4\n"
    "[[inputs]]\nname = \"b\"\nkind = \"grid\"\ncells = 8\n"
    "[[inputs]]\nname = \"c\"\nkind = \"delaunay\"\n";
const std::string pipeline =
    "[[pipeline]]\nstep = \"build\"\nmap = \"subdivision\"\n"
    "[[pipeline]]\nstep = \"evaluate\"\n";

/// (input name, evaluate.threads) of every run, in order.
std::vector<std::pair<std::string, int>> names_and_threads(const std::vector<RunSpec>& runs) {
  std::vector<std::pair<std::string, int>> out;
  for (const auto& r : runs) out.emplace_back(r.columns["input.name"], r.columns["evaluate.threads"].get<int>());
  return out;
}

TEST(SweepGroups, EachGroupRunsItsInputsAndTheGroupsFollowEachOther) {
  const auto config = parse(header + inputs + pipeline +
                            "[[sweep]]\n\"evaluate.threads\" = [1]\n"
                            "[[sweep]]\ninputs = [\"c\", \"a\"]\n\"evaluate.threads\" = [2, 4]\n");
  ASSERT_EQ(config.sweeps.size(), 2u);
  EXPECT_EQ(config.sweeps[1].key, "sweep[1]");
  const auto runs = expand_runs(config);
  EXPECT_EQ(run_count(config), runs.size());
  // the listed inputs run in the config's order, whatever the order of the list
  const std::vector<std::pair<std::string, int>> expected = {{"a", 1}, {"b", 1}, {"c", 1}, {"a", 2},
                                                             {"a", 4}, {"c", 2}, {"c", 4}};
  EXPECT_EQ(names_and_threads(runs), expected);
  for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].index, int(i));
}

TEST(SweepGroups, AnInputAxisOfAGroupOnlyTouchesTheGroupsInputs) {
  const auto config = parse(header + inputs + pipeline +
                            "[[sweep]]\ninputs = [\"a\"]\n\"input.cells\" = [12, 16]\n"
                            "[[sweep]]\ninputs = [\"b\", \"c\"]\n\"inputs.b.cells\" = [20]\n");
  const auto runs = expand_runs(config);
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_EQ(runs[0].columns["input.cells"], 12);
  EXPECT_EQ(runs[1].columns["input.cells"], 16);
  EXPECT_EQ(runs[2].columns["input.name"], "b");
  EXPECT_EQ(runs[2].columns["input.cells"], 20);
  EXPECT_EQ(runs[3].columns["input.name"], "c");  // a delaunay input: no cells, and not refused
}

TEST(SweepGroups, OneSweepTableIsOneGroupOfEveryInput) {
  const auto config = parse(header + inputs + pipeline + "[sweep]\n\"evaluate.threads\" = [1, 2]\n");
  ASSERT_EQ(config.sweeps.size(), 1u);
  EXPECT_EQ(config.sweeps[0].key, "sweep");
  EXPECT_TRUE(config.sweeps[0].inputs.empty());
  EXPECT_EQ(expand_runs(config).size(), 6u);
}

/// The ConfigError of a config with `sweep` as its sweep part; fails the test if it parses.
ConfigError error_of(const std::string& sweep) {
  try {
    (void)parse(header + inputs + "[[inputs]]\nname = \"t\"\nkind = \"grid\"\nrun = false\n" + pipeline + sweep);
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "parsed: " << sweep;
  return ConfigError("", "", "");
}

TEST(SweepGroups, MistakesAreRefusedNamingTheGroup) {
  struct Case {
    std::string sweep, key, mentions;
  };
  const std::vector<Case> cases = {
      {"[[sweep]]\n\"evaluate.threads\" = [1]\n[[sweep]]\ninputs = [\"a\"]\n\"evaluate.threads\" = [1, 2]\n",
       "sweep[1]", "repeats run 1 (sweep[0], input \"a\")"},
      {"[[sweep]]\ninputs = [\"a\", \"z\"]\n\"evaluate.threads\" = [1]\n", "sweep[0].inputs[1]", "unknown input \"z\""},
      {"[[sweep]]\ninputs = [\"a\", \"a\"]\n\"evaluate.threads\" = [1]\n", "sweep[0].inputs[1]", "listed twice"},
      {"[[sweep]]\ninputs = [\"t\"]\n\"evaluate.threads\" = [1]\n", "sweep[0].inputs[0]", "run = false"},
      {"[[sweep]]\ninputs = []\n", "sweep[0].inputs", "non-empty array"},
      {"[[sweep]]\ninputs = [\"a\"]\n\"inputs.b.cells\" = [4]\n", "sweep[0].\"inputs.b.cells\"",
       "not among the inputs"},
      {"[[sweep]]\n\"evaluate.threads\" = [1]\n[[sweep]]\n\"evaluate.threads\" = [-2]\n",
       "sweep[1].\"evaluate.threads\"[0]", "at least"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.sweep);
    const ConfigError e = error_of(c.sweep);
    EXPECT_EQ(e.key(), c.key) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.mentions), std::string::npos) << e.what();
  }
  try {
    (void)parse("sweep = 3\n" + header + inputs + pipeline);
    ADD_FAILURE() << "a number as sweep parsed";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "sweep");
    EXPECT_NE(std::string(e.what()).find("array of tables"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plmap::experiment
