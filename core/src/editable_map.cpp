// EditableMap: the identity start, the queries, apply() of a planned vertex removal, and the
// hand-over of the edited state to MapBuilder (which closes the elements and finalizes).
// Planning a removal lives in editable_map_removal*.cpp (removal_planning.hpp lists its phases).

#include "editable_map_state.hpp"

#include <plmap/core/errors.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace plmap {

const char* to_string(RemovalRefusal reason) {
  switch (reason) {
    case RemovalRefusal::none: return "none";
    case RemovalRefusal::not_a_disk_star: return "not_a_disk_star";
    case RemovalRefusal::flattening_not_simple: return "flattening_not_simple";
    case RemovalRefusal::no_triangulation: return "no_triangulation";
    case RemovalRefusal::existing_edge: return "existing_edge";
    case RemovalRefusal::degenerate_triangle: return "degenerate_triangle";
    case RemovalRefusal::fold_over: return "fold_over";
    case RemovalRefusal::node_on_new_edge: return "node_on_new_edge";
    case RemovalRefusal::edge_along_new_edge: return "edge_along_new_edge";
    case RemovalRefusal::crossing_edges: return "crossing_edges";
    case RemovalRefusal::single_triangle_side: return "single_triangle_side";
    case RemovalRefusal::edge_reenters_triangle: return "edge_reenters_triangle";
    case RemovalRefusal::straight_fold: return "straight_fold";
  }
  return "unknown";
}

EditableMap::EditableMap(std::shared_ptr<const Surface<2>> target, EditOptions options)
    : impl_(std::make_unique<Impl>()) {
  if (!target) throw Error("EditableMap: no target surface given");
  Impl& s = *impl_;
  s.target = std::move(target);
  s.options = options;
  const Surface<2>& t2 = *s.target;
  const Index nv = t2.vertex_count(), nt = t2.element_count(), ne = t2.edge_count();
  s.triangles = t2.elements();
  s.triangle_live.assign(nt, 1);
  s.vertex_live.assign(nv, 1);
  s.vertex_triangles.resize(nv);
  for (Index v = 0; v < nv; ++v) {
    auto span = t2.vertex_elements(v);
    s.vertex_triangles[v].assign(span.begin(), span.end());
  }
  s.live_vertices = nv;
  s.live_triangles = nt;
  s.preimage_triangle.assign(nv, invalid_index);
  s.preimage_barycentric.assign(nv, Eigen::Vector3d::Zero());
  s.preimage_edge.assign(nv, {invalid_index, invalid_index});
  s.preimage_edge_parameter.assign(nv, 0.0);
  s.triangle_vertices.add_slots(static_cast<std::size_t>(nt));
  s.triangle_edges.add_slots(static_cast<std::size_t>(nt));
  s.polylines.resize(ne);
  s.polyline_version.assign(ne, 0);
  // Each S2 edge starts in the first triangle around it: the triangles' lists of edges, sized first.
  {
    std::vector<std::size_t> edges_per_triangle(static_cast<std::size_t>(nt), 0);
    for (Index e = 0; e < ne; ++e) ++edges_per_triangle[static_cast<std::size_t>(t2.edge_elements(e).front().element)];
    s.list_sizes.clear();
    for (Index t = 0; t < nt; ++t)
      if (edges_per_triangle[static_cast<std::size_t>(t)] > 0) s.list_sizes.emplace_back(t, edges_per_triangle[static_cast<std::size_t>(t)]);
    s.triangle_edges.open(s.list_sizes);
  }
  for (Index e = 0; e < ne; ++e) {
    const auto ab = t2.edge_vertices(e);
    EdgePolyline& p = s.polylines[e];
    const Index t = t2.edge_elements(e).front().element;
    p.points.resize(2);
    p.points[0].vertex = ab[0];
    p.points[0].segment_triangle = t;
    p.points[1].vertex = ab[1];
    p.points[1].target_parameter = 1.0;
    s.triangle_edges.append(t, e);
  }
}

EditableMap::~EditableMap() = default;
EditableMap::EditableMap(EditableMap&&) noexcept = default;
EditableMap& EditableMap::operator=(EditableMap&&) noexcept = default;

