// Plots through gnuplot (plots.hpp).

#include "process.hpp"

#include <plmap/core/io/atomic_file.hpp>
#include <plmap/experiment/plots.hpp>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

namespace plmap::experiment {

std::filesystem::path find_executable(const std::string& name) {
  if (name.empty()) return {};
  if (name.find('/') != std::string::npos)
    return access(name.c_str(), X_OK) == 0 ? std::filesystem::path(name) : std::filesystem::path{};
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const auto candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

namespace {

struct Point {
  double x, y, y_min, y_max;
};

/// A gnuplot single-quoted string: no escapes are processed, a quote is written twice.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

std::optional<double> numeric(const nlohmann::json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_boolean()) return v.get<bool>() ? 1.0 : 0.0;
  return std::nullopt;
}

std::string group_label(const nlohmann::json& v) {
  if (v.is_null()) return "";
  return v.is_string() ? v.get<std::string>() : v.dump();
}

/// The reference curve as a gnuplot expression in x, and its value at x.
std::pair<std::string, double> reference_function(ReferenceSlope slope, double x) {
  switch (slope) {
    case ReferenceSlope::constant: return {"1", 1.0};
    case ReferenceSlope::log_n: return {"log(x)", std::log(x)};
    case ReferenceSlope::sqrt_n: return {"sqrt(x)", std::sqrt(x)};
    case ReferenceSlope::n: return {"x", x};
    case ReferenceSlope::n_log_n: return {"x*log(x)", x * std::log(x)};
    case ReferenceSlope::n_squared: return {"x**2", x * x};
    case ReferenceSlope::none: break;
  }
  return {"", 0.0};
}

/// Position of `value` in `values`, appended if new.
int index_of(std::vector<std::string>& values, const std::string& value) {
  const auto it = std::find(values.begin(), values.end(), value);
  if (it != values.end()) return static_cast<int>(it - values.begin());
  values.push_back(value);
  return static_cast<int>(values.size()) - 1;
}

bool has_terminal(const std::filesystem::path& gnuplot, const std::string& terminal) {
  return detail::run_process({gnuplot.string(), "-e", "set terminal " + terminal}).exit_code == 0;
}

}  // namespace

std::vector<PlotOutcome> write_plots(const ExperimentConfig& config, const std::vector<RunResult>& rows,
                                     const std::filesystem::path& output_dir, const PlotOptions& options) {
  std::vector<PlotOutcome> outcomes;
  const auto gnuplot = find_executable(options.gnuplot);
  const bool png = !gnuplot.empty() && has_terminal(gnuplot, "pngcairo");
  const auto dir = std::filesystem::absolute(output_dir / "plots");
  std::filesystem::create_directories(dir);
  for (const PlotConfig& plot : config.plots) {
    PlotOutcome outcome;
    outcome.name = plot.name;
    // Series: one per value of group_by, in order of first appearance, sorted by x.
    std::vector<std::string> groups;
    std::map<std::string, std::vector<Point>> series;
    std::vector<std::string> colour_values, dash_values;
    std::map<std::string, std::pair<int, int>> style;  // group -> (colour, dash) index, from 0
    bool timing = false;
    for (const auto& row : rows) {
      const auto x = numeric(column_value(row, plot.x));
      const auto y = numeric(column_value(row, plot.y));
      if (!x || !y) continue;
      if (plot.log_x && *x <= 0) continue;
      if (plot.log_y && *y <= 0) continue;
      Point p{*x, *y, *y, *y};
      if (row.timings.contains(plot.y)) {
        timing = true;
        p.y_min = row.timings[plot.y]["min"].get<double>();
        p.y_max = row.timings[plot.y]["max"].get<double>();
      }
      std::string g;
      for (const auto& column : plot.group_by)
        g += (g.empty() ? "" : ", ") + (plot.group_by.size() > 1 ? column + " = " : "") +
             group_label(column_value(row, column));
      if (plot.group_by.empty()) g = plot.y;
      if (!series.count(g)) {
        groups.push_back(g);
        // With two or more group_by columns, the colour tells the value of the first and the line
        // and point style the rest: 5 inputs x 3 tools would otherwise cycle through gnuplot's
        // 8 colours and show two series alike.
        if (plot.group_by.size() >= 2) {
          std::string rest;
          for (std::size_t c = 1; c < plot.group_by.size(); ++c)
            rest += group_label(column_value(row, plot.group_by[c])) + ", ";
          style[g] = {index_of(colour_values, group_label(column_value(row, plot.group_by[0]))),
                      index_of(dash_values, rest)};
        }
      }
      series[g].push_back(p);
    }
    if (groups.empty()) {
      outcome.warning = fmt::format("no numeric values of {} against {}", plot.y, plot.x);
      outcomes.push_back(std::move(outcome));
      continue;
    }
    const auto data = dir / (plot.name + ".dat");
    write_file_atomically(
        data,
        [&](std::ostream& out) {
          out << "# " << plot.x << "  " << plot.y << (timing ? " (median)  min  max" : "") << "\n";
          for (const auto& g : groups) {
            auto& points = series[g];
            std::stable_sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.x < b.x; });
            out << "# " << g << "\n";
            for (const auto& p : points) out << fmt::format("{} {} {} {}\n", p.x, p.y, p.y_min, p.y_max);
            out << "\n\n";
          }
        },
        false);

