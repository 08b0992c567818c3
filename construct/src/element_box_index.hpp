#pragma once
/// \file
/// Which elements of a surface may pass within a distance r of a point: the question of the
/// vertex preimage search (projection_vertex_preimages.cpp) when it adds the long elements that
/// the nearest centroids miss.
///
/// Asked of the centroid kd-tree alone, the question needs the radius r + R, R the largest
/// centroid-to-corner distance of the whole surface, and on meshes of uneven element size (the
/// CGAL remeshes of the real-mesh pairs: R is 7 typical element sizes on the armadillo) that
/// radius holds dozens of centroids for every query; the radius queries took as long as the
/// nearest-centroid queries themselves. Here the elements are split into classes by their reach
/// (the largest distance from the centroid to a point of the bounding box), each class within a
/// factor 2 and with a kd-tree of its own, and each class is asked with r plus its own largest
/// reach: the small elements, nearly all of them, with a small radius.
///
/// The answer is a superset of the elements whose bounding box lies within r of the point (an
/// element's box within r puts its centroid within r plus its reach); the caller filters it
/// with its own exact tests, so it does not change what the search finds.

#include "element_index.hpp"

#include <plmap/core/surface.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace plmap::projection {

template <int d>
class ElementBoxIndex {
 public:
  /// Axis-aligned bounding box of an element.
  struct Box {
    WorldPoint<d> low, high;
  };

  explicit ElementBoxIndex(const Surface<d>& s) {
    const Index n = s.element_count();
    boxes_.resize(static_cast<std::size_t>(n));
    std::vector<double> reach(static_cast<std::size_t>(n));
    double smallest = std::numeric_limits<double>::infinity();
    for (Index t = 0; t < n; ++t) {
      Box& box = boxes_[t];
      box.low = box.high = s.corner(t, 0);
      for (int k = 1; k <= d; ++k) {
        box.low = box.low.cwiseMin(s.corner(t, k));
        box.high = box.high.cwiseMax(s.corner(t, k));
      }
      const WorldPoint<d> c = element_centroid(s, t);
      reach[t] = (c - box.low).cwiseAbs().cwiseMax((box.high - c).cwiseAbs()).norm();
      if (reach[t] > 0.0) smallest = std::min(smallest, reach[t]);
    }
    // class c: reach up to smallest * 2^(c + 1) (the last class takes the rest)
    auto class_of = [&](double r) {
      if (!(r > smallest)) return 0;
      return std::min(max_classes - 1, static_cast<int>(std::log2(r / smallest)));
    };
    int lowest = max_classes, highest = -1;
    for (Index t = 0; t < n; ++t) {
      lowest = std::min(lowest, class_of(reach[t]));
      highest = std::max(highest, class_of(reach[t]));
    }
    // One class (reaches within a factor 2: the spheres): the one wide query is as tight, and
    // building the class would cost more than it saves. A few odd elements are enough to make
    // the classes pay (the 200k planes: 19 elements in a second class).
    if (highest == lowest) return;
    classes_.resize(max_classes);
    for (Index t = 0; t < n; ++t) {
      SizeClass& sc = classes_[class_of(reach[t])];
      sc.element.push_back(t);
      sc.centroids.points.push_back(element_centroid(s, t));
      sc.reach = std::max(sc.reach, reach[t]);
    }
    std::erase_if(classes_, [](const SizeClass& sc) { return sc.element.empty(); });
    for (SizeClass& sc : classes_)
      sc.tree = std::make_unique<KdTree<d + 1>>(d + 1, sc.centroids, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  }

  /// Whether the element sizes are uneven enough for the classes (else visit_near must not be
  /// called: the caller asks the centroid tree).
  bool has_classes() const { return !classes_.empty(); }

  const Box& box(Index t) const { return boxes_[t]; }

  /// Calls visit(t) for every element t whose bounding box may lie within r of x (at least those
  /// that do; each once, in no particular order).
  template <class Visit>
  void visit_near(const WorldPoint<d>& x, double r, Visit&& visit) const {
    for (const SizeClass& sc : classes_) {
      // the margin covers the rounding of the reach and of the tree's distances
      const double radius = (r + sc.reach) * (1.0 + 1e-9);
      Collector<Visit> collect{radius * radius, sc.element.data(), visit};
      sc.tree->findNeighbors(collect, x.data(), nanoflann::SearchParams());
    }
  }

  /// The centroid as ElementIndex computes it (corner sum over d + 1).
  static WorldPoint<d> element_centroid(const Surface<d>& s, Index t) {
    WorldPoint<d> c = WorldPoint<d>::Zero();
    for (int k = 0; k <= d; ++k) c += s.corner(t, k);
    c /= d + 1;
    return c;
  }

 private:
  static constexpr int max_classes = 24;

  struct SizeClass {
    std::vector<Index> element;  // the class's elements, in the order of its centroids
    PointCloud<d + 1> centroids;
    std::unique_ptr<KdTree<d + 1>> tree;
    double reach = 0.0;  // the largest reach in the class
  };

  /// A nanoflann result set that hands each point within the radius to the visitor instead of
  /// collecting it (no allocation per query).
  template <class Visit>
  struct Collector {
    double squared_radius;
    const Index* element;
    Visit& visit;
    void init() {}
    void clear() {}
    std::size_t size() const { return 0; }
    bool full() const { return true; }
    bool addPoint(double squared_distance, std::uint32_t i) {
      if (squared_distance < squared_radius) visit(element[i]);
      return true;
    }
    double worstDist() const { return squared_radius; }
  };

  std::vector<Box> boxes_;
  std::vector<SizeClass> classes_;
};

}  // namespace plmap::projection
