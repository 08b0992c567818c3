#include "polygon_triangulation.hpp"

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace plmap::surface_io_detail {

namespace {

using Point2 = Eigen::Vector2d;

/// Twice the signed area of (a, b, c).
double orientation(const Point2& a, const Point2& b, const Point2& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

/// The polygon's corners in order, from its fan (0, k, k+1) in `count` triangles from `first`.
void corners_of_fan(const RawMesh<2>& mesh, std::size_t first, std::size_t count, std::vector<Index>& corners) {
  corners.assign({mesh.elements[first][0], mesh.elements[first][1]});
  for (std::size_t k = 0; k < count; ++k) corners.push_back(mesh.elements[first + k][2]);
}

/// The corners projected onto the plane through the polygon normal to its Newell normal (the
/// polygon's area vector), in a frame in which the polygon turns counter-clockwise, into
/// `points`; left empty if the normal vanishes (a degenerate polygon, which the fan leaves for
/// Surface to reject).
void in_plane(const RawMesh<2>& mesh, const std::vector<Index>& corners, std::vector<Point2>& points) {
  points.clear();
  // relative to the first corner, so that a mesh far from the origin loses no digits
  const WorldPoint<2>& origin = mesh.vertices[corners[0]];
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  const std::size_t n = corners.size();
  for (std::size_t i = 1; i + 1 < n; ++i)
    normal += (mesh.vertices[corners[i]] - origin).cross(mesh.vertices[corners[i + 1]] - origin);
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return;
  normal /= length;
  // any unit vector normal to `normal`, and the third of a right-handed frame
  const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
  for (Index c : corners) {
    const Eigen::Vector3d p = mesh.vertices[c] - origin;
    points.emplace_back(p.dot(u), p.dot(v));
  }
}

/// Whether every fan triangle turns the polygon's way (then the fan lies inside it).
bool fan_is_inside(const std::vector<Point2>& p) {
  for (std::size_t k = 1; k + 1 < p.size(); ++k)
    if (!(orientation(p[0], p[k], p[k + 1]) > 0.0)) return false;
  return true;
}

/// Ear clipping: the triangles as triples of positions in `p`, or empty if at some point no
/// corner is an ear (a triangle turning the polygon's way with no other remaining corner in or
/// on it). The scan goes on from the last ear instead of starting over, so a polygon of n
/// corners costs O(n^2) tests where ears come in turn (the usual case), O(n^3) at worst.
std::vector<std::array<std::size_t, 3>> ear_clipping(const std::vector<Point2>& p) {
  std::vector<std::size_t> left(p.size());
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = i;
  const auto is_ear = [&](std::size_t a, std::size_t b, std::size_t c) {
    if (!(orientation(p[a], p[b], p[c]) > 0.0)) return false;
    for (std::size_t j : left) {
      if (j == a || j == b || j == c) continue;
      if (orientation(p[a], p[b], p[j]) >= 0.0 && orientation(p[b], p[c], p[j]) >= 0.0 &&
          orientation(p[c], p[a], p[j]) >= 0.0)
        return false;
    }
    return true;
  };
  std::vector<std::array<std::size_t, 3>> triangles;
  std::size_t i = 0, tried = 0;  // corners tried since the last ear
  while (left.size() > 3) {
    const std::size_t m = left.size();
    if (tried == m) return {};  // a full turn without an ear
    i %= m;
    const std::size_t a = left[(i + m - 1) % m], b = left[i], c = left[(i + 1) % m];
    if (is_ear(a, b, c)) {
      triangles.push_back({a, b, c});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(i));
      i = i == 0 ? 0 : i - 1;  // the corner before the ear may have become one
      tried = 0;
    } else {
      ++i;
      ++tried;
    }
  }
  if (!(orientation(p[left[0]], p[left[1]], p[left[2]]) > 0.0)) return {};
  triangles.push_back({left[0], left[1], left[2]});
  return triangles;
}

}  // namespace

void triangulate_polygons_in_their_planes(RawMesh<2>& mesh) {
  // reused from polygon to polygon: most are quads, read by the million in a quad mesh
  std::vector<Index> corners;
  std::vector<Point2> points;
  for (const auto& [first, count] : mesh.polygons) {
    corners_of_fan(mesh, first, count, corners);
    in_plane(mesh, corners, points);
    if (points.empty() || fan_is_inside(points)) continue;
    const std::vector<std::array<std::size_t, 3>> triangles = ear_clipping(points);
    if (triangles.size() != count) continue;
    for (std::size_t k = 0; k < count; ++k)
      mesh.elements[first + k] = {corners[triangles[k][0]], corners[triangles[k][1]], corners[triangles[k][2]]};
  }
}

}  // namespace plmap::surface_io_detail
