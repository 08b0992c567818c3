// Vertex removal planning, the cut: every S2 edge polyline with a segment in the star is cut
// along the new triangles' interior edges (the sheets' diagonals). Its old crossings on the
// removed spokes disappear, so inside each new triangle it becomes the straight segment between
// its new crossings; each such piece is kept for the check (editable_map_removal_check.cpp).

#include "removal_planning.hpp"

#include <plmap/core/predicates.hpp>

#include <algorithm>

namespace plmap {

using removal::Cut;
using removal::PlanarPoint;
using removal::SheetPlan;
using removal::Vec2;

namespace {

/// True if the straight piece between p and q would run along an edge of the new triangulation:
/// both on one edge, or both corners (in a triangle, two corners always share an edge).
bool shares_an_edge(const PlanarPoint& p, const PlanarPoint& q) {
  if (p.corner != invalid_index && q.corner != invalid_index) return true;
  if (p.edge[0] != invalid_index && q.edge[0] != invalid_index) return p.edge == q.edge;
  if (p.corner != invalid_index && q.edge[0] != invalid_index) return q.edge[0] == p.corner || q.edge[1] == p.corner;
  if (q.corner != invalid_index && p.edge[0] != invalid_index) return p.edge[0] == q.corner || p.edge[1] == q.corner;
  return false;
}

/// Copies point i of polyline p into the edit unchanged (with the triangle of the segment that
/// leaves it, which the cut overwrites where that segment changes).
void push_point(VertexRemovalPlan::PolylineEdit& edit, const EdgePolyline& p, int i) { edit.points.push_back(p.points[i]); }

/// The preimage must meet each new triangle in one straight piece (a minimal embedding): a
/// polyline that leaves the star and comes back, or bends at the old spokes, can reach one new
/// triangle twice, in pieces that are not consecutive.
bool reenters_a_new_triangle(const VertexRemovalPlan::PolylineEdit& edit) {
  const std::vector<PolylinePoint>& points = edit.points;
  for (std::size_t k = 1; k + 1 < points.size(); ++k) {
    const Index t = points[k].segment_triangle;
    if (t >= 0 || t == points[k - 1].segment_triangle) continue;
    for (std::size_t j = 0; j + 1 < k; ++j)
      if (points[j].segment_triangle == t) return true;
  }
  return false;
}

/// The bounding box of every diagonal of the sheet, made once per plan by the first polyline
/// that runs through the sheet.
void box_diagonals(SheetPlan& sh) {
  if (sh.diagonal_boxes.size() == sh.diagonals.size()) return;
  sh.diagonal_boxes.clear();
  for (const auto& [di, dj] : sh.diagonals)
    sh.diagonal_boxes.emplace_back(sh.flat[di].cwiseMin(sh.flat[dj]), sh.flat[di].cwiseMax(sh.flat[dj]));
}

}  // namespace

RemovalRefusal EditableMap::RemovalPlanning::cut_polylines() {
  std::vector<Index>& edges = scratch.edges;
  edges.clear();
  for (Index t : plan.old_triangles) edges.insert(edges.end(), s.triangle_edges[t].begin(), s.triangle_edges[t].end());
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  scratch.pieces.clear();
  // A polyline lives in two places that earlier plans seldom left in the cache: its entry in
  // `polylines` (size and pointer) and its points. Waiting for them was most of the time spent
  // cutting polylines (perf on the armadillo → 500: 80 % of cut_polyline's samples on those two
  // loads), so both are asked for a few polylines ahead: the entry first, its points once the
  // entry has arrived. Prefetching changes no result.
  constexpr std::size_t entry_ahead = 8, points_ahead = 4;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (i + entry_ahead < edges.size()) __builtin_prefetch(&s.polylines[edges[i + entry_ahead]]);
    if (i + points_ahead < edges.size()) {
      const PolylinePoint* points = s.polylines[edges[i + points_ahead]].points.data();
      __builtin_prefetch(points);
      __builtin_prefetch(points + 2);  // a polyline of three or four points spans two cache lines
    }
    if (const RemovalRefusal why = cut_polyline(edges[i]); why != RemovalRefusal::none) return why;
  }
  return RemovalRefusal::none;
}

