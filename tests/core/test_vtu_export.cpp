// VTU export and the regions CSV: the files are well-formed XML with the counts the map implies,
// and the CSV has one row per region with values that match the map.

#include "test_map_file_fixtures.hpp"

#include <plmap/core/io/regions_csv.hpp>
#include <plmap/core/io/vtu_export.hpp>
#include <plmap/core/regions.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <charconv>
#include <regex>
#include <set>
#include <sstream>

namespace plmap {
namespace {

using namespace test_maps;

/// A light well-formedness check: every start tag is closed in order, the declaration and
/// comments are skipped. Returns an empty string when the document is fine, else the problem.
std::string xml_structure_problem(const std::string& xml) {
  std::vector<std::string> open;
  std::size_t i = 0;
  while ((i = xml.find('<', i)) != std::string::npos) {
    const std::size_t close = xml.find('>', i);
    if (close == std::string::npos) return "unterminated tag";
    const std::string tag = xml.substr(i + 1, close - i - 1);
    i = close + 1;
    if (tag.starts_with("?") || tag.starts_with("!--")) continue;
    if (tag.starts_with("/")) {
      if (open.empty() || open.back() != tag.substr(1)) return "mismatched </" + tag.substr(1) + ">";
      open.pop_back();
      continue;
    }
    if (tag.ends_with("/")) continue;
    open.push_back(tag.substr(0, tag.find(' ')));
  }
  return open.empty() ? "" : "unclosed <" + open.back() + ">";
}

struct PieceCounts {
  long points = -1;
  long cells = -1;
};

PieceCounts piece_counts(const std::string& xml) {
  std::smatch match;
  PieceCounts c;
  if (std::regex_search(xml, match,
                        std::regex(R"re(<Piece NumberOfPoints="(\d+)" NumberOfCells="(\d+)">)re"))) {
    c.points = std::stol(match[1]);
    c.cells = std::stol(match[2]);
  }
  return c;
}

/// The whitespace-separated values of the DataArray named `name`.
std::vector<double> data_array(const std::string& xml, const std::string& name) {
  const std::regex pattern("<DataArray[^>]*Name=\"" + name + "\"[^>]*>([^<]*)</DataArray>");
  std::smatch match;
  if (!std::regex_search(xml, match, pattern)) {
    ADD_FAILURE() << "no DataArray " << name;
    return {};
  }
  std::istringstream values(match[1].str());
  std::vector<double> out;
  for (double v; values >> v;) out.push_back(v);
  return out;
}

template <int d>
std::size_t graph_edge_count(const PlMap<d>& map) {
  std::set<std::pair<Index, Index>> edges;
  for (Index n = 0; n < map.node_count(); ++n) {
    for (Index m : map.neighbors(n)) edges.insert({std::min(n, m), std::max(n, m)});
  }
  return edges.size();
}

template <int d>
void check_vtu_export(const PlMap<d>& map, const std::string& name) {
  const auto dir = scratch_directory(name) / "vtu";  // not yet existing: export creates it
  const auto files = export_vtu(map, dir);
  ASSERT_EQ(files.size(), 6u);
  EXPECT_EQ(files.back().filename(), "map.pvd");

  std::map<std::string, std::string> content;
  for (const auto& f : files) {
    ASSERT_TRUE(std::filesystem::exists(f)) << f;
    content[f.filename().string()] = read_bytes(f);
    EXPECT_EQ(xml_structure_problem(content[f.filename().string()]), "") << f;
  }
  const long simplex_points = d + 1;
  const long cell_type = d == 1 ? 3 : 5;

  const auto check_grid = [&](const std::string& file, long points, long cells, long corners,
                              long type) {
    SCOPED_TRACE(file);
    const std::string& xml = content[file];
    const PieceCounts c = piece_counts(xml);
    EXPECT_EQ(c.points, points);
    EXPECT_EQ(c.cells, cells);
    EXPECT_EQ(static_cast<long>(data_array(xml, "Points").size()), 3 * points);
    EXPECT_EQ(static_cast<long>(data_array(xml, "connectivity").size()), corners * cells);
    const auto offsets = data_array(xml, "offsets");
    ASSERT_EQ(static_cast<long>(offsets.size()), cells);
    if (cells > 0) {
      EXPECT_EQ(offsets.back(), static_cast<double>(corners * cells));
    }
    for (double t : data_array(xml, "types")) EXPECT_EQ(t, type);
    for (double v : data_array(xml, "connectivity")) {
      EXPECT_GE(v, 0);
      EXPECT_LT(v, points);
    }
  };
  check_grid("domain.vtu", map.domain().vertex_count(), map.domain().element_count(),
             simplex_points, cell_type);
  check_grid("target.vtu", map.target().vertex_count(), map.target().element_count(),
             simplex_points, cell_type);
  check_grid("graph.vtu", map.node_count(), static_cast<long>(graph_edge_count(map)), 2, 3);
  check_grid("regions.vtu", simplex_points * map.region_count(), map.region_count(),
             simplex_points, cell_type);
  check_grid("images.vtu", simplex_points * map.region_count(), map.region_count(),
             simplex_points, cell_type);

  // Point and cell data carry the map's values.
  const auto node_type = data_array(content["graph.vtu"], "node_type");
  ASSERT_EQ(static_cast<Index>(node_type.size()), map.node_count());
  for (Index n = 0; n < map.node_count(); ++n) {
    EXPECT_EQ(node_type[n], static_cast<double>(map.data().node_type[n]));
  }
  for (double kind : data_array(content["graph.vtu"], "edge_kind")) {
    EXPECT_TRUE(kind == 0 || kind == 1);
  }
  const auto target_element = data_array(content["images.vtu"], "target_element");
  ASSERT_EQ(static_cast<Index>(target_element.size()), map.region_count());
  for (Index r = 0; r < map.region_count(); ++r) {
    EXPECT_EQ(target_element[r], map.data().region_target[r]);
  }
  // The graph's points are the nodes' world positions on S1 (written exactly).
  const auto points = data_array(content["graph.vtu"], "Points");
  for (Index n = 0; n < map.node_count(); ++n) {
    const auto x = map.node_domain_world(n);
    for (int i = 0; i <= d; ++i) EXPECT_EQ(points[3 * n + i], x(i));
    if (d == 1) {
      EXPECT_EQ(points[3 * n + 2], 0.0);
    }
  }

  const std::string& pvd = content["map.pvd"];
  for (const char* part : {"domain.vtu", "target.vtu", "graph.vtu", "regions.vtu", "images.vtu"}) {
    EXPECT_THAT(pvd, ::testing::HasSubstr(std::string("file=\"") + part + "\""));
  }
}

TEST(VtuExport, TriangleMapWithIntersections) { check_vtu_export(builder_square_flip(), "vtu2"); }

TEST(VtuExport, PolylineMap) { check_vtu_export(builder_polyline(), "vtu1"); }

TEST(VtuExport, HandMadeMaps) {
  check_vtu_export(hand_made_triangle(), "vtu_hand2");
  check_vtu_export(hand_made_segment(), "vtu_hand1");
}

TEST(VtuExport, ExportIntoAnExistingDirectoryReplacesTheFiles) {
  const auto dir = scratch_directory("vtu_again");
  export_vtu(builder_square_flip(), dir);
  export_vtu(hand_made_triangle(), dir);
  EXPECT_EQ(piece_counts(read_bytes(dir / "regions.vtu")).cells, 1);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            6);
}

// ---- regions CSV ------------------------------------------------------------------------------

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::istringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    rows.push_back(std::move(cells));
  }
  return rows;
}

