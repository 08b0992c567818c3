// clip_regions (region_clipping.hpp): regions cut along lines, the part beyond leaving D.
//
// The map's stored arrays are rebuilt once: the elements that change (those of the clipped
// regions, and those across an S1 edge where a cut ends on it) are re-made from their old nodes,
// regions and graph (stored, or derived from their regions: element_graph.hpp) plus the new
// nodes; every other element is copied with its indices shifted. Nothing is derived for the
// unchanged elements: a changed element keeps its new graph in the stored graph where its
// regions do not give it back, the other elements keep what they stored. The phases: the cuts
// planned per element (plan_cuts), the changed elements made (make_element, on all threads), and
// the arrays rewritten with them (region_clipping_rewrite.cpp).

#include <plmap/core/errors.hpp>
#include <plmap/core/freed_heap.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/region_clipping.hpp>

#include "element_graph.hpp"
#include "region_clipping_rewrite.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

namespace plmap {

using detail::MadeElement;

namespace {

/// A cut closer than this (as a fraction of the side) to a corner passes through the corner.
constexpr double corner_snap = 1e-6;
/// Two cuts of one side closer than this (fraction of the side) share their node.
constexpr double same_point = 1e-9;
/// An image within this of an S2 edge (in barycentric coordinates) is put on it.
constexpr double on_target_edge = 1e-9;

using Side = std::pair<Index, Index>;  // old node indices of one element, smaller first

Side side_of(Index a, Index b) { return a < b ? Side{a, b} : Side{b, a}; }

/// A node the cuts add to one element.
struct NewNode {
  Side side;       // the old side it lies on
  double s = 0.0;  // from side.first to side.second
  LocalPoint<2> position = LocalPoint<2>::Zero();
  SurfacePoint<2> image;
  Index target = invalid_index;  // the S2 edge its image lies on, if the side is the preimage of one
  std::int8_t location = -1;     // local edge of the element (a rim_on_edge node), or -1 inside
};

/// What happens to one clipped region.
struct Cut {
  std::array<double, 3> f{};            // the line's value at the corners (after snapping)
  std::array<int, 3> own{-1, -1, -1};   // the new node where the line crosses side i (corner i to i+1)
  bool removed = false;
};

/// The changes to one element.
struct ElementEdit {
  std::vector<NewNode> nodes;
  std::map<Side, std::vector<int>> on_side;  // new nodes per old side
  std::map<Index, Cut> cuts;                 // per clipped region

  /// The node at parameter s of `side` (from side.first), made if none is that close.
  int node_at(const Side& side, double s, const NewNode& made) {
    auto& list = on_side[side];
    for (int i : list)
      if (std::abs(nodes[static_cast<std::size_t>(i)].s - s) <= same_point) return i;
    nodes.push_back(made);
    nodes.back().side = side;
    nodes.back().s = s;
    list.push_back(static_cast<int>(nodes.size()) - 1);
    return list.back();
  }
};

/// Bit k set when old node n lies on local edge k of its element.
std::uint8_t element_edges_through(const MapData<2>& m, Index n) {
  const int k = m.node_location[n];
  if (is_at_corner(m.node_type[n])) return static_cast<std::uint8_t>((1u << k) | (1u << ((k + 2) % 3)));
  if (is_on_edge(m.node_type[n])) return static_cast<std::uint8_t>(1u << k);
  return 0;
}

/// The local edge both nodes lie on, or -1.
int common_local_edge(const MapData<2>& m, Index a, Index b) {
  const std::uint8_t both = element_edges_through(m, a) & element_edges_through(m, b);
  for (int k = 0; k < 3; ++k)
    if (both & (1u << k)) return k;
  return -1;
}

/// An element's graph before the cuts, with where each node's list starts.
struct OldGraph {
  detail::ElementGraph graph;
  std::vector<Index> begin;  // per node of the element + 1
  Index first_node = 0;