/// The edit of S2 edge e's polyline: its points and segments outside the star are kept, each run
/// of segments through the star is replaced by its cut.
RemovalRefusal EditableMap::RemovalPlanning::cut_polyline(Index e) {
  const EdgePolyline& p = s.polylines[e];
  const int segments = p.segment_count();
  bool touches_star = false;
  for (int i = 0; i < segments; ++i) touches_star = touches_star || star_position(p.points[i].segment_triangle) >= 0;
  if (!touches_star) return RemovalRefusal::none;  // a stale entry of triangle_edges

  VertexRemovalPlan::PolylineEdit edit;
  if (!plan.spare_edits.empty()) {
    edit = std::move(plan.spare_edits.back());
    plan.spare_edits.pop_back();
  }
  edit.target_edge = e;
  edit.version_at_planning = s.polyline_version[e];
  // Room for the polyline and a few crossings at once: the edit then grows without
  // reallocating point by point. Spare edits come back in any order, so one too small for this
  // polyline at least doubles: after a few plans every spare is large enough.
  const std::size_t room = p.points.size() + 8;
  if (edit.points.capacity() < room) edit.points.reserve(std::max(room, 2 * edit.points.capacity()));

  if (segments == 1) {
    const auto [runs_along, n] = triangle_along_kept_edge(p);
    if (runs_along) {
      if (n < 0) return RemovalRefusal::edge_along_new_edge;
      push_point(edit, p, 0);
      edit.points.back().segment_triangle = -(n + 1);
      push_point(edit, p, 1);
      plan.polyline_edits.push_back(std::move(edit));
      return RemovalRefusal::none;
    }
  }

  push_point(edit, p, 0);
  int i = 0;
  while (i < segments) {
    if (star_position(p.points[i].segment_triangle) < 0) {  // kept as it is, with its triangle
      push_point(edit, p, i + 1);
      ++i;
      continue;
    }
    int run_end = i;  // segments i .. run_end lie in the star, all in one sheet
    while (run_end + 1 < segments && star_position(p.points[run_end + 1].segment_triangle) >= 0) ++run_end;
    if (const RemovalRefusal why = cut_run(p, i, run_end, edit); why != RemovalRefusal::none) return why;
    push_point(edit, p, run_end + 1);
    i = run_end + 1;
  }
  if (reenters_a_new_triangle(edit)) return RemovalRefusal::edge_reenters_triangle;
  plan.polyline_edits.push_back(std::move(edit));
  return RemovalRefusal::none;
}

/// An S2 edge whose preimage runs along an S1 edge stays along it: along a ring edge, it now
/// borders the new triangle of its sheet there; along a removed line edge, it is now a piece of
/// the new line edge. {true, that new triangle (-1 if there is none)} for such an edge of one
/// segment p, {false, -1} otherwise.
std::pair<bool, int> EditableMap::RemovalPlanning::triangle_along_kept_edge(const EdgePolyline& p) const {
  const std::array<Index, 2> along = common_edge(p.points[0].vertex, p.points[1].vertex);
  const bool on_removed_line_edge =
      on_line && (along == sorted_pair(v, line_key[0]) || along == sorted_pair(v, line_key[1]));
  if (along[0] == invalid_index || !(on_removed_line_edge || (along[0] != v && along[1] != v))) return {false, -1};
  const int g = on_removed_line_edge ? 0 : plan.old_triangle_sheet[star_position(p.points[0].segment_triangle)];
  return {true, on_removed_line_edge ? new_triangle_with(0, line_key[0], line_key[1])
                                     : new_triangle_with(g, along[0], along[1])};
}

