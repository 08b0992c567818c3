#pragma once
// Small geometry of space triangles shared by the error oracles.

#include <plmap/core/editable_map.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace plmap::oracle_detail {

inline Eigen::Vector3d corner(const EditableMap& map, const std::array<Index, 3>& t, int k) { return map.position(t[k]); }

/// Aspect ratio, longest edge × perimeter / (4√3 × area): 1 for the equilateral triangle.
inline double aspect_ratio(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
  const double area = 0.5 * (b - a).cross(c - a).norm();
  if (!(area > 0.0)) return std::numeric_limits<double>::infinity();
  return std::max({la, lb, lc}) * (la + lb + lc) / (4.0 * std::sqrt(3.0) * area);
}

inline double aspect_ratio(const EditableMap& map, const std::array<Index, 3>& t) {
  return aspect_ratio(map.position(t[0]), map.position(t[1]), map.position(t[2]));
}

inline Eigen::Vector3d unit_normal(const EditableMap& map, const std::array<Index, 3>& t) {
  return (map.position(t[1]) - map.position(t[0])).cross(map.position(t[2]) - map.position(t[0])).normalized();
}

}  // namespace plmap::oracle_detail