  /// The kind of the graph edge a-b (nodes of this element), if it is one.
  std::optional<GraphEdgeKind> kind(Index a, Index b) const {
    const Index e = graph.entry(begin, a - first_node, b);
    if (e == invalid_index) return std::nullopt;
    return graph.kind[static_cast<std::size_t>(e)];
  }
  /// The nodes on local edge k, from corner k to corner k + 1.
  std::span<const Index> edge_nodes(int k) const {
    std::size_t at = 0;
    for (int i = 0; i < k; ++i) at += static_cast<std::size_t>(graph.edge_node_count[static_cast<std::size_t>(i)]);
    return {graph.edge_node.data() + at, static_cast<std::size_t>(graph.edge_node_count[static_cast<std::size_t>(k)])};
  }
};

/// The old graph of an element the cuts change, taken when it is re-made (not kept: on the
/// femur pair all of them at once were half a MiB of the projection's peak).
class OldGraphs {
 public:
  explicit OldGraphs(const PlMap<2>& map) : map_(map), offsets_(map.stored(), map.stored_graph()) {}

  OldGraph of(Index t) {
    OldGraph g;
    const std::ptrdiff_t kept = detail::StoredGraphOffsets::find(map_.stored_graph(), t);
    if (kept >= 0) {
      g.graph = detail::stored_element_graph(map_.stored_graph(), offsets_, static_cast<std::size_t>(kept));
    } else if (std::optional<detail::ElementGraph> derived = detail::derived_element_graph(map_.stored(), map_.target(), t, scratch_)) {
      g.graph = std::move(*derived);
    } else {
      throw InvalidMapError(fmt::format("clip_regions: the regions of element {} do not give its graph", t));
    }
    g.begin = detail::list_begins(g.graph);
    g.first_node = map_.nodes_begin(t);
    return g;
  }

