#pragma once
// The cheap ranking of simplify()'s "estimate" ranking (SimplifyOptions::ranking): an estimate
// of the modified Hausdorff distance of removing an S1 vertex that needs no flattening, no
// hole triangulation and no relocation of preimages, a few dozen flops per star triangle
// instead of a ranking plan (about 25 k instructions on CGAL's femur).
//
// Removing v replaces its star by triangles spanned by its ring, so every point of the star
// moves by about the height of v above the ring: a node of the star that was `carried` away
// from its image lands at most about carried + height away (triangle inequality). The estimate
// is that sum, with
//  - carried: the largest node distance the star's triangles carry from the steps that made
//    them (SimplifyRankingEstimate keeps it per S1 triangle: the largest distance of the S2
//    vertex preimages the creating plan put into it, 0 for S2's own triangles);
//  - height: the distance of v to the plane through the mean of its ring with the star's
//    area-weighted normal, and for a vertex on a feature line also to the segment joining its
//    line neighbours, onto which its node moves.
// It is neither a lower nor an upper bound of the full plan's distance; simplify() corrects it
// when the vertex comes up (see simplify.hpp).

#include <plmap/core/editable_map.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
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

  /// The estimated largest node distance of removing v; `line` holds v's two neighbours along
  /// its feature line, or invalid_index if v is not on one.
  double distance(Index v, std::array<Index, 2> line) const {
    const Eigen::Vector3d& x = map_.position(v);
    Eigen::Vector3d normal = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
    double carried = 0.0;
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
    }
    double height = 0.0;
    const double n = normal.norm();
    if (corners > 0 && n > 0.0) height = std::abs((x - mean / corners).dot(normal / n));
    if (line[0] != invalid_index) {
      const Eigen::Vector3d p = map_.position(line[0]), d = map_.position(line[1]) - p;
      const double s = d.squaredNorm() > 0.0 ? std::clamp((x - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      height = std::max(height, (x - (p + s * d)).norm());
    }
    return carried + height;
  }

 private:
  const EditableMap& map_;
  std::vector<double> carried_;  ///< per S1 triangle slot
};

}  // namespace plmap::detail
