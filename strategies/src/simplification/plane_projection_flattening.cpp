#include <plmap/strategies/simplification/plane_projection_flattening.hpp>

#include <Eigen/Geometry>

namespace plmap {

std::optional<std::vector<Eigen::Vector2d>> PlaneProjectionFlattening::flatten(
    const Eigen::Vector3d& center, std::span<const Eigen::Vector3d> ring) const {
  const std::size_t k = ring.size();
  if (k < 3) return std::nullopt;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < k; ++i) normal += (ring[i] - center).cross(ring[(i + 1) % k] - center);
  if (!(normal.norm() > 0.0)) return std::nullopt;
  normal.normalize();
  Eigen::Vector3d u = (ring[0] - center) - (ring[0] - center).dot(normal) * normal;
  if (!(u.norm() > 0.0)) return std::nullopt;
  u.normalize();
  const Eigen::Vector3d w = normal.cross(u);
  std::vector<Eigen::Vector2d> out(k);
  for (std::size_t i = 0; i < k; ++i) out[i] = {(ring[i] - center).dot(u), (ring[i] - center).dot(w)};
  return out;
}

}  // namespace plmap
