#include <plmap/strategies/smoothing/floater_weights.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

namespace plmap {

namespace {

/// Floater's geodesic polar map of the star into `flat`: lengths kept, angles scaled to sum to
/// 2π. False if the star is degenerate. The buffers live per thread: a smoothing sweep asks for
/// the weights of every free node once per solve, and allocating them was a third of the cost.
/// `polar` gets each flattened point's polar angle (increasing from 0), and 2π after the last.
bool flatten_star(const Eigen::Vector3d& center, std::span<const Eigen::Vector3d> ring, std::vector<Eigen::Vector2d>& flat,
                  std::vector<double>& polar) {
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
  polar.resize(k + 1);
  double phi = 0.0;
  for (std::size_t j = 0; j < k; ++j) {
    polar[j] = phi;
    flat[j] = length[j] * Eigen::Vector2d(std::cos(phi), std::sin(phi));
    phi += scale * angle[j];
  }
  polar[k] = 2.0 * std::numbers::pi;
  return true;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Barycentric coordinates of the origin in the flattened triangle (p_j, p_r, p_{r+1}), and the
/// smallest of them; nothing if the triangle is degenerate.
std::optional<std::pair<std::array<double, 3>, double>> origin_coordinates(const std::vector<Eigen::Vector2d>& p,
                                                                            std::size_t j, std::size_t r) {
  const std::size_t s = (r + 1) % p.size();
  if (r == j || s == j) return std::nullopt;
  const double area = cross(p[r] - p[j], p[s] - p[j]);
  if (!(std::abs(area) > 0.0)) return std::nullopt;
  // (area(o, r, s), area(j, o, s), area(j, r, o)) / area
  const std::array<double, 3> b = {cross(p[r], p[s]) / area, cross(p[s], p[j]) / area, cross(p[j], p[r]) / area};
  return std::pair{b, std::min({b[0], b[1], b[2]})};
}

}  // namespace

std::optional<std::vector<double>> FloaterWeights::weights(const Eigen::Vector3d& center,
                                                           std::span<const Eigen::Vector3d> ring) const {
  const std::size_t k = ring.size();
  if (k < 3) return std::nullopt;
  thread_local std::vector<Eigen::Vector2d> p;
  thread_local std::vector<double> polar;
  if (!flatten_star(center, ring, p, polar)) return std::nullopt;
  std::vector<double> w(k, 0.0);
  for (std::size_t j = 0; j < k; ++j) {
    // The triangle (p_j, p_r, p_{r+1}) that contains the origin: the one whose angular sector
    // [polar_r, polar_r+1) holds the direction opposite p_j (the ray from p_j through the origin
    // leaves the ring there). One triangle instead of all k: the weights are computed for every
    // free node in every solve.
    double best_min = -std::numeric_limits<double>::infinity();
    std::array<double, 3> best{};
    std::size_t best_r = k;
    double opposite = polar[j] + std::numbers::pi;
    if (opposite >= polar[k]) opposite -= polar[k];
    std::size_t sector = 0;
    while (sector + 1 < k && !(opposite < polar[sector + 1])) ++sector;
    if (const auto b = origin_coordinates(p, j, sector); b && b->second >= -1e-12) {
      best = b->first, best_min = b->second, best_r = sector;
    } else {
      // Rounding put the opposite direction in a neighbouring sector, or the star is not
      // star-shaped: the triangle whose smallest barycentric coordinate of the origin is largest
      // (exactly one has all of them >= 0 up to rounding if the ring is star-shaped).
      for (std::size_t r = 0; r < k; ++r) {
        const auto c = origin_coordinates(p, j, r);
        if (c && c->second > best_min) best_min = c->second, best = c->first, best_r = r;
      }
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