const Surface<2>& EditableMap::target() const { return *impl_->target; }
const EditOptions& EditableMap::options() const { return impl_->options; }
Index EditableMap::live_vertex_count() const { return impl_->live_vertices; }
Index EditableMap::live_triangle_count() const { return impl_->live_triangles; }
bool EditableMap::is_live_vertex(Index v) const { return impl_->vertex_live[v] != 0; }
std::span<const Index> EditableMap::vertex_triangles(Index v) const { return impl_->vertex_triangles[v]; }
Index EditableMap::triangle_slot_count() const { return static_cast<Index>(impl_->triangles.size()); }
bool EditableMap::is_live_triangle(Index t) const { return impl_->triangle_live[t] != 0; }
const std::array<Index, 3>& EditableMap::triangle(Index t) const { return impl_->triangles[t]; }
bool EditableMap::has_edge(Index a, Index b) const { return impl_->has_edge(a, b); }
const Eigen::Vector3d& EditableMap::position(Index v) const { return impl_->target->vertex(v); }

double EditableMap::smallest_preimage_shape_ratio(const VertexRemovalPlan& plan) const {
  const Impl& s = *impl_;
  const Surface<2>& t2 = *s.target;
  // The plan's relocations by S2 vertex, for the lookups below (a late star relocates thousands).
  std::vector<std::pair<Index, std::size_t>> moved;
  moved.reserve(plan.relocations.size());
  for (std::size_t i = 0; i < plan.relocations.size(); ++i) moved.emplace_back(plan.relocations[i].target_vertex, i);
  std::sort(moved.begin(), moved.end());
  // Where the preimage of S2 vertex w lies in space: as the plan moves it, or as it is now.
  auto preimage = [&](Index w) -> Eigen::Vector3d {
    const auto at = std::lower_bound(moved.begin(), moved.end(), std::pair<Index, std::size_t>{w, 0});
    if (at != moved.end() && at->first == w) {
      const auto& r = plan.relocations[at->second];
      if (r.new_triangle < 0)
        return (1.0 - r.edge_parameter) * t2.vertex(plan.line_edge[0]) + r.edge_parameter * t2.vertex(plan.line_edge[1]);
      const auto& c = plan.new_triangles[static_cast<std::size_t>(r.new_triangle)];
      return r.barycentric(0) * t2.vertex(c[0]) + r.barycentric(1) * t2.vertex(c[1]) + r.barycentric(2) * t2.vertex(c[2]);
    }
    if (s.vertex_live[w]) return t2.vertex(w);
    if (s.on_edge(w)) {
      const auto e = s.preimage_edge[w];
      const double u = s.preimage_edge_parameter[w];
      return (1.0 - u) * t2.vertex(e[0]) + u * t2.vertex(e[1]);
    }
    const auto& c = s.triangles[s.preimage_triangle[w]];
    const Eigen::Vector3d& b = s.preimage_barycentric[w];
    return b(0) * t2.vertex(c[0]) + b(1) * t2.vertex(c[1]) + b(2) * t2.vertex(c[2]);
  };
  auto shape = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double sides = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    return sides > 0.0 ? 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / sides : 0.0;
  };
  double smallest = 1.0;
  for (const auto& r : plan.relocations)
    for (Index e : t2.vertex_elements(r.target_vertex)) {
      const auto& c = t2.element(e);
      const double own = shape(t2.vertex(c[0]), t2.vertex(c[1]), t2.vertex(c[2]));
      if (own <= 0.0) continue;
      smallest = std::min(smallest, shape(preimage(c[0]), preimage(c[1]), preimage(c[2])) / own);
    }
  return smallest;
}

std::vector<Index> EditableMap::closed_ring(Index v) const {
  const Impl& s = *impl_;
  const auto& star = s.vertex_triangles[v];
  if (star.size() < 3) return {};
  // Each star triangle (v, a, b), counter-clockwise, contributes the ring edge a -> b; the ring
  // is a closed fan when these edges form one cycle through all of them.
  std::vector<std::array<Index, 2>> next;
  next.reserve(star.size());
  for (Index t : star) {
    const auto& c = s.triangles[t];
    const int k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
    const Index a = c[(k + 1) % 3], b = c[(k + 2) % 3];
    for (const auto& n : next)
      if (n[0] == a || n[1] == b) return {};
    next.push_back({a, b});
  }
  std::vector<Index> ring;
  ring.reserve(star.size());
  Index current = next.front()[0];
  for (std::size_t step = 0; step < next.size(); ++step) {
    ring.push_back(current);
    Index following = invalid_index;
    for (const auto& n : next)
      if (n[0] == current) following = n[1];
    if (following == invalid_index) return {};
    current = following;
  }
  if (current != ring.front()) return {};
  return ring;
}

