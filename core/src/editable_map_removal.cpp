// EditableMap::plan_vertex_removal: one step of paper 3.3.1 on the editing form.
//
// The star of v is flattened by the caller (one planar position per ring vertex, v at the
// origin); each star triangle maps affinely onto its fan triangle, so every node of the star's
// graphs keeps its barycentric coordinates and gets a planar position: the graphs are merged
// into one plane graph on the polygon. Vertex preimages are located in the new triangles; every
// S2 edge polyline that runs through the star is cut along the new triangles' interior edges
// (its old crossings on the removed spokes disappear, so inside each new triangle it becomes the
// straight segment between its new crossings). Finally each new triangle's segments are checked
// not to cross, with exact predicates on the shared planar coordinates.

#include "editable_map_state.hpp"

#include <plmap/core/predicates.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace plmap {

namespace {

using Vec2 = Eigen::Vector2d;

/// Barycentric coordinates of p in the planar triangle (a, b, c).
Eigen::Vector3d planar_barycentric(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& p) {
  const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
  const double l1 = ((p.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (p.y() - a.y())) / det;
  const double l2 = ((b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y())) / det;
  return {1.0 - l1 - l2, l1, l2};
}

/// A point of a polyline inside the star, with what it lies on in the new triangulation.
struct PlanarPoint {
  Vec2 position;
  Index corner = invalid_index;                          ///< S1 vertex it is, if any
  std::array<Index, 2> edge{invalid_index, invalid_index};  ///< S1 edge it lies on, if any
};

/// True if the straight piece between p and q would run along an edge of the new triangulation:
/// both on one edge, or both corners (in a triangle, two corners always share an edge).
bool shares_an_edge(const PlanarPoint& p, const PlanarPoint& q) {
  if (p.corner != invalid_index && q.corner != invalid_index) return true;
  if (p.edge[0] != invalid_index && q.edge[0] != invalid_index) return p.edge == q.edge;
  if (p.corner != invalid_index && q.edge[0] != invalid_index) return q.edge[0] == p.corner || q.edge[1] == p.corner;
  if (q.corner != invalid_index && p.edge[0] != invalid_index) return p.edge[0] == q.corner || p.edge[1] == q.corner;
  return false;
}

struct Piece {
  int triangle;  ///< new triangle
  Vec2 from, to;
};

}  // namespace

VertexRemovalPlan EditableMap::plan_vertex_removal(Index v, std::span<const Vec2> flattened_ring,
                                                   std::span<const std::array<int, 3>> triangulation) const {
  const Impl& s = *impl_;
  const double clearance = s.options.edge_clearance;
  VertexRemovalPlan plan;
  plan.vertex = v;
  plan.triangle_count_at_planning = static_cast<Index>(s.triangles.size());
  auto refuse = [&plan](RemovalRefusal why) {
    plan.refusal = why;
    return std::move(plan);
  };

  plan.ring = closed_ring(v);
  const std::vector<Index>& ring = plan.ring;
  const int k = static_cast<int>(ring.size());
  if (k < 3 || static_cast<int>(flattened_ring.size()) != k) return refuse(RemovalRefusal::not_a_disk_star);
  auto ring_index = [&ring](Index w) {
    for (std::size_t i = 0; i < ring.size(); ++i)
      if (ring[i] == w) return static_cast<int>(i);
    return -1;
  };
  auto planar_corner = [&](Index w) -> Vec2 { return w == v ? Vec2::Zero() : flattened_ring[ring_index(w)]; };

  // Star triangles in ring order: star[i] = (v, ring[i], ring[i+1]).
  plan.old_triangles.assign(k, invalid_index);
  for (Index t : s.vertex_triangles[v]) {
    const auto& c = s.triangles[t];
    const int at = c[0] == v ? 0 : c[1] == v ? 1 : 2;
    plan.old_triangles[ring_index(c[(at + 1) % 3])] = t;
  }
  auto star_position = [&plan](Index t) {
    const auto it = std::find(plan.old_triangles.begin(), plan.old_triangles.end(), t);
    return it == plan.old_triangles.end() ? -1 : static_cast<int>(it - plan.old_triangles.begin());
  };
  const Vec2 origin = Vec2::Zero();
  for (int i = 0; i < k; ++i)
    if (orient2d(origin, flattened_ring[i], flattened_ring[(i + 1) % k]) <= 0)
      return refuse(RemovalRefusal::flattening_not_simple);

  // ---- the new triangles ----
  if (static_cast<int>(triangulation.size()) != k - 2) return refuse(RemovalRefusal::no_triangulation);
  auto ring_adjacent = [k](int i, int j) { return (i + 1) % k == j || (j + 1) % k == i; };
  Eigen::Vector3d star_normal = Eigen::Vector3d::Zero();
  const double area_scale = (s.target->bounding_box_max() - s.target->bounding_box_min()).squaredNorm();
  const Eigen::Vector3d& pv = position(v);
  for (int i = 0; i < k; ++i) {
    const Eigen::Vector3d& a = position(ring[i]);
    const Eigen::Vector3d& b = position(ring[(i + 1) % k]);
    star_normal += (a - pv).cross(b - pv);
  }
  for (const auto& tri : triangulation) {
    for (int m = 0; m < 3; ++m) {
      const int i = tri[m], j = tri[(m + 1) % 3];
      if (i < 0 || i >= k || j < 0 || j >= k || i == j) return refuse(RemovalRefusal::no_triangulation);
      if (!ring_adjacent(i, j) && s.has_edge(ring[i], ring[j])) return refuse(RemovalRefusal::existing_edge);
    }
    if (orient2d(flattened_ring[tri[0]], flattened_ring[tri[1]], flattened_ring[tri[2]]) <= 0)
      return refuse(RemovalRefusal::no_triangulation);
    const std::array<Index, 3> corners{ring[tri[0]], ring[tri[1]], ring[tri[2]]};
    const Eigen::Vector3d normal =
        (position(corners[1]) - position(corners[0])).cross(position(corners[2]) - position(corners[0]));
    if (0.5 * normal.norm() <= s.options.min_relative_area * area_scale) return refuse(RemovalRefusal::degenerate_triangle);
    if (normal.dot(star_normal) <= 0.0) return refuse(RemovalRefusal::fold_over);
    plan.new_triangles.push_back(corners);
  }
  if (k == 3) {  // the hole's one triangle must not exist already (it would close a tetrahedron-like pocket)
    for (Index t : s.vertex_triangles[ring[0]]) {
      if (star_position(t) >= 0) continue;
      auto c = s.triangles[t];
      std::sort(c.begin(), c.end());
      auto n = plan.new_triangles[0];
      std::sort(n.begin(), n.end());
      if (c == n) return refuse(RemovalRefusal::existing_edge);
    }
  }
  // Planar corners of the new triangles, and where a planar point falls among them.
  std::vector<std::array<Vec2, 3>> new_planar(k - 2);
  for (int n = 0; n < k - 2; ++n)
    for (int m = 0; m < 3; ++m) new_planar[n][m] = flattened_ring[triangulation[n][m]];
  auto locate = [&](const Vec2& p, Eigen::Vector3d* barycentric) {
    int best = -1;
    double best_min = -std::numeric_limits<double>::infinity();
    for (int n = 0; n < k - 2; ++n) {
      const Eigen::Vector3d b = planar_barycentric(new_planar[n][0], new_planar[n][1], new_planar[n][2], p);
      if (b.minCoeff() > best_min) {
        best_min = b.minCoeff();
        best = n;
        if (barycentric) *barycentric = b;
      }
    }
    return std::pair{best, best_min};
  };
  auto world_on_new = [&](int n, const Eigen::Vector3d& b) {
    const auto& c = plan.new_triangles[n];
    return Eigen::Vector3d(b(0) * position(c[0]) + b(1) * position(c[1]) + b(2) * position(c[2]));
  };
  const Surface<2>& t2 = *s.target;
  auto record_node = [&](const Eigen::Vector3d& domain, const Eigen::Vector3d& image) {
    plan.node_domain_positions.push_back(domain);
    plan.node_target_positions.push_back(image);
    plan.max_node_distance = std::max(plan.max_node_distance, (domain - image).norm());
  };

  // ---- merge: planar positions of the vertex preimages of the star, and their new places ----
  std::vector<std::pair<Index, Vec2>> moved;  // S2 vertex, planar position
  moved.emplace_back(v, origin);
  for (int i = 0; i < k; ++i) {
    const Index t = plan.old_triangles[i];
    const auto& c = s.triangles[t];
    for (Index w : s.triangle_vertices[t]) {
      const Eigen::Vector3d& b = s.preimage_barycentric[w];
      moved.emplace_back(w, b(0) * planar_corner(c[0]) + b(1) * planar_corner(c[1]) + b(2) * planar_corner(c[2]));
    }
  }
  for (const auto& [w, p] : moved) {
    Eigen::Vector3d b;
    const auto [n, min_coordinate] = locate(p, &b);
    if (n < 0 || !(min_coordinate > clearance)) {
      if (n >= 0) {  // name the new edge it is on, if that is a diagonal, so the caller can avoid it
        int side = 0;
        for (int m = 1; m < 3; ++m)
          if (b(m) < b(side)) side = m;
        const int i = triangulation[n][(side + 1) % 3], j = triangulation[n][(side + 2) % 3];
        if (!ring_adjacent(i, j)) plan.blocking_diagonal = {std::min(i, j), std::max(i, j)};
      }
      return refuse(RemovalRefusal::node_on_new_edge);
    }
    plan.relocations.push_back({w, n, b});
    record_node(world_on_new(n, b), t2.vertex(w));
  }
  auto moved_position = [&moved](Index w) -> const Vec2* {
    for (const auto& [u, p] : moved)
      if (u == w) return &p;
    return nullptr;
  };

  // ---- cut: every S2 edge polyline with a segment in the star ----
  std::vector<Index> edges;
  for (Index t : plan.old_triangles) edges.insert(edges.end(), s.triangle_edges[t].begin(), s.triangle_edges[t].end());
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  // Interior edges of the new triangulation (the diagonals), as ring index pairs.
  std::vector<std::array<int, 2>> diagonals;
  for (const auto& tri : triangulation)
    for (int m = 0; m < 3; ++m) {
      const int i = tri[m], j = tri[(m + 1) % 3];
      if (i < j && !ring_adjacent(i, j)) diagonals.push_back({i, j});
    }
  auto new_triangle_with = [&](Index a, Index b) {
    for (int n = 0; n < k - 2; ++n) {
      const auto& c = plan.new_triangles[n];
      const bool has_a = c[0] == a || c[1] == a || c[2] == a, has_b = c[0] == b || c[1] == b || c[2] == b;
      if (has_a && has_b) return n;
    }
    return -1;
  };

  std::vector<Piece> pieces;
  for (Index e : edges) {
    const EdgePolyline& p = s.polylines[e];
    const int segments = static_cast<int>(p.segment_triangle.size());
    bool touches_star = false;
    for (Index t : p.segment_triangle) touches_star = touches_star || star_position(t) >= 0;
    if (!touches_star) continue;  // a stale entry of triangle_edges

    VertexRemovalPlan::PolylineEdit edit;
    edit.target_edge = e;
    auto push_point = [&edit, &p](int i) {
      edit.point_vertex.push_back(p.vertex[i]);
      edit.point_edge.push_back(p.edge[i]);
      edit.point_edge_parameter.push_back(p.edge_parameter[i]);
      edit.point_target_parameter.push_back(p.target_parameter[i]);
    };
    push_point(0);
    int i = 0;
    while (i < segments) {
      if (star_position(p.segment_triangle[i]) < 0) {
        edit.segment_triangle.push_back(p.segment_triangle[i]);
        push_point(i + 1);
        ++i;
        continue;
      }
      int run_end = i;  // segments i .. run_end lie in the star
      while (run_end + 1 < segments && star_position(p.segment_triangle[run_end + 1]) >= 0) ++run_end;

      // The S2 edge runs along a ring edge (its preimage is that S1 edge): it stays, only its
      // triangle is now the new one on the hole's side.
      const bool along_ring_edge = i == run_end && p.vertex[i] != invalid_index && p.vertex[i + 1] != invalid_index &&
                                   s.vertex_live[p.vertex[i]] && s.vertex_live[p.vertex[i + 1]] &&
                                   p.vertex[i] != v && p.vertex[i + 1] != v;
      if (along_ring_edge) {
        const int n = new_triangle_with(p.vertex[i], p.vertex[i + 1]);
        if (n < 0) return refuse(RemovalRefusal::edge_along_new_edge);
        edit.segment_triangle.push_back(-(n + 1));
        push_point(i + 1);
        i = run_end + 1;
        continue;
      }

      // Planar points of the run, each from the first star triangle that holds it.
      std::vector<PlanarPoint> points;
      for (int j = i; j <= run_end + 1; ++j) {
        const Index t = p.segment_triangle[std::min(j, run_end)];
        const auto& c = s.triangles[t];
        PlanarPoint q;
        if (p.vertex[j] != invalid_index) {
          const Index w = p.vertex[j];
          if (s.vertex_live[w] && w != v) {
            q.position = planar_corner(w);
            q.corner = w;
          } else {
            const Vec2* at = moved_position(w);
            if (!at) return refuse(RemovalRefusal::crossing_edges);  // inconsistent state; never expected
            q.position = *at;
          }
        } else {
          const auto [a, b] = p.edge[j];
          if ((a != c[0] && a != c[1] && a != c[2]) || (b != c[0] && b != c[1] && b != c[2]))
            return refuse(RemovalRefusal::crossing_edges);  // inconsistent state; never expected
          q.position = (1.0 - p.edge_parameter[j]) * planar_corner(a) + p.edge_parameter[j] * planar_corner(b);
          if (a != v && b != v) q.edge = p.edge[j];  // on a ring edge: it stays a crossing
        }
        points.push_back(q);
      }

      // Cut every planar segment of the run along the diagonals.
      PlanarPoint previous = points.front();
      std::array<Index, 2> previous_diagonal{invalid_index, invalid_index};
      auto emit_piece_to = [&](const PlanarPoint& to) -> bool {
        if (shares_an_edge(previous, to)) return false;
        Vec2 mid = 0.5 * (previous.position + to.position);
        const auto [n, min_coordinate] = locate(mid, nullptr);
        if (n < 0 || !(min_coordinate > 0.0)) return false;
        edit.segment_triangle.push_back(-(n + 1));
        pieces.push_back({n, previous.position, to.position});
        previous = to;
        return true;
      };
      for (int j = 0; j + 1 < static_cast<int>(points.size()); ++j) {
        const Vec2& from = points[j].position;
        const Vec2& to = points[j + 1].position;
        struct Cut {
          double along;      // parameter on the segment
          int diagonal;
          double parameter;  // on the diagonal, from its first ring vertex
        };
        std::vector<Cut> cuts;
        for (int g = 0; g < static_cast<int>(diagonals.size()); ++g) {
          const Index da = ring[diagonals[g][0]], db = ring[diagonals[g][1]];
          // A point that is a diagonal's own end never crosses it.
          if (points[j].corner == da || points[j].corner == db || points[j + 1].corner == da || points[j + 1].corner == db)
            continue;
          const Vec2& d0 = flattened_ring[diagonals[g][0]];
          const Vec2& d1 = flattened_ring[diagonals[g][1]];
          const int o1 = orient2d(from, to, d0), o2 = orient2d(from, to, d1);
          const int o3 = orient2d(d0, d1, from), o4 = orient2d(d0, d1, to);
          if (o1 == 0 || o2 == 0 || o3 == 0 || o4 == 0) {
            if (segments_cross_properly(from, to, d0, d1)) return refuse(RemovalRefusal::edge_along_new_edge);
            continue;
          }
          if (o1 == o2 || o3 == o4) continue;
          const Vec2 r = to - from, q = d1 - d0;
          const double denom = r.x() * q.y() - r.y() * q.x();
          const Vec2 w = d0 - from;
          const double along = (w.x() * q.y() - w.y() * q.x()) / denom;
          const double parameter = (w.x() * r.y() - w.y() * r.x()) / denom;
          if (!(parameter > clearance && parameter < 1.0 - clearance)) return refuse(RemovalRefusal::edge_along_new_edge);
          cuts.push_back({std::clamp(along, 0.0, 1.0), g, parameter});
        }
        std::sort(cuts.begin(), cuts.end(), [](const Cut& x, const Cut& y) { return x.along < y.along; });
        for (const Cut& cut : cuts) {
          const int di = diagonals[cut.diagonal][0], dj = diagonals[cut.diagonal][1];
          const std::array<Index, 2> key = sorted_pair(ring[di], ring[dj]);
          if (key == previous_diagonal) return refuse(RemovalRefusal::edge_along_new_edge);
          const double t_on_edge = ring[di] < ring[dj] ? cut.parameter : 1.0 - cut.parameter;
          PlanarPoint crossing;
          crossing.position = (1.0 - cut.parameter) * flattened_ring[di] + cut.parameter * flattened_ring[dj];
          crossing.edge = key;
          const double target_parameter =
              (1.0 - cut.along) * p.target_parameter[i + j] + cut.along * p.target_parameter[i + j + 1];
          if (!emit_piece_to(crossing)) return refuse(RemovalRefusal::edge_along_new_edge);
          edit.point_vertex.push_back(invalid_index);
          edit.point_edge.push_back(key);
          edit.point_edge_parameter.push_back(t_on_edge);
          edit.point_target_parameter.push_back(target_parameter);
          previous_diagonal = key;
          const auto [sa, sb] = t2.edge_vertices(e);
          record_node((1.0 - t_on_edge) * position(key[0]) + t_on_edge * position(key[1]),
                      (1.0 - target_parameter) * t2.vertex(sa) + target_parameter * t2.vertex(sb));
        }
      }
      if (!emit_piece_to(points.back())) return refuse(RemovalRefusal::edge_along_new_edge);
      push_point(run_end + 1);
      i = run_end + 1;
    }
    plan.polyline_edits.push_back(std::move(edit));
  }

  // ---- check: straightened pieces in one new triangle must not meet except at shared ends ----
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.triangle < b.triangle; });
  for (std::size_t a = 0; a < pieces.size(); ++a)
    for (std::size_t b = a + 1; b < pieces.size() && pieces[b].triangle == pieces[a].triangle; ++b)
      if (segments_cross_properly(pieces[a].from, pieces[a].to, pieces[b].from, pieces[b].to))
        return refuse(RemovalRefusal::crossing_edges);
  return plan;
}

}  // namespace plmap
