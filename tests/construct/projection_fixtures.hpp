#pragma once
// Small surfaces for the projection tests: circles (d = 1), planar grids and sphere-like
// surfaces (d = 2), with deterministic jitter so that grids do not match; transformed copies;
// and the messages the tests print when a map fails verify or an edge is not inserted.

#include <plmap/construct/projection_result.hpp>
#include <plmap/core/surface.hpp>
#include <plmap/verify/check.hpp>

#include "../verify_violations.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>

namespace plmap::test {

/// Counter-clockwise polygon with n vertices on a circle: outward normals.
inline std::shared_ptr<const Surface<1>> circle(int n, double radius, double phase = 0.0) {
  std::vector<WorldPoint<1>> v;
  std::vector<ElementCorners<1>> e;
  for (int i = 0; i < n; ++i) {
    const double a = phase + 2.0 * std::numbers::pi * i / n;
    v.emplace_back(radius * std::cos(a), radius * std::sin(a));
    e.push_back({i, (i + 1) % n});
  }
  return std::make_shared<const Surface<1>>(std::move(v), std::move(e));
}

/// Open polyline along the x-axis from x0 to x1 at height y, n segments; normals +y unless
/// `down`.
inline std::shared_ptr<const Surface<1>> line(int n, double x0, double x1, double y, bool down = false) {
  std::vector<WorldPoint<1>> v;
  std::vector<ElementCorners<1>> e;
  for (int i = 0; i <= n; ++i) v.emplace_back(x0 + (x1 - x0) * i / n, y);
  for (int i = 0; i < n; ++i) e.push_back(down ? ElementCorners<1>{i, i + 1} : ElementCorners<1>{i + 1, i});
  return std::make_shared<const Surface<1>>(std::move(v), std::move(e));
}

/// nx x ny grid of squares over [x0, x1] x [y0, y1] at height z, each split into two triangles;
/// normals +z (or -z if `down`). Interior vertices are moved by up to `jitter` of a cell.
inline std::shared_ptr<const Surface<2>> grid(int nx, int ny, double x0, double x1, double y0, double y1,
                                              double z, bool down = false, double jitter = 0.0) {
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  const double hx = (x1 - x0) / nx, hy = (y1 - y0) / ny;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double x = x0 + i * hx, y = y0 + j * hy;
      if (i > 0 && i < nx && j > 0 && j < ny) {
        x += jitter * hx * std::sin(12.9898 * i + 78.233 * j);
        y += jitter * hy * std::sin(39.3468 * i + 11.135 * j);
      }
      v.emplace_back(x, y, z);
    }
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      ElementCorners<2> a{id(i, j), id(i + 1, j), id(i + 1, j + 1)};
      ElementCorners<2> b{id(i, j), id(i + 1, j + 1), id(i, j + 1)};
      if (down) {
        std::swap(a[1], a[2]);
        std::swap(b[1], b[2]);
      }
      e.push_back(a);
      e.push_back(b);
    }
  return std::make_shared<const Surface<2>>(std::move(v), std::move(e));
}

/// Octahedron refined `levels` times by midpoint subdivision, projected onto a sphere of the
/// given radius: outward normals unless `inward`.
inline std::shared_ptr<const Surface<2>> sphere(int levels, double radius, bool inward = false,
                                                double rotation = 0.0) {
  std::vector<Eigen::Vector3d> v = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<ElementCorners<2>> f = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                      {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<Index, Index>, Index> mid;
    auto midpoint = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((0.5 * (v[a] + v[b])).normalized());
      const Index id = static_cast<Index>(v.size()) - 1;
      mid.emplace(key, id);
      return id;
    };
    std::vector<ElementCorners<2>> g;
    for (const auto& t : f) {
      const Index ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      g.push_back({t[0], ab, ca});
      g.push_back({ab, t[1], bc});
      g.push_back({ca, bc, t[2]});
      g.push_back({ab, bc, ca});
    }
    f = std::move(g);
  }
  const Eigen::Matrix3d r = Eigen::AngleAxisd(rotation, Eigen::Vector3d(0.3, 0.5, 0.8).normalized()).matrix();
  std::vector<WorldPoint<2>> w;
  for (const auto& p : v) w.push_back(radius * (r * p));
  if (inward)
    for (auto& t : f) std::swap(t[1], t[2]);
  return std::make_shared<const Surface<2>>(std::move(w), std::move(f));
}

/// The same triangles with every vertex moved by `f` (rigid motions, lifts, affine copies).
template <int d>
std::shared_ptr<const Surface<d>> transformed(const Surface<d>& s,
                                              const std::function<WorldPoint<d>(const WorldPoint<d>&)>& f) {
  std::vector<WorldPoint<d>> v;
  v.reserve(s.vertex_count());
  for (const auto& p : s.vertices()) v.push_back(f(p));
  return std::make_shared<const Surface<d>>(std::move(v), s.elements());
}

/// The same surface with every element's orientation reversed (normals flipped).
template <int d>
std::shared_ptr<const Surface<d>> flipped(const Surface<d>& s) {
  auto e = s.elements();
  for (auto& t : e) std::swap(t[0], t[1]);
  return std::make_shared<const Surface<d>>(s.vertices(), std::move(e));
}

/// The same direction for every S1 vertex, as ProjectionOptions::directions wants them.
template <int d>
std::vector<double> constant_directions(const Surface<d>& s1, const WorldPoint<d>& direction) {
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(s1.vertex_count()) * (d + 1));
  for (Index v = 0; v < s1.vertex_count(); ++v)
    for (int k = 0; k <= d; ++k) out.push_back(direction(k));
  return out;
}

/// The edges a projection could not insert, one a line (reason, place, detail).
template <int d>
std::string describe_failures(const ProjectionReport<d>& r) {
  std::ostringstream s;
  for (const auto& f : r.edges_not_inserted)
    s << (d == 2 ? "edge " : "segment ") << f.target_edge << ": " << to_string(f.reason) << " at element "
      << f.domain_element << " eta " << f.target_parameter << " " << f.detail << "\n";
  return s.str();
}

/// How many S2 edges (segments) the report lists as not inserted for `reason`.
template <int d>
std::ptrdiff_t count_failures(const ProjectionReport<d>& r, EdgeFailureReason reason) {
  return std::count_if(r.edges_not_inserted.begin(), r.edges_not_inserted.end(),
                       [reason](const auto& f) { return f.reason == reason; });
}

/// Area of the intersection of two axis-parallel rectangles given as {x0, x1, y0, y1}.
inline double rectangle_overlap(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  const double w = std::min(a[1], b[1]) - std::max(a[0], b[0]);
  const double h = std::min(a[3], b[3]) - std::max(a[2], b[2]);
  return w > 0.0 && h > 0.0 ? w * h : 0.0;
}

}  // namespace plmap::test
