#pragma once
// The cheap ranking of simplify()'s "estimate" ranking (SimplifyOptions::ranking): estimates
// of what the Hausdorff and aspect-ratio oracles will say about removing an S1 vertex, with no
// flattening, no hole triangulation and no relocation of preimages: a few dozen aspect ratios
// and dot products per vertex instead of a ranking plan (about 25 k instructions on CGAL's
// femur).
//
// Distance. Removing v replaces its star by triangles spanned by its ring, so the star's points
// move by about the height of v above its ring, and the nodes already carried away from their
// images by earlier steps stay about as far. The estimate is max(carried, height), with
//  - carried: the largest node distance the star's triangles carry from the steps that made
//    them (kept per S1 triangle: the largest distance of the S2 vertex preimages the creating
//    plan put into it, 0 for S2's own triangles);
//  - height: the distance of v to the plane through the mean of its ring with the star's
//    area-weighted normal, and for a vertex on a feature line also to the segment joining its
//    line neighbours, onto which its node moves.
// (carried + height, nearer an upper bound, ranked too late: on the femur → 500 the final error
// was 0.022 instead of 0.020 relative to the diagonal, and on the camel → 2,000 0.012 instead
// of 0.010.) It is neither a lower nor an upper bound of the full plan's distance.
//
// Aspect ratio. The worst aspect ratio of the star's triangles, and a lower bound of the worst
// of the new ones (see Estimate::best_new_aspect), so that their difference bounds the
// aspect-ratio oracle's cost from below; without it a vertex whose removal would clear thin
// triangles comes up late, and the removal order loses the coarse triangles' shape.
//
// simplify() corrects the estimate when the vertex comes up (see simplify.hpp).

#include <plmap/core/editable_map.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace plmap::detail {

class SimplifyRankingEstimate {
 public:
  /// The carried distance of every S1 triangle slot, growing as removals append triangles.
  explicit SimplifyRankingEstimate(const EditableMap& map) : map_(map), carried_(map.triangle_slot_count(), 0.0) {}

  /// After a plan was applied: each triangle it appended carries the largest distance of the
  /// S2 vertex preimages the plan put into it (or onto its line edge). The crossings of S2
  /// edges are left out: they lie between such preimages, and the full plan counts them.
  void on_applied(const VertexRemovalPlan& plan) {
    const std::size_t base = static_cast<std::size_t>(plan.triangle_count_at_planning);
    carried_.resize(static_cast<std::size_t>(map_.triangle_slot_count()), 0.0);
    const Surface<2>& target = map_.target();
    for (const VertexRemovalPlan::Relocation& r : plan.relocations) {
      if (r.new_triangle >= 0) {
        const auto& c = plan.new_triangles[static_cast<std::size_t>(r.new_triangle)];
        const Eigen::Vector3d x = r.barycentric[0] * map_.position(c[0]) + r.barycentric[1] * map_.position(c[1]) +
                                  r.barycentric[2] * map_.position(c[2]);
        double& carried = carried_[base + static_cast<std::size_t>(r.new_triangle)];
        carried = std::max(carried, (x - target.vertex(r.target_vertex)).norm());
        continue;
      }
      const Eigen::Vector3d& p = map_.position(plan.line_edge[0]);
      const Eigen::Vector3d x = p + r.edge_parameter * (map_.position(plan.line_edge[1]) - p);
      const double distance = (x - target.vertex(r.target_vertex)).norm();
      for (std::size_t k = 0; k < plan.new_triangles.size(); ++k) {
        const auto& c = plan.new_triangles[k];
        const auto holds = [&](Index w) { return c[0] == w || c[1] == w || c[2] == w; };
        if (holds(plan.line_edge[0]) && holds(plan.line_edge[1])) carried_[base + k] = std::max(carried_[base + k], distance);
      }
    }
  }

  struct Estimate {
    double distance;            ///< estimated largest node distance of the step
    double worst_star_aspect;   ///< largest aspect ratio among the star's triangles (as the aspect-ratio oracle)
    /// A lower bound of the largest aspect ratio among the new triangles: each edge of the
    /// star opposite v bounds the hole, so some new triangle joins it to another neighbour of
    /// v; the bound is the largest, over these edges, of the best such triangle.
    double best_new_aspect;
  };

