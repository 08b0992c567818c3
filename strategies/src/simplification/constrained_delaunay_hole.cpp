#include <plmap/strategies/simplification/constrained_delaunay_hole.hpp>

#include <plmap/strategies/simplification/min_max_aspect_triangulation.hpp>

#include <plmap/core/predicates.hpp>

#include "apex_table_listing.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace plmap {

namespace {

/// Working tables of one triangulation, kept per thread: a simplification triangulates tens of
/// thousands of small holes.
struct Workspace {
  std::vector<int> remaining;               ///< ear clipping: ring indices not yet cut off
  std::vector<int> owner;                   ///< n × n: triangle holding the directed edge x → y, or -1
  std::vector<std::array<int, 2>> pending;  ///< Lawson: directed edges still to test
  std::vector<int> split;                   ///< n × n: apex m of the triangle inside chord i < m < j
  std::vector<std::array<int, 2>> stack;
};

/// A first triangulation by ear clipping, O(n²) tests of O(n) each for n ring vertices (the
/// min-max-aspect programme is O(n³) with an O(n) diagonal test per pair). An ear (p, i, q) of
/// the remaining polygon is convex, holds no other remaining vertex in its closed triangle (then
/// p-q is a diagonal of the remaining polygon) and uses an allowed diagonal. Empty if every
/// remaining corner is blocked by a forbidden diagonal: the caller falls back to the programme,
/// which finds a triangulation whenever one exists.
bool clip_ears(std::span<const Eigen::Vector2d> polygon, const DiagonalAllowed& allowed, Workspace& w,
               HoleTriangles& out) {
  const int n = static_cast<int>(polygon.size());
  std::vector<int>& rem = w.remaining;
  rem.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) rem[i] = i;
  out.clear();
  int at = 0;  // where the next ear is looked for: next to the last one cut off
  while (rem.size() > 3) {
    const int size = static_cast<int>(rem.size());
    bool cut = false;
    for (int tried = 0; tried < size && !cut; ++tried) {
      const int k = (at + tried) % size;
      const int p = rem[(k + size - 1) % size], i = rem[k], q = rem[(k + 1) % size];
      const Eigen::Vector2d &pp = polygon[p], &pi = polygon[i], &pq = polygon[q];
      if (orient2d(pp, pi, pq) <= 0) continue;
      bool empty = true;
      for (int x : rem) {
        if (x == p || x == i || x == q) continue;
        const Eigen::Vector2d& px = polygon[x];
        if (orient2d(pp, pi, px) >= 0 && orient2d(pi, pq, px) >= 0 && orient2d(pq, pp, px) >= 0) {
          empty = false;
          break;
        }
      }
      if (!empty || !allowed(p, q)) continue;
      out.push_back({p, i, q});
      rem.erase(rem.begin() + k);
      at = k == 0 ? 0 : k - 1;
      cut = true;
    }
    if (!cut) return false;
  }
  if (orient2d(polygon[rem[0]], polygon[rem[1]], polygon[rem[2]]) <= 0) return false;
  out.push_back({rem[0], rem[1], rem[2]});
  return true;
}

