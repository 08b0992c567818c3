#pragma once
// What the simplification tests check on a result, beyond verify(): each S2 vertex has exactly
// one preimage, the region images tile S2 by measure, and the features of S2 are kept.

#include <plmap/construct/simplify.hpp>
#include <plmap/verify/check.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <map>
#include <string>
#include <tuple>

namespace plmap::simplify_test {

/// S2 vertices whose preimage count (copies of one node count once) is not exactly one, as text.
inline std::string vertices_without_one_preimage(const PlMap<2>& map) {
  const MapData<2>& m = map.data();
  std::vector<std::vector<Eigen::Vector3d>> seen(map.target().vertex_count());
  for (Index n = 0; n < map.node_count(); ++n) {
    if (m.node_type[n] == NodeType::intersection || m.node_type[n] == NodeType::ghost) continue;
    const Eigen::Vector3d x = map.node_domain_world(n);
    auto& list = seen[m.node_target[n]];
    bool known = false;
    for (const auto& y : list) known = known || (x - y).norm() <= 1e-9 * map.domain().max_edge_length();
    if (!known) list.push_back(x);
  }
  std::string out;
  for (std::size_t v = 0; v < seen.size(); ++v)
    if (seen[v].size() != 1) out += " v" + std::to_string(v) + ":" + std::to_string(seen[v].size());
  return out;
}

/// Sum of the image areas of all regions.
inline double image_area(const PlMap<2>& map) {
  const MapData<2>& m = map.data();
  double total = 0.0;
  for (Index r = 0; r < map.region_count(); ++r) {
    const auto& c = m.region_corners[r];
    const Eigen::Vector3d a = map.node_target_world(c[0]), b = map.node_target_world(c[1]), d = map.node_target_world(c[2]);
    total += 0.5 * (b - a).cross(d - a).norm();
  }
  return total;
}

/// Distance from x to the segment [p, q].
inline double distance_to_segment(const Eigen::Vector3d& x, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = q - p;
  const double t = std::clamp((x - p).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (x - (p + t * d)).norm();
}

/// Features of S2 (by simplify's rule) that S1 lost, as text: a feature edge whose preimage does
/// not lie along one S1 edge (both end preimages on one S1 edge: the coarse feature lines are
/// chains of S1 edges that carry S2's feature edges), or a feature corner (a vertex on one or
/// more than two feature edges, or where its line turns by more than the feature angle) that is
/// not an S1 vertex.
inline std::string lost_features(const PlMap<2>& map, double feature_angle) {
  const Surface<2>& s1 = map.domain();
  const Surface<2>& s2 = map.target();
  const MapData<2>& m = map.data();
  // Per S2 vertex: its preimage in space, whether it is a corner node, and the S1 edges of the
  // elements its node copies belong to.
  std::vector<Eigen::Vector3d> preimage(s2.vertex_count(), Eigen::Vector3d::Constant(std::nan("")));
  std::vector<char> at_corner(s2.vertex_count(), 0);
  std::vector<std::vector<std::array<Index, 2>>> nearby_edges(s2.vertex_count());
  for (Index n = 0; n < map.node_count(); ++n) {
    if (m.node_type[n] == NodeType::intersection || m.node_type[n] == NodeType::ghost) continue;
    const Index w = m.node_target[n];
    preimage[w] = map.node_domain_world(n);
    at_corner[w] = at_corner[w] || m.node_type[n] == NodeType::corner;
    const auto& c = s1.element(map.node_element(n));
    for (int k = 0; k < 3; ++k) nearby_edges[w].push_back({c[k], c[(k + 1) % 3]});
  }
  const double tolerance = 1e-9 * s1.max_edge_length();
  const std::vector<char> feature = feature_edges(s2, feature_angle);
  std::vector<int> degree(s2.vertex_count(), 0);
  std::string out;
  for (Index e = 0; e < s2.edge_count(); ++e) {
    if (!feature[e]) continue;
    const auto ab = s2.edge_vertices(e);
    ++degree[ab[0]];
    ++degree[ab[1]];
    bool along = false;
    for (const auto& pq : nearby_edges[ab[0]])
      along = along || (distance_to_segment(preimage[ab[0]], s1.vertex(pq[0]), s1.vertex(pq[1])) <= tolerance &&
                        distance_to_segment(preimage[ab[1]], s1.vertex(pq[0]), s1.vertex(pq[1])) <= tolerance);
    if (!along) out += " edge" + std::to_string(e);
  }
  // Corners: not on exactly two feature edges, or the line turns by more than the angle there.
  std::vector<std::vector<Index>> line_neighbours(s2.vertex_count());
  for (Index e = 0; e < s2.edge_count(); ++e)
    if (feature[e]) {
      const auto ab = s2.edge_vertices(e);
      line_neighbours[ab[0]].push_back(ab[1]);
      line_neighbours[ab[1]].push_back(ab[0]);
    }
  const double cos_limit = std::cos(feature_angle * std::numbers::pi / 180.0);
  for (Index w = 0; w < s2.vertex_count(); ++w) {
    bool corner = degree[w] != 0 && degree[w] != 2;
    if (degree[w] == 2 && feature_angle < 180.0) {
      const Eigen::Vector3d in = (s2.vertex(w) - s2.vertex(line_neighbours[w][0])).normalized();
      const Eigen::Vector3d out = (s2.vertex(line_neighbours[w][1]) - s2.vertex(w)).normalized();
      corner = in.dot(out) < cos_limit;
    }
    if (corner && !at_corner[w]) out += " corner" + std::to_string(w);
  }
  return out;
}

/// The refusals that left the run's remaining vertices, as " reason:count" pairs (for messages).
inline std::string skipped_reasons(const SimplifyReport& r) {
  std::string out;
  for (const auto& [why, count] : r.skipped_by_reason) out += " " + why + ":" + std::to_string(count);
  return out;
}

/// What keeps a simplification's map from being a parametrization that keeps S2's features, as
/// text, empty if nothing does: verify() as a parametrization, S2 vertices without exactly one
/// preimage, region images that do not tile S2's measure (within area_tolerance of it,
/// relative), and features of S2 that S1 lost.
inline std::string parametrization_problems(const SimplifyResult& result, double feature_angle,
                                            double area_tolerance = 1e-9) {
  std::string out;
  VerifyOptions v;
  v.expect_parametrization = true;
  const VerificationReport report = verify(result.map, v);
  if (!report.ok()) out += " verify: " + summary(report);
  if (const std::string w = vertices_without_one_preimage(result.map); !w.empty()) out += " preimages:" + w;
  const double area = result.map.target().measure(), covered = image_area(result.map);
  if (std::abs(covered - area) > area_tolerance * area)
    out += " image area " + std::to_string(covered) + " of " + std::to_string(area);
  if (const std::string f = lost_features(result.map, feature_angle); !f.empty()) out += " lost features:" + f;
  return out;
}

}  // namespace plmap::simplify_test
