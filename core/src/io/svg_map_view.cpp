// Views of a whole map as SVG: S1 in 3-D with the preimage of S2's edge graph (paper Fig. 2),
// and for d = 1 the two curves in the plane with the node correspondence (paper Fig. 1).

#include "plmap/core/io/svg_drawing.hpp"

#include "plmap/core/errors.hpp"
#include "svg_support.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <set>
#include <vector>

namespace plmap {
namespace {

constexpr double title_height = 30.0;

/// An orthographic camera looking at the centre of a bounding box, and the pixel frame that fits
/// the projected points into the image.
struct Camera {
  Eigen::Vector3d centre, right, up, toward_viewer;
  double scale = 1.0;            // pixels per world unit
  double offset_x = 0.0, offset_y = 0.0;  // pixel position of the projected centre

  /// `centre` in world coordinates; `up_axis` 0, 1 or 2, `up_sign` +1 or -1.
  static Camera looking_from(double azimuth_degrees, double elevation_degrees,
                             const Eigen::Vector3d& world_centre, int up_axis = 2,
                             double up_sign = 1.0) {
    const double a = azimuth_degrees * std::numbers::pi / 180.0;
    const double e = elevation_degrees * std::numbers::pi / 180.0;
    Camera c;
    c.up_axis = up_axis;
    c.up_sign = up_sign;
    c.centre = c.permuted(world_centre);
    c.toward_viewer = Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
    const Eigen::Vector3d forward = -c.toward_viewer;
    // World z is "up" in the picture, except when looking straight down or up, where the
    // horizontal direction away from the viewer's azimuth takes its place.
    Eigen::Vector3d up_hint(0.0, 0.0, 1.0);
    if (forward.cross(up_hint).norm() < 1e-9)
      up_hint = (e > 0 ? -1.0 : 1.0) * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
    c.right = forward.cross(up_hint).normalized();
    c.up = c.right.cross(forward).normalized();
    return c;
  }

  /// Which world coordinate plays the role of "up" (z after the rotation below), and whether
  /// it points down (-x, -y, -z).
  int up_axis = 2;
  double up_sign = 1.0;

  /// World coordinates with the up axis moved to z by a cyclic permutation, followed for a
  /// negative axis by a half turn about the new x axis. Both are rotations, so front and back
  /// faces stay what they are.
  Eigen::Vector3d permuted(const Eigen::Vector3d& x) const {
    return {x((up_axis + 1) % 3), up_sign * x((up_axis + 2) % 3), up_sign * x(up_axis)};
  }

  /// Screen coordinates before framing (world units) and depth (larger = nearer the viewer).
  Eigen::Vector3d view(const Eigen::Vector3d& world) const {
    const Eigen::Vector3d r = permuted(world) - centre;
    return {r.dot(right), r.dot(up), r.dot(toward_viewer)};
  }
  /// Pixel position (y grows downwards in SVG).
  Eigen::Vector2d pixel(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d v = view(x);
    return {offset_x + scale * v.x(), offset_y - scale * v.y()};
  }

  /// Chooses scale and offset so that the projected points fill [x0, x1] x [y0, y1].
  template <class Points>
  void frame(const Points& points, double x0, double y0, double x1, double y1) {
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector2d hi = -lo;
    for (const auto& p : points) {
      const Eigen::Vector3d v = view(p);
      lo = lo.cwiseMin(v.head<2>());
      hi = hi.cwiseMax(v.head<2>());
    }
    if (!std::isfinite(lo.x())) lo = hi = Eigen::Vector2d::Zero();
    const Eigen::Vector2d extent = (hi - lo).cwiseMax(1e-300);
    scale = std::min((x1 - x0) / extent.x(), (y1 - y0) / extent.y());
    if (!std::isfinite(scale) || scale <= 0) scale = 1.0;
    const Eigen::Vector2d mid = 0.5 * (lo + hi);
    offset_x = 0.5 * (x0 + x1) - scale * mid.x();
    offset_y = 0.5 * (y0 + y1) + scale * mid.y();
  }
};

std::string hex_colour(const Eigen::Vector3d& rgb) {
  const auto channel = [](double c) { return static_cast<int>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); };
  return fmt::format("#{:02x}{:02x}{:02x}", channel(rgb.x()), channel(rgb.y()), channel(rgb.z()));
}

/// Median of the projected lengths of the S2-edge preimages, in pixels; the automatic line width
/// follows it so that dense graphs do not turn into a black smear.
double median_graph_edge_pixels(const PlMap<2>& map, const Camera& camera) {
  const MapData<2>& data = map.data();
  std::vector<double> lengths;
  for (Index n = 0; n < map.node_count(); ++n) {
    for (Index k = data.neighbor_begin[n]; k < data.neighbor_begin[n + 1]; ++k) {
      const Index m = data.neighbor[k];
      if (m <= n || data.neighbor_edge_kind[k] != GraphEdgeKind::target_edge) continue;
      const Eigen::Vector3d a = map.node_domain_world(n), b = map.node_domain_world(m);
      lengths.push_back(camera.scale * (a - b).norm());
    }
  }
  if (lengths.empty()) return 0.0;
  auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), mid, lengths.end());
  return *mid;
}