  /// The estimate of removing v; `line` holds v's two neighbours along its feature line, or
  /// invalid_index if v is not on one.
  Estimate estimate(Index v, std::array<Index, 2> line) const {
    // v's neighbours, each once, with their positions, and per star triangle the neighbour
    // indices of its two corners other than v (counter-clockwise).
    const Eigen::Vector3d& x = map_.position(v);
    neighbours_.clear();
    positions_.clear();
    outer_edges_.clear();
    double carried = 0.0;
    const auto neighbour_index = [&](Index w) {
      for (std::size_t i = 0; i < neighbours_.size(); ++i)
        if (neighbours_[i] == w) return static_cast<int>(i);
      neighbours_.push_back(w);
      positions_.push_back(map_.position(w));
      return static_cast<int>(neighbours_.size() - 1);
    };
    for (Index t : map_.vertex_triangles(v)) {
      const auto& c = map_.triangle(t);
      const int k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
      outer_edges_.push_back({neighbour_index(c[(k + 1) % 3]), neighbour_index(c[(k + 2) % 3])});
      carried = std::max(carried, carried_[static_cast<std::size_t>(t)]);
    }
    const int n = static_cast<int>(neighbours_.size());
    // Distances between neighbours and to v, each computed once.
    lengths_.assign(static_cast<std::size_t>(n * n), 0.0);
    spoke_.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      spoke_[i] = (positions_[i] - x).norm();
      for (int j = i + 1; j < n; ++j) lengths_[i * n + j] = lengths_[j * n + i] = (positions_[i] - positions_[j]).norm();
    }
    Eigen::Vector3d normal = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
    double worst_aspect_squared = 1.0, best_new_aspect_squared = 1.0;
    for (const auto& [a, b] : outer_edges_) {
      const Eigen::Vector3d ab = positions_[b] - positions_[a];
      const Eigen::Vector3d star_normal = (positions_[a] - x).cross(positions_[b] - x);
      normal += star_normal;
      mean += positions_[a] + positions_[b];
      worst_aspect_squared = std::max(
          worst_aspect_squared, aspect_squared(spoke_[a], spoke_[b], lengths_[a * n + b], star_normal.squaredNorm()));
      // The new triangle on the outer edge ab has its third corner among the other neighbours.
      // The bound is the largest of these minima over the outer edges, so an edge whose minimum
      // comes down to the largest so far cannot raise it: its search stops there (the bound is
      // the same, bit for bit; most edges stop after a few corners). The search starts after b,
      // where the ring's next vertex usually is: a triangle of the ring's own edges is seldom
      // the worst choice.
      double best = std::numeric_limits<double>::infinity();
      for (int k = 1; k < n; ++k) {
        const int w = (b + k) % n;
        if (w == a) continue;
        best = std::min(best, aspect_squared(lengths_[a * n + w], lengths_[b * n + w], lengths_[a * n + b],
                                             ab.cross(positions_[w] - positions_[a]).squaredNorm()));
        if (best <= best_new_aspect_squared) break;
      }
      if (std::isfinite(best)) best_new_aspect_squared = std::max(best_new_aspect_squared, best);
    }
    double height = 0.0;
    const double normal_length = normal.norm();
    if (!outer_edges_.empty() && normal_length > 0.0)
      height = std::abs((x - mean / (2.0 * static_cast<double>(outer_edges_.size()))).dot(normal / normal_length));
    if (line[0] != invalid_index) {
      const Eigen::Vector3d p = map_.position(line[0]), d = map_.position(line[1]) - p;
      const double s = d.squaredNorm() > 0.0 ? std::clamp((x - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      height = std::max(height, (x - (p + s * d)).norm());
    }
    return {std::max(carried, height), std::sqrt(worst_aspect_squared), std::sqrt(best_new_aspect_squared)};
  }

 private:
  /// The square of the aspect-ratio oracle's measure, longest edge × perimeter / (4√3 × area)
  /// (1 for the equilateral triangle), from the edge lengths and the squared norm of twice the
  /// area vector: squares spare a root per candidate triangle.
  static double aspect_squared(double l0, double l1, double l2, double twice_area_squared) {
    if (!(twice_area_squared > 0.0)) return std::numeric_limits<double>::infinity();
    const double product = std::max({l0, l1, l2}) * (l0 + l1 + l2);
    return product * product / (12.0 * twice_area_squared);
  }

  const EditableMap& map_;
  std::vector<double> carried_;  ///< per S1 triangle slot
  // Working lists of estimate().
  mutable std::vector<Index> neighbours_;
  mutable std::vector<Eigen::Vector3d> positions_;
  mutable std::vector<std::array<int, 2>> outer_edges_;
  mutable std::vector<double> lengths_, spoke_;
};

}  // namespace plmap::detail