/// Segments first .. last of polyline p (of an S2 edge), which lie in the star, as straight pieces
/// in the new triangles, cut where they cross the sheet's diagonals: the crossings are new
/// points of the edit, the pieces its new segments (and the check's input).
RemovalRefusal EditableMap::RemovalPlanning::cut_run(const EdgePolyline& p, int first, int last,
                                                     VertexRemovalPlan::PolylineEdit& edit) {
  const int g = plan.old_triangle_sheet[star_position(p.points[first].segment_triangle)];
  for (int j = first; j <= last; ++j)
    if (plan.old_triangle_sheet[star_position(p.points[j].segment_triangle)] != g)
      return RemovalRefusal::crossing_edges;  // crosses the feature line; never expected
  if (const RemovalRefusal why = planar_points_of_run(g, p, first, last); why != RemovalRefusal::none) return why;
  SheetPlan& sh = sheets[g];
  const std::vector<Index>& ring = *sh.ring;
  box_diagonals(sh);
  const std::vector<PlanarPoint>& points = scratch.run_points;
  PlanarPoint previous = points.front();
  std::array<Index, 2> previous_diagonal{invalid_index, invalid_index};
  // The straight piece from `previous` to `to`, in the new triangle that holds its middle;
  // false if it would run along a new edge or its middle is on one.
  auto emit_piece_to = [&](const PlanarPoint& to) -> bool {
    if (shares_an_edge(previous, to)) {
      if (previous.corner != invalid_index && to.corner != invalid_index) name_diagonal(g, previous.corner, to.corner);
      return false;
    }
    Vec2 mid = 0.5 * (previous.position + to.position);
    const auto [n, min_coordinate] = locate(g, mid, nullptr);
    if (n < 0 || !(min_coordinate > 0.0)) return false;
    edit.points.back().segment_triangle = -(n + 1);
    scratch.pieces.push_back({n, previous.position, to.position});
    previous = to;
    return true;
  };
  // The S2 edge's ends are the polyline's ends (smaller vertex first, as edge_vertices(e) gives
  // them), already in the cache, unlike S2's edge array.
  const Index sa = p.points.front().vertex, sb = p.points.back().vertex;
  for (int j = 0; j + 1 < static_cast<int>(points.size()); ++j) {
    if (const RemovalRefusal why = find_cuts(g, points[j], points[j + 1]); why != RemovalRefusal::none) return why;
    for (const Cut& cut : scratch.cuts) {
      const int di = sh.diagonals[cut.diagonal][0], dj = sh.diagonals[cut.diagonal][1];
      const std::array<Index, 2> key = sorted_pair(ring[di], ring[dj]);
      if (key == previous_diagonal) {
        name_diagonal(g, key[0], key[1]);
        return RemovalRefusal::edge_along_new_edge;
      }
      const double t_on_edge = ring[di] < ring[dj] ? cut.parameter : 1.0 - cut.parameter;
      PlanarPoint crossing;
      crossing.position = (1.0 - cut.parameter) * sh.flat[di] + cut.parameter * sh.flat[dj];
      crossing.edge = key;
      const double target_parameter =
          (1.0 - cut.along) * p.points[first + j].target_parameter + cut.along * p.points[first + j + 1].target_parameter;
      if (!emit_piece_to(crossing)) return RemovalRefusal::edge_along_new_edge;
      PolylinePoint& point = edit.points.emplace_back();
      point.edge = key;
      point.edge_parameter = t_on_edge;
      point.target_parameter = target_parameter;
      previous_diagonal = key;
      record_node((1.0 - t_on_edge) * position(key[0]) + t_on_edge * position(key[1]),
                  (1.0 - target_parameter) * t2.vertex(sa) + target_parameter * t2.vertex(sb));
    }
  }
  if (!emit_piece_to(points.back())) return RemovalRefusal::edge_along_new_edge;
  return RemovalRefusal::none;
}