    std::ostringstream script;
    script << "# Generated by plmap experiment run for " << plot.key << " of " << config.source_name() << "\n";
    script << "set terminal svg size 800,520 dynamic font 'sans,11' background rgb 'white'\n";
    script << "set output " << quoted((dir / (plot.name + ".svg")).string()) << "\n";
    script << "set title " << quoted(plot.title) << " noenhanced\n";
    script << "set xlabel " << quoted(plot.x_label) << " noenhanced\n";
    script << "set ylabel " << quoted(plot.y_label + (timing ? " (median, bars: min-max)" : "")) << " noenhanced\n";
    if (plot.log_x) script << "set logscale x\n";
    if (plot.log_y) script << "set logscale y\n";
    script << "set grid\nset key left top noenhanced\n";
    std::vector<std::string> items;
    for (std::size_t i = 0; i < groups.size(); ++i) {
      std::string look;
      if (const auto it = style.find(groups[i]); it != style.end())
        look = fmt::format(" lc {} dt {} pt {}", it->second.first + 1, it->second.second + 1, it->second.second + 4);
      items.push_back(fmt::format("{} index {} using 1:2{} with {} lw 2{} title {}", quoted(data.string()), i,
                                  timing ? ":3:4" : "", timing ? "yerrorlines" : "linespoints", look,
                                  quoted(plot.group_by.size() == 1 ? plot.group_by[0] + " = " + groups[i] : groups[i])));
    }
    for (const ReferenceSlope reference : plot.references) {
      // Anchored at the first point of the first series where the reference is positive.
      for (const auto& p : series[groups.front()]) {
        const auto [expression, value] = reference_function(reference, p.x);
        if (value > 0 && std::isfinite(value)) {
          items.push_back(fmt::format("{} * {} with lines dt {} lc rgb 'gray40' title {}", p.y / value, expression,
                                      items.size() - groups.size() + 2, quoted("reference: " + to_string(reference))));
          break;
        }
      }
    }
    script << "plot ";
    for (std::size_t i = 0; i < items.size(); ++i) script << (i ? ", \\\n     " : "") << items[i];
    script << "\n";
    if (png) {
      script << "set terminal pngcairo size 1000,650 font 'sans,10' background rgb 'white'\n";
      script << "set output " << quoted((dir / (plot.name + ".png")).string()) << "\nreplot\n";
    }
    script << "unset output\n";
    const auto script_path = dir / (plot.name + ".gp");
    write_file_atomically(script_path, [&](std::ostream& out) { out << script.str(); }, false);

    if (gnuplot.empty()) {
      outcome.warning = fmt::format("gnuplot not found (\"{}\"); install Debian's gnuplot-nox and run plots/{}.gp",
                                    options.gnuplot, plot.name);
    } else {
      const auto result = detail::run_process({gnuplot.string(), script_path.string()}, dir);
      if (result.exit_code != 0) {
        auto message = result.errors.substr(0, result.errors.find_last_not_of("\n") + 1);
        std::replace(message.begin(), message.end(), '\n', ' ');
        outcome.warning = fmt::format("gnuplot failed on plots/{}.gp: {}", plot.name, message);
      } else {
        outcome.images.push_back(std::filesystem::path("plots") / (plot.name + ".svg"));
        if (png) outcome.images.push_back(std::filesystem::path("plots") / (plot.name + ".png"));
      }
    }
    outcomes.push_back(std::move(outcome));
  }
  return outcomes;
}

}  // namespace plmap::experiment
