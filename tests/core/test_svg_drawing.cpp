// SVG pictures of maps: well-formed XML, one symbol per node with the class of its type, one
// path per region, one line per graph edge of the right kind, faces in painter's order, and
// clear errors for elements that do not exist.

#include "test_map_file_fixtures.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/svg_drawing.hpp>
#include <plmap/core/map_builder.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace plmap {
namespace {

// ---- a map with every node type ----------------------------------------------------------------

/// S1: the unit square cut into four triangles around its centre (vertex 4). S2: the same square
/// triangulated with a vertex inside S1 triangle 0 (an interior node), a vertex on the S1 edge
/// from vertex 3 to the centre (touching nodes), two S2 edges that cross S1 edges next to the
/// centre (intersection nodes), and no S2 vertex at the centre (ghost nodes); the square's
/// corners are shared (corner nodes).
PlMap<2> every_node_type_map() {
  const std::vector<WorldPoint<2>> s1_vertices{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  auto s1 = std::make_shared<const Surface<2>>(
      s1_vertices, std::vector<ElementCorners<2>>{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
  const std::vector<WorldPoint<2>> s2_vertices{{0, 0, 0},     {1, 0, 0},      {1, 1, 0},
                                               {0, 1, 0},     {0.5, 0.2, 0},  {0.25, 0.75, 0}};
  const std::vector<ElementCorners<2>> s2_triangles{{0, 1, 4}, {1, 2, 4}, {4, 2, 5},
                                                    {0, 4, 5}, {0, 5, 3}, {5, 2, 3}};
  auto s2 = std::make_shared<const Surface<2>>(s2_vertices, s2_triangles);

  MapBuilder<2> b(s1, s2);
  for (Index v = 0; v < 4; ++v) b.add_vertex_preimage_at_vertex(v, v);
  b.add_vertex_preimage(4, SurfacePoint<2>{0, LocalPoint<2>(0.3, 0.4)});  // (0.5, 0.2) on S1 T0
  b.add_vertex_preimage_on_edge(5, s1->find_edge(3, 4), 0.5);            // (0.25, 0.75)

  // The centre of S1 lies inside S2 triangle 2 = (4, 2, 5): a ghost node with that image.
  const Eigen::Vector2d c0 = s2_vertices[4].head<2>(), c1 = s2_vertices[2].head<2>(),
                        c2 = s2_vertices[5].head<2>();
  Eigen::Matrix2d frame;
  frame << (c1 - c0), (c2 - c0);
  const Eigen::Vector2d ghost_local = frame.inverse() * (Eigen::Vector2d(0.5, 0.5) - c0);
  b.add_ghost_node(4, SurfacePoint<2>{2, ghost_local});

  // S2 edge (2, 4) crosses S1 edge (1, 4) at (8/13, 5/13): parameter 10/13 from vertex 1.
  const EdgeCrossing cross_1_4{s1->find_edge(1, 4), 10.0 / 13.0};
  b.add_edge(s2->find_edge(2, 4), std::span<const EdgeCrossing>(&cross_1_4, 1));
  // S2 edge (4, 5) crosses S1 edge (0, 4) at (0.40625, 0.40625): parameter 0.8125 from vertex 0.
  const EdgeCrossing cross_0_4{s1->find_edge(0, 4), 0.8125};
  b.add_edge(s2->find_edge(4, 5), std::span<const EdgeCrossing>(&cross_0_4, 1));
  for (auto [p, q] : {std::pair{0, 1}, std::pair{1, 4}, std::pair{0, 4}, std::pair{1, 2},
                      std::pair{2, 5}, std::pair{0, 5}, std::pair{0, 3}, std::pair{3, 5},
                      std::pair{2, 3}})
    b.add_edge(s2->find_edge(p, q));
  return std::move(b).finalize();
}

// ---- reading the SVG back --------------------------------------------------------------------

/// A light well-formedness check that needs no XML library: tags nest and close in order,
/// attribute quotes are balanced, CDATA sections, comments and the declaration are skipped.
/// Returns an empty string when the document is fine, else the first problem.
std::string xml_nesting_problem(const std::string& xml) {
  std::vector<std::string> open;
  std::size_t i = 0;
  bool saw_root = false;
  while ((i = xml.find('<', i)) != std::string::npos) {
    if (xml.compare(i, 9, "<![CDATA[") == 0) {
      i = xml.find("]]>", i);
      if (i == std::string::npos) return "unterminated CDATA";
      continue;
    }
    if (xml.compare(i, 4, "<!--") == 0) {
      i = xml.find("-->", i);
      if (i == std::string::npos) return "unterminated comment";
      continue;
    }
    const std::size_t close = xml.find('>', i);
    if (close == std::string::npos) return "unterminated tag";
    const std::string tag = xml.substr(i + 1, close - i - 1);
    i = close + 1;
    if (tag.starts_with("?")) continue;
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return "unbalanced quotes in <" + tag + ">";
    if (tag.starts_with("/")) {
      if (open.empty() || open.back() != tag.substr(1)) return "mismatched </" + tag.substr(1) + ">";
      open.pop_back();
      continue;
    }
    if (open.empty() && saw_root) return "content after the root element";
    saw_root = true;
    if (!tag.ends_with("/")) open.push_back(tag.substr(0, tag.find_first_of(" \n")));
  }
  if (!open.empty()) return "unclosed <" + open.back() + ">";
  return saw_root ? "" : "no root element";
}

/// Also asks xmllint (libxml2-utils), when it is installed, for a strict parse.
void expect_well_formed(const std::string& svg, const std::string& name) {
  EXPECT_EQ(xml_nesting_problem(svg), "") << name;
  EXPECT_TRUE(svg.starts_with("<?xml")) << name;
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos) << name;
  if (!std::filesystem::exists("/usr/bin/xmllint")) return;
  const auto dir = std::filesystem::path(PLMAP_TEST_BINARY_DIR) / "svg_scratch";
  std::filesystem::create_directories(dir);
  const auto file = dir / (name + ".svg");
  write_svg_file(file, svg);
  const std::string command = "/usr/bin/xmllint --noout '" + file.string() + "' 2>/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << "xmllint rejects " << file;
}

/// Every start tag (with its attributes) whose class attribute starts with `class_prefix`.
std::vector<std::string> tags_with_class(const std::string& svg, const std::string& class_prefix) {
  std::vector<std::string> found;
  const std::string needle = "class=\"" + class_prefix;
  for (std::size_t i = svg.find(needle); i != std::string::npos; i = svg.find(needle, i + 1)) {
    const std::size_t begin = svg.rfind('<', i), end = svg.find('>', i);
    found.push_back(svg.substr(begin, end - begin + 1));
  }
  return found;
}

std::string attribute(const std::string& tag, const std::string& name) {
  const std::regex pattern(" " + name + "=\"([^\"]*)\"");
  std::smatch m;
  return std::regex_search(tag, m, pattern) ? m[1].str() : std::string();
}

/// Graph edges of the element of the given kind, each once.
template <int d>
std::set<std::pair<Index, Index>> graph_edges(const PlMap<d>& map, Index element, GraphEdgeKind kind) {
  std::set<std::pair<Index, Index>> edges;
  const auto& data = map.data();
  for (Index n = map.nodes_begin(element); n < map.nodes_end(element); ++n)
    for (Index k = data.neighbor_begin[n]; k < data.neighbor_begin[n + 1]; ++k)
      if (data.neighbor_edge_kind[k] == kind) edges.insert(std::minmax(n, data.neighbor[k]));
  return edges;
}

/// Checks the element picture against the map: one symbol per node with the class of its type,
/// one path per region with its target, one line per graph edge with its kind.
template <int d>
void expect_element_picture_matches(const PlMap<d>& map, Index element, const std::string& svg) {
  const auto& data = map.data();
  std::map<Index, std::string> symbol_class;
  for (const std::string& tag : tags_with_class(svg, "node ")) {
    const std::string node = attribute(tag, "data-node");
    if (node.empty()) continue;  // a legend sample
    EXPECT_TRUE(symbol_class.emplace(std::stoi(node), attribute(tag, "class")).second)
        << "node " << node << " drawn twice";
  }
  EXPECT_EQ(symbol_class.size(), static_cast<std::size_t>(map.nodes_end(element) - map.nodes_begin(element)));
  for (Index n = map.nodes_begin(element); n < map.nodes_end(element); ++n) {
    ASSERT_TRUE(symbol_class.count(n)) << "no symbol for node " << n;
    EXPECT_EQ(symbol_class[n], "node " + std::string(to_string(data.node_type[n]))) << "node " << n;
  }

  std::set<Index> regions;
  for (const std::string& tag : tags_with_class(svg, "region\"")) {
    const Index r = std::stoi(attribute(tag, "data-region"));
    regions.insert(r);
    EXPECT_EQ(std::stoi(attribute(tag, "data-target")), data.region_target[r]);
    EXPECT_THAT(attribute(tag, "fill"), testing::MatchesRegex("#[0-9a-f]{6}"));
  }
  std::set<Index> expected_regions;
  for (Index r = map.regions_begin(element); r < map.regions_end(element); ++r) expected_regions.insert(r);
  EXPECT_EQ(regions, expected_regions);

  for (const auto& [kind, name] : {std::pair{GraphEdgeKind::target_edge, "graph-edge target"},
                                   std::pair{GraphEdgeKind::closure, "graph-edge closure"}}) {
    std::set<std::pair<Index, Index>> drawn;
    for (const std::string& tag : tags_with_class(svg, name))
      drawn.insert({std::stoi(attribute(tag, "data-from")), std::stoi(attribute(tag, "data-to"))});
    EXPECT_EQ(drawn, graph_edges(map, element, kind)) << name;
  }
  EXPECT_EQ(tags_with_class(svg, "legend\"").size(), 1u);
  EXPECT_EQ(tags_with_class(svg, "outline element-outline").size(), 1u);
}

// ---- element pictures --------------------------------------------------------------------------

TEST(SvgElementDrawing, EveryNodeTypeGetsItsSymbolOnEveryElement) {
  const PlMap<2> map = every_node_type_map();
  std::set<NodeType> types_seen;
  for (Index t = 0; t < map.domain().element_count(); ++t) {
    const std::string svg = draw_element_graph_svg(map, t);
    expect_well_formed(svg, "element" + std::to_string(t));
    expect_element_picture_matches(map, t, svg);
    for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n) types_seen.insert(map.data().node_type[n]);
  }
  // The fixture is meant to exercise all five symbols; if the builder changes, say so.
  EXPECT_EQ(types_seen.size(), 5u);
}

TEST(SvgElementDrawing, NeighbouringRegionsWithDifferentTargetsGetDifferentColours) {
  const PlMap<2> map = every_node_type_map();
  for (Index t = 0; t < map.domain().element_count(); ++t) {
    const std::string svg = draw_element_graph_svg(map, t);
    std::map<Index, std::string> fill;  // by region
    std::map<Index, std::set<std::string>> colours_by_target;
    for (const std::string& tag : tags_with_class(svg, "region\"")) {
      fill[std::stoi(attribute(tag, "data-region"))] = attribute(tag, "fill");
      colours_by_target[std::stoi(attribute(tag, "data-target"))].insert(attribute(tag, "fill"));
    }
    for (const auto& [target, colours] : colours_by_target)
      EXPECT_EQ(colours.size(), 1u) << "target " << target << " has several colours";
    for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) {
      for (Index other : map.data().region_neighbors[r]) {
        if (other == invalid_index || map.data().region_target[other] == map.data().region_target[r])
          continue;
        EXPECT_NE(fill[r], fill[other]) << "regions " << r << " and " << other;
      }
    }
  }
}

TEST(SvgElementDrawing, OptionsChangeWhatIsDrawn) {
  const PlMap<2> map = every_node_type_map();
  ElementDrawingOptions options;
  options.legend = false;
  options.node_labels = true;
  const std::string svg = draw_element_graph_svg(map, 0, options);
  expect_well_formed(svg, "options");
  EXPECT_TRUE(tags_with_class(svg, "legend\"").empty());
  EXPECT_EQ(tags_with_class(svg, "node-labels").size(), 1u);
  // Equilateral drawing: the three corners of the outline are equally far apart.
  const std::string outline = tags_with_class(svg, "outline element-outline").front();
  std::smatch m;
  const std::regex numbers("M([0-9.]+) ([0-9.]+)L([0-9.]+) ([0-9.]+)L([0-9.]+) ([0-9.]+)Z");
  const std::string d = attribute(outline, "d");
  ASSERT_TRUE(std::regex_match(d, m, numbers)) << d;
  const Eigen::Vector2d a(std::stod(m[1]), std::stod(m[2])), b(std::stod(m[3]), std::stod(m[4])),
      c(std::stod(m[5]), std::stod(m[6]));
  EXPECT_NEAR((a - b).norm(), (b - c).norm(), 0.02);
  EXPECT_NEAR((a - b).norm(), (c - a).norm(), 0.02);
  // Counter-clockwise on the page (y down): corner 2 above the edge from corner 0 to corner 1.
  EXPECT_LT(c.y(), a.y());
  EXPECT_LT(a.x(), b.x());
}

TEST(SvgElementDrawing, SegmentElementsOfCurves) {
  const PlMap<1> map = test_maps::builder_polyline();
  for (Index t = 0; t < map.domain().element_count(); ++t) {
    const std::string svg = draw_element_graph_svg(map, t);
    expect_well_formed(svg, "segment" + std::to_string(t));
    expect_element_picture_matches(map, t, svg);
  }
}

TEST(SvgElementDrawing, ElementsThatDoNotExistAreClearErrors) {
  const PlMap<2> map = every_node_type_map();
  for (Index bad : {Index{-1}, Index{4}, Index{1000}}) {
    try {
      (void)draw_element_graph_svg(map, bad);
      ADD_FAILURE() << "element " << bad << " was drawn";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), testing::HasSubstr("element " + std::to_string(bad)));
      EXPECT_THAT(e.what(), testing::HasSubstr("4 elements"));
    }
  }
  EXPECT_THROW((void)draw_element_graph_svg(test_maps::builder_polyline(), 3), Error);
}

