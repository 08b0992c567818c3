// The facts `plmap info` and Python's Map.info() report (plmap/verify/facts_json.hpp).

#include <plmap/verify/facts_json.hpp>

#include <plmap/core/regions.hpp>
#include <plmap/verify/quality.hpp>
#include <plmap/verify/report_json.hpp>

#include <algorithm>
#include <numeric>
#include <vector>

namespace plmap {

namespace {

using Json = nlohmann::ordered_json;

/// JSON array of a fixed-size Eigen vector.
template <class Vector>
Json json_vector(const Vector& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i));
  return a;
}

/// Number of edge-connected fans of triangles around vertex v (d = 2). A manifold vertex has
/// exactly one; two sheets touching at a vertex give two.
int fan_count(const Surface<2>& s, Index v) {
  const auto star = s.vertex_elements(v);
  std::vector<int> parent(star.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto star_index = [&](Index t) {
    return static_cast<int>(std::lower_bound(star.begin(), star.end(), t) - star.begin());
  };
  for (std::size_t i = 0; i < star.size(); ++i) {
    const Index t = star[i];
    const int c = s.local_corner(t, v);
    // The two local edges of t that end at v: k = c (c -> c+1) and k = c-1 (c-1 -> c).
    for (const int k : {c, (c + 2) % 3})
      for (const EdgeIncidence& inc : s.edge_elements(s.element_edge(t, k)))
        parent[find(static_cast<int>(i))] = find(star_index(inc.element));
  }
  int fans = 0;
  for (std::size_t i = 0; i < star.size(); ++i) fans += find(static_cast<int>(i)) == static_cast<int>(i);
  return fans;
}

}  // namespace

template <int d>
Index coincident_vertex_count(const Surface<d>& s) {
  std::vector<WorldPoint<d>> points(static_cast<std::size_t>(s.vertex_count()));
  for (Index v = 0; v < s.vertex_count(); ++v) points[static_cast<std::size_t>(v)] = s.vertex(v);
  std::sort(points.begin(), points.end(), [](const WorldPoint<d>& a, const WorldPoint<d>& b) {
    return std::lexicographical_compare(a.data(), a.data() + a.size(), b.data(), b.data() + b.size());
  });
  Index coincident = 0;
  for (std::size_t i = 1; i < points.size(); ++i) coincident += points[i] == points[i - 1];
  return coincident;
}

template <int d>
Json surface_facts_json(const Surface<d>& s) {
  Json j;
  j["dimension"] = d;
  j["vertices"] = s.vertex_count();
  j["elements"] = s.element_count();
  j["edges"] = s.edge_count();
  j["measure"] = s.measure();
  j["max_edge_length"] = s.max_edge_length();
  j["bounding_box"] = {{"min", json_vector(s.bounding_box_min())},
                       {"max", json_vector(s.bounding_box_max())}};
  Index isolated = 0, boundary_vertices = 0, non_manifold_vertices = 0;
  for (Index v = 0; v < s.vertex_count(); ++v) {
    const auto star = s.vertex_elements(v);
    if (star.empty()) {
      ++isolated;
      continue;
    }
    if (s.is_boundary_vertex(v)) ++boundary_vertices;
    if constexpr (d == 1) {
      if (star.size() > 2) ++non_manifold_vertices;
    } else {
      if (fan_count(s, v) > 1) ++non_manifold_vertices;
    }
  }
  j["isolated_vertices"] = isolated;
  j["boundary_vertices"] = boundary_vertices;
  j["non_manifold_vertices"] = non_manifold_vertices;
  j["coincident_vertices"] = coincident_vertex_count(s);
  if constexpr (d == 2) {
    Index boundary_edges = 0, non_manifold_edges = 0;
    for (Index e = 0; e < s.edge_count(); ++e) {
      const std::size_t n = s.edge_elements(e).size();
      boundary_edges += n == 1;
      non_manifold_edges += n > 2;
    }
    j["boundary_edges"] = boundary_edges;
    j["non_manifold_edges"] = non_manifold_edges;
  }
  return j;
}

template <int d>
Json map_facts_json(const PlMap<d>& map, bool with_quality) {
  Json j;
  j["dimension"] = d;
  j["orientation"] = map.stored().orientation;
  j["domain"] = surface_facts_json(map.domain());
  j["target"] = surface_facts_json(map.target());
  Json by_type;
  std::array<Index, node_type_count> counts{};
  for (const NodeType t : map.stored().node_type) ++counts[static_cast<std::size_t>(t)];
  for (int t = 0; t < node_type_count; ++t)
    by_type[std::string(to_string(static_cast<NodeType>(t)))] = counts[static_cast<std::size_t>(t)];
  j["nodes"] = {{"total", map.node_count()}, {"by_type", by_type}};
  j["regions"] = map.region_count();
  const CoveredMeasure covered = covered_measure(map);
  const double s1 = map.domain().measure(), s2 = map.target().measure();
  j["coverage"] = {{"domain_measure", covered.domain},
                   {"target_measure", covered.target},
                   {"domain_fraction", s1 > 0 ? covered.domain / s1 : 0.0},
                   {"target_fraction", s2 > 0 ? covered.target / s2 : 0.0}};
  j["memory_bytes"] = map.memory_bytes();
  // how the map was made (the projection's acceptance rules, for one), when its maker recorded it
  if (!map.provenance().empty()) j["provenance"] = map.provenance();
  if (with_quality) j["quality"] = to_json(compute_quality(map));
  return j;
}

template Index coincident_vertex_count<1>(const Surface<1>&);
template Index coincident_vertex_count<2>(const Surface<2>&);
template Json surface_facts_json<1>(const Surface<1>&);
template Json surface_facts_json<2>(const Surface<2>&);
template Json map_facts_json<1>(const PlMap<1>&, bool);
template Json map_facts_json<2>(const PlMap<2>&, bool);

}  // namespace plmap