/// The planar points (scratch.run_points) of points first .. last + 1 of polyline p in sheet g,
/// each from the first star triangle that holds it.
RemovalRefusal EditableMap::RemovalPlanning::planar_points_of_run(int g, const EdgePolyline& p, int first, int last) {
  std::vector<PlanarPoint>& points = scratch.run_points;
  points.clear();
  for (int j = first; j <= last + 1; ++j) {
    const PolylinePoint& point = p.points[j];
    const Index t = p.points[std::min(j, last)].segment_triangle;
    const auto& c = s.triangles[t];
    PlanarPoint q;
    if (point.vertex != invalid_index) {
      if (!vertex_point(g, point.vertex, q)) return RemovalRefusal::crossing_edges;  // never expected
    } else {
      const auto [a, b] = point.edge;
      if ((a != c[0] && a != c[1] && a != c[2]) || (b != c[0] && b != c[1] && b != c[2]))
        return RemovalRefusal::crossing_edges;  // inconsistent state; never expected
      const bool line_spoke = on_line && (point.edge == sorted_pair(v, line_key[0]) || point.edge == sorted_pair(v, line_key[1]));
      if (line_spoke) return RemovalRefusal::edge_along_new_edge;  // crosses the feature line; never expected
      q.position = (1.0 - point.edge_parameter) * planar_corner(g, a) + point.edge_parameter * planar_corner(g, b);
      if (a != v && b != v) q.edge = point.edge;  // on a ring edge: it stays a crossing
    }
    points.push_back(q);
  }
  return RemovalRefusal::none;
}

/// The crossings (scratch.cuts, in order along the segment) of the planar segment from `from`
/// to `to` with sheet g's diagonals. A segment through a diagonal's end, or that would cross one
/// within the clearance of its ends, is refused: its preimage would run along a new edge.
RemovalRefusal EditableMap::RemovalPlanning::find_cuts(int g, const PlanarPoint& from_point,
                                                       const PlanarPoint& to_point) {
  const SheetPlan& sh = sheets[g];
  const std::vector<Index>& ring = *sh.ring;
  const Vec2& from = from_point.position;
  const Vec2& to = to_point.position;
  const Eigen::AlignedBox2d box(from.cwiseMin(to), from.cwiseMax(to));
  std::vector<Cut>& cuts = scratch.cuts;
  cuts.clear();
  for (int d = 0; d < static_cast<int>(sh.diagonals.size()); ++d) {
    // Closed boxes apart: the segment and the diagonal share no point, so the exact tests
    // below would find neither a crossing nor a touch (most pairs in a large star).
    if (!box.intersects(sh.diagonal_boxes[d])) continue;
    const Index da = ring[sh.diagonals[d][0]], db = ring[sh.diagonals[d][1]];
    // A point that is a diagonal's own end never crosses it.
    if (from_point.corner == da || from_point.corner == db || to_point.corner == da || to_point.corner == db) continue;
    const Vec2& d0 = sh.flat[sh.diagonals[d][0]];
    const Vec2& d1 = sh.flat[sh.diagonals[d][1]];
    const int o1 = orient2d(from, to, d0), o2 = orient2d(from, to, d1);
    const int o3 = orient2d(d0, d1, from), o4 = orient2d(d0, d1, to);
    if (o1 == 0 || o2 == 0 || o3 == 0 || o4 == 0) {
      if (segments_cross_properly(from, to, d0, d1)) return along_diagonal(g, d);
      continue;
    }
    if (o1 == o2 || o3 == o4) continue;
    const Vec2 r = to - from, q = d1 - d0;
    const double denom = r.x() * q.y() - r.y() * q.x();
    const Vec2 w = d0 - from;
    const double along = (w.x() * q.y() - w.y() * q.x()) / denom;
    const double parameter = (w.x() * r.y() - w.y() * r.x()) / denom;
    if (!(parameter > clearance && parameter < 1.0 - clearance)) return along_diagonal(g, d);
    cuts.push_back({std::clamp(along, 0.0, 1.0), d, parameter});
  }
  std::sort(cuts.begin(), cuts.end(), [](const Cut& x, const Cut& y) { return x.along < y.along; });
  return RemovalRefusal::none;
}

/// Planar position in sheet g of moved vertex preimage w, or null if it is not in that sheet.
const Vec2* EditableMap::RemovalPlanning::moved_position(int g, Index w) const {
  const auto& slot = scratch.moved_slot[static_cast<std::size_t>(w)];
  if (slot[0] == g) return &sheets[g].moved[static_cast<std::size_t>(slot[1])].second;
  return sheets[g].moved_position(w);  // listed first in another sheet: search this one's list
}