std::vector<StarSheet> EditableMap::line_star_sheets(Index v, Index a, Index b) const {
  const Impl& s = *impl_;
  // Each star triangle (v, x, y), counter-clockwise, contributes the ring arc x -> y. A sheet is
  // a chain of arcs from one line neighbour to the other; every other ring vertex must start
  // and end exactly one arc (the fan is manifold and consistently oriented there).
  std::vector<std::array<Index, 2>> arcs;
  for (Index t : s.vertex_triangles[v]) {
    const auto& c = s.triangles[t];
    const int k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
    arcs.push_back({c[(k + 1) % 3], c[(k + 2) % 3]});
  }
  auto is_end = [a, b](Index w) { return w == a || w == b; };
  std::vector<char> used(arcs.size(), 0);
  std::vector<StarSheet> sheets;
  for (std::size_t first = 0; first < arcs.size(); ++first) {
    if (used[first] || !is_end(arcs[first][0])) continue;
    used[first] = 1;
    StarSheet sheet{{arcs[first][0], arcs[first][1]}, false};
    while (!is_end(sheet.ring.back())) {
      std::size_t next = arcs.size();
      int starts = 0;
      for (std::size_t i = 0; i < arcs.size(); ++i)
        if (arcs[i][0] == sheet.ring.back()) {
          ++starts;
          next = i;
        }
      if (starts != 1 || used[next] || sheet.ring.size() > arcs.size()) return {};
      used[next] = 1;
      sheet.ring.push_back(arcs[next][1]);
    }
    if (sheet.ring.back() == sheet.ring.front()) return {};
    sheets.push_back(std::move(sheet));
  }
  for (char u : used)
    if (!u) return {};
  return sheets;
}

void EditableMap::apply(const VertexRemovalPlan& plan) {
  Impl& s = *impl_;
  if (!plan.accepted()) throw Error(fmt::format("EditableMap::apply: the removal of vertex {} was refused ({})",
                                                plan.vertex, to_string(plan.refusal)));
  if (plan.extent != PlanExtent::full)
    throw Error(fmt::format("EditableMap::apply: the plan for vertex {} is a ranking bound, not a full plan", plan.vertex));
  if (plan.triangle_count_at_planning != static_cast<Index>(s.triangles.size()) || !s.vertex_live[plan.vertex])
    throw Error(fmt::format("EditableMap::apply: the plan for vertex {} was made on another state", plan.vertex));

  for (Index t : plan.old_triangles) {
    s.triangle_live[t] = 0;
    for (Index c : s.triangles[t]) {
      auto& list = s.vertex_triangles[c];
      list.erase(std::remove(list.begin(), list.end(), t), list.end());
    }
    s.triangle_vertices.clear(t);
    s.triangle_edges.clear(t);
  }
  s.vertex_live[plan.vertex] = 0;
  s.vertex_triangles[plan.vertex].clear();
  --s.live_vertices;

  const Index base = static_cast<Index>(s.triangles.size());
  for (const auto& c : plan.new_triangles) {
    const Index t = static_cast<Index>(s.triangles.size());
    s.triangles.push_back(c);
    s.triangle_live.push_back(1);
    for (Index v : c) s.vertex_triangles[v].push_back(t);
  }
  {
    // Each new triangle's lists of vertex preimages and S2 edges get their ranges at once,
    // counted from the plan, and are filled below in the plan's order.
    const std::size_t count = plan.new_triangles.size();
    s.triangle_vertices.add_slots(count);
    s.triangle_edges.add_slots(count);
    s.list_sizes.assign(count, {0, 0});
    for (std::size_t n = 0; n < count; ++n) s.list_sizes[n].first = base + static_cast<Index>(n);
    for (const auto& r : plan.relocations)
      if (r.new_triangle >= 0) ++s.list_sizes[static_cast<std::size_t>(r.new_triangle)].second;
    s.triangle_vertices.open(s.list_sizes);
    for (auto& size : s.list_sizes) size.second = 0;
    for (const auto& edit : plan.polyline_edits)
      for (std::size_t i = 0; i + 1 < edit.points.size(); ++i)
        if (const Index t = edit.points[i].segment_triangle; t < 0) ++s.list_sizes[static_cast<std::size_t>(-t - 1)].second;
    s.triangle_edges.open(s.list_sizes);
  }
  s.live_triangles += static_cast<Index>(plan.new_triangles.size()) - static_cast<Index>(plan.old_triangles.size());

  if (plan.line_edge[0] != invalid_index) {
    // The nodes of the two removed line edges are among the relocations, onto the new edge.
    for (Index end : plan.line_edge) s.edge_vertices.erase(Impl::edge_key(sorted_pair(plan.vertex, end)));
  }
  for (const auto& r : plan.relocations) {
    const Index w = r.target_vertex;
    if (r.new_triangle >= 0) {
      const Index t = base + r.new_triangle;
      s.preimage_triangle[w] = t;
      s.preimage_barycentric[w] = r.barycentric;
      s.preimage_edge[w] = {invalid_index, invalid_index};
      s.triangle_vertices.append(t, w);
    } else {
      s.preimage_triangle[w] = invalid_index;
      s.preimage_edge[w] = plan.line_edge;
      s.preimage_edge_parameter[w] = r.edge_parameter;
      s.edge_vertices[Impl::edge_key(plan.line_edge)].push_back(w);
    }
  }
  // As when the plan read them (cut_polylines), the polylines written here are asked for a few
  // edits ahead: their entries and points have mostly left the cache since.
  constexpr std::size_t entry_ahead = 8, points_ahead = 4;
  const auto& edits = plan.polyline_edits;
  for (std::size_t k = 0; k < edits.size(); ++k) {
    if (k + entry_ahead < edits.size()) __builtin_prefetch(&s.polylines[edits[k + entry_ahead].target_edge]);
    if (k + points_ahead < edits.size()) __builtin_prefetch(s.polylines[edits[k + points_ahead].target_edge].points.data(), 1);
    const auto& edit = edits[k];
    EdgePolyline& p = s.polylines[edit.target_edge];
    ++s.polyline_version[edit.target_edge];
    // A polyline gains points as S1 coarsens: its array grows by half at least, not by the few
    // points of one step (a copy into a too small vector allocates exactly its size).
    if (p.points.capacity() < edit.points.size())
      p.points.reserve(std::max(edit.points.size(), p.points.capacity() * 3 / 2));
    p.points = edit.points;
    for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
      Index& t = p.points[i].segment_triangle;
      if (t < 0) {
        t = base + (-t - 1);
        s.triangle_edges.append(t, edit.target_edge);
      }
    }
  }
}

