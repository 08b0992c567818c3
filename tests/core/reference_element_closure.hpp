#pragma once
// The closure's fast path as it was before its speed-ups (neighbours paired by sorting side keys,
// every ear tested against all three sides, incircle out of line), kept as the reference the
// white-box tests compare the library's version with: same triangles in the same order, same
// neighbours, same rings.

#include "element_closure.hpp"

#include <plmap/core/predicates.hpp>

#include <algorithm>
#include <numeric>
#include <tuple>

namespace plmap::reference {

struct Closure {
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 3>> neighbors;
  std::vector<int> face;
  int face_count = 0;
  void clear() {
    triangles.clear();
    neighbors.clear();
    face.clear();
    face_count = 0;
  }
};

struct Scratch {
  std::vector<int> out_begin, out_half_edge, position, next, half_edge_face, cycle, polygon;
  std::vector<char> visited;
  std::vector<int> order;
  std::vector<std::pair<std::uint64_t, int>> side_keys;
};

namespace reference_detail {

/// 0 for directions in the upper half plane (angle in [0, pi)), 1 for the lower one; exact,
/// because it only compares coordinates.
inline int half_plane(const LocalPoint<2>& center, const LocalPoint<2>& p) {
  return (p.y() > center.y() || (p.y() == center.y() && p.x() > center.x())) ? 0 : 1;
}

/// Shape of a candidate ear: area over the sum of squared sides (largest for equilateral).
inline double ear_shape(const LocalPoint<2>& a, const LocalPoint<2>& b, const LocalPoint<2>& c) {
  const LocalPoint<2> u = b - a, v = c - a, w = c - b;
  const double area = u.x() * v.y() - u.y() * v.x();
  return area / (u.squaredNorm() + v.squaredNorm() + w.squaredNorm());
}

// Faces larger than this go to the general triangulation: ear clipping with shape choice is
// cubic in the face size.
constexpr int largest_face = 96;

/// Lawson flips inside faces: a diagonal (a side whose two triangles belong to the same face)
/// whose far vertex lies inside the other triangle's circumcircle is flipped, until none is left.
/// Graph edges and the element boundary are never flipped, so the result is the constrained
/// Delaunay triangulation of each face (up to cocircular ties).
inline void make_faces_delaunay(std::span<const LocalPoint<2>> points, Closure& out,
                         Scratch& s) {
  auto& tri = out.triangles;
  auto& nb = out.neighbors;
  const int nt = static_cast<int>(tri.size());
  auto& stack = s.polygon;  // (triangle, side) pairs as 3 * t + i
  stack.clear();
  for (int t = 0; t < nt; ++t)
    for (int i = 0; i < 3; ++i)
      if (nb[t][i] > t && out.face[nb[t][i]] == out.face[t]) stack.push_back(3 * t + i);
  auto side_towards = [&](int u, int t) {
    for (int j = 0; j < 3; ++j)
      if (nb[u][j] == t) return j;
    return -1;
  };
  // Each flip removes a non-Delaunay side for good; the bound only guards against a logic error.
  for (long budget = 16L * nt * nt + 64; !stack.empty() && budget > 0; --budget) {
    const int t = stack.back() / 3, i = stack.back() % 3;
    stack.pop_back();
    const int u = nb[t][i];
    if (u < 0 || out.face[u] != out.face[t]) continue;
    const int j = side_towards(u, t);
    if (j < 0) continue;
    // t = (p, a, b) and u = (q, b, a), counter-clockwise, sharing side a-b.
    const int p = tri[t][i], a = tri[t][(i + 1) % 3], b = tri[t][(i + 2) % 3];
    const int q = tri[u][j];
    if (detail::incircle_exact(points[p], points[a], points[b], points[q]) <= 0) continue;
    if (orient2d(points[p], points[a], points[q]) <= 0 || orient2d(points[q], points[b], points[p]) <= 0)
      continue;  // not a convex quadrilateral: cannot flip
    const int t_opp_a = nb[t][(i + 1) % 3];  // across side b-p
    const int t_opp_b = nb[t][(i + 2) % 3];  // across side p-a
    const int u_opp_b = nb[u][(j + 1) % 3];  // across side a-q (u = (q, b, a))
    const int u_opp_a = nb[u][(j + 2) % 3];  // across side q-b
    tri[t] = {p, a, q};
    nb[t] = {u_opp_b, u, t_opp_b};
    tri[u] = {q, b, p};
    nb[u] = {t_opp_a, t, u_opp_a};
    if (u_opp_b >= 0) nb[u_opp_b][side_towards(u_opp_b, u)] = t;
    if (t_opp_a >= 0) nb[t_opp_a][side_towards(t_opp_a, t)] = u;
    stack.push_back(3 * t + 0);
    stack.push_back(3 * t + 2);
    stack.push_back(3 * u + 0);
    stack.push_back(3 * u + 2);
  }
}

}  // namespace reference_detail
using namespace reference_detail;

inline bool close_by_faces(std::span<const LocalPoint<2>> points,
                    std::span<const std::array<int, 2>> segments, std::array<int, 2> boundary_start,
                    Closure& out, Scratch& s) {
  out.clear();
  const int nv = static_cast<int>(points.size());
  const int ne = static_cast<int>(segments.size());
  const int nh = 2 * ne;
  if (nv < 3) return false;

  // Distinct points (coincident nodes are an error the general path reports).
  s.order.resize(nv);
  std::iota(s.order.begin(), s.order.end(), 0);
  std::sort(s.order.begin(), s.order.end(), [&](int a, int b) {
    return std::tie(points[a].x(), points[a].y()) < std::tie(points[b].x(), points[b].y());
  });
  for (int i = 1; i < nv; ++i)
    if (points[s.order[i]] == points[s.order[i - 1]]) return false;

  // Half-edge h = 2i + r runs from segments[i][r] to segments[i][1 - r]; its twin is h ^ 1.
  auto origin = [&](int h) { return segments[h >> 1][h & 1]; };
  auto target = [&](int h) { return segments[h >> 1][1 - (h & 1)]; };
  s.out_begin.assign(nv + 1, 0);
  for (int h = 0; h < nh; ++h) ++s.out_begin[origin(h) + 1];
  for (int v = 0; v < nv; ++v) {
    if (s.out_begin[v + 1] < 2) return false;  // isolated or dangling: not a plain tiling
    s.out_begin[v + 1] += s.out_begin[v];
  }
  s.out_half_edge.resize(nh);
  s.position.resize(nh);
  {
    s.cycle.assign(s.out_begin.begin(), s.out_begin.end() - 1);  // fill cursors
    for (int h = 0; h < nh; ++h) s.out_half_edge[s.cycle[origin(h)]++] = h;
  }
  // Counter-clockwise order of the edges around each vertex, decided by exact predicates only.
  bool degenerate = false;
  for (int v = 0; v < nv; ++v) {
    const LocalPoint<2>& c = points[v];
    auto first = s.out_half_edge.begin() + s.out_begin[v];
    auto last = s.out_half_edge.begin() + s.out_begin[v + 1];
    std::sort(first, last, [&](int ha, int hb) {
      const LocalPoint<2>& a = points[target(ha)];
      const LocalPoint<2>& b = points[target(hb)];
      const int qa = half_plane(c, a), qb = half_plane(c, b);
      if (qa != qb) return qa < qb;
      const int o = orient2d(c, a, b);
      if (o == 0 && ha != hb) degenerate = true;  // two edges leave v in the same direction
      return o > 0;
    });
    for (int i = s.out_begin[v]; i < s.out_begin[v + 1]; ++i) s.position[s.out_half_edge[i]] = i;
  }
  if (degenerate) return false;

  // The face left of u->v continues with the edge that precedes v->u around v.
  s.next.resize(nh);
  for (int h = 0; h < nh; ++h) {
    const int twin = h ^ 1;
    const int v = origin(twin);
    const int p = s.position[twin];
    s.next[h] = s.out_half_edge[p == s.out_begin[v] ? s.out_begin[v + 1] - 1 : p - 1];
  }
  s.half_edge_face.assign(nh, -1);
  int faces = 0;
  for (int h0 = 0; h0 < nh; ++h0) {
    if (s.half_edge_face[h0] >= 0) continue;
    int h = h0, guard = 0;
    do {
      s.half_edge_face[h] = faces;
      h = s.next[h];
      if (++guard > nh) return false;
    } while (h != h0);
    ++faces;
  }
  // A connected plane graph has E - V + 2 faces; fewer means parts floating inside a face.
  if (faces != ne - nv + 2) return false;

  int boundary_half_edge = -1;
  for (int i = 0; i < ne && boundary_half_edge < 0; ++i) {
    if (segments[i][0] == boundary_start[0] && segments[i][1] == boundary_start[1]) boundary_half_edge = 2 * i;
    if (segments[i][1] == boundary_start[0] && segments[i][0] == boundary_start[1]) boundary_half_edge = 2 * i + 1;
  }
  if (boundary_half_edge < 0) return false;
  const int outer = s.half_edge_face[boundary_half_edge ^ 1];
  if (s.half_edge_face[boundary_half_edge] == outer) return false;

  // Renumber the inner faces 0 .. faces - 2 and cut each into triangles.
  s.visited.assign(nv, 0);
  s.cycle.assign(faces, 0);  // cycle[f] = 1 once face f has been triangulated
  int face_id = 0;
  std::vector<int>& poly = s.polygon;
  for (int h0 = 0; h0 < nh; ++h0) {
    const int f = s.half_edge_face[h0];
    if (f == outer || s.cycle[f]) continue;
    s.cycle[f] = 1;
    poly.clear();
    int h = h0;
    do {
      const int v = origin(h);
      if (s.visited[v]) {  // a vertex twice on one face: dangling edge or pinched face
        for (int u : poly) s.visited[u] = 0;
        return false;
      }
      s.visited[v] = 1;
      poly.push_back(v);
      h = s.next[h];
    } while (h != h0);
    for (int u : poly) s.visited[u] = 0;
    const int k = static_cast<int>(poly.size());
    if (k < 3 || k > largest_face) return false;

    // Counter-clockwise: the turn at the lexicographically smallest vertex is a left turn.
    int low = 0;
    for (int i = 1; i < k; ++i)
      if (std::tie(points[poly[i]].x(), points[poly[i]].y()) <
          std::tie(points[poly[low]].x(), points[poly[low]].y()))
        low = i;
    if (orient2d(points[poly[(low + k - 1) % k]], points[poly[low]], points[poly[(low + 1) % k]]) <= 0)
      return false;
    // Simple: no two sides meet except consecutive ones at their common vertex. A convex face
    // that winds once is simple, and that is decided in O(k); other faces take the O(k^2) test.
    if (k > 3 && !detail::convex_and_winding_once(points, poly))
      for (int i = 0; i < k; ++i)
        for (int j = i + 1; j < k; ++j)
          if (segments_cross_properly(points[poly[i]], points[poly[(i + 1) % k]], points[poly[j]],
                                      points[poly[(j + 1) % k]]))
            return false;

    // Ear clipping; of the ears, the best-shaped one goes first.
    while (poly.size() > 3) {
      const int m = static_cast<int>(poly.size());
      int best = -1;
      double best_shape = 0.0;
      for (int i = 0; i < m; ++i) {
        const LocalPoint<2>& a = points[poly[(i + m - 1) % m]];
        const LocalPoint<2>& b = points[poly[i]];
        const LocalPoint<2>& c = points[poly[(i + 1) % m]];
        if (orient2d(a, b, c) <= 0) continue;
        bool empty = true;
        for (int j = 0; j < m && empty; ++j) {
          if (j == i || j == (i + 1) % m || j == (i + m - 1) % m) continue;
          const LocalPoint<2>& x = points[poly[j]];
          if (orient2d(a, b, x) >= 0 && orient2d(b, c, x) >= 0 && orient2d(c, a, x) >= 0) empty = false;
        }
        if (!empty) continue;
        const double shape = ear_shape(a, b, c);
        if (best < 0 || shape > best_shape) {
          best = i;
          best_shape = shape;
        }
      }
      if (best < 0) return false;
      out.triangles.push_back({poly[(best + m - 1) % m], poly[best], poly[(best + 1) % m]});
      out.face.push_back(face_id);
      poly.erase(poly.begin() + best);
    }
    if (orient2d(points[poly[0]], points[poly[1]], points[poly[2]]) <= 0) return false;
    out.triangles.push_back({poly[0], poly[1], poly[2]});
    out.face.push_back(face_id);
    ++face_id;
  }
  out.face_count = face_id;

  // Neighbours: pair the triangle sides by their vertex pair.
  // Side ts = 3 t + i (opposite corner i) gets the key (smaller vertex, larger vertex) packed into
  // one integer, computed once: sorting the keys is much cheaper than comparing vertex pairs.
  const int nt = static_cast<int>(out.triangles.size());
  auto& keys = s.side_keys;
  keys.resize(3 * static_cast<std::size_t>(nt));
  for (int ts = 0; ts < 3 * nt; ++ts) {
    const auto& tri = out.triangles[ts / 3];
    const auto a = static_cast<std::uint32_t>(tri[(ts % 3 + 1) % 3]), b = static_cast<std::uint32_t>(tri[(ts % 3 + 2) % 3]);
    keys[ts] = {(static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b), ts};
  }
  std::sort(keys.begin(), keys.end());
  out.neighbors.assign(nt, {-1, -1, -1});
  for (int i = 0; i < 3 * nt;) {
    int j = i + 1;
    while (j < 3 * nt && keys[j].first == keys[i].first) ++j;
    if (j - i > 2) return false;
    if (j - i == 2) {
      const int x = keys[i].second, y = keys[i + 1].second;
      out.neighbors[x / 3][x % 3] = y / 3;
      out.neighbors[y / 3][y % 3] = x / 3;
    }
    i = j;
  }
  make_faces_delaunay(points, out, s);
  return true;
}

inline void closure_rings(const Closure& closure, int vertex_count, std::vector<int>& ring_begin,
                   std::vector<int>& ring) {
  const int nt = static_cast<int>(closure.triangles.size());
  // one incident (triangle, corner) per vertex
  std::vector<int> incident(vertex_count, -1);
  for (int t = 0; t < nt; ++t)
    for (int i = 0; i < 3; ++i)
      if (incident[closure.triangles[t][i]] < 0) incident[closure.triangles[t][i]] = 3 * t + i;
  ring_begin.assign(1, 0);
  ring.clear();
  auto corner_of = [&](int t, int v) {
    const auto& tri = closure.triangles[t];
    return tri[0] == v ? 0 : (tri[1] == v ? 1 : 2);
  };
  for (int v = 0; v < vertex_count; ++v) {
    if (incident[v] < 0) {
      ring_begin.push_back(static_cast<int>(ring.size()));
      continue;
    }
    // Around v in triangle (v, a, b): a comes before b counter-clockwise; the next triangle
    // shares side v-b (opposite a), the previous one side v-a (opposite b).
    int t = incident[v] / 3;
    const int t0 = t;
    bool boundary = false;
    for (int guard = 0; guard <= nt; ++guard) {
      const int prev = closure.neighbors[t][(corner_of(t, v) + 2) % 3];
      if (prev < 0) {
        boundary = true;
        break;
      }
      t = prev;
      if (t == t0) break;
    }
    const std::size_t first = ring.size();
    const int start = t;
    ring.push_back(closure.triangles[t][(corner_of(t, v) + 1) % 3]);
    for (int guard = 0; guard <= nt; ++guard) {
      const int i = corner_of(t, v);
      const int next = closure.neighbors[t][(i + 1) % 3];
      if (next < 0) {
        ring.push_back(closure.triangles[t][(i + 2) % 3]);
        break;
      }
      t = next;
      if (t == start) break;
      ring.push_back(closure.triangles[t][(corner_of(t, v) + 1) % 3]);
    }
    if (!boundary) {
      const auto smallest = std::min_element(ring.begin() + static_cast<std::ptrdiff_t>(first), ring.end());
      std::rotate(ring.begin() + static_cast<std::ptrdiff_t>(first), smallest, ring.end());
    }
    ring_begin.push_back(static_cast<int>(ring.size()));
  }
}

}  // namespace plmap::reference