 private:
  const PlMap<2>& map_;
  detail::StoredGraphOffsets offsets_;
  detail::GraphDerivationScratch scratch_;
};

/// Barycentric coordinate i of a local point of a triangle: (1 - x - y, x, y).
double barycentric(const LocalPoint<2>& y, int i) { return i == 0 ? 1.0 - y.x() - y.y() : y(i - 1); }

/// The local point with barycentric coordinate i set to zero exactly (the others rescaled).
LocalPoint<2> onto_edge_opposite(const LocalPoint<2>& y, int i) {
  if (i == 1) return {0.0, y.y()};
  if (i == 2) return {y.x(), 0.0};
  const double sum = y.x() + y.y();
  return sum > 0.0 ? LocalPoint<2>(y.x() / sum, y.y() / sum) : LocalPoint<2>(0.5, 0.5);
}

/// The image of a point of side a-b of region r (corners' images by the region's affine map):
/// on the S2 edge that both ends' images lie on, if they lie on one (the side is then the
/// preimage of a piece of it, and the new node splits that piece).
void image_on_side(const PlMap<2>& map, Index r, Index a, Index b, NewNode& node) {
  const MapData<2>& m = map.stored();
  const Index t2 = m.region_target[r];
  LocalPoint<2> y = apply<2>(m.region_map[r], node.position);
  {
    const LocalPoint<2> ya = apply<2>(m.region_map[r], m.node_position[a]);
    const LocalPoint<2> yb = apply<2>(m.region_map[r], m.node_position[b]);
    for (int i = 0; i < 3; ++i)
      if (std::abs(barycentric(ya, i)) <= on_target_edge && std::abs(barycentric(yb, i)) <= on_target_edge) {
        y = onto_edge_opposite(y, i);
        // barycentric coordinate i vanishes on the local edge joining corners i + 1 and i + 2,
        // which is local edge (i + 1) mod 3
        node.target = map.target().element_edge(t2, (i + 1) % 3);
        break;
      }
  }
  node.image = {t2, y};
}

/// Parameter along local edge k of the reference triangle, from corner k to corner k + 1.
double along_local_edge(const LocalPoint<2>& p, int k) { return k == 0 ? p.x() : (k == 1 ? p.y() : 1.0 - p.y()); }

/// The copies, in element `other`, of the nodes a and b of element t that lie on the S1 edge
/// they share with it (matched by world position), or nothing.
std::optional<Side> copies_in(const PlMap<2>& map, Index t, Index a, Index b, Index other, int other_edge) {
  const Surface<2>& s1 = map.domain();
  const MapData<2>& m = map.stored();
  const WorldPoint<2> wa = s1.world_position(t, m.node_position[a]), wb = s1.world_position(t, m.node_position[b]);
  const double tolerance = 1e-9 * (wb - wa).norm() + 1e-300;
  Index ca = invalid_index, cb = invalid_index;
  for (Index n = map.nodes_begin(other); n < map.nodes_end(other); ++n) {
    const int k = m.node_location[n];
    const bool on_edge = is_at_corner(m.node_type[n]) ? (k == other_edge || k == (other_edge + 1) % 3)
                                                       : is_on_edge(m.node_type[n]) && k == other_edge;
    if (!on_edge) continue;
    const WorldPoint<2> w = s1.world_position(other, m.node_position[n]);
    if ((w - wa).norm() <= tolerance) ca = n;
    if ((w - wb).norm() <= tolerance) cb = n;
  }
  if (ca == invalid_index || cb == invalid_index || ca == cb) return std::nullopt;
  return Side{ca, cb};  // in the order of a, b
}

/// The polygon of old region r of element edit e: its corners, with the new nodes on its sides
/// in between. Entries >= 0 are old node indices; new node i is -(i + 1).
std::vector<Index> polygon_of(const MapData<2>& m, Index r, const ElementEdit& e) {
  std::vector<Index> polygon;
  const auto& c = m.region_corners[r];
  for (int i = 0; i < 3; ++i) {
    polygon.push_back(c[i]);
    const Side side = side_of(c[i], c[(i + 1) % 3]);
    const auto found = e.on_side.find(side);
    if (found == e.on_side.end()) continue;
    std::vector<int> list = found->second;
    const bool forward = side.first == c[i];
    std::sort(list.begin(), list.end(), [&](int x, int y) {
      const double sx = e.nodes[static_cast<std::size_t>(x)].s, sy = e.nodes[static_cast<std::size_t>(y)].s;
      return forward ? sx < sy : sx > sy;
    });
    for (int i_new : list) polygon.push_back(-(i_new + 1));
  }
  return polygon;
}

/// The cuts: where each line crosses its region's sides (new nodes per element, made once per
/// point of a side), their copies in the elements across S1 edges, and what becomes of each
/// named region. Counts clipped and removed regions in `rep`.
std::map<Index, ElementEdit> plan_cuts(const PlMap<2>& map, std::span<const RegionClip> clips, RegionClipReport& rep) {
  const Surface<2>& s1 = map.domain();
  const MapData<2>& m = map.stored();
  const Index nr = map.region_count();
  std::map<Index, ElementEdit> edits;
  {
    std::vector<char> named(static_cast<std::size_t>(nr), 0);
    for (const RegionClip& clip : clips) {
      if (clip.region < 0 || clip.region >= nr)
        throw InvalidMapError(fmt::format("clip_regions: region {} does not exist (the map has {})", clip.region, nr));
      if (named[static_cast<std::size_t>(clip.region)]++)
        throw InvalidMapError(fmt::format("clip_regions: region {} is named twice", clip.region));
      if (!(clip.normal.norm() > 0.0) || !std::isfinite(clip.offset))
        throw InvalidMapError(fmt::format("clip_regions: the line of region {} has no direction", clip.region));
    }
  }
  for (const RegionClip& clip : clips) {
    const Index r = clip.region;
    const auto& c = m.region_corners[r];
    const Index t = map.node_element(c[0]);
    Cut cut;
    for (int i = 0; i < 3; ++i) cut.f[i] = clip.normal.dot(m.node_position[c[i]]) + clip.offset;
    // a crossing next to a corner passes through it
    for (int i = 0; i < 3; ++i) {
      double& fa = cut.f[i];
      double& fb = cut.f[(i + 1) % 3];
      if (!(fa * fb < 0.0)) continue;
      const double s = fa / (fa - fb);
      if (s < corner_snap) fa = 0.0;
      else if (s > 1.0 - corner_snap) fb = 0.0;
    }
    const bool kept = std::any_of(cut.f.begin(), cut.f.end(), [](double f) { return f > 0.0; });
    const bool beyond = std::any_of(cut.f.begin(), cut.f.end(), [](double f) { return f < 0.0; });
    if (!beyond) continue;  // nothing leaves
    ElementEdit& edit = edits[t];
    if (!kept) {
      cut.removed = true;
      edit.cuts[r] = cut;
      ++rep.removed_regions;
      continue;
    }
    // The crossings, and where one lies on the element's boundary, the copies of its side's
    // ends in the elements across (found first: a cut whose copies are missing is not made,
    // and the region leaves whole).
    struct Crossing {
      int side;
      double s;  // from corner side to corner side + 1
      int local_edge;
      std::vector<std::pair<Index, Side>> copies;  // element across, the side's ends there
    };
    std::vector<Crossing> crossings;
    bool copies_found = true;
    for (int i = 0; i < 3; ++i) {
      const double fa = cut.f[i], fb = cut.f[(i + 1) % 3];
      if (!(fa * fb < 0.0)) continue;
      Crossing x{i, fa / (fa - fb), common_local_edge(m, c[i], c[(i + 1) % 3]), {}};
      if (x.local_edge >= 0) {
        const Index e = s1.element_edge(t, x.local_edge);
        for (const EdgeIncidence& inc : s1.edge_elements(e)) {
          if (inc.element == t) continue;
          const std::optional<Side> there = copies_in(map, t, c[i], c[(i + 1) % 3], inc.element, inc.local_edge);
          if (!there) {
            copies_found = false;
            break;
          }
          x.copies.emplace_back(inc.element, *there);
        }
      }
      crossings.push_back(std::move(x));
    }
    if (!copies_found || crossings.size() != 2) {
      cut.removed = true;
      edit.cuts[r] = cut;
      ++rep.removed_regions;
      continue;
    }
    for (const Crossing& x : crossings) {
      const Index a = c[x.side], b = c[(x.side + 1) % 3];
      const Side side = side_of(a, b);
      const double s = side.first == a ? x.s : 1.0 - x.s;
      NewNode made;
      made.position = m.node_position[side.first] + s * (m.node_position[side.second] - m.node_position[side.first]);
      made.location = static_cast<std::int8_t>(x.local_edge);
      image_on_side(map, r, a, b, made);
      const int own = edit.node_at(side, s, made);
      cut.own[x.side] = own;
      const NewNode& here = edit.nodes[static_cast<std::size_t>(own)];
      for (const auto& [other, ends] : x.copies) {
        // ends are the copies of a and b, in that order
        const Side there = side_of(ends.first, ends.second);
        const double s_there = there.first == ends.first ? x.s : 1.0 - x.s;
        NewNode copy = here;
        copy.position =
            m.node_position[there.first] + s_there * (m.node_position[there.second] - m.node_position[there.first]);
        copy.location = -1;
        for (int k = 0; k < 3; ++k)
          if (s1.element_edge(other, k) == s1.element_edge(t, x.local_edge)) copy.location = static_cast<std::int8_t>(k);
        edits[other].node_at(there, s_there, copy);
      }
    }
    edit.cuts[r] = cut;
    ++rep.clipped_regions;
  }

  return edits;
}

/// The graph edges of an element being re-made (element-local node indices, smaller first), with
/// the sides of its new regions and of its old ones (old node indices).
struct MadeEdges {
  std::map<Side, GraphEdgeKind> kind;
  std::map<Side, char> region_sides;
  std::map<Side, char> old_region_sides;
};

/// The nodes of element t re-made: its old nodes, then the cuts' new ones.
void gather_nodes(const PlMap<2>& map, Index t, const ElementEdit& edit, MadeElement& out) {
  const MapData<2>& m = map.stored();
  out.old_nodes = map.nodes_end(t) - map.nodes_begin(t);
  for (Index n = map.nodes_begin(t); n < map.nodes_end(t); ++n) {
    out.position.push_back(m.node_position[n]);
    out.type.push_back(m.node_type[n]);
    out.location.push_back(m.node_location[n]);
  }
  for (const NewNode& node : edit.nodes) {
    out.position.push_back(node.position);
    out.type.push_back(node.location >= 0 ? NodeType::rim_on_edge : NodeType::rim_inside);
    out.location.push_back(node.location);
    out.image.push_back(node.image);
    out.target.push_back(node.target);
  }
}

/// What region r's polygon (its vertices as polygon_of gives them, `kinds` the kind of the side
/// that starts at each) keeps of itself on the kept side of its cut: corners with f >= 0, the
/// line's own nodes, and the nodes of other cuts on the kept part of the sides; the side between
/// the own nodes is the new rim (a closure edge).
void keep_cut_side(const MapData<2>& m, Index r, const ElementEdit& edit, const Cut& cut, std::vector<Index>& polygon,
                   std::vector<GraphEdgeKind>& kinds) {
  const auto& c = m.region_corners[r];
  const auto own_id = [&](Index x) {
    if (x >= 0) return false;
    const int id = static_cast<int>(-x - 1);
    return id == cut.own[0] || id == cut.own[1] || id == cut.own[2];
  };
  std::vector<Index> kept;
  std::vector<GraphEdgeKind> kept_kinds;
  int corner = -1;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Index v = polygon[i];
    bool keep;
    if (v >= 0) {
      ++corner;
      keep = cut.f[corner] >= 0.0;
    } else {
      // the line's value there, interpolated along the side from the corners' (snapped)
      // values, so that a node of another cut is judged as the corners are
      const NewNode& node = edit.nodes[static_cast<std::size_t>(-v - 1)];
      const int ia = static_cast<int>(std::find(c.begin(), c.end(), node.side.first) - c.begin());
      const int ib = static_cast<int>(std::find(c.begin(), c.end(), node.side.second) - c.begin());
      const double f = (1.0 - node.s) * cut.f[ia] + node.s * cut.f[ib];
      keep = own_id(v) || f >= 0.0;
    }
    if (!keep) continue;
    kept.push_back(v);
    kept_kinds.push_back(kinds[i]);
  }
  // the side that leaves the first own node kept runs along the line: a closure edge
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (own_id(kept[i]) && own_id(kept[(i + 1) % kept.size()])) kept_kinds[i] = GraphEdgeKind::closure;
  polygon = std::move(kept);
  kinds = std::move(kept_kinds);
}

/// The convex polygon `ring` (element-local nodes, `kinds` of its sides) of old region r made
/// into regions, ear by ear at its strictly convex vertices; its sides and diagonals become
/// graph edges.
void triangulate_polygon(const MapData<2>& m, Index r, std::vector<Index> ring, const std::vector<GraphEdgeKind>& kinds,
                         MadeElement& out, MadeEdges& edges) {
  for (std::size_t i = 0; i < ring.size(); ++i) edges.kind[side_of(ring[i], ring[(i + 1) % ring.size()])] = kinds[i];
  const auto at = [&](Index v) { return out.position[static_cast<std::size_t>(v)]; };
  while (ring.size() >= 3) {
    bool cut_ear = false;
    for (std::size_t i = 0; i < ring.size() && !cut_ear; ++i) {
      const Index a = ring[(i + ring.size() - 1) % ring.size()], b = ring[i], cc = ring[(i + 1) % ring.size()];
      const LocalPoint<2> u = at(b) - at(a), w = at(cc) - at(a);
      const double area = u.x() * w.y() - u.y() * w.x();
      if (!(area > 1e-12 * u.norm() * w.norm())) continue;
      // nor may another vertex lie on the new side a-cc (the polygon has vertices in the
      // middle of its sides): that would be a corner of no triangle on that side
      const bool through_vertex = std::any_of(ring.begin(), ring.end(), [&](Index v) {
        if (v == a || v == b || v == cc) return false;
        const LocalPoint<2> x = at(v) - at(a);
        const double across = w.x() * x.y() - w.y() * x.x(), along = w.dot(x);
        return std::abs(across) <= 1e-12 * w.norm() * x.norm() && along > 0.0 && along < w.squaredNorm();
      });
      if (through_vertex) continue;
      out.corners.push_back({a, b, cc});
      out.region_target.push_back(m.region_target[r]);
      out.region_map.push_back(m.region_map[r]);
      for (const Side& s : {side_of(a, b), side_of(b, cc), side_of(cc, a)}) {
        edges.region_sides[s] = 1;
        edges.kind.emplace(s, GraphEdgeKind::closure);  // a diagonal, if not a polygon side
      }
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
      cut_ear = true;
    }
    if (!cut_ear) break;  // what is left is flat
  }
}

/// Element t's old graph edges split at the new nodes on them: the pieces that border no new
/// region stay if they are pieces of S2 edges, or if the old edge bordered no region either.
void split_old_edges(const PlMap<2>& map, Index t, const ElementEdit& edit, const OldGraph& old_graph,
                     MadeEdges& edges) {
  const Index first = map.nodes_begin(t), old_count = map.nodes_end(t) - first;
  for (Index n = first; n < map.nodes_end(t); ++n)
    for (Index i = old_graph.begin[static_cast<std::size_t>(n - first)]; i < old_graph.begin[static_cast<std::size_t>(n - first) + 1]; ++i) {
      const Index q = old_graph.graph.neighbor[static_cast<std::size_t>(i)];
      const GraphEdgeKind old_kind = old_graph.graph.kind[static_cast<std::size_t>(i)];
      if (q < n) continue;
      const Side old = {n, q};
      std::vector<std::pair<double, Index>> chain{{0.0, n - first}, {1.0, q - first}};
      if (const auto found = edit.on_side.find(old); found != edit.on_side.end())
        for (int id : found->second)
          chain.emplace_back(edit.nodes[static_cast<std::size_t>(id)].s, old_count + id);
      std::sort(chain.begin(), chain.end());
      const bool bordered = edges.old_region_sides.contains(old);
      for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
        const Side piece = side_of(chain[k].second, chain[k + 1].second);
        if (edges.region_sides.contains(piece)) continue;
        if (old_kind == GraphEdgeKind::target_edge || !bordered) edges.kind[piece] = old_kind;
        else edges.kind.erase(piece);
      }
    }
}