bool EditableMap::refresh_plan(VertexRemovalPlan& plan) const {
  const Impl& s = *impl_;
  if (!plan.accepted() || plan.extent != PlanExtent::full || plan.line_edge[0] != invalid_index) return false;
  const Index v = plan.vertex;
  if (v < 0 || v >= static_cast<Index>(s.vertex_live.size()) || !s.vertex_live[v]) return false;
  // The same star: its triangles never change while alive, so all alive and no other around v.
  if (s.vertex_triangles[v].size() != plan.old_triangles.size()) return false;
  for (Index t : plan.old_triangles)
    if (!s.triangle_live[t]) return false;
  for (const auto& edit : plan.polyline_edits)
    if (s.polyline_version[edit.target_edge] != edit.version_at_planning) return false;
  // New edges and the single new triangle of a three-vertex hole must still be new.
  const std::vector<Index>& ring = plan.ring;
  const std::size_t k = ring.size();
  auto ring_side = [&](Index a, Index b) {
    for (std::size_t i = 0; i < k; ++i)
      if ((ring[i] == a && ring[(i + 1) % k] == b) || (ring[i] == b && ring[(i + 1) % k] == a)) return true;
    return false;
  };
  for (const auto& c : plan.new_triangles)
    for (int m = 0; m < 3; ++m)
      if (!ring_side(c[m], c[(m + 1) % 3]) && s.has_edge(c[m], c[(m + 1) % 3])) return false;
  if (k == 3) {
    auto n = plan.new_triangles.front();
    std::sort(n.begin(), n.end());
    for (Index t : s.vertex_triangles[ring[0]]) {
      if (std::find(plan.old_triangles.begin(), plan.old_triangles.end(), t) != plan.old_triangles.end()) continue;
      auto c = s.triangles[t];
      std::sort(c.begin(), c.end());
      if (c == n) return false;
    }
  }
  plan.triangle_count_at_planning = static_cast<Index>(s.triangles.size());
  return true;
}

Surface<2> EditableMap::domain_surface(std::vector<Index>* domain_to_target_vertex) const {
  const Impl& s = *impl_;
  std::vector<Index> renumber(s.vertex_live.size(), invalid_index);
  std::vector<WorldPoint<2>> vertices;
  std::vector<Index> back;
  for (std::size_t v = 0; v < s.vertex_live.size(); ++v)
    if (s.vertex_live[v]) {
      renumber[v] = static_cast<Index>(vertices.size());
      vertices.push_back(s.target->vertex(static_cast<Index>(v)));
      back.push_back(static_cast<Index>(v));
    }
  std::vector<ElementCorners<2>> elements;
  elements.reserve(s.live_triangles);
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    if (s.triangle_live[t]) {
      const auto& c = s.triangles[t];
      elements.push_back({renumber[c[0]], renumber[c[1]], renumber[c[2]]});
    }
  if (domain_to_target_vertex) *domain_to_target_vertex = std::move(back);
  return Surface<2>(std::move(vertices), std::move(elements));
}