void legend_box(svg::Writer& w, double x, double y, double width, int rows) {
  w.rect(x, y, width, 20.0 * rows + 16.0, "legend-box");
}

}  // namespace

std::string draw_map_3d_svg(const PlMap<2>& map, const MapViewOptions& options) {
  const Surface<2>& s1 = map.domain();
  const MapData<2>& data = map.data();
  const double width = options.width, height = options.height;
  const std::string& up = options.up_axis;
  const bool negative = up.size() == 2 && up[0] == '-';
  const char axis = up.empty() ? '?' : up.back();
  if (up.size() != (negative ? 2u : 1u) || axis < 'x' || axis > 'z')
    throw Error(fmt::format("up axis '{}' is not one of x, y, z, -x, -y, -z", up));
  const Eigen::Vector3d centre = 0.5 * (s1.bounding_box_min() + s1.bounding_box_max());
  Camera camera = Camera::looking_from(options.azimuth_degrees, options.elevation_degrees, centre,
                                       axis - 'x', negative ? -1.0 : 1.0);
  const double legend_height = options.legend ? 116.0 : 0.0;
  camera.frame(s1.vertices(), options.margin, title_height + options.margin, width - options.margin,
               height - options.margin - legend_height);

  double graph_width = options.graph_line_width;
  if (graph_width <= 0.0)
    graph_width = std::clamp(0.05 * median_graph_edge_pixels(map, camera), 0.4, 1.4);
  const double domain_edge_width = 1.25 * graph_width;

  // Light from above-left of the viewer; Lambert term on the side of the face the viewer sees.
  const Eigen::Vector3d light =
      (camera.toward_viewer + 0.55 * camera.up - 0.35 * camera.right).normalized();
  const Eigen::Vector3d front_colour(0.93, 0.80, 0.60), back_colour(0.55, 0.62, 0.74);

  struct Face {
    Index element;
    double depth;
  };
  std::vector<Face> faces;
  faces.reserve(static_cast<std::size_t>(s1.element_count()));
  for (Index t = 0; t < s1.element_count(); ++t) {
    const Eigen::Vector3d centroid = (s1.corner(t, 0) + s1.corner(t, 1) + s1.corner(t, 2)) / 3.0;
    faces.push_back({t, camera.view(centroid).z()});
  }
  // Back to front; ties by element index so the output is deterministic.
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) {
    return a.depth != b.depth ? a.depth < b.depth : a.element < b.element;
  });

  svg::Writer w(width, height);
  w.style(fmt::format(
      ".face{{stroke-width:0.6;stroke-linejoin:round}}\n"
      ".domain-edges{{fill:none;stroke:#a5322a;stroke-width:{3:.2f};stroke-linejoin:round;"
      "stroke-opacity:0.9}}\n"
      ".element-label{{font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;font-size:12px;"
      "font-weight:bold;fill:#0b3d91;stroke:#ffffff;stroke-width:2.5;paint-order:stroke}}\n"
      ".legend-domain{{stroke:#a5322a;stroke-width:2.5}}\n"
      ".graph{{fill:none;stroke:#1b1b1b;stroke-width:{0:.2f};stroke-linecap:round}}\n"
      ".graph.closure{{stroke:#555555;stroke-width:{1:.2f};stroke-dasharray:{2:.2f} {2:.2f}}}\n"
      ".legend-graph{{stroke:#1b1b1b;stroke-width:2}}\n"
      ".label{{font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;font-size:12px;fill:#1b1b1b}}\n"
      ".title{{font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;font-size:14px;"
      "font-weight:bold;fill:#1b1b1b}}\n"
      ".legend-box{{fill:#ffffff;fill-opacity:0.9;stroke:#b0b0b0;stroke-width:1}}\n",
      graph_width, 0.5 * graph_width, 2.5 * graph_width, domain_edge_width));
  w.background(width, height);
  w.text(options.margin, 22.0,
         fmt::format("S1: {} triangles with the preimage of the edge graph of S2 ({} triangles)",
                     s1.element_count(), map.target().element_count()),
         "title");

  w.raw("<g class=\"surface\">\n");
  std::string path;
  for (const Face& f : faces) {
    const Index t = f.element;
    const Eigen::Vector3d p0 = s1.corner(t, 0), p1 = s1.corner(t, 1), p2 = s1.corner(t, 2);
    Eigen::Vector3d normal = camera.permuted((p1 - p0).cross(p2 - p0));
    const double norm = normal.norm();
    if (norm > 0) normal /= norm;
    const bool front = normal.dot(camera.toward_viewer) >= 0.0;
    const Eigen::Vector3d seen_normal = front ? normal : Eigen::Vector3d(-normal);
    const double lambert = std::max(0.0, seen_normal.dot(light));
    const Eigen::Vector3d fill = (front ? front_colour : back_colour) * (0.38 + 0.62 * lambert);
    // The stroke in the fill colour closes the hairline seams that anti-aliasing leaves
    // between neighbouring polygons.
    const auto a = camera.pixel(p0), b = camera.pixel(p1), c = camera.pixel(p2);
    const std::string triangle = fmt::format("M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z", a.x(),
                                             a.y(), b.x(), b.y(), c.x(), c.y());
    w.raw(fmt::format("<path class=\"face {}\" data-element=\"{}\" fill=\"{}\" stroke=\"{}\" d=\"{}\"/>\n",
                      front ? "front" : "back", t, hex_colour(fill), hex_colour(fill), triangle));

    // This triangle's graph edges, right after it: nearer triangles drawn later cover them.
    for (const GraphEdgeKind kind : {GraphEdgeKind::closure, GraphEdgeKind::target_edge}) {
      if (kind == GraphEdgeKind::closure && !options.closure_edges) continue;
      path.clear();
      for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n) {
        for (Index k = data.neighbor_begin[n]; k < data.neighbor_begin[n + 1]; ++k) {
          const Index m = data.neighbor[k];
          if (m <= n || data.neighbor_edge_kind[k] != kind) continue;
          const auto u = camera.pixel(map.node_domain_world(n));
          const auto v = camera.pixel(map.node_domain_world(m));
          fmt::format_to(std::back_inserter(path), "M{:.2f} {:.2f}L{:.2f} {:.2f}", u.x(), u.y(),
                         v.x(), v.y());
        }
      }
      if (!path.empty())
        w.raw(fmt::format("<path class=\"graph{}\" data-element=\"{}\" d=\"{}\"/>\n",
                          kind == GraphEdgeKind::closure ? " closure" : "", t, path));
    }
    if (options.domain_edges)
      w.raw(fmt::format("<path class=\"domain-edges\" data-element=\"{}\" d=\"{}\"/>\n", t, triangle));
    if (options.element_labels) {
      const Eigen::Vector2d centroid = (a + b + c) / 3.0;
      w.text(centroid.x(), centroid.y() + 4.0, fmt::format("{}", t), "element-label", "middle");
    }
  }
  w.raw("</g>\n");

  if (options.legend) {
    const double x = options.margin, y = height - options.margin - legend_height + 12.0;
    w.raw("<g class=\"legend\">\n");
    legend_box(w, x, y, 330.0, options.domain_edges ? 4 : 3);
    double row = y + 18.0;
    w.line(x + 10.0, row, x + 40.0, row, "legend-graph");
    w.text(x + 50.0, row + 4.0, "preimage of an S2 edge (graph edge)", "label");
    row += 20.0;
    if (options.domain_edges) {
      w.line(x + 10.0, row, x + 40.0, row, "legend-domain");
      w.text(x + 50.0, row + 4.0, "edge of an S1 triangle", "label");
      row += 20.0;
    }
    w.rect(x + 10.0, row - 7.0, 30.0, 14.0, "legend-swatch",
           fmt::format(" fill=\"{}\" stroke=\"#555555\" stroke-width=\"0.6\"", hex_colour(front_colour * 0.9)));
    w.text(x + 50.0, row + 4.0, "S1 triangle, front side", "label");
    row += 20.0;
    w.rect(x + 10.0, row - 7.0, 30.0, 14.0, "legend-swatch",
           fmt::format(" fill=\"{}\" stroke=\"#555555\" stroke-width=\"0.6\"", hex_colour(back_colour * 0.9)));
    w.text(x + 50.0, row + 4.0, "S1 triangle seen from behind", "label");
    w.text(width - options.margin, height - options.margin,
           fmt::format("azimuth {:g}\u00b0, elevation {:g}\u00b0", options.azimuth_degrees,
                       options.elevation_degrees),
           "label", "end");
    w.raw("</g>\n");
  }
  return w.finish();
}