/// Every node's neighbours, counter-clockwise: from the element's boundary for a node on it,
/// else from the smallest neighbour.
void order_neighbors(const std::map<Side, GraphEdgeKind>& edges, MadeElement& out) {
  const auto total = static_cast<Index>(out.position.size());
  std::vector<std::vector<std::pair<Index, GraphEdgeKind>>> neighbors(static_cast<std::size_t>(total));
  for (const auto& [s, kind] : edges) {
    neighbors[static_cast<std::size_t>(s.first)].emplace_back(s.second, kind);
    neighbors[static_cast<std::size_t>(s.second)].emplace_back(s.first, kind);
  }
  static const std::array<LocalPoint<2>, 3> corner_at = {LocalPoint<2>(0, 0), LocalPoint<2>(1, 0), LocalPoint<2>(0, 1)};
  for (Index v = 0; v < total; ++v) {
    auto& list = neighbors[static_cast<std::size_t>(v)];
    const LocalPoint<2> p = out.position[static_cast<std::size_t>(v)];
    std::optional<LocalPoint<2>> start;
    const NodeType type = out.type[static_cast<std::size_t>(v)];
    const int k = out.location[static_cast<std::size_t>(v)];
    if (is_at_corner(type) || is_on_edge(type)) start = corner_at[(k + 1) % 3] - corner_at[k];
    const auto angle = [&](Index q) {
      const LocalPoint<2> d = out.position[static_cast<std::size_t>(q)] - p;
      const LocalPoint<2> s0 = start.value_or(LocalPoint<2>(1.0, 0.0));
      double a = std::atan2(s0.x() * d.y() - s0.y() * d.x(), s0.dot(d));
      if (a < 0.0) a += 2.0 * std::numbers::pi;
      if (start && a > 2.0 * std::numbers::pi - 1e-9) a = 0.0;
      return a;
    };
    std::sort(list.begin(), list.end(), [&](const auto& x, const auto& y) { return angle(x.first) < angle(y.first); });
    if (!start && !list.empty()) {
      const auto smallest = std::min_element(list.begin(), list.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      std::rotate(list.begin(), smallest, list.end());
    }
  }
  for (const auto& list : neighbors) {
    out.neighbor_count.push_back(static_cast<Index>(list.size()));
    out.neighbors.insert(out.neighbors.end(), list.begin(), list.end());
  }
}

/// The nodes on each local edge k of the re-made element, from corner k to corner k + 1.
void list_edge_nodes(const OldGraph& old_graph, const ElementEdit& edit, Index first, MadeElement& out) {
  for (int k = 0; k < 3; ++k) {
    auto& list = out.edge_nodes[static_cast<std::size_t>(k)];
    for (Index n : old_graph.edge_nodes(k)) list.push_back(n - first);
    for (std::size_t i = 0; i < edit.nodes.size(); ++i)
      if (edit.nodes[i].location == k) list.push_back(out.old_nodes + static_cast<Index>(i));
    std::stable_sort(list.begin(), list.end(), [&](Index x, Index y) {
      return along_local_edge(out.position[static_cast<std::size_t>(x)], k) <
             along_local_edge(out.position[static_cast<std::size_t>(y)], k);
    });
  }
}

/// The region across each side of every new region (or invalid_index).
void link_regions_across(MadeElement& out) {
  out.across.assign(out.corners.size(), {invalid_index, invalid_index, invalid_index});
  std::map<Side, std::pair<Index, int>> first_with;
  for (std::size_t r = 0; r < out.corners.size(); ++r)
    for (int i = 0; i < 3; ++i) {
      const Side s = side_of(out.corners[r][(i + 1) % 3], out.corners[r][(i + 2) % 3]);
      const auto [it, fresh] = first_with.try_emplace(s, static_cast<Index>(r), i);
      if (fresh) continue;
      out.across[r][i] = it->second.first;
      out.across[static_cast<std::size_t>(it->second.first)][it->second.second] = static_cast<Index>(r);
    }
}

/// Element t re-made with the cuts' nodes: its old nodes and the new ones, its regions cut and
/// split (ear by ear, each polygon convex), its graph (old edges split at the new nodes, closure
/// edges of the parts that left dropped, neighbours counter-clockwise) and edge arrays.
MadeElement make_element(const PlMap<2>& map, Index t, const ElementEdit& edit, OldGraphs& graphs, RegionClipReport& rep) {
  const MapData<2>& m = map.stored();
  MadeElement out;
  const OldGraph old_graph = graphs.of(t);
  const Index first = map.nodes_begin(t);
  gather_nodes(map, t, edit, out);
  rep.new_nodes += static_cast<Index>(edit.nodes.size());
  const auto local = [&](Index entry) { return entry >= 0 ? entry - first : out.old_nodes - entry - 1; };
  MadeEdges edges;
  for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) {
    const auto& c = m.region_corners[r];
    for (int i = 0; i < 3; ++i) edges.old_region_sides[side_of(c[i], c[(i + 1) % 3])] = 1;
  }
  for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) {
    const auto found = edit.cuts.find(r);
    if (found != edit.cuts.end() && found->second.removed) continue;
    const auto& c = m.region_corners[r];
    std::vector<Index> polygon = polygon_of(m, r, edit);
    // the kind of each polygon side: that of the old side it lies on
    std::vector<GraphEdgeKind> kinds;  // of the side that starts at each vertex
    int corner = -1;
    for (Index v : polygon) {
      if (v >= 0) ++corner;
      kinds.push_back(old_graph.kind(c[corner], c[(corner + 1) % 3]).value_or(GraphEdgeKind::closure));
    }
    if (found != edit.cuts.end())
      keep_cut_side(m, r, edit, found->second, polygon, kinds);
    else if (polygon.size() > 3)
      ++rep.split_regions;
    std::vector<Index> ring(polygon.size());
    for (std::size_t i = 0; i < polygon.size(); ++i) ring[i] = local(polygon[i]);
    triangulate_polygon(m, r, std::move(ring), kinds, out, edges);
  }
  split_old_edges(map, t, edit, old_graph, edges);
  order_neighbors(edges.kind, out);
  list_edge_nodes(old_graph, edit, first, out);
  link_regions_across(out);
  // the old nodes' values stay in the arrays: only the new nodes' are kept
  const auto old_part = static_cast<std::ptrdiff_t>(out.old_nodes);
  out.position.erase(out.position.begin(), out.position.begin() + old_part);
  out.type.erase(out.type.begin(), out.type.begin() + old_part);
  out.location.erase(out.location.begin(), out.location.begin() + old_part);
  return out;
}

