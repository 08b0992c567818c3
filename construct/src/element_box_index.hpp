#pragma once
/// \file
/// Which elements of a surface may pass within a distance r of a point: the questions of the
/// vertex preimage search (projection_vertex_preimages.cpp) when it adds the long elements that
/// the nearest centroids miss, and when it asks whether any element that could hold a nearer
/// preimage than the one found is left unsolved (preimage_rank_floor.hpp).
///
/// Asked of the centroid kd-tree alone, the question needs the radius r + R, R the largest
/// centroid-to-corner distance of the whole surface, and on meshes of uneven element size (the
/// CGAL remeshes of the real-mesh pairs: R is 7 typical element sizes on the armadillo) that
/// radius holds dozens of centroids for every query. Centroid trees per size class (reaches within
/// a factor 2, each class asked with r plus its own reach) still descended every class's tree for
/// every query, and on the armadillo pair that was a tenth of the projection's time: the classes
/// of the elements a little larger than those around the point are asked with a radius of
/// several of their sizes. And a kd-tree bounds its cells by splitting planes only, so for a point
/// a gap of many element sizes above a flat surface every cell under the ball is entered. Here the
/// question is asked of the boxes themselves (where the element sizes are uneven, see the
/// constructor): a bounding volume hierarchy of the elements'
/// bounding boxes (median splits of the centroids along the longest axis, up to `leaf_size`
/// elements per leaf), whose search only enters nodes whose box lies within r, so it costs about
/// the depth of the tree plus the elements near the point, whatever the element sizes and the
/// point's distance to the surface.
///
/// The answer is a superset of the elements whose bounding box lies within r of the point (those
/// within r times 1 + 1e-9, the margin covering rounding); the caller filters it with its own
/// exact tests, so it does not change what the search finds.

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/surface.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace plmap::projection {

template <int d>
class ElementBoxIndex {
 public:
  /// Axis-aligned bounding box of an element.
  struct Box {
    WorldPoint<d> low, high;
  };

  /// The tree is built only where the element sizes are uneven (reaches, centroid to farthest box
  /// corner, spread over more than a factor 2: the remeshed real meshes, a few odd elements of the
  /// planes). Elsewhere the caller's one centroid query is as tight for the long elements, and the
  /// tree costs more than it saves: built for the vertex preimage search's skipped walks
  /// (preimage_rank_floor.hpp) on the L7 spheres (327k even elements), it took 0.2 s of set-up
  /// and gave back 0.03 s of walks (it saves more instructions than it costs, but its median
  /// splits wait on memory); on a curve a segment's box is loose where it runs at 45 degrees to
  /// the axes, so the walks it lets the search skip cost about as much to prove skippable.
  explicit ElementBoxIndex(const Surface<d>& s) {
    const Index n = s.element_count();
    reserve_for_writing(boxes_, static_cast<std::size_t>(n));  // read at random by the searches
    boxes_.resize(static_cast<std::size_t>(n));
    double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
    for (Index t = 0; t < n; ++t) {
      Box& box = boxes_[t];
      box.low = box.high = s.corner(t, 0);
      for (int k = 1; k <= d; ++k) {
        box.low = box.low.cwiseMin(s.corner(t, k));
        box.high = box.high.cwiseMax(s.corner(t, k));
      }
      const WorldPoint<d> c = element_centroid(s, t);
      const double reach = (c - box.low).cwiseAbs().cwiseMax((box.high - c).cwiseAbs()).norm();
      if (reach > 0.0) smallest = std::min(smallest, reach);
      largest = std::max(largest, reach);
    }
    if (n == 0 || !(largest >= 2.0 * smallest)) return;
    build_tree(s);
  }

  /// Whether the tree was built (else visit_near must not be called: the caller asks the centroid
  /// tree).
  bool has_tree() const { return !nodes_.empty(); }

  const Box& box(Index t) const { return boxes_[t]; }

  /// Calls visit(t) for every element t whose bounding box lies within r of x, and perhaps a few
  /// more within r (1 + 1e-9); each once, in no particular order.
  template <class Visit>
  void visit_near(const WorldPoint<d>& x, double r, Visit&& visit) const {
    // squared distances: no root per box (the margin covers their rounding)
    const double reach2 = r * r * (1.0 + 1.9e-9);
    if (nodes_.empty()) return;
    std::array<std::uint32_t, 64> stack;
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (squared_box_distance(x, node.box) > reach2) continue;
      if (node.count > 0) {
        for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
          if (squared_box_distance(x, ordered_boxes_[i]) <= reach2) visit(ordered_element_[i]);
      } else {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
  }

  /// The centroid as ElementIndex computes it (corner sum over d + 1).
  static WorldPoint<d> element_centroid(const Surface<d>& s, Index t) {
    WorldPoint<d> c = WorldPoint<d>::Zero();
    for (int k = 0; k <= d; ++k) c += s.corner(t, k);
    c /= d + 1;
    return c;
  }

  /// Distance from x to a box (0 inside it).
  static double box_distance(const WorldPoint<d>& x, const Box& box) {
    return (x.cwiseMax(box.low).cwiseMin(box.high) - x).norm();
  }

  static double squared_box_distance(const WorldPoint<d>& x, const Box& box) {
    return (x.cwiseMax(box.low).cwiseMin(box.high) - x).squaredNorm();
  }

 private:
  static constexpr std::uint32_t leaf_size = 8;

  /// A node of the hierarchy: its box, and either its elements (count > 0: ordered_*[first,
  /// first + count)) or its two children (count = 0: nodes first and first + 1).
  struct Node {
    Box box;
    std::uint32_t first = 0, count = 0;
  };

  /// Median splits of the centroids along the longest axis of their bounds, depth first; the
  /// depth is about log2(n / leaf_size), far below the search stack's 64 for any Index count.
  void build_tree(const Surface<d>& s) {
    const auto n = static_cast<std::uint32_t>(boxes_.size());
    std::vector<WorldPoint<d>> centroid;
    reserve_for_writing(centroid, n);
    centroid.resize(n);
    for (std::uint32_t t = 0; t < n; ++t) centroid[t] = element_centroid(s, static_cast<Index>(t));
    reserve_for_writing(ordered_element_, n);
    ordered_element_.resize(n);
    std::iota(ordered_element_.begin(), ordered_element_.end(), 0);
    reserve_on_huge_pages(nodes_, 2 * (n / leaf_size + 1));
    nodes_.emplace_back();
    struct Range {
      std::uint32_t node, begin, end;
    };
    std::vector<Range> todo{{0, 0, n}};
    while (!todo.empty()) {
      const Range range = todo.back();
      todo.pop_back();
      Box box = boxes_[ordered_element_[range.begin]];
      WorldPoint<d> low = centroid[ordered_element_[range.begin]], high = low;
      for (std::uint32_t i = range.begin; i < range.end; ++i) {
        const auto t = static_cast<std::size_t>(ordered_element_[i]);
        box.low = box.low.cwiseMin(boxes_[t].low);
        box.high = box.high.cwiseMax(boxes_[t].high);
        low = low.cwiseMin(centroid[t]);
        high = high.cwiseMax(centroid[t]);
      }
      nodes_[range.node].box = box;
      if (range.end - range.begin <= leaf_size) {
        nodes_[range.node].first = range.begin;
        nodes_[range.node].count = range.end - range.begin;
        continue;
      }
      int axis = 0;
      (high - low).maxCoeff(&axis);
      const std::uint32_t middle = range.begin + (range.end - range.begin) / 2;
      std::nth_element(ordered_element_.begin() + range.begin, ordered_element_.begin() + middle,
                       ordered_element_.begin() + range.end, [&](Index a, Index b) {
                         return centroid[a](axis) < centroid[b](axis) || (centroid[a](axis) == centroid[b](axis) && a < b);
                       });
      const auto children = static_cast<std::uint32_t>(nodes_.size());
      nodes_[range.node].first = children;
      nodes_.emplace_back();
      nodes_.emplace_back();
      todo.push_back({children, range.begin, middle});
      todo.push_back({children + 1, middle, range.end});
    }
    reserve_for_writing(ordered_boxes_, n);
    ordered_boxes_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) ordered_boxes_[i] = boxes_[ordered_element_[i]];
  }

  std::vector<Box> boxes_;          // by element
  std::vector<Node> nodes_;         // the hierarchy, root first (empty: no tree)
  std::vector<Index> ordered_element_;  // the elements in the order of the leaves
  std::vector<Box> ordered_boxes_;  // their boxes in that order (a leaf's are contiguous)
};

}  // namespace plmap::projection
