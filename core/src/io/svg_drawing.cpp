// The plane graph on one S1 element as SVG (paper Fig. 3), and writing SVG files.

#include "plmap/core/io/svg_drawing.hpp"

#include "plmap/core/errors.hpp"
#include "plmap/core/io/atomic_file.hpp"
#include "svg_support.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <ostream>
#include <vector>

namespace plmap {
namespace {

constexpr double margin = 48.0;       // room for the corner labels around the element
constexpr double title_height = 34.0;
constexpr double legend_width = 300.0;
constexpr double legend_line = 20.0;  // height of one legend entry
constexpr int max_legend_targets = 12;

template <int d>
void require_element(const PlMap<d>& map, Index element) {
  const Index count = map.domain().element_count();
  if (element >= 0 && element < count) return;
  if (count == 0) throw Error(fmt::format("element {} does not exist: S1 has no elements", element));
  throw Error(fmt::format("element {} does not exist: S1 has {} elements, numbered 0 to {}",
                          element, count, count - 1));
}

/// Where local coordinates land in the picture. d = 2: the reference triangle drawn
/// equilateral, corner 0 bottom left, corner 1 bottom right, corner 2 on top (counter-clockwise,
/// like the local coordinates, so the picture is not mirrored). d = 1: a horizontal segment.
template <int d>
struct ElementFrame {
  double side;          // length of a side (d = 2) / of the segment (d = 1) in pixels
  double left, bottom;  // picture position of corner 0

