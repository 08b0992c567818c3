#include <plmap/strategies/smoothing/floater_weights.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace plmap {

namespace {

/// Floater's geodesic polar map of the star into `flat`: lengths kept, angles scaled to sum to
/// 2π. False if the star is degenerate. The buffers live per thread: a smoothing sweep asks for
/// the weights of every free node once per solve, and allocating them was a third of the cost.
bool flatten_star(const Eigen::Vector3d& center, std::span<const Eigen::Vector3d> ring, std::vector<Eigen::Vector2d>& flat) {
  const std::size_t k = ring.size();
  thread_local std::vector<double> angle, length;
  angle.resize(k);
  length.resize(k);
  double total = 0.0;
  for (std::size_t j = 0; j < k; ++j) {
    const Eigen::Vector3d a = ring[j] - center, b = ring[(j + 1) % k] - center;
    length[j] = a.norm();
    angle[j] = std::atan2(a.cross(b).norm(), a.dot(b));
    if (!(length[j] > 0.0) || !(angle[j] > 0.0)) return false;
    total += angle[j];
  }
  const double scale = 2.0 * std::numbers::pi / total;
  flat.resize(k);
  double phi = 0.0;
  for (std::size_t j = 0; j < k; ++j) {
    flat[j] = length[j] * Eigen::Vector2d(std::cos(phi), std::sin(phi));
    phi += scale * angle[j];
  }
  return true;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

std::optional<std::vector<double>> FloaterWeights::weights(const Eigen::Vector3d& center,
                                                           std::span<const Eigen::Vector3d> ring) const {
  const std::size_t k = ring.size();
  if (k < 3) return std::nullopt;
  thread_local std::vector<Eigen::Vector2d> p;
  if (!flatten_star(center, ring, p)) return std::nullopt;
  std::vector<double> w(k, 0.0);
  for (std::size_t j = 0; j < k; ++j) {
    // The triangle (p_j, p_r, p_{r+1}) that contains the origin: the one whose smallest
    // barycentric coordinate of the origin is largest (exactly one has all of them >= 0 up to
    // rounding, since the flattened ring is star-shaped around the origin).
    double best_min = -std::numeric_limits<double>::infinity();
    std::array<double, 3> best{};
    std::size_t best_r = k;
    for (std::size_t r = 0; r < k; ++r) {
      const std::size_t s = (r + 1) % k;
      if (r == j || s == j) continue;
      const double area = cross(p[r] - p[j], p[s] - p[j]);
      if (!(std::abs(area) > 0.0)) continue;
      // barycentric coordinates of the origin o: (area(o, r, s), area(j, o, s), area(j, r, o)) / area
      const std::array<double, 3> b = {cross(p[r], p[s]) / area, cross(p[s], p[j]) / area, cross(p[j], p[r]) / area};
      const double smallest = std::min({b[0], b[1], b[2]});
      if (smallest > best_min) best_min = smallest, best = b, best_r = r;
    }
    // Rounding may leave the containing triangle's smallest coordinate a hair below zero; a
    // clearly negative one means the layout is not star-shaped (cannot happen for a valid polar map).
    if (best_r == k || best_min < -1e-9) return std::nullopt;
    w[j] += std::max(best[0], 0.0);
    w[best_r] += std::max(best[1], 0.0);
    w[(best_r + 1) % k] += std::max(best[2], 0.0);
  }
  return normalized_positive_weights(std::move(w));
}

}  // namespace plmap
