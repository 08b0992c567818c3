#include <plmap/strategies/simplification/min_max_aspect_triangulation.hpp>

#include <plmap/core/predicates.hpp>

#include <cmath>
#include <limits>

namespace plmap {

double planar_aspect_ratio(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
  const double area = 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  if (!(area > 0.0)) return std::numeric_limits<double>::infinity();
  return std::max({la, lb, lc}) * (la + lb + lc) / (4.0 * std::sqrt(3.0) * area);
}

bool is_polygon_diagonal(std::span<const Eigen::Vector2d> polygon, int i, int j) {
  const int n = static_cast<int>(polygon.size());
  const Eigen::Vector2d& a = polygon[i];
  const Eigen::Vector2d& b = polygon[j];
  // Inside the polygon near i: within the cone of the interior angle at i.
  const Eigen::Vector2d& prev = polygon[(i + n - 1) % n];
  const Eigen::Vector2d& next = polygon[(i + 1) % n];
  const bool convex = orient2d(prev, a, next) > 0;
  const bool in_cone = convex ? orient2d(a, b, prev) > 0 && orient2d(b, a, next) > 0
                              : !(orient2d(a, b, next) >= 0 && orient2d(b, a, prev) >= 0);
  if (!in_cone) return false;
  // No polygon side meets it except at its ends, and it passes through no other vertex.
  for (int k = 0; k < n; ++k) {
    const int l = (k + 1) % n;
    if (k != i && k != j && orient2d(a, b, polygon[k]) == 0 && (polygon[k] - a).dot(polygon[k] - b) <= 0) return false;
    if (k == i || k == j || l == i || l == j) continue;
    if (segments_cross_properly(a, b, polygon[k], polygon[l])) return false;
  }
  return true;
}

std::optional<HoleTriangles> MinMaxAspectTriangulation::triangulate(std::span<const Eigen::Vector2d> polygon,
                                                                    const DiagonalAllowed& allowed) const {
  const int n = static_cast<int>(polygon.size());
  if (n < 3) return std::nullopt;
  const double inf = std::numeric_limits<double>::infinity();
  // usable[i][j]: i-j is a side, or an admissible diagonal.
  std::vector<char> usable(n * n, 0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const bool side = j == i + 1 || (i == 0 && j == n - 1);
      usable[i * n + j] = usable[j * n + i] = side || (allowed(i, j) && is_polygon_diagonal(polygon, i, j));
    }
  // best[i][j]: the smallest possible largest aspect ratio of a triangulation of the
  // sub-polygon i, i+1, ..., j (closed by the chord i-j); split[i][j]: its apex.
  std::vector<double> best(n * n, inf);
  std::vector<int> split(n * n, -1);
  for (int i = 0; i + 1 < n; ++i) best[i * n + i + 1] = 0.0;
  for (int length = 2; length < n; ++length)
    for (int i = 0; i + length < n; ++i) {
      const int j = i + length;
      if (!usable[i * n + j]) continue;
      for (int m = i + 1; m < j; ++m) {
        if (!usable[i * n + m] || !usable[m * n + j]) continue;
        if (orient2d(polygon[i], polygon[m], polygon[j]) <= 0) continue;
        const double worst = std::max({best[i * n + m], best[m * n + j], planar_aspect_ratio(polygon[i], polygon[m], polygon[j])});
        if (worst < best[i * n + j]) {
          best[i * n + j] = worst;
          split[i * n + j] = m;
        }
      }
    }
  if (split[n - 1] < 0) return std::nullopt;
  HoleTriangles out;
  std::vector<std::array<int, 2>> stack = {{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int m = split[i * n + j];
    out.push_back({i, m, j});
    stack.push_back({i, m});
    stack.push_back({m, j});
  }
  return out;
}

}  // namespace plmap
