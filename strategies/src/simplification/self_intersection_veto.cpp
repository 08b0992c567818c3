#include <plmap/strategies/simplification/self_intersection_veto.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <boost/geometry.hpp>  // the whole library: the R-tree's strategies need its algorithms
#include <boost/geometry/index/rtree.hpp>

#include <algorithm>
#include <iterator>
#include <utility>
#include <vector>

namespace plmap {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BoxPoint = bg::model::point<double, 3, bg::cs::cartesian>;
using Box = bg::model::box<BoxPoint>;
using Entry = std::pair<Box, plmap::Index>;
// R*-tree: its insertions keep the boxes' overlap low, which is what the queries pay for; the
// index changes by a few triangles per step, against one query per new triangle.
using Tree = bgi::rtree<Entry, bgi::rstar<16>>;

// The bounding box of a triangle: min and max of double coordinates are exact, so two triangles
// that intersect (CGAL's exact test) always have intersecting boxes.
Box bounding_box(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
  return {BoxPoint(lo(0), lo(1), lo(2)), BoxPoint(hi(0), hi(1), hi(2))};
}

Box bounding_box(const EditableMap& map, const std::array<plmap::Index, 3>& t) {
  return bounding_box(map.position(t[0]), map.position(t[1]), map.position(t[2]));
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
  Tree tree;
  std::vector<Box> boxes;  // by S1 triangle slot, to remove a triangle's entry again

  Entry entry(const EditableMap& map, plmap::Index t) {
    if (boxes.size() <= static_cast<std::size_t>(t)) boxes.resize(static_cast<std::size_t>(t) + 1);
    boxes[static_cast<std::size_t>(t)] = bounding_box(map, map.triangle(t));
    return {boxes[static_cast<std::size_t>(t)], t};
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
    std::vector<Entry> live;
    for (plmap::Index t = 0; t < map.triangle_slot_count(); ++t)
      if (map.is_live_triangle(t)) live.push_back(index_->entry(map, t));
    index_->tree = Tree(live.begin(), live.end());  // bulk loading (packing): one pass, balanced
  }
  std::vector<Entry> hits;
  for (const auto& t : plan.new_triangles) {
    hits.clear();
    index_->tree.query(bgi::intersects(bounding_box(map, t)), std::back_inserter(hits));
    const Kernel::Triangle_3 fresh = cgal_triangle(map, t);
    for (const auto& [box, o] : hits) {
      if (!map.is_live_triangle(o)) continue;  // a step applied without on_applied()
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
  for (plmap::Index t : plan.old_triangles)  // a triangle made by a step applied unannounced was never indexed
    if (static_cast<std::size_t>(t) < index_->boxes.size()) index_->tree.remove(Entry{index_->boxes[static_cast<std::size_t>(t)], t});
  const plmap::Index first = plan.triangle_count_at_planning;
  const auto count = static_cast<plmap::Index>(plan.new_triangles.size());
  for (plmap::Index t = first; t < first + count; ++t) index_->tree.insert(index_->entry(map, t));
}

}  // namespace plmap