PlMap<2> clip(PlMap<2>&& map, std::span<const RegionClip> clips, RegionClipReport* report, unsigned threads) {
  RegionClipReport rep;
  std::map<Index, ElementEdit> edits = plan_cuts(map, clips, rep);
  // Each changed element is made from the old map and its own edit alone, so the elements are
  // made in contiguous pieces on all threads (half the clip's time on the femur pair of the
  // projection peers), each piece with its own graph scratch and counts; the result is the same
  // for every thread count. (Each element's edit is freed once the element is made: memory the
  // next ones reuse.)
  std::vector<std::pair<Index, ElementEdit>> listed;
  listed.reserve(edits.size());
  while (!edits.empty()) {
    auto taken = edits.extract(edits.begin());
    listed.emplace_back(taken.key(), std::move(taken.mapped()));
  }
  std::vector<MadeElement> made_list(listed.size());
  const std::size_t pieces = std::min(listed.size(), std::size_t{4} * resolve_thread_count(threads));
  std::vector<RegionClipReport> counts(std::max<std::size_t>(pieces, 1));
  parallel_for_pieces(listed.size(), pieces, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    OldGraphs graphs(map);
    for (std::size_t i = begin; i < end; ++i) {
      made_list[i] = make_element(map, listed[i].first, listed[i].second, graphs, counts[k]);
      listed[i].second = ElementEdit{};
    }
  });
  for (const RegionClipReport& c : counts) {
    rep.clipped_regions += c.clipped_regions;
    rep.removed_regions += c.removed_regions;
    rep.split_regions += c.split_regions;
    rep.new_nodes += c.new_nodes;
  }
  std::map<Index, MadeElement> made;
  for (std::size_t i = 0; i < listed.size(); ++i) made.emplace_hint(made.end(), listed[i].first, std::move(made_list[i]));
  std::vector<MadeElement>().swap(made_list);
  for (const auto& [t, e] : made) rep.changed_elements.push_back(t);
  if (report) *report = rep;
  if (made.empty()) return std::move(map);
  return detail::rewrite_with_made_elements(std::move(map), made, threads);
}

}  // namespace

PlMap<2> clip_regions(PlMap<2>&& map, std::span<const RegionClip> clips, RegionClipReport* report, unsigned threads) {
  PlMap<2> out = clip(std::move(map), clips, report, threads);
  // The cut's working data (the old graphs, the made elements, the old stored graph) are freed
  // into malloc's heap by now, where they would stay resident under what the caller allocates
  // next (as after a face removal, face_removal.hpp). Given back.
  give_freed_heap_back();
  return out;
}

PlMap<2> clip_regions(const PlMap<2>& map, std::span<const RegionClip> clips, RegionClipReport* report, unsigned threads) {
  return clip_regions(PlMap<2>(map), clips, report, threads);
}

}  // namespace plmap
