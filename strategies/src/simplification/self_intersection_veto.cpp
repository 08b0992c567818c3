#include <plmap/strategies/simplification/self_intersection_veto.hpp>

// nanoflann's dynamic index copies a sub-index whose root_bbox it fills only when built; GCC's
// -Wmaybe-uninitialized flags that copy once the code is inlined here (a false positive that
// -Werror would turn into a build failure).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <nanoflann.hpp>

#include <Eigen/Geometry>

namespace plmap {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

struct Centroids {
  std::vector<Eigen::Vector3d> points;  // by S1 triangle id (dead ones keep their slot)
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i](static_cast<Eigen::Index>(dim)); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<double, Centroids>, Centroids, 3>;

double circumradius_bound(const Eigen::Vector3d& centroid, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
  return std::sqrt(std::max({(a - centroid).squaredNorm(), (b - centroid).squaredNorm(), (c - centroid).squaredNorm()}));
}

Kernel::Triangle_3 cgal_triangle(const EditableMap& map, const std::array<plmap::Index, 3>& t) {
  auto p = [&](int k) {
    const auto& x = map.position(t[k]);
    return Kernel::Point_3(x(0), x(1), x(2));
  };
  return {p(0), p(1), p(2)};
}

}  // namespace

struct SelfIntersectionVeto::Index {
  Centroids centroids;
  Tree tree{3, centroids, nanoflann::KDTreeSingleIndexAdaptorParams(10)};
  double largest_radius = 0.0;

  void add(const EditableMap& map, plmap::Index t) {
    const auto& c = map.triangle(t);
    const Eigen::Vector3d centroid = (map.position(c[0]) + map.position(c[1]) + map.position(c[2])) / 3.0;
    if (centroids.points.size() <= static_cast<std::size_t>(t)) centroids.points.resize(t + 1, Eigen::Vector3d::Zero());
    centroids.points[t] = centroid;
    largest_radius = std::max(largest_radius, circumradius_bound(centroid, map.position(c[0]), map.position(c[1]), map.position(c[2])));
  }
};

SelfIntersectionVeto::SelfIntersectionVeto() = default;
SelfIntersectionVeto::~SelfIntersectionVeto() = default;
SelfIntersectionVeto::SelfIntersectionVeto(SelfIntersectionVeto&&) noexcept = default;
SelfIntersectionVeto& SelfIntersectionVeto::operator=(SelfIntersectionVeto&&) noexcept = default;

OracleVerdict SelfIntersectionVeto::evaluate(const RemovalCandidate& candidate) const {
  const EditableMap& map = candidate.map;
  const VertexRemovalPlan& plan = candidate.plan;
  if (!index_) {
    index_ = std::make_unique<Index>();
    // nanoflann's dynamic index takes points in the order of their ids, so every triangle slot
    // is added and the dead ones removed again.
    const plmap::Index slots = map.triangle_slot_count();
    for (plmap::Index t = 0; t < slots; ++t) index_->add(map, t);
    if (slots > 0) index_->tree.addPoints(0, slots - 1);
    for (plmap::Index t = 0; t < slots; ++t)
      if (!map.is_live_triangle(t)) index_->tree.removePoint(t);
  }
  std::vector<std::pair<std::size_t, double>> hits;
  for (const auto& t : plan.new_triangles) {
    const Eigen::Vector3d a = map.position(t[0]), b = map.position(t[1]), c = map.position(t[2]);
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    const double radius = circumradius_bound(centroid, a, b, c) + index_->largest_radius;
    nanoflann::RadiusResultSet<double, std::size_t> result(radius * radius, hits);
    index_->tree.findNeighbors(result, centroid.data(), nanoflann::SearchParams());
    const Kernel::Triangle_3 fresh = cgal_triangle(map, t);
    for (const auto& [other, distance] : hits) {
      const auto o = static_cast<plmap::Index>(other);
      if (!map.is_live_triangle(o)) continue;
      if (std::find(plan.old_triangles.begin(), plan.old_triangles.end(), o) != plan.old_triangles.end()) continue;
      const auto& oc = map.triangle(o);
      bool shares = false;
      for (plmap::Index x : oc) shares = shares || x == t[0] || x == t[1] || x == t[2];
      if (shares) continue;
      if (CGAL::do_intersect(fresh, cgal_triangle(map, oc))) return OracleVerdict::vetoed();
    }
  }
  return {0.0, false};
}

void SelfIntersectionVeto::on_applied(const EditableMap& map, const VertexRemovalPlan& plan) {
  if (!index_) return;
  for (plmap::Index t : plan.old_triangles) index_->tree.removePoint(static_cast<std::size_t>(t));
  const plmap::Index first = plan.triangle_count_at_planning;
  const plmap::Index count = static_cast<plmap::Index>(plan.new_triangles.size());
  for (plmap::Index t = first; t < first + count; ++t) index_->add(map, t);
  if (count > 0) index_->tree.addPoints(first, first + count - 1);
}

}  // namespace plmap