  Eigen::Vector2d operator()(const LocalPoint<d>& xi) const {
    if constexpr (d == 2) {
      return {left + side * (xi(0) + 0.5 * xi(1)), bottom - side * (0.5 * std::sqrt(3.0)) * xi(1)};
    } else {
      return {left + side * xi(0), bottom};
    }
  }
};

/// Colour per target element. All regions onto one S2 element share a colour; targets whose
/// regions touch get different colours (greedy colouring of the target adjacency, in order of
/// first appearance), so that twelve colours suffice for busy elements too.
template <int d>
std::map<Index, std::string_view> region_colours(const PlMap<d>& map, Index element) {
  const MapData<d>& data = map.data();
  std::vector<Index> order;
  std::map<Index, std::set<Index>> touching;
  for (Index r = map.regions_begin(element); r < map.regions_end(element); ++r) {
    const Index target = data.region_target[r];
    if (touching.emplace(target, std::set<Index>{}).second) order.push_back(target);
    for (Index other : data.region_neighbors[r]) {
      if (other == invalid_index || data.region_target[other] == target) continue;
      touching[target].insert(data.region_target[other]);
    }
  }
  std::map<Index, std::size_t> index;
  std::array<std::size_t, svg::region_palette.size()> uses{};
  for (Index target : order) {
    std::set<std::size_t> used;
    for (Index other : touching[target])
      if (auto it = index.find(other); it != index.end()) used.insert(it->second);
    // Among the colours its neighbours do not use, the least used so far: neighbours differ
    // and the picture uses the whole palette before repeating a colour.
    std::size_t best = 0, best_uses = std::numeric_limits<std::size_t>::max();
    for (std::size_t c = 0; c < svg::region_palette.size(); ++c) {
      if (used.count(c) != 0) continue;
      if (uses[c] < best_uses) best = c, best_uses = uses[c];
    }
    index[target] = best;
    ++uses[best];
  }
  std::map<Index, std::string_view> colour;
  for (const auto& [target, c] : index) colour[target] = svg::region_palette[c];
  return colour;
}

/// The legend: node symbols of the types that can occur for this d, the two line styles, the
/// outline and the region colours. Returns its height.
template <int d>
double draw_legend(svg::Writer& w, double x, double y, double radius,
                   const std::map<Index, std::string_view>& colours, bool filled_regions) {
  std::vector<NodeType> types;
  if constexpr (d == 2)
    types = {NodeType::corner, NodeType::touching, NodeType::intersection, NodeType::ghost,
             NodeType::interior};
  else
    types = {NodeType::corner, NodeType::ghost, NodeType::interior};

  const int target_rows =
      filled_regions ? std::min<int>(static_cast<int>(colours.size()), max_legend_targets) +
                           (colours.size() > static_cast<std::size_t>(max_legend_targets) ? 1 : 0)
                     : 0;
  const int rows = static_cast<int>(types.size()) + 3 + (filled_regions ? 1 + target_rows : 0);
  const double height = legend_line * rows + 2 * 12.0;
  w.raw("<g class=\"legend\">\n");
  w.rect(x, y, legend_width - 16.0, height, "legend-box");
  double row_y = y + 12.0 + 0.5 * legend_line;
  const double symbol_x = x + 22.0;
  const double text_x = x + 44.0;
  for (NodeType t : types) {
    w.node_symbol(t, symbol_x, row_y, radius, " data-legend=\"1\"");
    w.text(text_x, row_y + 4.0, svg::node_type_description(t), "label");
    row_y += legend_line;
  }
  w.line(symbol_x - 14.0, row_y, symbol_x + 14.0, row_y, "legend-sample target-line");
  w.text(text_x, row_y + 4.0, "preimage of an S2 edge", "label");
  row_y += legend_line;
  w.line(symbol_x - 14.0, row_y, symbol_x + 14.0, row_y, "legend-sample closure-line");
  w.text(text_x, row_y + 4.0, "closure edge (added)", "label");
  row_y += legend_line;
  w.line(symbol_x - 14.0, row_y, symbol_x + 14.0, row_y, "legend-sample outline-line");
  w.text(text_x, row_y + 4.0, "boundary of the S1 element", "label");
  row_y += legend_line;
  if (filled_regions) {
    w.text(x + 10.0, row_y + 4.0, "region colour = S2 element:", "label");
    row_y += legend_line;
    int shown = 0;
    for (const auto& [target, colour] : colours) {
      if (shown == max_legend_targets) {
        w.text(text_x, row_y + 4.0, fmt::format("... ({} more)", colours.size() - shown), "label");
        break;
      }
      w.rect(symbol_x - 12.0, row_y - 7.0, 24.0, 14.0, "legend-swatch",
             fmt::format(" fill=\"{}\"", colour));
      w.text(text_x, row_y + 4.0, fmt::format("S2 element {}", target), "label");
      row_y += legend_line;
      ++shown;
    }
  }
  w.raw("</g>\n");
  return height;
}

constexpr std::string_view element_css =
    ".region{stroke:none}\n"
    ".outline{fill:none;stroke:#7a7a7a;stroke-width:2.5;stroke-linejoin:round}\n"
    ".graph-edge.target{stroke:#1b1b1b;stroke-width:2.2;stroke-linecap:round}\n"
    ".graph-edge.closure{stroke:#6f6f6f;stroke-width:1;stroke-dasharray:5 4}\n"
    ".legend-sample.target-line{stroke:#1b1b1b;stroke-width:2.2}\n"
    ".legend-sample.closure-line{stroke:#6f6f6f;stroke-width:1;stroke-dasharray:5 4}\n"
    ".legend-sample.outline-line{stroke:#7a7a7a;stroke-width:2.5}\n"
    ".legend-swatch{stroke:#9a9a9a;stroke-width:0.5}\n"
    ".band{stroke:none}\n";

}  // namespace

template <int d>
std::string draw_element_graph_svg(const PlMap<d>& map, Index element,
                                   const ElementDrawingOptions& options) {
  require_element(map, element);
  const MapData<d>& data = map.data();
  const double side = std::max(options.element_width - 2 * margin, 50.0);
  const double element_height = d == 2 ? side * 0.5 * std::sqrt(3.0) : 60.0;
  const auto colours = region_colours(map, element);
  const Index node_begin = map.nodes_begin(element), node_end = map.nodes_end(element);
  const Index region_begin = map.regions_begin(element), region_end = map.regions_end(element);

  // The legend may be taller than the element (d = 1, many targets): size the canvas for both.
  const int legend_rows = (d == 2 ? 5 : 3) + 3 +
                          (options.fill_regions ? 1 + std::min<int>(static_cast<int>(colours.size()),
                                                                    max_legend_targets + 1)
                                                : 0);
  const double legend_height = options.legend ? legend_line * legend_rows + 24.0 : 0.0;
  const double body_height = std::max(element_height + 2 * margin, legend_height + margin);
  const double width = side + 2 * margin + (options.legend ? legend_width : 0.0);
  const double height = title_height + body_height;
  const ElementFrame<d> frame{side, margin,
                              title_height + (d == 2 ? margin + element_height : margin + 30.0)};

  svg::Writer w(width, height);
  w.style(std::string(svg::node_css) + std::string(element_css));
  w.background(width, height);

  const auto& corners = map.domain().element(element);
  std::string corner_list;
  for (int k = 0; k <= d; ++k) corner_list += fmt::format("{}{}", k ? ", " : "", corners[k]);
  w.text(margin * 0.5, 22.0,
         fmt::format("S1 element {} (vertices {}): {} nodes, {} regions onto {} S2 element{}",
                     element, corner_list, node_end - node_begin, region_end - region_begin,
                     colours.size(), colours.size() == 1 ? "" : "s"),
         "title");
  if (node_begin == node_end)
    w.text(margin * 0.5, title_height + 12.0, "(outside the domain D of the map: no graph here)",
           "label");

  // Regions first, so that everything else is drawn on top of them.
  w.raw(fmt::format("<g class=\"regions\"{}>\n", options.fill_regions ? "" : " display=\"none\""));
  for (Index r = region_begin; r < region_end; ++r) {
    const auto& rc = data.region_corners[r];
    const std::string_view fill = colours.at(data.region_target[r]);
    if constexpr (d == 2) {
      const auto a = frame(data.node_position[rc[0]]), b = frame(data.node_position[rc[1]]),
                 c = frame(data.node_position[rc[2]]);
      w.raw(fmt::format("<path class=\"region\" data-region=\"{}\" data-target=\"{}\" fill=\"{}\" "
                        "d=\"M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z\"/>\n",
                        r, data.region_target[r], fill, a.x(), a.y(), b.x(), b.y(), c.x(), c.y()));
    } else {
      const auto a = frame(data.node_position[rc[0]]), b = frame(data.node_position[rc[1]]);
      const double half = 16.0;
      w.raw(fmt::format("<path class=\"region\" data-region=\"{}\" data-target=\"{}\" fill=\"{}\" "
                        "d=\"M{:.2f} {:.2f}H{:.2f}V{:.2f}H{:.2f}Z\"/>\n",
                        r, data.region_target[r], fill, a.x(), a.y() - half, b.x(), a.y() + half,
                        a.x()));
    }
  }
  w.raw("</g>\n");

  // The element boundary (its pieces are also graph edges, drawn over it below).
  if constexpr (d == 2) {
    const auto a = frame(reference_corner<2>(0)), b = frame(reference_corner<2>(1)),
               c = frame(reference_corner<2>(2));
    w.raw(fmt::format("<path class=\"outline element-outline\" d=\"M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z\"/>\n",
                      a.x(), a.y(), b.x(), b.y(), c.x(), c.y()));
  } else {
    const auto a = frame(reference_corner<1>(0)), b = frame(reference_corner<1>(1));
    w.line(a.x(), a.y(), b.x(), b.y(), "outline element-outline");
  }

  // Graph edges: closure edges first, so the S2-edge preimages are never hidden under dashes.
  for (const GraphEdgeKind pass : {GraphEdgeKind::closure, GraphEdgeKind::target_edge}) {
    w.raw(fmt::format("<g class=\"graph-edges {}\">\n",
                      pass == GraphEdgeKind::closure ? "closure" : "target"));
    for (Index n = node_begin; n < node_end; ++n) {
      for (Index k = data.neighbor_begin[n]; k < data.neighbor_begin[n + 1]; ++k) {
        const Index m = data.neighbor[k];
        if (m <= n || data.neighbor_edge_kind[k] != pass) continue;  // each edge once
        const auto a = frame(data.node_position[n]), b = frame(data.node_position[m]);
        w.line(a.x(), a.y(), b.x(), b.y(),
               pass == GraphEdgeKind::closure ? "graph-edge closure" : "graph-edge target",
               fmt::format(" data-from=\"{}\" data-to=\"{}\"", n, m));
      }
    }
    w.raw("</g>\n");
  }

  // Corner labels: below the two bottom corners (flush with them, so they stay inside the
  // picture), above the top one.
  for (int k = 0; k <= d; ++k) {
    const Eigen::Vector2d p = frame(reference_corner<d>(k));
    const bool top = d == 2 && k == 2;
    const double x = top ? p.x() : (k == 0 ? p.x() - 8.0 : p.x() + 8.0);
    const double y = top ? p.y() - 14.0 : p.y() + (d == 1 ? 40.0 : 26.0);
    w.text(x, y, fmt::format("corner {} = vertex {}", k, corners[k]), "label small",
           top ? "middle" : (k == 0 ? "start" : "end"));
  }

  // Nodes last, on top of all lines.
  w.raw("<g class=\"nodes\">\n");
  for (Index n = node_begin; n < node_end; ++n) {
    const auto p = frame(data.node_position[n]);
    w.node_symbol(data.node_type[n], p.x(), p.y(), options.node_radius,
                  fmt::format(" data-node=\"{}\" data-target=\"{}\"", n, data.node_target[n]));
  }
  w.raw("</g>\n");
  if (options.node_labels) {
    w.raw("<g class=\"node-labels\">\n");
    for (Index n = node_begin; n < node_end; ++n) {
      const auto p = frame(data.node_position[n]);
      w.text(p.x() + options.node_radius + 2.0, p.y() - options.node_radius - 1.0,
             fmt::format("{}", n), "label small");
    }
    w.raw("</g>\n");
  }

  if (options.legend)
    draw_legend<d>(w, side + 2 * margin, title_height + 8.0, options.node_radius, colours,
                   options.fill_regions);
  return w.finish();
}

template std::string draw_element_graph_svg(const PlMap<1>&, Index, const ElementDrawingOptions&);
template std::string draw_element_graph_svg(const PlMap<2>&, Index, const ElementDrawingOptions&);

void write_svg_file(const std::filesystem::path& path, const std::string& svg) {
  write_file_atomically(path, [&](std::ostream& out) { out << svg; }, false);
}

}  // namespace plmap
