// summary.md (summary.hpp).

#include <plmap/experiment/summary.hpp>

#include <fmt/format.h>

#include <set>
#include <sstream>

namespace plmap::experiment {

namespace {

std::string cell(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return fmt::format("{:.4g}", v.get<double>());
  return v.dump();
}

std::string timing_cell(const nlohmann::json& t) {
  const double median = t["median"].get<double>(), min = t["min"].get<double>(), max = t["max"].get<double>();
  if (min == max) return fmt::format("{:.3g}", median);
  return fmt::format("{:.3g} [{:.3g}, {:.3g}]", median, min, max);
}

/// Markdown table cells must not contain a bare "|".
std::string escape(std::string s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::string summary_markdown(const ExperimentConfig& config, const std::vector<RunResult>& rows,
                             const Provenance& provenance, const std::vector<PlotOutcome>& plots) {
  std::ostringstream md;
  md << "# " << config.name << "\n\n";
  if (!config.description.empty()) md << config.description << "\n\n";
  md << fmt::format("{} runs, {} repetitions each, seed {}. Configuration: `config.toml`; every run: "
                    "`results.jsonl`, `results.csv`.\n\n",
                    rows.size(), config.repetitions, config.seed);

  md << "## Provenance\n\n| | |\n|---|---|\n";
  const auto provenance_json = to_json(provenance);
  for (const auto& [k, v] : provenance_json.items()) md << "| " << k << " | " << escape(cell(v)) << " |\n";

  // Configuration columns: the constant ones once, the varying ones in the table.
  std::vector<std::string> columns;
  std::set<std::string> seen;
  for (const auto& row : rows)
    for (const auto& [k, v] : row.config.items())
      if (seen.insert(k).second) columns.push_back(k);
  std::vector<std::string> varying, constant;
  for (const auto& c : columns) {
    bool same = true;
    for (const auto& row : rows)
      if (column_value(row, c) != column_value(rows.front(), c)) same = false;
    (same ? constant : varying).push_back(c);
  }
  if (std::find(varying.begin(), varying.end(), "input.name") == varying.end())
    varying.insert(varying.begin(), "input.name");
  std::vector<std::string> metrics, timings;
  seen.clear();
  for (const auto& row : rows) {
    for (const auto& [k, v] : row.metrics.items())
      if (seen.insert(k).second) metrics.push_back(k);
    for (const auto& [k, v] : row.timings.items())
      if (seen.insert(k).second) timings.push_back(k);
  }

  md << "\n## Results\n\n";
  if (!rows.empty() && !constant.empty()) {
    md << "Same in every run: ";
    for (std::size_t i = 0; i < constant.size(); ++i)
      md << (i ? ", " : "") << "`" << constant[i] << " = " << cell(column_value(rows.front(), constant[i])) << "`";
    md << ".\n\n";
  }
  md << "Timings: median [min, max] over the repetitions.\n\n| run";
  for (const auto& c : varying) md << " | " << c;
  for (const auto& c : metrics) md << " | " << c;
  for (const auto& c : timings) md << " | " << c;
  md << " |\n|---:";
  for (std::size_t i = 0; i < varying.size(); ++i) md << "|---";
  for (std::size_t i = 0; i < metrics.size() + timings.size(); ++i) md << "|---:";
  md << "|\n";
  for (const auto& row : rows) {
    md << "| " << row.run;
    for (const auto& c : varying) md << " | " << escape(cell(column_value(row, c)));
    for (const auto& c : metrics) md << " | " << escape(cell(row.metrics.contains(c) ? row.metrics[c] : nullptr));
    for (const auto& c : timings) md << " | " << (row.timings.contains(c) ? timing_cell(row.timings[c]) : "");
    md << " |\n";
  }

  if (!plots.empty()) {
    md << "\n## Plots\n\n";
    bool any_warning = false;
    for (const auto& p : plots) {
      for (const auto& image : p.images)
        if (image.extension() == ".svg") md << "![" << p.name << "](" << image.generic_string() << ")\n\n";
      any_warning = any_warning || !p.warning.empty();
    }
    if (any_warning) {
      md << "| plot | warning |\n|---|---|\n";
      for (const auto& p : plots)
        if (!p.warning.empty()) md << "| " << p.name << " | " << escape(p.warning) << " |\n";
    }
  }
  std::vector<std::string> notes;
  for (const auto& row : rows)
    for (const auto& n : row.notes) notes.push_back(fmt::format("run {}: {}", row.run, n));
  if (!notes.empty()) {
    md << "\n## Notes\n\n";
    for (const auto& n : notes) md << "- " << n << "\n";
  }
  return md.str();
}

}  // namespace plmap::experiment