PlMap<2> EditableMap::to_map(BuilderOptions options) const {
  const Impl& s = *impl_;
  // With the deferred cut the polylines were never cut: every S2 edge is traced now.
  const std::vector<std::vector<TracedCrossing>> traced = s.options.defer_cut ? Trace::run(s) : std::vector<std::vector<TracedCrossing>>{};
  std::vector<Index> domain_to_target;
  auto domain = std::make_shared<const Surface<2>>(domain_surface(&domain_to_target));
  std::vector<Index> vertex_number(s.vertex_live.size(), invalid_index);
  for (std::size_t i = 0; i < domain_to_target.size(); ++i) vertex_number[domain_to_target[i]] = static_cast<Index>(i);
  std::vector<Index> triangle_number(s.triangles.size(), invalid_index);
  Index next = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    if (s.triangle_live[t]) triangle_number[t] = next++;

  if (options.orientation == 0) options.orientation = 1;  // S1 starts as S2 with its orientation
  MapBuilder<2> builder(domain, s.target, options);
  const Surface<2>& t2 = *s.target;
  for (Index w = 0; w < t2.vertex_count(); ++w) {
    if (s.vertex_live[w]) {
      builder.add_vertex_preimage_at_vertex(w, vertex_number[w]);
    } else if (s.on_edge(w)) {
      // Renumbering keeps the order of vertices, so the parameter's direction stays.
      const Index edge = domain->find_edge(vertex_number[s.preimage_edge[w][0]], vertex_number[s.preimage_edge[w][1]]);
      if (edge == invalid_index)
        throw InvalidMapError(fmt::format("EditableMap: the preimage of S2 vertex {} lies on S1 vertices {} and {}, which share no edge",
                                          w, s.preimage_edge[w][0], s.preimage_edge[w][1]));
      builder.add_vertex_preimage_on_edge(w, edge, s.preimage_edge_parameter[w]);
    } else {
      const Eigen::Vector3d& b = s.preimage_barycentric[w];
      builder.add_vertex_preimage(w, {triangle_number[s.preimage_triangle[w]], LocalPoint<2>(b(1), b(2))});
    }
  }
  std::vector<EdgeCrossing> crossings;
  auto add_crossing = [&](Index e, std::array<Index, 2> s1_edge, double edge_parameter, double target_parameter) {
    const Index edge = domain->find_edge(vertex_number[s1_edge[0]], vertex_number[s1_edge[1]]);
    if (edge == invalid_index)
      throw InvalidMapError(fmt::format("EditableMap: S2 edge {} crosses S1 vertices {} and {}, which share no edge", e,
                                        s1_edge[0], s1_edge[1]));
    crossings.push_back({edge, edge_parameter, target_parameter});
  };
  for (Index e = 0; e < t2.edge_count(); ++e) {
    crossings.clear();
    if (!traced.empty()) {
      for (const TracedCrossing& c : traced[e]) add_crossing(e, c.edge, c.edge_parameter, c.target_parameter);
    } else {
      const std::vector<PolylinePoint>& points = s.polylines[e].points;
      for (std::size_t i = 1; i + 1 < points.size(); ++i)
        add_crossing(e, points[i].edge, points[i].edge_parameter, points[i].target_parameter);
    }
    if (crossings.empty())
      builder.add_edge(e);
    else
      builder.add_edge(e, crossings);
  }
  if (!s.options.defer_cut) return std::move(builder).finalize();
  // The traced graph passed the trace's checks (no crossings, S2's rotation order); the builder
  // and the tiling of S2 by the region images confirm it, else the caller falls back.
  PlMap<2> map = [&] {
    try {
      return std::move(builder).finalize();
    } catch (const Error& e) {
      throw DeferredCutFailure(fmt::format("deferred cut: the builder refused the traced graph: {}", e.what()));
    }
  }();
  const MapData<2>& m = map.stored();  // region corners are stored: no graph is derived
  double image_area = 0.0;
  for (Index r = 0; r < map.region_count(); ++r) {
    const auto& c = m.region_corners[r];
    const Eigen::Vector3d a = map.node_target_world(c[0]), b = map.node_target_world(c[1]), d = map.node_target_world(c[2]);
    image_area += 0.5 * (b - a).cross(d - a).norm();
  }
  if (!(std::abs(image_area - t2.measure()) <= 1e-8 * t2.measure()))
    throw DeferredCutFailure(fmt::format("deferred cut: the region images cover {} of S2's area {}", image_area, t2.measure()));
  return map;
}

}  // namespace plmap
