// The config parser rejects malformed experiments with a message that names the key.

#include <plmap/experiment/cgal_data.hpp>
#include <plmap/experiment/config.hpp>
#include <plmap/experiment/config_error.hpp>
#include <plmap/experiment/schema.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace plmap::experiment {
namespace {

/// A valid config; each bad case replaces one part of it.
struct Parts {
  std::string top = "";
  std::string experiment = "[experiment]\nname = \"t\"\nrepetitions = 1\n";
  std::string inputs = "[[inputs]]\nkind = \"grid\"\ncells = 4\n";
  std::string pipeline =
      "[[pipeline]]\nstep = \"build\"\nmap = \"subdivision\"\nk = 2\n"
      "[[pipeline]]\nstep = \"evaluate\"\nqueries = 100\n";
  std::string sweep = "";
  std::string plots = "";
  std::string text() const { return top + experiment + inputs + pipeline + sweep + plots; }
};

ExperimentConfig parse(const std::string& text) {
  return parse_experiment_text(text, "bad.toml", std::filesystem::temp_directory_path());
}

struct BadCase {
  std::string name;
  Parts parts;
  std::string key;       ///< ConfigError::key()
  std::string mentions;  ///< a further word the message must contain
};

Parts with(std::string Parts::*member, std::string value) {
  Parts p;
  p.*member = std::move(value);
  return p;
}

std::vector<BadCase> bad_cases() {
  std::vector<BadCase> cases = {
      {"unknown top-level key", with(&Parts::top, "colour = 3\n"), "colour", "unknown key"},
      {"unknown experiment key", with(&Parts::experiment, "[experiment]\nname = \"t\"\nrepetition = 2\n"),
       "experiment.repetition", "unknown key"},
      {"missing experiment", with(&Parts::experiment, ""), "experiment", "missing"},
      {"missing name", with(&Parts::experiment, "[experiment]\nrepetitions = 2\n"), "experiment.name", "missing"},
      {"repetitions wrong type", with(&Parts::experiment, "[experiment]\nname = \"t\"\nrepetitions = \"three\"\n"),
       "experiment.repetitions", "integer"},
      {"repetitions zero", with(&Parts::experiment, "[experiment]\nname = \"t\"\nrepetitions = 0\n"),
       "experiment.repetitions", "at least 1"},
      {"negative seed", with(&Parts::experiment, "[experiment]\nname = \"t\"\nseed = -1\n"), "experiment.seed",
       "at least 0"},
      {"unknown metric", with(&Parts::experiment, "[experiment]\nname = \"t\"\nmetrics = [\"build.nodes\", \"speed\"]\n"),
       "experiment.metrics[1]", "unknown metric"},
      {"empty metrics", with(&Parts::experiment, "[experiment]\nname = \"t\"\nmetrics = []\n"), "experiment.metrics",
       "empty"},
      {"missing inputs", with(&Parts::inputs, ""), "inputs", "missing"},

      {"unknown input kind", with(&Parts::inputs, "[[inputs]]\nkind = \"sphere\"\n"), "inputs[0].kind",
       "unknown input kind"},
      {"unknown input key", with(&Parts::inputs, "[[inputs]]\nkind = \"grid\"\ncels = 4\n"), "inputs[0].cels",
       "unknown key"},
      {"input wrong type", with(&Parts::inputs, "[[inputs]]\nkind = \"grid\"\ncells = 2.5\n"), "inputs[0].cells",
       "integer"},
      {"negative count", with(&Parts::inputs, "[[inputs]]\nkind = \"grid\"\ncells = -3\n"), "inputs[0].cells",
       "at least 1"},
      {"jitter out of range", with(&Parts::inputs, "[[inputs]]\nkind = \"grid\"\njitter = 0.5\n"),
       "inputs[0].jitter", "at most 0.2"},
      {"hole needs multiple of 4", with(&Parts::inputs, "[[inputs]]\nkind = \"grid\"\ncells = 6\nhole = true\n"),
       "inputs[0].cells", "multiple of 4"},
      {"missing input file", with(&Parts::inputs, "[[inputs]]\nkind = \"file\"\npath = \"no/such/surface.off\"\n"),
       "inputs[0].path", "not found"},
      {"file without path", with(&Parts::inputs, "[[inputs]]\nkind = \"file\"\n"), "inputs[0].path", "missing"},
      {"duplicate input name",
       with(&Parts::inputs, "[[inputs]]\nkind = \"grid\"\nname = \"a\"\n[[inputs]]\nkind = \"delaunay\"\nname = \"a\"\n"),
       "inputs[1].name", "twice"},
      {"run must be boolean", with(&Parts::inputs, "[[inputs]]\nkind = \"grid\"\nrun = 1\n"), "inputs[0].run",
       "boolean"},
      {"missing pipeline", with(&Parts::pipeline, ""), "pipeline", "missing"},
      {"unknown step", with(&Parts::pipeline, "[[pipeline]]\nstep = \"polish\"\n"), "pipeline[0].step",
       "unknown step"},
      {"missing map kind", with(&Parts::pipeline, "[[pipeline]]\nstep = \"build\"\n"), "pipeline[0].map", "missing"},
      {"unknown map kind", with(&Parts::pipeline, "[[pipeline]]\nstep = \"build\"\nmap = \"magic\"\n"),
       "pipeline[0].map", "unknown map kind"},
      {"parameter of another map kind", with(&Parts::pipeline, "[[pipeline]]\nstep = \"build\"\nmap = \"identity\"\nk = 3\n"),
       "pipeline[0].k", "only for map = subdivision"},
      {"unknown step key", with(&Parts::pipeline, "[[pipeline]]\nstep = \"build\"\nmap = \"identity\"\nfast = true\n"),
       "pipeline[0].fast", "unknown key"},
      {"unknown strategy",
       with(&Parts::pipeline, "[[pipeline]]\nstep = \"build\"\nmap = \"identity\"\n[[pipeline]]\nstep = \"evaluate\"\nlocator = \"foo\"\n"),
       "pipeline[1].locator", "unknown point locator \"foo\" (valid:"},
      {"negative query count",
       with(&Parts::pipeline, "[[pipeline]]\nstep = \"build\"\nmap = \"identity\"\n[[pipeline]]\nstep = \"evaluate\"\nqueries = -5\n"),
       "pipeline[1].queries", "at least 1"},
      {"evaluate without a map", with(&Parts::pipeline, "[[pipeline]]\nstep = \"evaluate\"\n"), "pipeline[0].step",
       "needs a map"},
      {"duplicate step name",
       with(&Parts::pipeline, "[[pipeline]]\nstep = \"build\"\nmap = \"identity\"\n[[pipeline]]\nstep = \"check\"\n[[pipeline]]\nstep = \"check\"\n"),
       "pipeline[2].name", "twice"},
      {"empty sweep list", with(&Parts::sweep, "[sweep]\n\"evaluate.threads\" = []\n"), "sweep.\"evaluate.threads\"",
       "empty list"},
      {"sweep not a list", with(&Parts::sweep, "[sweep]\n\"evaluate.threads\" = 2\n"), "sweep.\"evaluate.threads\"",
       "array"},
      {"sweep unknown step", with(&Parts::sweep, "[sweep]\n\"evalute.threads\" = [1, 2]\n"), "sweep.\"evalute.threads\"",
       "unknown step"},
      {"sweep unknown parameter", with(&Parts::sweep, "[sweep]\n\"evaluate.colour\" = [1, 2]\n"),
       "sweep.\"evaluate.colour\"", "no parameter"},
      {"sweep bad value", with(&Parts::sweep, "[sweep]\n\"evaluate.locator\" = [\"brute-force\", \"foo\"]\n"),
       "sweep.\"evaluate.locator\"[1]", "unknown point locator"},
      {"sweep negative count", with(&Parts::sweep, "[sweep]\n\"evaluate.queries\" = [-1, 10]\n"),
       "sweep.\"evaluate.queries\"[0]", "at least 1"},
      {"sweep wrong type", with(&Parts::sweep, "[sweep]\n\"build.k\" = [2, \"three\"]\n"), "sweep.\"build.k\"[1]",
       "integer"},
      {"sweep unknown input", with(&Parts::sweep, "[sweep]\n\"inputs.nothere.cells\" = [4]\n"),
       "sweep.\"inputs.nothere.cells\"", "unknown input"},
      {"sweep input parameter", with(&Parts::sweep, "[sweep]\n\"input.segments\" = [4]\n"), "sweep.\"input.segments\"",
       "no parameter"},
      {"sweep name", with(&Parts::sweep, "[sweep]\n\"build.name\" = [\"a\"]\n"), "sweep.\"build.name\"", "cannot be swept"},
      {"plot unknown column", with(&Parts::plots, "[[plots]]\nx = \"build.k\"\ny = \"evaluate.speed\"\n"), "plots[0].y",
       "unknown column"},
      {"plot missing x", with(&Parts::plots, "[[plots]]\ny = \"evaluate.seconds\"\n"), "plots[0].x", "missing"},
      {"plot unknown reference",
       with(&Parts::plots, "[[plots]]\nx = \"build.k\"\ny = \"evaluate.seconds\"\nreference = \"n^3\"\n"),
       "plots[0].reference", "unknown reference slope"},
      {"plot unknown reference in a list",
       with(&Parts::plots, "[[plots]]\nx = \"build.k\"\ny = \"evaluate.seconds\"\nreference = [\"n\", \"e^n\"]\n"),
       "plots[0].reference[1]", "unknown reference slope"},
      {"plot log must be boolean",
       with(&Parts::plots, "[[plots]]\nx = \"build.k\"\ny = \"evaluate.seconds\"\nlog_x = \"yes\"\n"), "plots[0].log_x",
       "boolean"},
      {"plot unknown group column",
       with(&Parts::plots, "[[plots]]\nx = \"build.k\"\ny = \"evaluate.seconds\"\ngroup_by = [\"input.name\", \"locator\"]\n"),
       "plots[0].group_by[1]", "unknown column"},
      {"plot unknown key", with(&Parts::plots, "[[plots]]\nx = \"build.k\"\ny = \"evaluate.seconds\"\ncolor = 1\n"),
       "plots[0].color", "unknown key"},
  };
  Parts scalar_inputs;
  scalar_inputs.top = "inputs = 3\n";
  scalar_inputs.inputs = "";
  cases.push_back({"inputs not tables", scalar_inputs, "inputs", "array of tables"});
  // A locator of triangle surfaces on a curve.
  Parts curve;
  curve.inputs = "[[inputs]]\nkind = \"open-polyline\"\n";
  curve.pipeline = "[[pipeline]]\nstep = \"build\"\nmap = \"identity\"\n[[pipeline]]\nstep = \"evaluate\"\nlocator = \"brown-faigle\"\n";
  cases.push_back({"locator of another dimension", curve, "pipeline[1].locator", "curves"});
  if (projection_available()) {
    Parts project;
    project.pipeline = "[[pipeline]]\nstep = \"project\"\ntarget = \"nowhere\"\n";
    cases.push_back({"project onto an unknown input", project, "pipeline[0].target", "unknown input"});
    project.pipeline = "[[pipeline]]\nstep = \"project\"\ntarget = \"grid\"\nsolver = \"magic\"\n";
    cases.push_back({"unknown solver", project, "pipeline[0].solver", "unknown projection solver"});
    project.pipeline = "[[pipeline]]\nstep = \"project\"\ntarget = \"grid\"\nrenumbering = \"shuffled\"\n";
    cases.push_back({"unknown renumbering", project, "pipeline[0].renumbering", "unknown renumbering"});
  }
  if (peer_benchmark_available()) {
    Parts peer;
    peer.pipeline = "[[pipeline]]\nstep = \"peer_project\"\ntool = \"plmap\"\n";
    cases.push_back({"peer_project on a grid input", peer, "inputs[0].kind", "contact-pair"});
    peer.inputs = "[[inputs]]\nkind = \"contact-pair\"\ncase = \"plane\"\nsize = 200\n";
    peer.pipeline = "[[pipeline]]\nstep = \"peer_project\"\ntool = \"abaqus\"\n";
    cases.push_back({"unknown peer tool", peer, "pipeline[0].tool", "unknown projection tool"});
    peer.pipeline = "[[pipeline]]\nstep = \"peer_project\"\n";
    cases.push_back({"peer_project without a tool", peer, "pipeline[0].tool", "missing"});
    peer.pipeline = "[[pipeline]]\nstep = \"peer_project\"\ntool = \"plmap\"\n[[pipeline]]\nstep = \"check\"\n";
    cases.push_back({"check after peer_project", peer, "pipeline[1].step", "needs a map"});
    peer.inputs = "[[inputs]]\nkind = \"contact-pair\"\ncase = \"cube\"\n";
    peer.pipeline = "[[pipeline]]\nstep = \"peer_project\"\ntool = \"plmap\"\n";
    cases.push_back({"unknown contact case", peer, "inputs[0].case", "unknown contact pair"});
    peer.inputs = "[[inputs]]\nkind = \"contact-circles\"\nsegments = 2\n";
    cases.push_back({"too few circle segments", peer, "inputs[0].segments", "at least 3"});
  }
  if (!cgal_data_location().empty()) {
    Parts cgal;
    cgal.inputs = "[[inputs]]\nkind = \"cgal\"\nmesh = \"no-such-mesh\"\n";
    cases.push_back({"unknown CGAL mesh", cgal, "inputs[0].mesh", "no mesh \"no-such-mesh\""});
  }
  return cases;
}

TEST(ExperimentConfig, TheBaseConfigIsValid) {
  const auto config = parse(Parts{}.text());
  EXPECT_EQ(config.name, "t");
  ASSERT_EQ(config.pipeline.size(), 2u);
  EXPECT_EQ(config.pipeline[1].name, "evaluate");
}

TEST(ExperimentConfig, EveryBadConfigIsRejectedNamingTheKey) {
  for (const BadCase& c : bad_cases()) {
    SCOPED_TRACE(c.name + "\n" + c.parts.text());
    try {
      parse(c.parts.text());
      ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
      EXPECT_EQ(e.key(), c.key) << e.what();
      const std::string message = e.what();
      EXPECT_NE(message.find(c.key), std::string::npos) << message;
      EXPECT_NE(message.find(c.mentions), std::string::npos) << message;
      EXPECT_EQ(message.rfind("bad.toml", 0), 0u) << message;
    }
  }
}

TEST(ExperimentConfig, ATomlSyntaxErrorNamesTheFileAndLine) {
  try {
    parse("[experiment]\nname = \"t\"\nrepetitions = = 2\n");
    ADD_FAILURE() << "accepted";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.file(), "bad.toml");
    EXPECT_EQ(e.location().rfind("3:", 0), 0u) << e.what();
  }
}

TEST(ExperimentConfig, ErrorsOnAKnownLineCarryIt) {
  Parts p;
  p.inputs = "[[inputs]]\nkind = \"grid\"\ncells = -3\n";
  try {
    parse(p.text());
    ADD_FAILURE() << "accepted";
  } catch (const ConfigError& e) {
    // experiment (3 lines) then the inputs table: `cells` is on line 6.
    EXPECT_NE(std::string(e.what()).find("bad.toml:6:"), std::string::npos) << e.what();
  }
}

TEST(ExperimentConfig, MissingFileIsAnError) {
  EXPECT_THROW(parse_experiment_file("/nonexistent/experiment.toml"), Error);
}

}  // namespace
}  // namespace plmap::experiment
