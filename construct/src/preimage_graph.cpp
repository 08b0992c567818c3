// PreimageGraph: extraction from a compact map and hand-over to MapBuilder (see the header).

#include "preimage_graph.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace plmap::smoothing {

namespace {

/// Parameter of a point on local edge k of element t, measured from the S1 edge's smaller vertex.
double edge_parameter(const Surface<2>& s, Index t, int k, const LocalPoint<2>& local) {
  const Barycentric<2> b = barycentric_from_local<2>(local);
  const double from = b(k), to = b((k + 1) % 3);
  const double along = to / (from + to);
  return s.local_edge_is_forward(t, k) ? along : 1.0 - along;
}

bool contains(std::span<const Index> list, Index x) { return std::find(list.begin(), list.end(), x) != list.end(); }

}  // namespace

std::optional<PreimageGraph> PreimageGraph::from_map(const PlMap<2>& map, std::string* why) {
  const MapData<2>& m = map.stored();
  const Surface<2>& s1 = map.domain();
  const Surface<2>& s2 = map.target();
  PreimageGraph g;
  g.orientation = m.orientation;
  g.vertex.assign(static_cast<std::size_t>(s2.vertex_count()), DomainPlace{});
  g.crossings.assign(static_cast<std::size_t>(s2.edge_count()), {});
  auto refuse = [why](std::string text) {
    if (why != nullptr) *why = std::move(text);
    return std::nullopt;
  };
  for (Index t = 0; t < s1.element_count(); ++t) {
    for (Index n = m.node_begin[t]; n < m.node_begin[t + 1]; ++n) {
      const int k = m.node_location[n];
      switch (m.node_type[n]) {
        case NodeType::rim_on_edge:
        case NodeType::rim_inside:
          return refuse(fmt::format("node {} lies on the rim of D inside S1 element {} (the map stops there)", n, t));
        case NodeType::ghost:
          return refuse(fmt::format("S1 vertex {} is a ghost node (not the preimage of an S2 vertex)", s1.element(t)[k]));
        case NodeType::corner:
          g.vertex[m.node_target[n]] = {DomainPlace::Kind::vertex, s1.element(t)[k], 0.0, LocalPoint<2>::Zero()};
          break;
        case NodeType::touching:
          g.vertex[m.node_target[n]] = {DomainPlace::Kind::edge, s1.element_edge(t, k),
                                        edge_parameter(s1, t, k, m.node_position[n]), LocalPoint<2>::Zero()};
          break;
        case NodeType::interior:
          g.vertex[m.node_target[n]] = {DomainPlace::Kind::element, t, 0.0, m.node_position[n]};
          break;
        case NodeType::intersection: {
          const Index domain_edge = s1.element_edge(t, k);
          if (s1.edge_elements(domain_edge).front().element != t) break;  // one copy per S1 edge
          const Index target_edge = m.node_target[n];
          const auto uw = s2.edge_vertices(target_edge);
          const SurfacePoint<2> image = m.node_image(n);
          const int ku = s2.local_corner(image.element, uw[0]), kw = s2.local_corner(image.element, uw[1]);
          if (ku < 0 || kw < 0)
            return refuse(fmt::format("node {} lies on S2 edge {} but its image is on an element without it", n, target_edge));
          const Barycentric<2> b = barycentric_from_local<2>(image.local);
          g.crossings[target_edge].push_back({domain_edge, edge_parameter(s1, t, k, m.node_position[n]), b(kw) / (b(ku) + b(kw))});
          break;
        }
      }
    }
  }
  for (Index v = 0; v < s2.vertex_count(); ++v)
    if (g.vertex[v].where == invalid_index) return refuse(fmt::format("S2 vertex {} has no preimage", v));
  for (auto& list : g.crossings)
    std::sort(list.begin(), list.end(),
              [](const EdgeCrossing& a, const EdgeCrossing& b) { return a.target_parameter < b.target_parameter; });
  return g;
}

MapBuilder<2> PreimageGraph::builder(const std::shared_ptr<const Surface<2>>& domain,
                                     const std::shared_ptr<const Surface<2>>& target) const {
  BuilderOptions options;
  options.orientation = orientation;
  MapBuilder<2> b(domain, target, options);
  for (Index v = 0; v < target->vertex_count(); ++v) {
    const DomainPlace& p = vertex[v];
    switch (p.kind) {
      case DomainPlace::Kind::vertex: b.add_vertex_preimage_at_vertex(v, p.where); break;
      case DomainPlace::Kind::edge: b.add_vertex_preimage_on_edge(v, p.where, p.edge_parameter); break;
      case DomainPlace::Kind::element: b.add_vertex_preimage(v, SurfacePoint<2>{p.where, p.local}); break;
    }
  }
  for (Index e = 0; e < target->edge_count(); ++e) {
    if (crossings[e].empty())
      b.add_edge(e);
    else
      b.add_edge(e, crossings[e]);
  }
  return b;
}

PlMap<2> PreimageGraph::to_map(const std::shared_ptr<const Surface<2>>& domain,
                               const std::shared_ptr<const Surface<2>>& target, FinalizeReport* report) const {
  return builder(domain, target).finalize(report);
}

PlMap<2> PreimageGraph::to_map_reusing(const std::shared_ptr<const Surface<2>>& domain,
                                       const std::shared_ptr<const Surface<2>>& target, const PlMap<2>& previous,
                                       std::span<const char> reuse, FinalizeReport* report) const {
  return builder(domain, target).finalize_reusing(previous, reuse, report);
}

DomainPlace polyline_point(const PreimageGraph& g, const Surface<2>& target, Index edge, std::size_t i) {
  const auto& c = g.crossings[edge];
  if (i == 0) return g.vertex[target.edge_vertices(edge)[0]];
  if (i == c.size() + 1) return g.vertex[target.edge_vertices(edge)[1]];
  return {DomainPlace::Kind::edge, c[i - 1].domain_edge, c[i - 1].domain_parameter, LocalPoint<2>::Zero()};
}

double polyline_target_parameter(const PreimageGraph& g, Index edge, std::size_t i) {
  const auto& c = g.crossings[edge];
  if (i == 0) return 0.0;
  if (i == c.size() + 1) return 1.0;
  return c[i - 1].target_parameter;
}

Index common_element(const Surface<2>& domain, const DomainPlace& a, const DomainPlace& b, bool* along_edge) {
  // Called for every segment of every polyline a quadrilateral step touches: no allocation.
  const auto holds = [&domain](const DomainPlace& p, Index t) {
    switch (p.kind) {
      case DomainPlace::Kind::vertex: return contains(domain.vertex_elements(p.where), t);
      case DomainPlace::Kind::edge:
        for (const EdgeIncidence& i : domain.edge_elements(p.where))
          if (i.element == t) return true;
        return false;
      case DomainPlace::Kind::element: return p.where == t;
    }
    return false;
  };
  Index found = invalid_index;
  int count = 0;
  const auto consider = [&](Index t) {
    if (holds(b, t)) found = t, ++count;
  };
  switch (a.kind) {
    case DomainPlace::Kind::vertex:
      for (Index t : domain.vertex_elements(a.where)) consider(t);
      break;
    case DomainPlace::Kind::edge:
      for (const EdgeIncidence& i : domain.edge_elements(a.where)) consider(i.element);
      break;
    case DomainPlace::Kind::element: consider(a.where); break;
  }
  if (along_edge != nullptr) *along_edge = count > 1;
  return count == 1 ? found : invalid_index;
}

}  // namespace plmap::smoothing
