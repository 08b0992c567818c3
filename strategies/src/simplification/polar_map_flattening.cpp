#include <plmap/strategies/simplification/polar_map_flattening.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace plmap {

std::optional<std::vector<Eigen::Vector2d>> PolarMapFlattening::flatten(const Eigen::Vector3d& center,
                                                                        std::span<const Eigen::Vector3d> ring) const {
  const std::size_t k = ring.size();
  if (k < 3) return std::nullopt;
  // Per-thread buffers (as the hole triangulation's workspace): every entry is written before
  // it is read, and a simplifier flattens a star for every ranking attempt.
  thread_local std::vector<double> radius, angle;
  radius.resize(k);
  angle.resize(k);
  double total = 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    const Eigen::Vector3d a = ring[i] - center, b = ring[(i + 1) % k] - center;
    radius[i] = a.norm();
    // atan2 of |a x b| and a . b: accurate for small and obtuse angles alike.
    angle[i] = std::atan2(a.cross(b).norm(), a.dot(b));
    if (!(radius[i] > 0.0) || !(angle[i] > 0.0)) return std::nullopt;
    total += angle[i];
  }
  const double scale = 2.0 * std::numbers::pi / total;
  // Radii are measured relative to the longest spoke before the power, so that the result does
  // not depend on the surface's units.
  double longest = 0.0;
  for (double r : radius) longest = std::max(longest, r);
  std::vector<Eigen::Vector2d> out(k);
  double phi = 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    const double r = std::pow(radius[i] / longest, scale);
    out[i] = {r * std::cos(phi), r * std::sin(phi)};
    phi += scale * angle[i];
  }
  return out;
}

std::optional<std::vector<Eigen::Vector2d>> PolarMapFlattening::flatten_half(const Eigen::Vector3d& center,
                                                                             std::span<const Eigen::Vector3d> ring) const {
  const std::size_t k = ring.size();
  if (k < 3) return std::nullopt;
  thread_local std::vector<double> radius, angle;  // as in flatten()
  radius.resize(k);
  angle.resize(k - 1);
  double total = 0.0, longest = 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    radius[i] = (ring[i] - center).norm();
    if (!(radius[i] > 0.0)) return std::nullopt;
    longest = std::max(longest, radius[i]);
  }
  for (std::size_t i = 0; i + 1 < k; ++i) {
    const Eigen::Vector3d a = ring[i] - center, b = ring[i + 1] - center;
    angle[i] = std::atan2(a.cross(b).norm(), a.dot(b));
    if (!(angle[i] > 0.0)) return std::nullopt;
    total += angle[i];
  }
  const double scale = std::numbers::pi / total;
  std::vector<Eigen::Vector2d> out(k);
  // The ends lie exactly on the x axis, so that the removed vertex (the origin) is exactly on
  // the segment between them.
  out[0] = {radius[0] / longest, 0.0};
  out[k - 1] = {-radius[k - 1] / longest, 0.0};
  double phi = 0.0;
  for (std::size_t i = 1; i + 1 < k; ++i) {
    phi += scale * angle[i - 1];
    const double r = radius[i] / longest;
    out[i] = {r * std::cos(phi), r * std::sin(phi)};
  }
  return out;
}

}  // namespace plmap
