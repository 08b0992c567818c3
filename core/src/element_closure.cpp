// Fast triangular closure of one element's plane graph: faces traced from the rotation system,
// each face cut into triangles by ear clipping. See element_closure.hpp for the contract.

#include "element_closure.hpp"

#include <plmap/core/predicates.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace plmap::detail {

namespace {

/// Shape of a candidate ear: area over the sum of squared sides (largest for equilateral).
double ear_shape(const LocalPoint<2>& a, const LocalPoint<2>& b, const LocalPoint<2>& c) {
  const LocalPoint<2> u = b - a, v = c - a, w = c - b;
  const double area = u.x() * v.y() - u.y() * v.x();
  return area / (u.squaredNorm() + v.squaredNorm() + w.squaredNorm());
}

// Faces larger than this go to the general triangulation: ear clipping with shape choice is
// cubic in the face size.
constexpr int largest_face = 96;

/// Exact sign of the cross product of the directions u = a - c and v = b - c (the orientation of
/// c, a, b), given u and v as computed in floating point: the same static filter as orient2d, whose
/// bound covers the rounding of the differences, and orient2d itself when the filter cannot tell.
int turn_sign(const LocalPoint<2>& u, const LocalPoint<2>& v, const LocalPoint<2>& c,
              const LocalPoint<2>& a, const LocalPoint<2>& b) {
  const double left = u.x() * v.y(), right = u.y() * v.x();
  const double det = left - right;
  constexpr double error_factor = 3.3306690738754716e-16;  // as in orient2d
  // never below 2^-940, as in orient2d: no decision where underflow could matter
  const double bound = std::max(error_factor * (std::abs(left) + std::abs(right)), 0x1p-940);
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return orient2d(c, a, b);
}

/// Sides of triangles are numbered 3 t + i (the side opposite corner i of triangle t). While a
/// face is being cut, each side of the remaining polygon is owned by a half-edge of the graph
/// (h >= 0) or by the side of a triangle already cut off (encoded as -1 - side).
constexpr int owned_by_side(int side) { return -1 - side; }

}  // namespace

bool flip_side(std::span<const LocalPoint<2>> points, ElementClosure& out, int t, int i) {
  auto& tri = out.triangles;
  auto& nb = out.neighbors;
  auto& graph = out.graph_sides;
  const int u = nb[t][i];
  if (u < 0) return false;
  auto side_towards = [&](int from, int to) {
    for (int j = 0; j < 3; ++j)
      if (nb[from][j] == to) return j;
    return -1;
  };
  const int j = side_towards(u, t);
  if (j < 0) return false;
  // t = (p, a, b) and u = (q, b, a), counter-clockwise, sharing side a-b.
  const int p = tri[t][i], a = tri[t][(i + 1) % 3], b = tri[t][(i + 2) % 3];
  const int q = tri[u][j];
  if (orient2d(points[p], points[a], points[q]) <= 0 || orient2d(points[q], points[b], points[p]) <= 0)
    return false;  // not a convex quadrilateral
  auto graph_bit = [&](int x, int k) -> std::uint8_t { return (graph[x] >> k) & 1u; };
  const int t_opp_a = nb[t][(i + 1) % 3];  // across side b-p
  const int t_opp_b = nb[t][(i + 2) % 3];  // across side p-a
  const int u_opp_b = nb[u][(j + 1) % 3];  // across side a-q (u = (q, b, a))
  const int u_opp_a = nb[u][(j + 2) % 3];  // across side q-b
  // The four outer sides keep their graph flags; the new diagonal p-q is not a graph edge.
  const std::uint8_t g_bp = graph_bit(t, (i + 1) % 3), g_pa = graph_bit(t, (i + 2) % 3);
  const std::uint8_t g_aq = graph_bit(u, (j + 1) % 3), g_qb = graph_bit(u, (j + 2) % 3);
  tri[t] = {p, a, q};
  nb[t] = {u_opp_b, u, t_opp_b};
  graph[t] = static_cast<std::uint8_t>(g_aq | (g_pa << 2));
  tri[u] = {q, b, p};
  nb[u] = {t_opp_a, t, u_opp_a};
  graph[u] = static_cast<std::uint8_t>(g_bp | (g_qb << 2));
  if (u_opp_b >= 0) nb[u_opp_b][side_towards(u_opp_b, u)] = t;
  if (t_opp_a >= 0) nb[t_opp_a][side_towards(t_opp_a, t)] = u;
  return true;
}

