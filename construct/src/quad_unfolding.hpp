#pragma once
// The quadrilateral of a smoothing step laid into the plane (quad_smoothing.hpp, step 1): the two
// S1 triangles T1 = (A, B, C1) and T2 = (B, A, C2) that share the edge e = AB, isometrically,
// A at the origin, B on the positive x axis, C1 above and C2 below; and the affine maps between
// each triangle's local coordinates and the plane. Private to the smoothing.

#include "preimage_graph.hpp"

#include <plmap/core/surface.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <array>
#include <optional>

namespace plmap::smoothing {

struct Unfolding {
  Index e = invalid_index, t1 = invalid_index, t2 = invalid_index;
  Index a = invalid_index, b = invalid_index, c1 = invalid_index, c2 = invalid_index;
  Eigen::Vector2d pa, pb, pc1, pc2;
  std::array<Eigen::Vector2d, 3> corners1, corners2;  ///< plane positions of each triangle's corners 0, 1, 2
  double length = 0.0;

  const std::array<Eigen::Vector2d, 3>& corners(Index t) const { return t == t1 ? corners1 : corners2; }
  Eigen::Vector2d plane(Index t, const LocalPoint<2>& x) const {
    const auto& c = corners(t);
    return c[0] + x.x() * (c[1] - c[0]) + x.y() * (c[2] - c[0]);
  }
  LocalPoint<2> local(Index t, const Eigen::Vector2d& p) const {
    const auto& c = corners(t);
    Eigen::Matrix2d m;
    m.col(0) = c[1] - c[0];
    m.col(1) = c[2] - c[0];
    return m.inverse() * (p - c[0]);
  }
  std::optional<Eigen::Vector2d> vertex(Index v) const {
    if (v == a) return pa;
    if (v == b) return pb;
    if (v == c1) return pc1;
    if (v == c2) return pc2;
    return std::nullopt;
  }
  /// Plane position of a place in the closed quadrilateral (the caller knows it is there).
  std::optional<Eigen::Vector2d> place(const Surface<2>& s1, const DomainPlace& p) const {
    switch (p.kind) {
      case DomainPlace::Kind::vertex: return vertex(p.where);
      case DomainPlace::Kind::edge: {
        const auto ends = s1.edge_vertices(p.where);
        const auto lo = vertex(ends[0]), hi = vertex(ends[1]);
        if (!lo || !hi) return std::nullopt;
        return Eigen::Vector2d(*lo + p.edge_parameter * (*hi - *lo));
      }
      case DomainPlace::Kind::element:
        if (p.where != t1 && p.where != t2) return std::nullopt;
        return plane(p.where, p.local);
    }
    return std::nullopt;
  }
};

}  // namespace plmap::smoothing
