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
    const Eigen::Vector3d& x = map_.position(v);
    Eigen::Vector3d normal = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
    double carried = 0.0, worst_aspect = 1.0;
    int corners = 0;
    for (Index t : map_.vertex_triangles(v)) {
      const auto& c = map_.triangle(t);
      const Eigen::Vector3d& a = map_.position(c[0]);
      normal += (map_.position(c[1]) - a).cross(map_.position(c[2]) - a);
      for (Index w : c)
        if (w != v) {
          mean += map_.position(w);
          ++corners;
        }
      carried = std::max(carried, carried_[static_cast<std::size_t>(t)]);
      worst_aspect = std::max(worst_aspect, aspect_ratio(a, map_.position(c[1]), map_.position(c[2])));
    }
    // The neighbours of v (each once) and the bound on the new triangles' aspect ratios.
    neighbours_.clear();
    for (Index t : map_.vertex_triangles(v))
      for (Index w : map_.triangle(t))
        if (w != v && std::find(neighbours_.begin(), neighbours_.end(), w) == neighbours_.end()) neighbours_.push_back(w);
    double best_new_aspect = 1.0;
    for (Index t : map_.vertex_triangles(v)) {
      const auto& c = map_.triangle(t);
      const int k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
      const Index a = c[(k + 1) % 3], b = c[(k + 2) % 3];
      double best = std::numeric_limits<double>::infinity();
      for (Index w : neighbours_)
        if (w != a && w != b) best = std::min(best, aspect_ratio(map_.position(a), map_.position(b), map_.position(w)));
      if (std::isfinite(best)) best_new_aspect = std::max(best_new_aspect, best);
    }
    double height = 0.0;
    const double n = normal.norm();
    if (corners > 0 && n > 0.0) height = std::abs((x - mean / corners).dot(normal / n));
    if (line[0] != invalid_index) {
      const Eigen::Vector3d p = map_.position(line[0]), d = map_.position(line[1]) - p;
      const double s = d.squaredNorm() > 0.0 ? std::clamp((x - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      height = std::max(height, (x - (p + s * d)).norm());
    }
    return {std::max(carried, height), worst_aspect, best_new_aspect};
  }

 private:
  /// Longest edge × perimeter / (4√3 × area), 1 for the equilateral triangle (the aspect-ratio
  /// oracle's measure).
  static double aspect_ratio(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (!(area > 0.0)) return std::numeric_limits<double>::infinity();
    return std::max({la, lb, lc}) * (la + lb + lc) / (4.0 * std::sqrt(3.0) * area);
  }

  const EditableMap& map_;
  std::vector<double> carried_;  ///< per S1 triangle slot
  mutable std::vector<Index> neighbours_;  ///< working list of estimate()
};

}  // namespace plmap::detail