namespace {

/// Lawson flips inside faces: a diagonal (a side whose two triangles belong to the same face)
/// whose far vertex lies inside the other triangle's circumcircle is flipped, until none is left.
/// Graph edges and the element boundary are never flipped, so the result is the constrained
/// Delaunay triangulation of each face (up to cocircular ties). `stack` starts with the diagonals
/// as sides 3 t + i whose other triangle comes after t, in increasing order; it is used up.
void make_faces_delaunay(std::span<const LocalPoint<2>> points, ElementClosure& out, std::vector<int>& stack) {
  if (stack.empty()) return;  // every face a triangle: no diagonal
  auto& tri = out.triangles;
  auto& nb = out.neighbors;
  const int nt = static_cast<int>(tri.size());
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
    if (incircle(points[p], points[a], points[b], points[q]) <= 0) continue;
    if (!flip_side(points, out, t, i)) continue;  // not a convex quadrilateral
    stack.push_back(3 * t + 0);
    stack.push_back(3 * t + 2);
    stack.push_back(3 * u + 0);
    stack.push_back(3 * u + 2);
  }
}

}  // namespace

/// Whether the closed polygon turns left or goes straight at every vertex, never doubles back,
/// and its sides' directions go round exactly once: then it is convex and simple. Exact: turns by
/// orient2d, and the direction of a side (its half plane, whether two sides point opposite ways)
/// only by comparing coordinates. The direction angle only grows, by less than pi per vertex, so
/// it passes from the lower half plane into the upper one once per turn round.
bool convex_and_winding_once(std::span<const LocalPoint<2>> points, std::span<const int> poly) {
  const int k = static_cast<int>(poly.size());
  auto sign = [](double from, double to) { return (to > from) - (to < from); };
  auto upper = [&](int i) {  // side i runs from poly[i] to poly[i + 1]
    const LocalPoint<2>& p = points[poly[i]];
    const LocalPoint<2>& q = points[poly[(i + 1) % k]];
    return q.y() > p.y() || (q.y() == p.y() && q.x() > p.x());
  };
  int rounds = 0;
  for (int i = 0; i < k; ++i) {
    const LocalPoint<2>& a = points[poly[(i + k - 1) % k]];
    const LocalPoint<2>& b = points[poly[i]];
    const LocalPoint<2>& c = points[poly[(i + 1) % k]];
    const int turn = orient2d(a, b, c);
    if (turn < 0) return false;
    if (turn == 0 && (sign(a.x(), b.x()) * sign(b.x(), c.x()) < 0 || sign(a.y(), b.y()) * sign(b.y(), c.y()) < 0))
      return false;  // doubles back along a line
    if (!upper((i + k - 1) % k) && upper(i)) ++rounds;
  }
  return rounds == 1;
}