// ---- whole-map views -----------------------------------------------------------------------------

/// Two horizontal, counter-clockwise triangles, one above the other, mapped onto themselves.
PlMap<2> stacked_triangles_map() {
  auto s = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
      std::vector<ElementCorners<2>>{{3, 4, 5}, {0, 1, 2}});  // upper one first
  MapBuilder<2> b(s, s);
  for (Index v = 0; v < 6; ++v) b.add_vertex_preimage_at_vertex(v, v);
  b.add_target_element(0);
  b.add_target_element(1);
  return std::move(b).finalize();
}

std::vector<std::string> face_order(const std::string& svg) {
  std::vector<std::string> order;
  for (const std::string& tag : tags_with_class(svg, "face ")) order.push_back(attribute(tag, "data-element"));
  return order;
}

TEST(SvgMapView, OneFacePerTriangleAndGraphPathsOfPreimageEdges) {
  const PlMap<2> map = every_node_type_map();
  const std::string svg = draw_map_3d_svg(map);
  expect_well_formed(svg, "view3d");
  EXPECT_EQ(tags_with_class(svg, "face ").size(), 4u);
  // Each element draws its S2-edge preimages as one path right after its face.
  std::vector<std::string> sequence;
  for (const std::string& tag : tags_with_class(svg, "")) {
    const std::string cls = attribute(tag, "class");
    if (cls.starts_with("face") || cls == "graph") sequence.push_back(cls.substr(0, 4) + attribute(tag, "data-element"));
  }
  ASSERT_EQ(sequence.size(), 8u);
  for (std::size_t i = 0; i < 8; i += 2) {
    EXPECT_EQ(sequence[i].substr(0, 4), "face");
    EXPECT_EQ(sequence[i + 1], "grap" + sequence[i].substr(4));
  }
  // Count the segments of the graph paths: every target edge of every element once.
  std::size_t segments = 0, expected = 0;
  for (const std::string& tag : tags_with_class(svg, "graph\"")) {
    const std::string d = attribute(tag, "d");
    segments += static_cast<std::size_t>(std::count(d.begin(), d.end(), 'M'));
  }
  for (Index t = 0; t < 4; ++t) expected += graph_edges(map, t, GraphEdgeKind::target_edge).size();
  EXPECT_EQ(segments, expected);
  EXPECT_TRUE(tags_with_class(svg, "graph closure").empty());

  MapViewOptions with_closure;
  with_closure.closure_edges = true;
  EXPECT_FALSE(tags_with_class(draw_map_3d_svg(map, with_closure), "graph closure").empty());
}