double exact_double(const std::string& s) {
  double v = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), v);
  EXPECT_TRUE(error == std::errc() && end == s.data() + s.size()) << s;
  return v;
}

template <int d>
void check_regions_csv(const PlMap<d>& map, const std::string& name) {
  const auto path = scratch_directory(name) / "regions.csv";
  write_regions_csv(path, map);
  const auto rows = csv_rows(read_bytes(path));
  ASSERT_EQ(static_cast<Index>(rows.size()), map.region_count() + 1);
  // region, two elements, local corners on both sides, world corners on both sides, 2 measures
  const std::size_t columns = 3 + 2 * (d + 1) * d + 2 * (d + 1) * (d + 1) + 2;
  const auto& header = rows.front();
  ASSERT_EQ(header.size(), columns);
  EXPECT_EQ(header[0], "region");
  EXPECT_EQ(header[3], "domain_local_0_xi0");
  EXPECT_EQ(header[columns - 2], "domain_measure");
  EXPECT_EQ(header[columns - 1], "target_measure");

  const auto world_column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t target_world_1_y = world_column("target_world_1_y");
  ASSERT_LT(target_world_1_y, columns);

  for (Index r = 0; r < map.region_count(); ++r) {
    const auto& row = rows[r + 1];
    ASSERT_EQ(row.size(), columns);
    const auto ri = remote_intersection(map, r);
    EXPECT_EQ(std::stoi(row[0]), r);
    EXPECT_EQ(std::stoi(row[1]), ri.domain_element);
    EXPECT_EQ(std::stoi(row[2]), ri.target_element);
    // Exact: the printed doubles parse back to the very same values.
    EXPECT_EQ(exact_double(row[target_world_1_y]), ri.target_world[1](1));
    EXPECT_EQ(exact_double(row[columns - 2]), ri.domain_measure());
    EXPECT_EQ(exact_double(row[columns - 1]), ri.target_measure());
  }
}

TEST(RegionsCsv, OneExactRowPerRegion) {
  check_regions_csv(builder_square_flip(), "csv2");
  check_regions_csv(builder_polyline(), "csv1");
  check_regions_csv(hand_made_triangle(), "csv_hand2");
}

}  // namespace
}  // namespace plmap