namespace {

/// No two points coincide (coincident nodes are an error the general path reports): few points
/// are compared pairwise, many sorted by value (equal points are then neighbours).
bool points_distinct(std::span<const LocalPoint<2>> points, ClosureScratch& s) {
  const int nv = static_cast<int>(points.size());
  const LocalPoint<2>* p = points.data();
  if (nv <= 32) {
    for (int i = 1; i < nv; ++i)
      for (int j = 0; j < i; ++j)
        if (p[i] == p[j]) return false;
  } else {
    auto& sorted = s.sorted_points;
    sorted.assign(points.begin(), points.end());
    std::sort(sorted.begin(), sorted.end(), [](const LocalPoint<2>& a, const LocalPoint<2>& b) {
      return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    for (int i = 1; i < nv; ++i)
      if (sorted[i] == sorted[i - 1]) return false;
  }
  return true;
}

/// The half-edges of the segments (h = 2i + r runs from segments[i][r] to segments[i][1 - r]; its
/// twin is h ^ 1), and around each vertex the half-edges leaving it in counter-clockwise order.
/// False if a vertex has fewer than two edges or two edges leave one vertex in the same direction.
bool order_half_edges(std::span<const LocalPoint<2>> points, std::span<const ClosureSegment> segments,
                      ClosureScratch& s) {
  const int nv = static_cast<int>(points.size());
  const int ne = static_cast<int>(segments.size());
  const int nh = 2 * ne;
  const LocalPoint<2>* p = points.data();
  s.half_edges.resize(nh);
  ClosureScratch::HalfEdge* he = s.half_edges.data();
  for (int i = 0; i < ne; ++i) {
    const int a = segments[i].a, b = segments[i].b;
    he[2 * i].from = he[2 * i + 1].to = a;
    he[2 * i].to = he[2 * i + 1].from = b;
  }
  s.out_begin.assign(nv + 1, 0);
  int* out_begin = s.out_begin.data();
  for (int h = 0; h < nh; ++h) ++out_begin[he[h].from + 1];
  for (int v = 0; v < nv; ++v) {
    if (out_begin[v + 1] < 2) return false;  // isolated or dangling: not a plain tiling
    out_begin[v + 1] += out_begin[v];
  }
  s.out_half_edge.resize(nh);
  int* around = s.out_half_edge.data();
  s.cursor.assign(out_begin, out_begin + nv);
  for (int h = 0; h < nh; ++h) around[s.cursor[he[h].from]++] = h;
  // Counter-clockwise order of the edges around each vertex, decided by exact predicates only:
  // first the half plane of the direction (angle in [0, pi) or [pi, 2 pi), by comparing
  // coordinates), then within a half plane the orientation.
  for (int h = 0; h < nh; ++h) {
    const LocalPoint<2>& c = p[he[h].from];
    const LocalPoint<2>& q = p[he[h].to];
    he[h].direction = q - c;
    he[h].upper = q.y() > c.y() || (q.y() == c.y() && q.x() > c.x());
    he[h].side = -1;
  }
  auto turn = [&](int ha, int hb) {  // orientation of (from, to(ha), to(hb)), exact
    return turn_sign(he[ha].direction, he[hb].direction, p[he[ha].from], p[he[ha].to], p[he[hb].to]);
  };
  auto precedes = [&](int ha, int hb) {  // strictly, counter-clockwise from angle 0
    if (he[ha].upper != he[hb].upper) return he[ha].upper;
    return turn(ha, hb) > 0;
  };
  for (int v = 0; v < nv; ++v) {
    int* first = around + out_begin[v];
    const int degree = out_begin[v + 1] - out_begin[v];
    for (int i = 1; i < degree; ++i) {  // insertion sort: degrees are small
      const int h = first[i];
      int j = i;
      for (; j > 0 && precedes(h, first[j - 1]); --j) first[j] = first[j - 1];
      first[j] = h;
    }
    // Two edges leaving v in the same direction (an overlap) end up side by side.
    for (int i = 1; i < degree; ++i)
      if (he[first[i - 1]].upper == he[first[i]].upper && turn(first[i - 1], first[i]) == 0) return false;
    for (int i = 0; i < degree; ++i) he[first[i]].position = out_begin[v] + i;
  }
  return true;
}

/// The faces of the plane graph: each half-edge's next one on the face to its left, and its face,
/// numbered in the order of their first (smallest) half-edge. Returns the number of faces, or -1
/// if a face does not close.
int trace_faces(int nh, ClosureScratch& s) {
  ClosureScratch::HalfEdge* he = s.half_edges.data();
  const int* out_begin = s.out_begin.data();
  const int* around = s.out_half_edge.data();
  // The face left of u->v continues with the edge that precedes v->u around v.
  for (int h = 0; h < nh; ++h) {
    const int v = he[h].to;
    const int at = he[h ^ 1].position;
    he[h].next = around[at == out_begin[v] ? out_begin[v + 1] - 1 : at - 1];
    he[h].face = -1;
  }
  // Faces are numbered in the order of their first (smallest) half-edge, where each is traced from.
  int faces = 0;
  s.face_first.clear();
  for (int h0 = 0; h0 < nh; ++h0) {
    if (he[h0].face >= 0) continue;
    int h = h0, guard = 0;
    do {
      he[h].face = faces;
      h = he[h].next;
      if (++guard > nh) return -1;
    } while (h != h0);
    s.face_first.push_back(h0);
    ++faces;
  }
  return faces;
}

/// The outer face: the one right of the boundary half-edge (a, b) = boundary_start, which must be
/// a segment with another face on its left; -1 if it is not.
int outer_face(std::span<const ClosureSegment> segments, std::array<int, 2> boundary_start, const ClosureScratch& s) {
  const int ne = static_cast<int>(segments.size());
  const ClosureScratch::HalfEdge* he = s.half_edges.data();
  int boundary_half_edge = -1;
  for (int i = 0; i < ne && boundary_half_edge < 0; ++i) {
    if (segments[i].a == boundary_start[0] && segments[i].b == boundary_start[1]) boundary_half_edge = 2 * i;
    if (segments[i].b == boundary_start[0] && segments[i].a == boundary_start[1]) boundary_half_edge = 2 * i + 1;
  }
  if (boundary_half_edge < 0) return -1;
  const int outer = he[boundary_half_edge ^ 1].face;
  if (he[boundary_half_edge].face == outer) return -1;
  return outer;
}

/// Cuts the inner faces into triangles, one face at a time (cut), into `out`. Once the inner faces
/// are known to tile the element (each a simple counter-clockwise polygon, the outer face its
/// boundary), the triangles form a triangulation with 2 V - B - 2 triangles (B vertices on the
/// boundary), and every diagonal lies inside its face, so no side is shared by three triangles.
class FaceCutter {
 public:
  FaceCutter(std::span<const LocalPoint<2>> points, std::span<const ClosureSegment> segments, ElementClosure& out,
             ClosureScratch& s)
      : points_(points), p(points.data()), segments_(segments), he(s.half_edges.data()), out(out), s(s) {
    const auto nv = static_cast<std::size_t>(points.size());
    out.triangles.reserve(2 * nv);
    out.neighbors.reserve(2 * nv);
    out.graph_sides.reserve(2 * nv);
    out.face.reserve(2 * nv);
    s.flips.clear();
  }

  /// Cuts face f (traced from s.face_first[f]); false if it is not a simple counter-clockwise
  /// polygon of at most largest_face sides.
  bool cut(int f) {
    const int h0 = s.face_first[f];
    int k = 0;
    int h = h0;
    do {
      if (k == largest_face) return false;
      poly[k] = he[h].from;
      poly_side[k] = h;
      ++k;
      h = he[h].next;
    } while (h != h0);
    if (k < 3) return false;
    if (k == 3) {  // already a triangle (most faces): counter-clockwise is all there is to check
      if (poly[0] == poly[1] || poly[1] == poly[2] || poly[2] == poly[0]) return false;
      return close_face();
    }
    // A vertex twice on one face: dangling edge or pinched face.
    for (int i = 1; i < k; ++i)
      for (int j = 0; j < i; ++j)
        if (poly[i] == poly[j]) return false;

    // Counter-clockwise: the turn at the lexicographically smallest vertex is a left turn.
    int low = 0;
    for (int i = 1; i < k; ++i)
      if (std::tie(p[poly[i]].x(), p[poly[i]].y()) < std::tie(p[poly[low]].x(), p[poly[low]].y())) low = i;
    if (orient2d(p[poly[low == 0 ? k - 1 : low - 1]], p[poly[low]], p[poly[low + 1 == k ? 0 : low + 1]]) <= 0)
      return false;
    // Simple: no two sides meet except consecutive ones at their common vertex. A convex face
    // that winds once is simple, and that is decided in O(k); other faces take the O(k^2) test.
    const bool convex = k == 3 || convex_and_winding_once(points_, std::span<const int>(poly.data(), k));
    if (!convex)
      for (int i = 0; i < k; ++i)
        for (int j = i + 1; j < k; ++j)
          if (segments_cross_properly(p[poly[i]], p[poly[(i + 1) % k]], p[poly[j]], p[poly[(j + 1) % k]]))
            return false;

    // Ear clipping; of the ears, the best-shaped one goes first.
    for (int m = k; m > 3; --m) {
      int best = -1;
      double best_shape = 0.0;
      for (int i = 0; i < m; ++i) {
        const int before = i == 0 ? m - 1 : i - 1, after = i + 1 == m ? 0 : i + 1;
        const LocalPoint<2>& a = p[poly[before]];
        const LocalPoint<2>& b = p[poly[i]];
        const LocalPoint<2>& c = p[poly[after]];
        if (orient2d(a, b, c) <= 0) continue;
        // An ear is empty when no other vertex lies in the closed triangle a, b, c.
        bool empty = true;
        if (convex) {
          // The vertices of a convex polygon (and of what is left of one after cutting ears) are
          // in convex position: the chord c-a has b strictly on one side and all other vertices
          // on the other side or on the chord. One of them on the chord means the chord is a
          // supporting line, so all of them are on it, the one after c among them; and then that
          // one lies on the closed segment c-a (the polygon does not double back), in the ear.
          const int beyond = after + 1 == m ? 0 : after + 1;
          empty = orient2d(c, a, p[poly[beyond]]) < 0;
        } else {
          for (int j = 0; j < m && empty; ++j) {
            if (j == i || j == after || j == before) continue;
            const LocalPoint<2>& x = p[poly[j]];
            if (orient2d(a, b, x) >= 0 && orient2d(b, c, x) >= 0 && orient2d(c, a, x) >= 0) empty = false;
          }
        }
        if (!empty) continue;
        const double shape = ear_shape(a, b, c);
        if (best < 0 || shape > best_shape) {
          best = i;
          best_shape = shape;
        }
      }
      if (best < 0) return false;
      const int before = best == 0 ? m - 1 : best - 1, after = best + 1 == m ? 0 : best + 1;
      const int t = add_triangle(poly[before], poly[best], poly[after]);
      attach(3 * t + 0, poly_side[best]);
      attach(3 * t + 2, poly_side[before]);
      // The diagonal poly[before] -> poly[after] is side 1 of t; its other triangle comes later
      // in the same face, so it is a candidate for a Lawson flip.
      poly_side[before] = owned_by_side(3 * t + 1);
      s.flips.push_back(3 * t + 1);
      std::copy(poly.begin() + best + 1, poly.begin() + m, poly.begin() + best);
      std::copy(poly_side.begin() + best + 1, poly_side.begin() + m, poly_side.begin() + best);
    }
    return close_face();
  }

  int faces_cut() const { return face_id; }

 private:
  // The sides of a new triangle are paired with what owned them: a graph half-edge (paired with
  // its twin's triangle once every face is cut) or a diagonal cut earlier in the same face.
  void attach(int side, int owner) {
    const int t = side / 3, i = side % 3;
    if (owner >= 0) {
      he[owner].side = side;
      if (segments_[owner >> 1].graph) out.graph_sides[t] = static_cast<std::uint8_t>(out.graph_sides[t] | (1u << i));
    } else {
      const int other = -1 - owner;
      out.neighbors[t][i] = other / 3;
      out.neighbors[other / 3][other % 3] = t;
    }
  }
  int add_triangle(int a, int b, int c) {
    const int t = static_cast<int>(out.triangles.size());
    out.triangles.push_back({a, b, c});
    out.neighbors.push_back({-1, -1, -1});
    out.graph_sides.push_back(0);
    out.face.push_back(face_id);
    return t;
  }
  // The triangle poly[0..2] that is left of a face (or is the whole face): false if it is not
  // counter-clockwise, else it closes the face.
  bool close_face() {
    if (orient2d(p[poly[0]], p[poly[1]], p[poly[2]]) <= 0) return false;
    const int t = add_triangle(poly[0], poly[1], poly[2]);
    attach(3 * t + 0, poly_side[1]);
    attach(3 * t + 1, poly_side[2]);
    attach(3 * t + 2, poly_side[0]);
    ++face_id;
    return true;
  }

  std::span<const LocalPoint<2>> points_;
  const LocalPoint<2>* p;
  std::span<const ClosureSegment> segments_;
  ClosureScratch::HalfEdge* he;
  ElementClosure& out;
  ClosureScratch& s;
  int face_id = 0;
  // The polygon of the face being cut, and the owner of each of its sides poly[m] -> poly[m + 1]:
  // a graph half-edge, or the diagonal of a triangle cut off earlier.
  std::array<int, largest_face> poly, poly_side;
};

}  // namespace

bool close_by_faces(std::span<const LocalPoint<2>> points, std::span<const ClosureSegment> segments,
                    std::array<int, 2> boundary_start, ElementClosure& out, ClosureScratch& s) {
  out.clear();
  const int nv = static_cast<int>(points.size());
  const int ne = static_cast<int>(segments.size());
  const int nh = 2 * ne;
  if (nv < 3) return false;
  if (!points_distinct(points, s) || !order_half_edges(points, segments, s)) return false;
  const int faces = trace_faces(nh, s);
  // A connected plane graph has E - V + 2 faces; fewer means parts floating inside a face.
  if (faces < 0 || faces != ne - nv + 2) return false;
  const int outer = outer_face(segments, boundary_start, s);
  if (outer < 0) return false;
  FaceCutter cutter(points, segments, out, s);
  for (int f = 0; f < faces; ++f)
    if (f != outer && !cutter.cut(f)) return false;
  out.face_count = cutter.faces_cut();
  const ClosureScratch::HalfEdge* he = s.half_edges.data();
  // Triangles on either side of a graph edge or boundary piece: the twin half-edge's triangle,
  // none where the twin is on the outer face.
  for (int h = 0; h < nh; ++h) {
    const int side = he[h].side;
    if (side < 0) continue;
    const int twin_side = he[h ^ 1].side;
    out.neighbors[side / 3][side % 3] = twin_side >= 0 ? twin_side / 3 : -1;
  }
  make_faces_delaunay(points, out, s.flips);
  return true;
}

void ring_starts(const ElementClosure& closure, int vertex_count, std::vector<int>& start) {
  const int nt = static_cast<int>(closure.triangles.size());
  const auto* tri = closure.triangles.data();
  const auto* nb = closure.neighbors.data();
  start.assign(vertex_count, -1);
  for (int t = 0; t < nt; ++t)
    for (int i = 0; i < 3; ++i) {
      const int v = tri[t][i];
      if (start[v] < 0 || nb[t][(i + 2) % 3] < 0) start[v] = 3 * t + i;
    }
}

void closure_rings(const ElementClosure& closure, int vertex_count, int wanted, std::vector<int>& ring_begin,
                   std::vector<RingEntry>& ring, std::vector<int>& start) {
  ring_starts(closure, vertex_count, start);
  ring_begin.resize(wanted + 1);
  ring_begin[0] = 0;
  ring.clear();
  for (int v = 0; v < wanted; ++v) {
    visit_ring(closure, v, start[v], [&](const RingEntry& entry) { ring.push_back(entry); });
    ring_begin[v + 1] = static_cast<int>(ring.size());
  }
}

}  // namespace plmap::detail
