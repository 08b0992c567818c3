// Vertex removal planning, first phases: the star's triangles sheet by sheet (sheet triangle i
// is (v, ring[i], ring[i+1])) and the new triangles that fill each sheet's polygon.

#include "removal_planning.hpp"

#include <plmap/core/predicates.hpp>

#include <algorithm>
#include <cmath>

namespace plmap {

using removal::SheetPlan;
using removal::Vec2;

RemovalRefusal EditableMap::RemovalPlanning::collect_star_triangles(
    std::span<const StarSheet> star_sheets, std::span<const std::vector<Vec2>> flattened,
    std::span<const std::vector<std::array<int, 3>>> triangulations) {
  for (int g = 0; g < sheet_count; ++g) {
    SheetPlan& sh = sheets[g];
    sh.diagonals.clear();
    sh.diagonal_boxes.clear();
    sh.moved.clear();
    sh.ring = &star_sheets[g].ring;
    sh.flat = flattened[g];
    sh.triangulation = triangulations[g];
    sh.closed = star_sheets[g].closed;
    if (const RemovalRefusal why = collect_fan(g); why != RemovalRefusal::none) return why;
  }
  // The fans must be v's whole star, each triangle once: otherwise v is not a disk's centre.
  std::vector<Index>& all = scratch.star_triangles;
  all.assign(plan.old_triangles.begin(), plan.old_triangles.end());
  std::sort(all.begin(), all.end());
  if (std::adjacent_find(all.begin(), all.end()) != all.end() || all.size() != s.vertex_triangles[v].size())
    return RemovalRefusal::not_a_disk_star;
  return RemovalRefusal::none;
}

/// Sheet g's fan of S1 triangles around v into the plan, its ring into the plan's ring, and the
/// check of its flattening.
RemovalRefusal EditableMap::RemovalPlanning::collect_fan(int g) {
  SheetPlan& sh = sheets[g];
  const int k = sh.size();
  if (k < 3 || static_cast<int>(sh.flat.size()) != k) return RemovalRefusal::not_a_disk_star;
  sh.first_old = static_cast<int>(plan.old_triangles.size());
  for (int i = 0; i < sh.fan_size(); ++i) {
    const Index found = fan_triangle((*sh.ring)[i], (*sh.ring)[(i + 1) % k]);
    if (found == invalid_index) return RemovalRefusal::not_a_disk_star;
    plan.old_triangles.push_back(found);
    plan.old_triangle_sheet.push_back(g);
  }
  for (Index w : *sh.ring)
    if (std::find(plan.ring.begin(), plan.ring.end(), w) == plan.ring.end()) plan.ring.push_back(w);
  return check_flattening(g);
}

/// The live S1 triangle (v, x, y) in that orientation, or invalid.
Index EditableMap::RemovalPlanning::fan_triangle(Index x, Index y) const {
  Index found = invalid_index;
  for (Index t : s.vertex_triangles[v]) {
    const auto& c = s.triangles[t];
    const int at = c[0] == v ? 0 : c[1] == v ? 1 : 2;
    if (c[(at + 1) % 3] == x && c[(at + 2) % 3] == y) found = t;
  }
  return found;
}

/// Sheet g's flattening must be a simple fan around the origin; an open sheet's must put its
/// line neighbours on the x axis on either side of v and its other ring vertices above.
RemovalRefusal EditableMap::RemovalPlanning::check_flattening(int g) const {
  const SheetPlan& sh = sheets[g];
  const int k = sh.size();
  for (int i = 0; i < sh.fan_size(); ++i)
    if (orient2d(origin, sh.flat[i], sh.flat[(i + 1) % k]) <= 0) return RemovalRefusal::flattening_not_simple;
  if (sh.closed) return RemovalRefusal::none;
  if (sh.flat.front().y() != 0.0 || sh.flat.back().y() != 0.0 || !(sh.flat.front().x() > 0.0) ||
      !(sh.flat.back().x() < 0.0))
    return RemovalRefusal::flattening_not_simple;
  for (int i = 1; i + 1 < k; ++i)
    if (!(sh.flat[i].y() > 0.0)) return RemovalRefusal::flattening_not_simple;
  return RemovalRefusal::none;
}

/// Makes star_position() answer for the star's triangles (reset by SlotReset).
void EditableMap::RemovalPlanning::mark_star_triangles() {
  if (scratch.star_slot.size() < s.triangles.size()) scratch.star_slot.resize(s.triangles.size(), -1);
  for (std::size_t i = 0; i < plan.old_triangles.size(); ++i) {
    scratch.star_slot[static_cast<std::size_t>(plan.old_triangles[i])] = static_cast<int>(i);
    scratch.marked_triangles.push_back(plan.old_triangles[i]);
  }
}

/// On a feature line every sheet must place v (the origin) at the same parameter of the new
/// edge, or the sheets would disagree about where the line's nodes go.
RemovalRefusal EditableMap::RemovalPlanning::check_line_parameters() const {
  if (!on_line) return RemovalRefusal::none;
  for (int g = 1; g < sheet_count; ++g)
    if (std::abs(line_parameter(g, origin) - line_parameter(0, origin)) > 1e-12)
      return RemovalRefusal::flattening_not_simple;
  return RemovalRefusal::none;
}

/// The new triangles of every sheet; no new edge may exist already or be made twice.
RemovalRefusal EditableMap::RemovalPlanning::make_new_triangles() {
  const double area_scale = (s.target->bounding_box_max() - s.target->bounding_box_min()).squaredNorm();
  if (on_line && s.has_edge(line_key[0], line_key[1])) return RemovalRefusal::existing_edge;
  std::vector<std::array<Index, 2>>& new_edges = scratch.new_edges;
  new_edges.clear();
  for (int g = 0; g < sheet_count; ++g)
    if (const RemovalRefusal why = triangulate_sheet(g, area_scale); why != RemovalRefusal::none) return why;
  std::sort(new_edges.begin(), new_edges.end());
  if (std::adjacent_find(new_edges.begin(), new_edges.end()) != new_edges.end()) return RemovalRefusal::existing_edge;
  return RemovalRefusal::none;
}

/// Sheet g's triangulation into new triangles, oriented like the sheet's fan in space.
RemovalRefusal EditableMap::RemovalPlanning::triangulate_sheet(int g, double area_scale) {
  SheetPlan& sh = sheets[g];
  const int k = sh.size();
  const std::vector<Index>& ring = *sh.ring;
  const Eigen::Vector3d& pv = position(v);
  Eigen::Vector3d sheet_normal = Eigen::Vector3d::Zero();
  for (int i = 0; i < sh.fan_size(); ++i) sheet_normal += (position(ring[i]) - pv).cross(position(ring[(i + 1) % k]) - pv);
  sh.first_new = static_cast<int>(plan.new_triangles.size());
  if (static_cast<int>(sh.triangulation.size()) != k - 2) return RemovalRefusal::no_triangulation;
  for (const auto& tri : sh.triangulation)
    if (const RemovalRefusal why = add_new_triangle(g, tri, sheet_normal, area_scale); why != RemovalRefusal::none)
      return why;
  if (sh.closed && k == 3) return check_hole_triangle_is_new(g);
  return RemovalRefusal::none;
}

/// One triangle (ring indices) of sheet g's triangulation: its interior edges become the sheet's
/// diagonals; it must be counter-clockwise in the plane, not degenerate and not folded over in
/// space.
RemovalRefusal EditableMap::RemovalPlanning::add_new_triangle(int g, const std::array<int, 3>& tri,
                                                              const Eigen::Vector3d& sheet_normal, double area_scale) {
  SheetPlan& sh = sheets[g];
  const int k = sh.size();
  const std::vector<Index>& ring = *sh.ring;
  for (int m = 0; m < 3; ++m) {
    const int i = tri[m], j = tri[(m + 1) % 3];
    if (i < 0 || i >= k || j < 0 || j >= k || i == j) return RemovalRefusal::no_triangulation;
    if (!sh.adjacent(i, j)) {
      if (s.has_edge(ring[i], ring[j])) return RemovalRefusal::existing_edge;
      if (i < j) {
        sh.diagonals.push_back({i, j});
        scratch.new_edges.push_back(sorted_pair(ring[i], ring[j]));
      }
    }
  }
  if (orient2d(sh.flat[tri[0]], sh.flat[tri[1]], sh.flat[tri[2]]) <= 0) return RemovalRefusal::no_triangulation;
  const std::array<Index, 3> corners{ring[tri[0]], ring[tri[1]], ring[tri[2]]};
  const Eigen::Vector3d normal =
      (position(corners[1]) - position(corners[0])).cross(position(corners[2]) - position(corners[0]));
  if (0.5 * normal.norm() <= s.options.min_relative_area * area_scale) return RemovalRefusal::degenerate_triangle;
  if (normal.dot(sheet_normal) <= 0.0) {
    // Name a diagonal of the folded triangle: the caller may triangulate the sheet without it.
    for (int m = 0; m < 3; ++m) {
      const int i = tri[m], j = tri[(m + 1) % 3];
      if (!sh.adjacent(i, j)) {
        plan.blocking_diagonal = {std::min(i, j), std::max(i, j)};
        plan.blocking_sheet = g;
        break;
      }
    }
    return RemovalRefusal::fold_over;
  }
  plan.new_triangles.push_back(corners);
  plan.new_triangle_sheet.push_back(g);
  return RemovalRefusal::none;
}

/// A closed hole of three ring vertices: its one triangle must not exist already (a
/// tetrahedron-like pocket), or the surface would get that triangle twice.
RemovalRefusal EditableMap::RemovalPlanning::check_hole_triangle_is_new(int g) const {
  const SheetPlan& sh = sheets[g];
  auto n = plan.new_triangles[sh.first_new];
  std::sort(n.begin(), n.end());
  for (Index t : s.vertex_triangles[(*sh.ring)[0]]) {
    if (star_position(t) >= 0) continue;
    auto c = s.triangles[t];
    std::sort(c.begin(), c.end());
    if (c == n) return RemovalRefusal::existing_edge;
  }
  return RemovalRefusal::none;
}

}  // namespace plmap
