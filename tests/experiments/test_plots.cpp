// Plot scripts: with two group_by columns, series that share the first column's value share a
// colour, and series that share the second's share a line style, so a legend of 15 series can be
// read (gnuplot's default cycle has 8 colours).

#include <plmap/experiment/plots.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace plmap::experiment {
namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

RunResult row(const std::string& input, const std::string& tool, double x, double y) {
  RunResult r;
  r.config = {{"input.name", input}, {"tool", tool}, {"x", x}};
  r.metrics = {{"y", y}};
  return r;
}

/// (lc, dt) of the plotted series whose title contains `title`.
std::pair<int, int> style_of(const std::string& script, const std::string& title) {
  std::istringstream lines(script);
  const std::regex look(R"( lc (\d+) dt (\d+) pt \d+ title )");
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (line.find(title) != std::string::npos && std::regex_search(line, m, look))
      return {std::stoi(m[1]), std::stoi(m[2])};
  }
  ADD_FAILURE() << "no styled series titled " << title << " in\n" << script;
  return {0, 0};
}

TEST(Plots, TwoGroupColumnsGiveColourByTheFirstAndLineStyleByTheSecond) {
  ExperimentConfig config;
  PlotConfig plot;
  plot.key = "plots[0]";
  plot.name = "styled";
  plot.x = "x";
  plot.y = "y";
  plot.group_by = {"input.name", "tool"};
  config.plots.push_back(plot);
  std::vector<RunResult> rows;
  for (const char* input : {"plane", "sphere", "circle"})
    for (const char* tool : {"plmap", "contactmerge"})
      for (double x : {10.0, 100.0}) rows.push_back(row(input, tool, x, x * 2));
  const auto dir = std::filesystem::path(PLMAP_TEST_BINARY_DIR) / "plots_styled";
  std::filesystem::remove_all(dir);
  // The script is written whether or not gnuplot is installed.
  write_plots(config, rows, dir, PlotOptions{.gnuplot = ""});
  const std::string script = read_text(dir / "plots" / "styled.gp");

  const auto plane_plmap = style_of(script, "input.name = plane, tool = plmap");
  const auto plane_cm = style_of(script, "input.name = plane, tool = contactmerge");
  const auto sphere_plmap = style_of(script, "input.name = sphere, tool = plmap");
  const auto circle_cm = style_of(script, "input.name = circle, tool = contactmerge");
  EXPECT_EQ(plane_plmap.first, plane_cm.first);     // same input, same colour
  EXPECT_NE(plane_plmap.second, plane_cm.second);   // other tool, other line style
  EXPECT_NE(plane_plmap.first, sphere_plmap.first);  // other input, other colour
  EXPECT_EQ(plane_plmap.second, sphere_plmap.second);
  EXPECT_EQ(plane_cm.second, circle_cm.second);
  EXPECT_NE(sphere_plmap.first, circle_cm.first);
}

}  // namespace
}  // namespace plmap::experiment
