#pragma once
/// \file
/// The result of one run and how results are written: JSON lines (one object per run) and CSV
/// (one row per run, nested keys flattened with dots).
///
/// A row separates what must reproduce exactly (`config`, `metrics`) from what may not
/// (`timings`, `provenance`), so a comparison of two runs is a comparison of two objects.

#include <plmap/experiment/provenance.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace plmap::experiment {

/// Median and spread of a timing over the repetitions.
struct TimingSummary {
  double median = 0, min = 0, max = 0;
  std::vector<double> samples;
};

TimingSummary summarize(std::vector<double> samples);

struct RunResult {
  int run = 0;
  nlohmann::ordered_json config;   ///< RunSpec::columns
  nlohmann::ordered_json metrics;  ///< non-timing metrics: reproduce exactly
  /// Timing metrics: name -> {median, min, max, samples}.
  nlohmann::ordered_json timings;
  /// Things worth knowing, e.g. a non-timing metric that differed between repetitions.
  std::vector<std::string> notes;
};

/// The JSON-lines object of a row: {"run", "config", "metrics", "timings", "notes", "provenance"}.
nlohmann::ordered_json to_json(const RunResult& row, const Provenance& provenance);

/// Writes results.jsonl and results.csv (atomically).
void write_jsonl(const std::filesystem::path& path, const std::vector<RunResult>& rows,
                 const Provenance& provenance);
void write_csv(const std::filesystem::path& path, const std::vector<RunResult>& rows,
               const Provenance& provenance);

/// Reads a JSON-lines file (one object per non-empty line). Throws plmap::ParseError naming the
/// file and line.
std::vector<nlohmann::json> read_jsonl(const std::filesystem::path& path);

/// The value of column `name` of a row: a config column, a metric, or a timing's median.
/// Null if the row has no such column.
nlohmann::json column_value(const RunResult& row, const std::string& name);

}  // namespace plmap::experiment