TEST(SvgMapView, PaintersOrderAndBackFaces) {
  const PlMap<2> map = stacked_triangles_map();
  MapViewOptions from_above;
  from_above.elevation_degrees = 60.0;
  const std::string above = draw_map_3d_svg(map, from_above);
  expect_well_formed(above, "stacked_above");
  EXPECT_EQ(face_order(above), (std::vector<std::string>{"1", "0"}));  // lower triangle first
  EXPECT_EQ(tags_with_class(above, "face front").size(), 2u);

  MapViewOptions from_below;
  from_below.elevation_degrees = -60.0;
  const std::string below = draw_map_3d_svg(map, from_below);
  EXPECT_EQ(face_order(below), (std::vector<std::string>{"0", "1"}));
  EXPECT_EQ(tags_with_class(below, "face back").size(), 2u);

  // Straight down is a valid camera too (the up direction must not degenerate).
  MapViewOptions straight_down;
  straight_down.elevation_degrees = 90.0;
  const std::string down = draw_map_3d_svg(map, straight_down);
  EXPECT_EQ(down.find("nan"), std::string::npos);
  EXPECT_EQ(face_order(down), (std::vector<std::string>{"1", "0"}));
}

TEST(SvgMapView, ElementLabelsAndUpAxis) {
  const PlMap<2> map = stacked_triangles_map();
  MapViewOptions options;
  options.element_labels = true;
  const std::string labelled = draw_map_3d_svg(map, options);
  expect_well_formed(labelled, "labelled");
  EXPECT_EQ(tags_with_class(labelled, "element-label").size(), 2u);
  EXPECT_TRUE(tags_with_class(draw_map_3d_svg(map), "element-label").empty());

  // With y up, azimuth is measured about y from +z (the cyclic permutation (x, y, z) -> (z, x, y)
  // moves y to "up"): azimuth 0, elevation 0 puts the viewer on the +z side, facing the
  // triangles, so the one at z = 1 is nearer and drawn last.
  options.up_axis = "y";
  options.elevation_degrees = 0.0;
  options.azimuth_degrees = 0.0;
  const std::string side = draw_map_3d_svg(map, options);
  EXPECT_EQ(face_order(side), (std::vector<std::string>{"1", "0"}));  // z = 1 is nearer
  // Upside down (-y): the corner (0, 1, 1) of element 0 is above corner (0, 0, 1) with y up
  // and below it with -y up (SVG y grows downwards).
  const auto corner_heights = [](const std::string& svg) {
    for (const std::string& tag : tags_with_class(svg, "face "))
      if (attribute(tag, "data-element") == "0") {
        std::smatch m;
        const std::string d = attribute(tag, "d");
        const std::regex numbers("M[-0-9.]+ ([-0-9.]+)L[-0-9.]+ [-0-9.]+L[-0-9.]+ ([-0-9.]+)Z");
        if (std::regex_match(d, m, numbers)) return std::pair{std::stod(m[1]), std::stod(m[2])};
      }
    ADD_FAILURE() << "no face path for element 0";
    return std::pair{0.0, 0.0};
  };
  const auto [low_y, high_y] = corner_heights(side);
  EXPECT_LT(high_y, low_y - 10.0);
  options.up_axis = "-y";
  const std::string flipped = draw_map_3d_svg(map, options);
  const auto [low_flipped, high_flipped] = corner_heights(flipped);
  EXPECT_GT(high_flipped, low_flipped + 10.0);
  EXPECT_EQ(tags_with_class(flipped, "face front").size(), 2u);  // a rotation, not a mirror
  for (const char* bad : {"w", "", "--y", "yy", "+"}) {
    options.up_axis = bad;
    EXPECT_THROW((void)draw_map_3d_svg(map, options), Error) << bad;
  }
}

