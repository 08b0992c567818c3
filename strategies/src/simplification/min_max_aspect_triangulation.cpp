#include <plmap/strategies/simplification/min_max_aspect_triangulation.hpp>

#include <plmap/core/predicates.hpp>

#include "apex_table_listing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plmap {

namespace {

/// planar_aspect_ratio with the side lengths given (la opposite a, ...): the same arithmetic.
double aspect_ratio(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, double la, double lb,
                    double lc) {
  const double area = 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  if (!(area > 0.0)) return std::numeric_limits<double>::infinity();
  return std::max({la, lb, lc}) * (la + lb + lc) / (4.0 * std::sqrt(3.0) * area);
}

/// The dynamic programme's tables, n × n for n ring vertices.
struct Tables {
  std::vector<char> usable;
  std::vector<double> best, chord;  ///< chord: distance between ring vertices i and j
  std::vector<int> split;
  std::vector<std::array<int, 2>> stack;  ///< sub-polygons still to split when reading off the result
};

}  // namespace

double planar_aspect_ratio(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return aspect_ratio(a, b, c, (b - c).norm(), (c - a).norm(), (a - b).norm());
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
  // No polygon side meets it except at its ends, and it passes through no other vertex. A
  // vertex or side outside the closed bounding box of a-b cannot meet it: that test comes first
  // and saves the exact predicates for the few candidates near the diagonal (this runs for every
  // pair of ring vertices of every planned removal).
  const double low_x = std::min(a.x(), b.x()), high_x = std::max(a.x(), b.x());
  const double low_y = std::min(a.y(), b.y()), high_y = std::max(a.y(), b.y());
  const auto in_box = [&](const Eigen::Vector2d& p) {
    return p.x() >= low_x && p.x() <= high_x && p.y() >= low_y && p.y() <= high_y;
  };
  for (int k = 0; k < n; ++k) {
    const int l = (k + 1) % n;
    const Eigen::Vector2d& pk = polygon[k];
    const Eigen::Vector2d& pl = polygon[l];
    if (k != i && k != j && in_box(pk) && orient2d(a, b, pk) == 0 && (pk - a).dot(pk - b) <= 0) return false;
    if (k == i || k == j || l == i || l == j) continue;
    if (std::max(pk.x(), pl.x()) < low_x || std::min(pk.x(), pl.x()) > high_x || std::max(pk.y(), pl.y()) < low_y ||
        std::min(pk.y(), pl.y()) > high_y)
      continue;
    if (segments_cross_properly(a, b, pk, pl)) return false;
  }
  return true;
}

std::optional<HoleTriangles> MinMaxAspectTriangulation::triangulate(std::span<const Eigen::Vector2d> polygon,
                                                                    const DiagonalAllowed& allowed) const {
  const int n = static_cast<int>(polygon.size());
  if (n < 3) return std::nullopt;
  const double inf = std::numeric_limits<double>::infinity();
  // The tables live as long as the thread: a simplification triangulates hundreds of thousands
  // of small holes, and allocating them each time cost more than filling them.
  thread_local Tables tables;
  std::vector<char>& usable = tables.usable;
  std::vector<double>& best = tables.best;
  std::vector<double>& chord = tables.chord;
  std::vector<int>& split = tables.split;
  // usable[i][j]: i-j is a side, or an admissible diagonal.
  usable.assign(static_cast<std::size_t>(n * n), 0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const bool side = j == i + 1 || (i == 0 && j == n - 1);
      usable[i * n + j] = usable[j * n + i] = side || (allowed(i, j) && is_polygon_diagonal(polygon, i, j));
    }
  // best[i][j]: the smallest possible largest aspect ratio of a triangulation of the
  // sub-polygon i, i+1, ..., j (closed by the chord i-j); split[i][j]: its apex.
  best.assign(static_cast<std::size_t>(n * n), inf);
  split.assign(static_cast<std::size_t>(n * n), -1);
  for (int i = 0; i + 1 < n; ++i) best[i * n + i + 1] = 0.0;
  // side and diagonal lengths, each computed once instead of once per candidate triangle
  chord.assign(static_cast<std::size_t>(n * n), 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) chord[i * n + j] = chord[j * n + i] = (polygon[i] - polygon[j]).norm();
  for (int length = 2; length < n; ++length)
    for (int i = 0; i + length < n; ++i) {
      const int j = i + length;
      if (!usable[i * n + j]) continue;
      for (int m = i + 1; m < j; ++m) {
        if (!usable[i * n + m] || !usable[m * n + j]) continue;
        if (orient2d(polygon[i], polygon[m], polygon[j]) <= 0) continue;
        const double worst = std::max({best[i * n + m], best[m * n + j], aspect_ratio(polygon[i], polygon[m], polygon[j], chord[m * n + j], chord[j * n + i], chord[i * n + m])});
        if (worst < best[i * n + j]) {
          best[i * n + j] = worst;
          split[i * n + j] = m;
        }
      }
    }
  if (split[n - 1] < 0) return std::nullopt;
  HoleTriangles out;
  out.reserve(static_cast<std::size_t>(n - 2));
  if (!detail::list_from_apex_table(split, n, tables.stack, out)) return std::nullopt;
  return out;
}

}  // namespace plmap
