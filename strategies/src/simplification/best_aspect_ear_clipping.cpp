#include <plmap/strategies/simplification/best_aspect_ear_clipping.hpp>

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

std::optional<HoleTriangles> BestAspectEarClipping::triangulate(std::span<const Eigen::Vector2d> polygon,
                                                                const DiagonalAllowed& allowed) const {
  std::vector<int> left(polygon.size());
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = static_cast<int>(i);
  HoleTriangles out;
  while (left.size() > 3) {
    const std::size_t n = left.size();
    int best = -1;
    double best_ratio = std::numeric_limits<double>::infinity();
    for (std::size_t m = 0; m < n; ++m) {
      const int a = left[(m + n - 1) % n], b = left[m], c = left[(m + 1) % n];
      if (orient2d(polygon[a], polygon[b], polygon[c]) <= 0) continue;  // reflex or flat corner
      if (!allowed(a, c)) continue;
      bool empty = true;  // no other remaining vertex inside or on the ear
      for (std::size_t o = 0; o < n && empty; ++o) {
        const int p = left[o];
        if (p == a || p == b || p == c) continue;
        empty = !(orient2d(polygon[a], polygon[b], polygon[p]) >= 0 && orient2d(polygon[b], polygon[c], polygon[p]) >= 0 &&
                  orient2d(polygon[c], polygon[a], polygon[p]) >= 0);
      }
      if (!empty) continue;
      const double ratio = planar_aspect_ratio(polygon[a], polygon[b], polygon[c]);
      if (ratio < best_ratio) {
        best_ratio = ratio;
        best = static_cast<int>(m);
      }
    }
    if (best < 0) return std::nullopt;
    out.push_back({left[(best + n - 1) % n], left[best], left[(best + 1) % n]});
    left.erase(left.begin() + best);
  }
  if (orient2d(polygon[left[0]], polygon[left[1]], polygon[left[2]]) <= 0) return std::nullopt;
  out.push_back({left[0], left[1], left[2]});
  return out;
}

}  // namespace plmap