TEST(SvgMapView, CurvesInThePlane) {
  const PlMap<1> map = test_maps::builder_polyline();
  const std::string svg = draw_map_view_svg(map);
  expect_well_formed(svg, "curves");
  EXPECT_EQ(tags_with_class(svg, "domain-curve\"").size(), 2u);  // the curve and its legend sample
  EXPECT_EQ(tags_with_class(svg, "target-curve\"").size(), 2u);
  // One symbol per distinct node position: S1 vertices 0..3 and the interior node on segment 1.
  std::size_t symbols = 0;
  std::map<std::string, int> by_type;
  for (const std::string& tag : tags_with_class(svg, "node "))
    if (!attribute(tag, "data-node").empty()) ++symbols, ++by_type[attribute(tag, "class")];
  EXPECT_EQ(symbols, 5u);
  EXPECT_EQ(by_type["node ghost"], 2);
  EXPECT_EQ(by_type["node corner"], 2);
  EXPECT_EQ(by_type["node interior"], 1);
  EXPECT_EQ(tags_with_class(svg, "correspondence\"").size(), 5u + 1u);  // + legend sample
}

TEST(SvgFile, WrittenAtomicallyWithExactlyTheText) {
  const auto dir = std::filesystem::path(PLMAP_TEST_BINARY_DIR) / "svg_scratch";
  std::filesystem::create_directories(dir);
  const auto file = dir / "exact.svg";
  const std::string svg = draw_element_graph_svg(test_maps::builder_square_flip(), 1);
  write_svg_file(file, svg);
  std::ifstream in(file, std::ios::binary);
  const std::string back((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(back, svg);
  EXPECT_THROW(write_svg_file(dir / "no-such-dir" / "x.svg", svg), Error);
}

}  // namespace
}  // namespace plmap