std::string draw_map_curves_svg(const PlMap<1>& map, const MapViewOptions& options) {
  const Surface<1>& s1 = map.domain();
  const Surface<1>& s2 = map.target();
  const MapData<1>& data = map.data();
  const double width = options.width, height = options.height;

  // The plane seen from above: embed (x, y) as (x, y, 0) and look straight down.
  const auto lift = [](const WorldPoint<1>& p) { return Eigen::Vector3d(p.x(), p.y(), 0.0); };
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : s1.vertices()) points.push_back(lift(p));
  for (const auto& p : s2.vertices()) points.push_back(lift(p));
  Camera camera = Camera::looking_from(-90.0, 90.0, Eigen::Vector3d::Zero());
  const double legend_height = options.legend ? 136.0 : 0.0;
  camera.frame(points, options.margin, title_height + options.margin, width - options.margin,
               height - options.margin - legend_height);

  svg::Writer w(width, height);
  w.style(std::string(svg::node_css) +
          ".domain-curve{fill:none;stroke:#2f6db5;stroke-width:3;stroke-linecap:round}\n"
          ".target-curve{fill:none;stroke:#d9822b;stroke-width:3;stroke-linecap:round}\n"
          ".target-vertex{fill:#d9822b}\n"
          ".correspondence{stroke:#7a7a7a;stroke-width:1;stroke-dasharray:4 3}\n");
  w.background(width, height);
  w.text(options.margin, 22.0,
         fmt::format("S1 ({} segments, blue) and S2 ({} segments, orange); nodes on S1 and their images",
                     s1.element_count(), s2.element_count()),
         "title");

  std::string path;
  const auto polyline = [&](const Surface<1>& s, std::string_view css_class) {
    path.clear();
    for (Index t = 0; t < s.element_count(); ++t) {
      const auto a = camera.pixel(lift(s.corner(t, 0))), b = camera.pixel(lift(s.corner(t, 1)));
      fmt::format_to(std::back_inserter(path), "M{:.2f} {:.2f}L{:.2f} {:.2f}", a.x(), a.y(), b.x(), b.y());
    }
    w.raw(fmt::format("<path class=\"{}\" d=\"{}\"/>\n", css_class, path));
  };
  polyline(s2, "target-curve");
  polyline(s1, "domain-curve");
  for (const auto& v : s2.vertices()) {
    const auto p = camera.pixel(lift(v));
    w.raw(fmt::format("<circle class=\"target-vertex\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3\"/>\n", p.x(), p.y()));
  }

  // One symbol per node position on S1: the copies of a node at a shared vertex (one per
  // incident segment) are drawn once.
  std::set<std::pair<long long, long long>> drawn;
  std::vector<Index> shown;
  for (Index n = 0; n < map.node_count(); ++n) {
    const auto p = camera.pixel(lift(map.node_domain_world(n)));
    const auto key = std::pair{std::llround(p.x() * 100.0), std::llround(p.y() * 100.0)};
    if (drawn.insert(key).second) shown.push_back(n);
  }
  w.raw("<g class=\"correspondences\">\n");
  for (Index n : shown) {
    const auto a = camera.pixel(lift(map.node_domain_world(n)));
    const auto b = camera.pixel(lift(map.node_target_world(n)));
    w.line(a.x(), a.y(), b.x(), b.y(), "correspondence");
  }
  w.raw("</g>\n<g class=\"nodes\">\n");
  for (Index n : shown) {
    const auto p = camera.pixel(lift(map.node_domain_world(n)));
    w.node_symbol(data.node_type[n], p.x(), p.y(), 5.0, fmt::format(" data-node=\"{}\"", n));
  }
  w.raw("</g>\n");

  if (options.legend) {
    const double x = options.margin, y = height - options.margin - legend_height + 8.0;
    w.raw("<g class=\"legend\">\n");
    legend_box(w, x, y, 330.0, 6);
    double row = y + 18.0;
    w.line(x + 10.0, row, x + 40.0, row, "domain-curve");
    w.text(x + 50.0, row + 4.0, "S1 (domain)", "label");
    row += 20.0;
    w.line(x + 10.0, row, x + 40.0, row, "target-curve");
    w.text(x + 50.0, row + 4.0, "S2 (target), dots at its vertices", "label");
    row += 20.0;
    w.line(x + 10.0, row, x + 40.0, row, "correspondence");
    w.text(x + 50.0, row + 4.0, "node on S1 -> its image on S2", "label");
    row += 20.0;
    for (NodeType t : {NodeType::corner, NodeType::ghost, NodeType::interior}) {
      w.node_symbol(t, x + 25.0, row, 5.0, " data-legend=\"1\"");
      w.text(x + 50.0, row + 4.0, svg::node_type_description(t), "label");
      row += 20.0;
    }
    w.raw("</g>\n");
  }
  return w.finish();
}

}  // namespace plmap
