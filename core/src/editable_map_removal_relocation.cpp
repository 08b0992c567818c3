// Vertex removal planning: the vertex preimages of the star move into the new triangles (each
// keeps its planar position in its sheet's flattening), and on a feature line v and the nodes
// of the two removed line edges move onto the new edge joining the line neighbours.

#include "removal_planning.hpp"

namespace plmap {

using removal::SheetPlan;
using removal::Vec2;

/// Every vertex preimage of the star (v itself for a closed star) gets a new triangle and its
/// barycentric coordinates there; a preimage on or within the clearance of a new edge is refused.
RemovalRefusal EditableMap::RemovalPlanning::relocate_preimages() {
  if (!on_line) sheets[0].moved.emplace_back(v, origin);
  for (int g = 0; g < sheet_count; ++g) {
    gather_moved_preimages(g);
    for (const auto& [w, p] : sheets[g].moved) {
      Eigen::Vector3d b;
      const auto [n, min_coordinate] = locate(g, p, &b);
      if (n < 0 || !(min_coordinate > clearance)) {
        if (n >= 0) name_blocking_diagonal(g, n, b);
        return RemovalRefusal::node_on_new_edge;
      }
      plan.relocations.push_back({w, n, b, 0.0});
      record_node(world_on_new(n, b), t2.vertex(w));
    }
  }
  return RemovalRefusal::none;
}

/// Planar positions in sheet g of the vertex preimages inside its fan's triangles: each star
/// triangle maps affinely onto its fan triangle, so a preimage keeps its barycentric coordinates.
void EditableMap::RemovalPlanning::gather_moved_preimages(int g) {
  SheetPlan& sh = sheets[g];
  for (int i = 0; i < sh.fan_size(); ++i) {
    const Index t = plan.old_triangles[sh.first_old + i];
    const auto& c = s.triangles[t];
    for (Index w : s.triangle_vertices[t]) {
      const Eigen::Vector3d& b = s.preimage_barycentric[w];
      sh.moved.emplace_back(w, b(0) * planar_corner(g, c[0]) + b(1) * planar_corner(g, c[1]) + b(2) * planar_corner(g, c[2]));
    }
  }
}

/// A preimage refused on new triangle n (barycentric b): name the new edge it is on, if that is
/// a diagonal, so the caller can re-triangulate the sheet without it.
void EditableMap::RemovalPlanning::name_blocking_diagonal(int g, int n, const Eigen::Vector3d& b) {
  const SheetPlan& sh = sheets[g];
  int side = 0;
  for (int m = 1; m < 3; ++m)
    if (b(m) < b(side)) side = m;
  const auto& tri = sh.triangulation[n - sh.first_new];
  const int i = tri[(side + 1) % 3], j = tri[(side + 2) % 3];
  if (!sh.adjacent(i, j)) {
    plan.blocking_diagonal = {std::min(i, j), std::max(i, j)};
    plan.blocking_sheet = g;
  }
}

/// The line's nodes (v, and the nodes of the two removed line edges) onto the new edge, at the
/// parameter sheet 0 gives them (check_line_parameters made the sheets agree).
RemovalRefusal EditableMap::RemovalPlanning::move_line_nodes() {
  if (!on_line) return RemovalRefusal::none;
  std::vector<std::pair<Index, Vec2>> line_nodes{{v, origin}};
  for (Index end : line_key)
    if (const auto* on = s.vertices_on_edge(sorted_pair(v, end)))
      for (Index w : *on) line_nodes.emplace_back(w, spoke_fraction(w) * planar_corner(0, end));
  for (const auto& [w, p] : line_nodes) {
    const double t = line_parameter(0, p);
    if (!(t > clearance && t < 1.0 - clearance)) return RemovalRefusal::node_on_new_edge;
    plan.relocations.push_back({w, -1, Eigen::Vector3d::Zero(), t});
    record_node((1.0 - t) * position(line_key[0]) + t * position(line_key[1]), t2.vertex(w));
  }
  return RemovalRefusal::none;
}

/// Where each moved vertex preimage is listed (its first entry), for the cut's vertex_point and
/// the fold check's straight_point (reset by SlotReset).
void EditableMap::RemovalPlanning::index_moved_preimages() {
  if (scratch.moved_slot.size() < static_cast<std::size_t>(s.target->vertex_count()))
    scratch.moved_slot.resize(static_cast<std::size_t>(s.target->vertex_count()), {-1, -1});
  for (int g = 0; g < sheet_count; ++g)
    for (std::size_t i = 0; i < sheets[g].moved.size(); ++i) {
      const Index w = sheets[g].moved[i].first;
      auto& slot = scratch.moved_slot[static_cast<std::size_t>(w)];
      if (slot[0] >= 0) continue;
      slot = {g, static_cast<int>(i)};
      scratch.marked_vertices.push_back(w);
    }
}

}  // namespace plmap
