#pragma once
/// \file
/// What an experiment may contain: the input kinds and pipeline step kinds with their parameters
/// (docs/experiments.md lists the same), and the metrics each step records.

#include <plmap/experiment/parameters.hpp>

#include <span>
#include <string>
#include <vector>

namespace plmap::experiment {

/// Input kinds: "file", "cgal", "grid", "delaunay", "bumpy-grid", "open-polyline",
/// "closed-polyline", "star-polyline".
std::span<const std::string> input_kinds();
/// Step kinds: "build", "project" (when plmap::construct is built), "evaluate", "check".
std::span<const std::string> step_kinds();

/// Parameters of an input kind (without the common keys `name`, `kind`, `run`).
const std::vector<ParameterSpec>& input_schema(const std::string& kind);
/// Parameters of a step kind (without the common keys `step`, `name`).
const std::vector<ParameterSpec>& step_schema(const std::string& kind);

/// Surface dimension an input kind produces: 1 or 2; 0 for "file" (decided by its parameters).
int input_kind_dimension(const std::string& kind);

struct MetricSpec {
  std::string suffix;   ///< full name: "<step name>.<suffix>" (inputs: "input.<suffix>")
  bool timing = false;  ///< repeated `repetitions` times, reported as median / min / max
  std::string doc;
};

/// Metrics of the loaded input (`input.vertices`, ...).
const std::vector<MetricSpec>& input_metrics();
/// Metrics a step kind records.
const std::vector<MetricSpec>& step_metrics(const std::string& kind);

/// Whether the projection step is available in this build.
bool projection_available();
/// True if this build can run experiments/peers' benchmark (the peer_project step).
bool peer_benchmark_available();
/// The benchmark the peer_project step runs: $PLMAP_PEER_BENCH if set, else the one built with
/// this runner (empty if none).
std::string peer_benchmark_program();
/// contact-pair and contact-circles: the inputs that peer_project accepts.
bool is_contact_input_kind(const std::string& kind);

/// Whether the peer_simplify step is available (experiments/peers' bench_simplification_peers is
/// built), and the program it runs (PLMAP_SIMPLIFICATION_BENCH overrides the built one).
bool simplification_benchmark_available();
std::string simplification_benchmark_program();

}  // namespace plmap::experiment
