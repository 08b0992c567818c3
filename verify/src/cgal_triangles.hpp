#pragma once
// A surface's elements as CGAL triangles in an AABB tree, for the ray check, which asks CGAL
// rather than plmap's own geometry, and where the elements meet each other although they share no
// vertex. Private to verify/. (self_intersections.cpp lists such pairs for the whole surface with
// a sweep over boxes instead: cheaper than a tree query per element.)

#include <plmap/core/surface.hpp>

#include <Eigen/Core>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace plmap::verify_detail {

using Kernel = CGAL::Simple_cartesian<double>;
using Point3 = Kernel::Point_3;
using Triangle3 = Kernel::Triangle_3;
using Segment3 = Kernel::Segment_3;
using TriangleIterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
// The tree's double triangles answer which pairs may meet; whether two of them meet is decided
// with exact predicates, so that a rounding error cannot make a surface cross itself.
using ExactKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactTriangle = ExactKernel::Triangle_3;

inline ExactTriangle exact_triangle(const Triangle3& t) {
  auto p = [](const Point3& q) { return ExactKernel::Point_3(q.x(), q.y(), q.z()); };
  return {p(t[0]), p(t[1]), p(t[2])};
}

template <int d>
Eigen::Vector3d lifted(const WorldPoint<d>& p) {
  if constexpr (d == 2)
    return p;
  else
    return Eigen::Vector3d(p.x(), p.y(), 0.0);
}

inline Point3 cgal_point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
inline Eigen::Vector3d eigen_point(const Point3& p) { return {p.x(), p.y(), p.z()}; }

/// A surface's elements as CGAL triangles, and for each triangle its element. Curves (d = 1) are
/// extruded: each segment becomes the rectangle segment x [-h, h] along z (two triangles), so
/// that a ray in the plane z = 0 meets the rectangle exactly where it meets the segment, and two
/// rectangles meet exactly where their segments do.
template <int d>
struct TargetTriangles {
  std::vector<Triangle3> triangles;
  std::vector<Index> element;

  explicit TargetTriangles(const Surface<d>& s) {
    if constexpr (d == 2) {
      for (Index t = 0; t < s.element_count(); ++t) {
        triangles.emplace_back(cgal_point(s.corner(t, 0)), cgal_point(s.corner(t, 1)), cgal_point(s.corner(t, 2)));
        element.push_back(t);
      }
    } else {
      // the rectangles' height only has to be nonzero; the curve's size keeps it relative to the input
      const double diagonal = (s.bounding_box_max() - s.bounding_box_min()).norm();
      const double h = diagonal > 0.0 ? diagonal : 1.0;
      for (Index t = 0; t < s.element_count(); ++t) {
        const Eigen::Vector3d a = lifted<1>(s.corner(t, 0)), b = lifted<1>(s.corner(t, 1)), z(0, 0, h);
        triangles.emplace_back(cgal_point(a - z), cgal_point(b - z), cgal_point(b + z));
        triangles.emplace_back(cgal_point(a - z), cgal_point(b + z), cgal_point(a + z));
        element.push_back(t);
        element.push_back(t);
      }
    }
  }

  std::size_t index_of(TriangleIterator it) const { return static_cast<std::size_t>(it - triangles.cbegin()); }
};

/// Where the elements of a surface meet others with which they share no vertex: the surface
/// crosses itself there (overlapping bodies, an offset copy folded over itself). Elements that
/// share a vertex are not compared (they meet there by construction). Per triangle of the tree,
/// computed when first asked and kept.
template <int d>
class SelfCrossings {
 public:
  /// The tree must hold `triangles` and outlive this object (it may be built after construction).
  SelfCrossings(const Surface<d>& s, const TargetTriangles<d>& triangles, const Tree& tree)
      : s_(s), triangles_(triangles), tree_(tree) {}

  /// Where triangle i meets the triangles that for_each_met names: one segment per such triangle
  /// (a point is a segment of length 0; where the two overlap in one plane, or touch where the
  /// rounded construction finds nothing, the line of triangle i in the other's plane or, failing
  /// that, triangle i's edges stand for the place).
  const std::vector<Segment3>& of(std::size_t i) {
    if (known_.empty()) {
      known_.assign(triangles_.triangles.size(), false);
      segments_.resize(triangles_.triangles.size());
    }
    std::vector<Segment3>& segments = segments_[i];
    if (known_[i]) return segments;
    known_[i] = true;
    const Triangle3& mine = triangles_.triangles[i];
    for_each_met(i, [&](std::size_t j) {
      const Triangle3& other = triangles_.triangles[j];
      if (const auto where = CGAL::intersection(mine, other)) {
        add(*where, mine, segments);
      } else if (const auto cut = CGAL::intersection(mine, other.supporting_plane())) {
        add(*cut, mine, segments);  // a touch the rounded construction misses: the line it lies on
      } else {
        add_edges(mine, segments);
      }
    });
    return segments;
  }

 private:
  /// Calls f(j) for each triangle j of the tree whose element shares no vertex with triangle i's
  /// and which meets triangle i (exact predicates).
  template <class F>
  void for_each_met(std::size_t i, F&& f) {
    const Index tau = triangles_.element[i];
    const auto& corners = s_.element(tau);
    const auto shares_a_vertex = [&](Index sigma) {
      for (Index v : s_.element(sigma))
        if (std::find(corners.begin(), corners.end(), v) != corners.end()) return true;
      return false;
    };
    const Triangle3& mine = triangles_.triangles[i];
    const ExactTriangle exact_mine = exact_triangle(mine);
    // CGAL's test requires proper triangles; a surface refuses elements of zero area, but the
    // area it computes in doubles may be the rounding of exactly collinear corners
    // (defensive: not seen in the meshes of libcgal-demo)
    if (exact_mine.is_degenerate()) return;
    candidates_.clear();
    // by box: cheaper per tree node than the triangle, and the exact test decides anyway
    const CGAL::Bbox_3 box = mine.bbox();
    tree_.all_intersected_primitives(Kernel::Iso_cuboid_3(box), std::back_inserter(candidates_));
    for (const TriangleIterator it : candidates_) {
      const std::size_t j = triangles_.index_of(it);
      const Index sigma = triangles_.element[j];
      if (sigma == tau || shares_a_vertex(sigma)) continue;
      const ExactTriangle exact_other = exact_triangle(*it);
      if (exact_other.is_degenerate() || !CGAL::do_intersect(exact_mine, exact_other)) continue;
      f(j);
    }
  }

  template <class Place>
  static void add(const Place& where, const Triangle3& mine, std::vector<Segment3>& segments) {
    if (const Point3* p = boost::get<Point3>(&where)) {
      segments.emplace_back(*p, *p);
    } else if (const Segment3* g = boost::get<Segment3>(&where)) {
      segments.push_back(*g);
    } else {
      add_edges(mine, segments);  // an overlap in one plane
    }
  }
  static void add_edges(const Triangle3& mine, std::vector<Segment3>& segments) {
    for (int k = 0; k < 3; ++k) segments.emplace_back(mine[k], mine[(k + 1) % 3]);
  }

  const Surface<d>& s_;
  const TargetTriangles<d>& triangles_;
  const Tree& tree_;
  std::vector<TriangleIterator> candidates_;
  std::vector<bool> known_;
  std::vector<std::vector<Segment3>> segments_;
};

}  // namespace plmap::verify_detail