/// Lawson flips until every diagonal is locally Delaunay (or may not be flipped: the new
/// diagonal is forbidden or the quadrilateral is not convex). Each flip pushes the four sides of
/// its quadrilateral, whose test may have changed; a flip strictly raises the triangulation in
/// the lexicographic angle order, so this ends.
void flip_to_delaunay(std::span<const Eigen::Vector2d> polygon, const DiagonalAllowed& allowed, Workspace& w,
                      HoleTriangles& t) {
  const int n = static_cast<int>(polygon.size());
  std::vector<int>& owner = w.owner;
  owner.assign(static_cast<std::size_t>(n * n), -1);
  auto own = [&](int tri) {
    for (int m = 0; m < 3; ++m) owner[t[tri][m] * n + t[tri][(m + 1) % 3]] = tri;
  };
  for (int a = 0; a < static_cast<int>(t.size()); ++a) own(a);
  auto is_side = [n](int i, int j) { return (i + 1) % n == j || (j + 1) % n == i; };
  std::vector<std::array<int, 2>>& pending = w.pending;
  pending.clear();
  for (const auto& tri : t)
    for (int m = 0; m < 3; ++m)
      if (tri[m] < tri[(m + 1) % 3] && !is_side(tri[m], tri[(m + 1) % 3])) pending.push_back({tri[m], tri[(m + 1) % 3]});
  auto third = [&t](int tri, int x, int y) {
    for (int c : t[tri])
      if (c != x && c != y) return c;
    return -1;
  };
  for (long guard = 0; !pending.empty() && guard < static_cast<long>(n) * n * n; ++guard) {
    const auto [p, q] = pending.back();
    pending.pop_back();
    const int a = owner[p * n + q], b = owner[q * n + p];
    if (a < 0 || b < 0) continue;  // flipped away since it was pushed
    const int r = third(a, p, q), s = third(b, p, q);
    if (incircle(polygon[p], polygon[q], polygon[r], polygon[s]) <= 0) continue;
    if (!allowed(r, s) || orient2d(polygon[s], polygon[q], polygon[r]) <= 0 ||
        orient2d(polygon[p], polygon[s], polygon[r]) <= 0)
      continue;
    owner[p * n + q] = owner[q * n + p] = -1;
    t[a] = {s, q, r};
    t[b] = {p, s, r};
    own(a);
    own(b);
    for (const auto& [x, y] : {std::array{q, r}, std::array{r, p}, std::array{p, s}, std::array{s, q}})
      if (!is_side(x, y)) pending.push_back({x, y});
  }
}

/// The triangles in a canonical form that depends only on the set of triangles (not on the first
/// triangulation or the order of the flips): each as (i, m, j) with i < m < j, read off from the
/// chord 0-(n-1) inwards, the order MinMaxAspectTriangulation emits.
bool canonical_order(int n, Workspace& w, HoleTriangles& t) {
  std::vector<int>& split = w.split;
  split.assign(static_cast<std::size_t>(n * n), -1);
  for (auto tri : t) {
    std::sort(tri.begin(), tri.end());
    split[tri[0] * n + tri[2]] = tri[1];
  }
  const std::size_t count = t.size();
  t.clear();
  // (a missing apex is never expected: a triangulation of the polygon has every chord's apex)
  return detail::list_from_apex_table(split, n, w.stack, t) && t.size() == count;
}

}  // namespace

std::optional<HoleTriangles> ConstrainedDelaunayHole::triangulate(std::span<const Eigen::Vector2d> polygon,
                                                                  const DiagonalAllowed& allowed) const {
  const int n = static_cast<int>(polygon.size());
  if (n < 3) return std::nullopt;
  thread_local Workspace workspace;
  HoleTriangles triangles;
  triangles.reserve(static_cast<std::size_t>(n - 2));
  // With a forbidden diagonal the flips may stop at a local optimum that depends on the first
  // triangulation; the ear clipping then gives way to the programme, whose start the results
  // were tuned with (where no diagonal is forbidden the fixed point is the one constrained
  // Delaunay triangulation from any start, up to cocircular ring vertices).
  bool forbidden_met = false;
  const DiagonalAllowed watched = [&](int i, int j) {
    const bool ok = allowed(i, j);
    forbidden_met = forbidden_met || !ok;
    return ok;
  };
  bool clipped = clip_ears(polygon, watched, workspace, triangles);
  if (clipped) flip_to_delaunay(polygon, watched, workspace, triangles);
  if (!clipped || forbidden_met) {
    auto start = MinMaxAspectTriangulation{}.triangulate(polygon, allowed);
    if (!start) return std::nullopt;
    triangles = std::move(*start);
    flip_to_delaunay(polygon, allowed, workspace, triangles);
  }
  if (!canonical_order(n, workspace, triangles)) return std::nullopt;
  return triangles;
}

}  // namespace plmap
