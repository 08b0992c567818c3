#pragma once
// What the simplification tests check on a result, beyond verify(): each S2 vertex has exactly
// one preimage, the region images tile S2 by measure, and the feature edges of S2 are S1 edges.

#include <plmap/construct/simplify.hpp>

#include <Eigen/Geometry>

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

/// Feature edges of S2 (by simplify's rule) that are not S1 edges, as text.
inline std::string lost_feature_edges(const PlMap<2>& map, double feature_angle) {
  const Surface<2>& s1 = map.domain();
  const Surface<2>& s2 = map.target();
  std::map<std::tuple<double, double, double>, Index> by_position;
  for (Index v = 0; v < s1.vertex_count(); ++v) by_position[{s1.vertex(v)(0), s1.vertex(v)(1), s1.vertex(v)(2)}] = v;
  auto s1_vertex = [&](Index w) {
    const auto it = by_position.find({s2.vertex(w)(0), s2.vertex(w)(1), s2.vertex(w)(2)});
    return it == by_position.end() ? invalid_index : it->second;
  };
  const std::vector<char> feature = feature_edges(s2, feature_angle);
  std::string out;
  for (Index e = 0; e < s2.edge_count(); ++e) {
    if (!feature[e]) continue;
    const auto ab = s2.edge_vertices(e);
    const Index a = s1_vertex(ab[0]), b = s1_vertex(ab[1]);
    if (a == invalid_index || b == invalid_index || s1.find_edge(a, b) == invalid_index) out += " e" + std::to_string(e);
  }
  return out;
}

}  // namespace plmap::simplify_test
