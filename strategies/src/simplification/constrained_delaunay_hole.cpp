#include <plmap/strategies/simplification/constrained_delaunay_hole.hpp>

#include <plmap/strategies/simplification/min_max_aspect_triangulation.hpp>

#include <plmap/core/predicates.hpp>

namespace plmap {

namespace {

/// Position of corner value `x` in triangle t, or -1.
int corner_of(const std::array<int, 3>& t, int x) {
  for (int m = 0; m < 3; ++m)
    if (t[m] == x) return m;
  return -1;
}

}  // namespace

std::optional<HoleTriangles> ConstrainedDelaunayHole::triangulate(std::span<const Eigen::Vector2d> polygon,
                                                                  const DiagonalAllowed& allowed) const {
  auto triangles = MinMaxAspectTriangulation{}.triangulate(polygon, allowed);
  if (!triangles) return std::nullopt;
  HoleTriangles& t = *triangles;
  const int n = static_cast<int>(polygon.size());
  auto is_side = [n](int i, int j) { return (i + 1) % n == j || (j + 1) % n == i; };
  // Lawson flips: a hole has few triangles, so a full rescan after each flip is cheap, and the
  // number of flips is bounded (each one strictly increases the triangulation in the
  // lexicographic angle order).
  for (int guard = 0; guard < n * n * n; ++guard) {
    bool flipped = false;
    for (std::size_t a = 0; a < t.size() && !flipped; ++a)
      for (int m = 0; m < 3 && !flipped; ++m) {
        const int p = t[a][m], q = t[a][(m + 1) % 3], r = t[a][(m + 2) % 3];
        if (is_side(p, q)) continue;
        for (std::size_t b = 0; b < t.size(); ++b) {
          if (b == a) continue;
          const int cp = corner_of(t[b], p), cq = corner_of(t[b], q);
          if (cp < 0 || cq < 0) continue;
          const int s = t[b][3 - cp - cq];
          if (incircle(polygon[p], polygon[q], polygon[r], polygon[s]) <= 0) break;
          // Flip p-q to r-s when the new triangles are proper and the diagonal is allowed.
          if (!allowed(r, s) || orient2d(polygon[s], polygon[q], polygon[r]) <= 0 ||
              orient2d(polygon[p], polygon[s], polygon[r]) <= 0)
            break;
          t[a] = {s, q, r};
          t[b] = {p, s, r};
          flipped = true;
          break;
        }
      }
    if (!flipped) break;
  }
  return triangles;
}

}  // namespace plmap
