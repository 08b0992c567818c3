#pragma once
/// \file
/// Pictures of a map as SVG text: the plane graph on one S1 element (paper Fig. 3) and a view of
/// the whole of S1 with the preimage of S2's edge graph drawn on it (paper Figs. 1 and 2).
///
/// The SVG is self-contained (no scripts, no external fonts or style sheets) and machine
/// readable: every drawn item carries a class naming what it is, so tests and scripts can count
/// and restyle them.
///   - element picture: `region` (one path per region, `data-region`, `data-target` = S2 element),
///     `graph-edge target` / `graph-edge closure` (one line per graph edge, `data-from`,
///     `data-to` = node indices), `node <type>` (one symbol per node, `data-node`, type one of
///     corner, touching, intersection, ghost, interior), `element-outline`, `legend`;
///   - d = 2 view: `face front` / `face back` (one polygon per S1 element, `data-element`) each
///     followed by its `graph` path (the element's S2-edge preimages), `legend`;
///   - d = 1 view: `domain-curve`, `target-curve`, `correspondence` (node -> image lines) and one
///     `node <type>` symbol per distinct node position on S1.
/// Coordinates are printed with two decimals (a hundredth of a pixel).

#include <plmap/core/pl_map.hpp>

#include <filesystem>
#include <string>

namespace plmap {

/// Options of draw_element_graph_svg. Sizes are in SVG pixels.
struct ElementDrawingOptions {
  /// Width of the drawing of the element itself (the legend is added to the right of it).
  double element_width = 560.0;
  /// Radius of the node symbols (squares and diamonds get the same visual weight).
  double node_radius = 6.0;
  /// Draw the legend explaining symbols, line styles and region colours.
  bool legend = true;
  /// Write each node's index next to its symbol (useful for debugging a map by hand).
  bool node_labels = false;
  /// Fill the regions lightly, one colour per target (S2) element.
  bool fill_regions = true;
};

/// The plane graph on S1 element `element` in its local (reference) coordinates, drawn like
/// paper Fig. 3. For d = 2 the reference triangle is drawn equilateral (an affine image of the
/// local coordinates, so straight lines stay straight and the picture looks like a triangle);
/// corner k of the element is labelled with its S1 vertex. Graph edges that are preimages of S2
/// edges are solid, edges of the triangular closure thin and dashed; regions are filled by target
/// element; nodes get symbols by type: corner filled disc, touching open square, intersection
/// filled diamond, ghost open circle, interior small dot. For d = 1 the element is a horizontal
/// segment with the nodes on it and the regions as coloured bands.
/// Throws plmap::Error if `element` is not an element of the map's domain.
template <int d>
std::string draw_element_graph_svg(const PlMap<d>& map, Index element,
                                   const ElementDrawingOptions& options = {});

/// Options of draw_map_3d_svg / draw_map_curves_svg.
struct MapViewOptions {
  /// Camera direction: the viewer looks at the centre of the bounding box from azimuth (degrees,
  /// counter-clockwise about +z from +x) and elevation (degrees above the xy plane). For d = 1
  /// (plane curves) the camera is ignored.
  double azimuth_degrees = 35.0;
  double elevation_degrees = 25.0;
  /// The world axis that points up in the picture: "x", "y", "z", "-x", "-y" or "-z" (many
  /// meshes are modelled with y up); azimuth turns about it, elevation is measured from the
  /// plane normal to it.
  std::string up_axis = "z";
  /// Image size in SVG pixels; the surface is framed automatically (orthographic projection,
  /// scaled so that the projected bounding box fills the image up to the margin).
  double width = 900.0;
  double height = 700.0;
  double margin = 24.0;
  /// Outline S1's triangles in a colour of their own, over the graph (d = 2): where S1 edges are
  /// also S2-edge preimages (refinements) the two structures stay distinguishable.
  bool domain_edges = true;
  /// Also draw the closure edges of the graph (thin, dashed); by default only the preimages of
  /// S2 edges are drawn, as in paper Fig. 2.
  bool closure_edges = false;
  /// Width of the graph lines; 0 chooses it from the projected size of the graph edges, so that
  /// fine graphs stay readable.
  double graph_line_width = 0.0;
  /// Write each S1 element's index at its centroid (d = 2), to find the element to draw with
  /// draw_element_graph_svg; hidden like the lines when the element is hidden.
  bool element_labels = false;
  /// Draw the legend.
  bool legend = true;
};

/// A 3-D view of S1 with the preimage of S2's edge graph on it (paper Fig. 2): flat-shaded
/// triangles (Lambert shading with a light near the camera; faces seen from behind darker and
/// cooler), drawn back to front by the depth of their centroids (painter's algorithm), each
/// triangle immediately followed by its own graph edges and outline, so that nearer triangles
/// hide the lines of farther ones. Orthographic projection; the camera follows `options`.
/// Throws plmap::Error if `options.up_axis` is not one of the six axis names.
std::string draw_map_3d_svg(const PlMap<2>& map, const MapViewOptions& options = {});

/// The d = 1 counterpart: S1 and S2 as curves in the plane, the nodes on S1 with symbols by
/// type and a thin line from each node to its image on S2 (paper Fig. 1).
std::string draw_map_curves_svg(const PlMap<1>& map, const MapViewOptions& options = {});

/// draw_map_3d_svg for d = 2, draw_map_curves_svg for d = 1.
template <int d>
std::string draw_map_view_svg(const PlMap<d>& map, const MapViewOptions& options = {}) {
  if constexpr (d == 2)
    return draw_map_3d_svg(map, options);
  else
    return draw_map_curves_svg(map, options);
}

/// Writes SVG text to `path` atomically (atomic_file.hpp). Throws plmap::Error naming the file.
void write_svg_file(const std::filesystem::path& path, const std::string& svg);

}  // namespace plmap