/// The planar point of S2 vertex w in sheet g, as it lies after the step; false if w is not in
/// that sheet (an inconsistent state; never expected).
bool EditableMap::RemovalPlanning::vertex_point(int g, Index w, PlanarPoint& q) const {
  const SheetPlan& sh = sheets[g];
  if (on_line && (w == v || line_end_of(w) != invalid_index)) {
    q.position = w == v ? origin : spoke_fraction(w) * planar_corner(g, line_end_of(w));
    q.edge = line_key;
    return true;
  }
  if (s.vertex_live[w] && w != v) {
    const int i = sh.ring_index(w);
    if (i < 0) return false;
    q.position = sh.flat[i];
    q.corner = w;
    return true;
  }
  if (s.vertex_live[w] || !s.on_edge(w)) {
    const Vec2* at = moved_position(g, w);
    if (!at) return false;
    q.position = *at;
    return true;
  }
  const auto e = s.preimage_edge[w];  // on a ring edge: it stays there
  const int i = sh.ring_index(e[0]), j = sh.ring_index(e[1]);
  if (i < 0 || j < 0) return false;
  q.position = (1.0 - s.preimage_edge_parameter[w]) * sh.flat[i] + s.preimage_edge_parameter[w] * sh.flat[j];
  q.edge = e;
  return true;
}

/// The S1 edge (smaller first) that both S2 vertices lie on (as corners or on-edge nodes), if any.
std::array<Index, 2> EditableMap::RemovalPlanning::common_edge(Index w1, Index w2) const {
  const std::array<Index, 2> none{invalid_index, invalid_index};
  const bool c1 = s.vertex_live[w1] != 0, c2 = s.vertex_live[w2] != 0;
  const bool e1 = !c1 && s.on_edge(w1), e2 = !c2 && s.on_edge(w2);
  if (c1 && c2) return s.has_edge(w1, w2) ? sorted_pair(w1, w2) : none;
  if (c1 && e2) return s.preimage_edge[w2][0] == w1 || s.preimage_edge[w2][1] == w1 ? s.preimage_edge[w2] : none;
  if (e1 && c2) return s.preimage_edge[w1][0] == w2 || s.preimage_edge[w1][1] == w2 ? s.preimage_edge[w1] : none;
  if (e1 && e2) return s.preimage_edge[w1] == s.preimage_edge[w2] ? s.preimage_edge[w1] : none;
  return none;
}

/// Names the S1 edge a-b as the plan's blocking diagonal if it is a diagonal of sheet g (not an
/// edge of its polygon): the caller may triangulate the sheet again without it.
void EditableMap::RemovalPlanning::name_diagonal(int g, Index a, Index b) {
  const int i = sheets[g].ring_index(a), j = sheets[g].ring_index(b);
  if (i < 0 || j < 0 || sheets[g].adjacent(i, j)) return;
  plan.blocking_diagonal = {std::min(i, j), std::max(i, j)};
  plan.blocking_sheet = g;
}

/// Refuses a segment that would pass through an end of diagonal d of sheet g, naming d.
RemovalRefusal EditableMap::RemovalPlanning::along_diagonal(int g, int d) {
  plan.blocking_diagonal = sheets[g].diagonals[d];
  plan.blocking_sheet = g;
  return RemovalRefusal::edge_along_new_edge;
}

/// The new triangle of sheet g with corners a and b, or -1.
int EditableMap::RemovalPlanning::new_triangle_with(int g, Index a, Index b) const {
  for (int n = sheets[g].first_new; n < sheets[g].first_new + sheets[g].size() - 2; ++n) {
    const auto& c = plan.new_triangles[n];
    const bool has_a = c[0] == a || c[1] == a || c[2] == a, has_b = c[0] == b || c[1] == b || c[2] == b;
    if (has_a && has_b) return n;
  }
  return -1;
}

}  // namespace plmap
