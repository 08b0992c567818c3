#include <plmap/core/errors.hpp>
#include <plmap/core/io/atomic_file.hpp>
#include <plmap/experiment/results.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

namespace plmap::experiment {

TimingSummary summarize(std::vector<double> samples) {
  TimingSummary t;
  t.samples = samples;
  if (samples.empty()) return t;
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  t.median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  t.min = samples.front();
  t.max = samples.back();
  return t;
}

nlohmann::ordered_json to_json(const RunResult& row, const Provenance& provenance) {
  nlohmann::ordered_json j;
  j["run"] = row.run;
  j["config"] = row.config;
  j["metrics"] = row.metrics;
  j["timings"] = row.timings;
  j["notes"] = row.notes;
  j["provenance"] = to_json(provenance);
  return j;
}

void write_jsonl(const std::filesystem::path& path, const std::vector<RunResult>& rows,
                 const Provenance& provenance) {
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        for (const auto& row : rows) out << to_json(row, provenance).dump() << '\n';
      },
      false);
}

namespace {

/// A CSV cell (RFC 4180): quoted when it holds a comma, quote or line break.
std::string csv_cell(const nlohmann::ordered_json& v) {
  std::string s;
  if (v.is_null()) return "";
  if (v.is_string()) s = v.get<std::string>();
  else s = v.dump();
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// Nested objects flattened to "a.b.c" keys (arrays stay JSON text).
void flatten(const nlohmann::ordered_json& v, const std::string& prefix, nlohmann::ordered_json& out) {
  if (v.is_object()) {
    for (const auto& [k, x] : v.items()) flatten(x, prefix.empty() ? k : prefix + "." + k, out);
  } else {
    out[prefix] = v;
  }
}

}  // namespace

void write_csv(const std::filesystem::path& path, const std::vector<RunResult>& rows,
               const Provenance& provenance) {
  std::vector<nlohmann::ordered_json> flat;
  // Columns grouped by section (config, metrics, timings, ...), each in order of first
  // appearance, so that the columns of an input kind met late still sit with the config.
  std::vector<std::string> sections;
  std::map<std::string, std::vector<std::string>> section_columns;
  std::set<std::string> seen;
  for (const auto& row : rows) {
    auto j = to_json(row, provenance);
    j["timings"] = nlohmann::ordered_json::object();  // without the samples arrays
    for (const auto& [name, t] : row.timings.items())
      for (const char* field : {"median", "min", "max"}) j["timings"][name][field] = t[field];
    j["notes"] = row.notes.empty() ? nlohmann::ordered_json("") : nlohmann::ordered_json(fmt::format("{}", fmt::join(row.notes, "; ")));
    nlohmann::ordered_json f;
    flatten(j, "", f);
    for (const auto& [k, v] : f.items()) {
      if (!seen.insert(k).second) continue;
      const std::string section = k.substr(0, k.find('.'));
      if (!section_columns.count(section)) sections.push_back(section);
      section_columns[section].push_back(k);
    }
    flat.push_back(std::move(f));
  }
  std::vector<std::string> header;
  for (const auto& section : sections)
    header.insert(header.end(), section_columns[section].begin(), section_columns[section].end());
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        for (std::size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << csv_cell(header[i]);
        out << '\n';
        for (const auto& f : flat) {
          for (std::size_t i = 0; i < header.size(); ++i)
            out << (i ? "," : "") << (f.contains(header[i]) ? csv_cell(f[header[i]]) : "");
          out << '\n';
        }
      },
      false);
}

std::vector<nlohmann::json> read_jsonl(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(fmt::format("{}: cannot open", path.string()));
  std::vector<nlohmann::json> rows;
  std::size_t line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      rows.push_back(nlohmann::json::parse(line));
    } catch (const nlohmann::json::parse_error& e) {
      throw ParseError(path.string(), std::to_string(line_number), e.what());
    }
  }
  return rows;
}

nlohmann::json column_value(const RunResult& row, const std::string& name) {
  if (row.config.contains(name)) return row.config[name];
  if (row.metrics.contains(name)) return row.metrics[name];
  if (row.timings.contains(name)) return row.timings[name]["median"];
  return nullptr;
}

}  // namespace plmap::experiment
