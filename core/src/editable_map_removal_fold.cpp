// Vertex removal planning with the deferred cut (EditOptions::defer_cut): the S2 edges are
// traced once, on the final S1 (to_map), so the polylines are neither cut nor checked per step.
// What the trace needs of the step is that the straight segments between the preimages keep
// S2's orientation where the trace will draw them: in the new triangles as they lie in space,
// unfolded into one plane (a polygon's triangulation has no inner vertex, so each ring vertex
// gets one position), and in the S1 triangles just outside the ring, unfolded across the ring
// edge. Every S2 triangle with a moved corner whose corners all lie there must stay
// counter-clockwise; otherwise a preimage has moved across the straight segment of two others
// and the traced edges would cross (RemovalRefusal::straight_fold).

#include "removal_planning.hpp"

#include <plmap/core/predicates.hpp>

#include <algorithm>

namespace plmap {

using removal::SheetPlan;
using removal::Vec2;

RemovalRefusal EditableMap::RemovalPlanning::check_straight_folds() {
  const double margin = clearance * star_size();
  std::size_t relocation_base = 0;  // sheet g's relocations follow those of the sheets before it
  for (int g = 0; g < sheet_count; ++g) {
    unfold_sheet(g);
    if (const RemovalRefusal why = check_sheet_folds(g, relocation_base, margin); why != RemovalRefusal::none) return why;
    relocation_base += sheets[g].moved.size();
  }
  return RemovalRefusal::none;
}

/// Sheet g's new triangles unfolded into one plane (scratch.unfolded, per ring index): the first
/// in its own plane, then across shared edges until all are placed.
void EditableMap::RemovalPlanning::unfold_sheet(int g) {
  const SheetPlan& sh = sheets[g];
  const std::vector<Index>& ring = *sh.ring;
  std::vector<Vec2>& unfolded = scratch.unfolded;
  std::vector<char>& placed = scratch.placed;
  unfolded.assign(static_cast<std::size_t>(sh.size()), Vec2::Zero());
  placed.assign(static_cast<std::size_t>(sh.size()), 0);
  const auto& t0 = sh.triangulation[0];
  const Eigen::Vector3d e1 = position(ring[t0[1]]) - position(ring[t0[0]]), e2 = position(ring[t0[2]]) - position(ring[t0[0]]);
  const double l1 = e1.norm();
  unfolded[t0[1]] = Vec2(l1, 0.0);
  unfolded[t0[2]] = Vec2(e2.dot(e1) / l1, e2.cross(e1).norm() / l1);
  placed[t0[0]] = placed[t0[1]] = placed[t0[2]] = 1;
  for (bool progress = true; progress;) {
    progress = false;
    for (const auto& tri : sh.triangulation) {
      int missing = -1, count = 0;
      for (int m = 0; m < 3; ++m)
        if (!placed[tri[m]]) missing = m, ++count;
      if (count != 1) continue;
      const int i = tri[(missing + 1) % 3], j = tri[(missing + 2) % 3];
      // The placed triangle on (i, j): its third corner is on the other side.
      Vec2 other = unfolded[i];
      for (const auto& u : sh.triangulation)
        if (&u != &tri) {
          int has = 0, third = -1;
          for (int m = 0; m < 3; ++m) {
            if (u[m] == i || u[m] == j) ++has;
            else third = u[m];
          }
          if (has == 2 && placed[third]) other = unfolded[third];
        }
      unfolded[tri[missing]] = unfold(ring[i], ring[j], ring[tri[missing]], unfolded[i], unfolded[j], other);
      placed[tri[missing]] = 1;
      progress = true;
    }
  }
}

/// The third corner r of a triangle on edge (a, b) (planar pa, pb), unfolded away from the side
/// of `away`.
Vec2 EditableMap::RemovalPlanning::unfold(Index a, Index b, Index r, const Vec2& pa, const Vec2& pb, const Vec2& away) const {
  const Eigen::Vector3d d = position(b) - position(a), x = position(r) - position(a);
  const double length = d.norm();
  const Vec2 unit = (pb - pa).normalized();
  Vec2 normal(-unit.y(), unit.x());
  if (normal.dot(away - pa) > 0.0) normal = -normal;
  return Vec2(pa + (x.dot(d) / length) * unit + (x.cross(d).norm() / length) * normal);
}

/// The unfolded third corner (c[unknown]) of S1 triangle t beyond a ring edge of sheet g
/// (at_ring: its corners' ring indices), away from the new triangle on that ring edge.
Vec2 EditableMap::RemovalPlanning::unfolded_beyond(int g, Index t, int unknown, const std::array<int, 3>& at_ring) const {
  const std::vector<Vec2>& unfolded = scratch.unfolded;
  const auto& c = s.triangles[t];
  const int m0 = (unknown + 1) % 3, m1 = (unknown + 2) % 3;
  Vec2 inside = unfolded[static_cast<std::size_t>(at_ring[m0])];
  for (const auto& tri : sheets[g].triangulation) {
    int has = 0, third = -1;
    for (int m = 0; m < 3; ++m) {
      if (tri[m] == at_ring[m0] || tri[m] == at_ring[m1]) ++has;
      else third = tri[m];
    }
    if (has == 2) inside = unfolded[static_cast<std::size_t>(third)];
  }
  return unfold(c[m0], c[m1], c[unknown], unfolded[static_cast<std::size_t>(at_ring[m0])],
                unfolded[static_cast<std::size_t>(at_ring[m1])], inside);
}

/// Where the trace will see S2 vertex w's preimage in sheet g's unfolding: a ring vertex, a
/// relocated preimage (sheet g's relocations start at relocation_base), or a preimage in an S1
/// triangle just outside a ring edge; false if it lies elsewhere.
bool EditableMap::RemovalPlanning::straight_point(int g, std::size_t relocation_base, Index w, Vec2& at) const {
  const SheetPlan& sh = sheets[g];
  const std::vector<Vec2>& unfolded = scratch.unfolded;
  if (s.vertex_live[w] && w != v) {
    const int i = sh.ring_index(w);
    if (i < 0) return false;
    at = unfolded[static_cast<std::size_t>(i)];
    return true;
  }
  const auto& slot = scratch.moved_slot[static_cast<std::size_t>(w)];
  if (slot[0] == g) {
    const auto& r = plan.relocations[relocation_base + static_cast<std::size_t>(slot[1])];
    if (r.new_triangle < 0) return false;
    const auto& tri = sh.triangulation[r.new_triangle - sh.first_new];
    at = r.barycentric(0) * unfolded[static_cast<std::size_t>(tri[0])] +
         r.barycentric(1) * unfolded[static_cast<std::size_t>(tri[1])] +
         r.barycentric(2) * unfolded[static_cast<std::size_t>(tri[2])];
    return true;
  }
  if (s.vertex_live[w] || s.on_edge(w)) return false;
  const Index t = s.preimage_triangle[w];
  if (star_position(t) >= 0) return false;
  const auto& c = s.triangles[t];
  std::array<int, 3> at_ring{sh.ring_index(c[0]), sh.ring_index(c[1]), sh.ring_index(c[2])};
  std::array<Vec2, 3> corner;
  int known = 0, unknown = -1;
  for (int m = 0; m < 3; ++m) {
    if (at_ring[m] >= 0) {
      corner[m] = unfolded[static_cast<std::size_t>(at_ring[m])];
      ++known;
    } else {
      unknown = m;
    }
  }
  if (known != 2) return false;
  if (!sh.adjacent(at_ring[(unknown + 1) % 3], at_ring[(unknown + 2) % 3])) return false;
  corner[unknown] = unfolded_beyond(g, t, unknown, at_ring);
  const Eigen::Vector3d& b = s.preimage_barycentric[w];
  at = b(0) * corner[0] + b(1) * corner[1] + b(2) * corner[2];
  return true;
}

/// True if an S2 triangle at w (preimage at pw), with all corners in the unfolding, is not
/// counter-clockwise or has a corner within the margin of the opposite side (the trace's test
/// of near-touching pieces).
bool EditableMap::RemovalPlanning::turns_over(int g, std::size_t relocation_base, Index w, const Vec2& pw,
                                              double margin) const {
  for (Index f : t2.vertex_elements(w)) {
    const auto& c = t2.element(f);
    const int m = t2.local_corner(f, w);
    Vec2 px, py;
    if (!straight_point(g, relocation_base, c[(m + 1) % 3], px) || !straight_point(g, relocation_base, c[(m + 2) % 3], py))
      continue;
    const double twice_area = (px - pw).x() * (py - pw).y() - (px - pw).y() * (py - pw).x();
    const double longest = std::max({(px - pw).norm(), (py - pw).norm(), (py - px).norm()});
    if (orient2d(pw, px, py) <= 0 || twice_area <= 2.0 * margin * longest) return true;
  }
  return false;
}

/// The S2 triangles of sheet g that the step moves: those at a moved preimage, and those that
/// span the star between the S1 triangles just outside it (their corners did not move, but
/// their straight edges through the star did).
RemovalRefusal EditableMap::RemovalPlanning::check_sheet_folds(int g, std::size_t relocation_base, double margin) const {
  const SheetPlan& sh = sheets[g];
  const std::vector<Index>& ring = *sh.ring;
  const int k = sh.size();
  for (const auto& [w, unused] : sh.moved) {
    (void)unused;
    if (scratch.moved_slot[static_cast<std::size_t>(w)][0] != g) continue;
    Vec2 pw;
    if (straight_point(g, relocation_base, w, pw) && turns_over(g, relocation_base, w, pw, margin))
      return RemovalRefusal::straight_fold;
  }
  for (int i = 0; i < k; ++i) {
    if (!sh.closed && i == k - 1) break;  // the new line edge: no triangle beyond in this sheet
    const Index x = ring[i], y = ring[(i + 1) % k];
    for (Index t : s.vertex_triangles[x]) {
      if (star_position(t) >= 0) continue;
      const auto& c = s.triangles[t];
      if (c[0] != y && c[1] != y && c[2] != y) continue;
      for (Index w : s.triangle_vertices[t]) {
        Vec2 pw;
        if (straight_point(g, relocation_base, w, pw) && turns_over(g, relocation_base, w, pw, margin))
          return RemovalRefusal::straight_fold;
      }
    }
  }
  return RemovalRefusal::none;
}

}  // namespace plmap
