// One quadrilateral smoothing step; see quad_smoothing.hpp for the method.

#include "quad_smoothing.hpp"
#include "piece_crossings.hpp"
#include "region_condition.hpp"

#include <plmap/core/predicates.hpp>
#include <plmap/core/segment_sweep.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <numbers>

namespace plmap::smoothing {

namespace {

using Vec2 = Eigen::Vector2d;

/// Barycentric clearance: an unknown closer than this (in its triangle's barycentric
/// coordinates) to an S1 edge, or a new crossing closer than this (edge parameter) to A or B,
/// makes the step refused. Far above MapBuilder's snap tolerance (1e-10), so the builder never
/// snaps what the step kept apart; relative to the element, hence scale free.
constexpr double clearance = 1e-8;

/// The lists of T1 and T2 as walking the edited polylines of `relevant` (in that order) would
/// find them, read off a step's pieces: every segment of a relevant S2 edge in T1 or T2 belongs
/// to one of its pieces, which after the cut lies in T1, in T2 or (cut) in both (`sides`: bit 0
/// T1, bit 1 T2). A step changes the graph only inside T1 ∪ T2, so only their lists change.
/// `edge_sides` gets the same per relevant edge (the lists are `relevant` filtered by it).
/// `position` is scratch indexed by S2 edge.
void index_quadrilateral_from_pieces(EdgesInElement& index, Index t1, Index t2, const std::vector<Index>& relevant,
                                     const std::vector<QuadPiece>& pieces, const std::vector<std::uint8_t>& sides,
                                     std::vector<Index>& position, std::vector<std::uint8_t>& edge_sides) {
  edge_sides.assign(relevant.size(), 0);
  for (std::size_t i = 0; i < relevant.size(); ++i) position[static_cast<std::size_t>(relevant[i])] = static_cast<Index>(i);
  for (std::size_t p = 0; p < pieces.size(); ++p)
    edge_sides[static_cast<std::size_t>(position[static_cast<std::size_t>(pieces[p].edge)])] |= sides[p];
  index[t1].clear();
  index[t2].clear();
  for (std::size_t i = 0; i < relevant.size(); ++i) {
    if (edge_sides[i] & 1) index[t1].push_back(relevant[i]);
    if (edge_sides[i] & 2) index[t2].push_back(relevant[i]);
  }
}

/// Condition number of the affine map from the plane triangle p to the space triangle w
/// (infinite if either is degenerate).
double condition(const std::array<Vec2, 3>& p, const std::array<Eigen::Vector3d, 3>& w) {
  Eigen::Matrix2d dp;
  dp.col(0) = p[1] - p[0];
  dp.col(1) = p[2] - p[0];
  const double det = dp.determinant();
  if (!(std::abs(det) > 0.0)) return std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, 3, 2> dw;
  dw.col(0) = w[1] - w[0];
  dw.col(1) = w[2] - w[0];
  const Eigen::Matrix<double, 3, 2> a = dw * dp.inverse();
  const Eigen::Matrix2d g = a.transpose() * a;
  const double mean = 0.5 * g.trace(), gap = std::sqrt(std::max(0.0, mean * mean - g.determinant()));
  const double smallest = mean - gap;
  if (!(smallest > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt((mean + gap) / smallest);
}


}  // namespace

QuadSmoother::QuadSmoother(PreimageGraph& graph, const Surface<2>& domain, const Surface<2>& target,
                           AnySmoothingWeights weights, const EdgesInElement* index)
    : g_(graph),
      s1_(domain),
      s2_(target),
      own_stars_(std::in_place, target, std::move(weights)),
      stars_(&*own_stars_),
      unknown_index_(static_cast<std::size_t>(target.vertex_count()), -1),
      edge_seen_(static_cast<std::size_t>(target.edge_count()), 0),
      position_in_relevant_(static_cast<std::size_t>(target.edge_count()), 0) {
  index_edges(index);
}

QuadSmoother::QuadSmoother(PreimageGraph& graph, const Surface<2>& domain, S2Stars& stars, const EdgesInElement* index)
    : g_(graph),
      s1_(domain),
      s2_(stars.target()),
      stars_(&stars),
      unknown_index_(static_cast<std::size_t>(s2_.vertex_count()), -1),
      edge_seen_(static_cast<std::size_t>(s2_.edge_count()), 0),
      position_in_relevant_(static_cast<std::size_t>(s2_.edge_count()), 0) {
  index_edges(index);
}

void QuadSmoother::index_edges(const EdgesInElement* index) {
  if (index != nullptr) {
    edges_in_element_ = *index;
    return;
  }
  edges_in_element_.assign(static_cast<std::size_t>(s1_.element_count()), {});
  for (Index e = 0; e < s2_.edge_count(); ++e) index_edge(e);
}

void QuadSmoother::index_edge(Index target_edge) {
  const std::size_t n = polyline_size(g_, target_edge);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Index t = common_element(s1_, polyline_point(g_, s2_, target_edge, i), polyline_point(g_, s2_, target_edge, i + 1), nullptr);
    if (t == invalid_index) continue;
    auto& list = edges_in_element_[t];
    if (std::find(list.begin(), list.end(), target_edge) == list.end()) list.push_back(target_edge);
  }
}

bool QuadSmoother::has_quadrilateral(Index e) const {
  const auto inc = s1_.edge_elements(e);
  return inc.size() == 2 && s1_.local_edge_is_forward(inc[0].element, inc[0].local_edge) !=
                                s1_.local_edge_is_forward(inc[1].element, inc[1].local_edge);
}

QuadOutcome QuadSmoother::smooth(Index e, QuadStepRecord* record) {
  const Index fallbacks_at_start = uniform_fallbacks_;
  if (record != nullptr) record->wrote = false;
  const QuadOutcome out = step(e, record);
  if (record != nullptr) {
    record->outcome = out;
    record->uniform_fallbacks = uniform_fallbacks_ - fallbacks_at_start;
  }
  return out;
}

QuadOutcome QuadSmoother::step(Index e, QuadStepRecord* record) {
  // the phases of quad_smoothing.hpp; each returns why it refuses the step, or nullptr, and a
  // refused step changes nothing
  Unfolding u;
  const char* refused = unfold(e, u);
  if (refused == nullptr) refused = merge(u);
  if (refused == nullptr && unknown_vertex_.empty()) return {};
  if (refused == nullptr) refused = solve_convex_combinations();
  if (refused == nullptr) refused = place_unknowns(u);
  if (refused == nullptr) refused = check_no_fold_over();
  if (refused == nullptr) refused = check_worst_condition(u);
  if (refused == nullptr) refused = cut_shared_edge(u);
  if (refused != nullptr) {
    QuadOutcome out;
    out.skipped = refused;
    return out;
  }
  return apply(u, record);
}

const char* QuadSmoother::unfold(Index e, Unfolding& u) const {
  const auto inc = s1_.edge_elements(e);
  u.e = e;
  u.t1 = inc[0].element;
  u.t2 = inc[1].element;
  const int k1 = inc[0].local_edge, k2 = inc[1].local_edge;
  const auto& e1 = s1_.element(u.t1);
  const auto& e2 = s1_.element(u.t2);
  u.a = e1[k1];
  u.b = e1[(k1 + 1) % 3];
  u.c1 = e1[(k1 + 2) % 3];
  u.c2 = e2[(k2 + 2) % 3];
  if (u.c1 == u.c2 || e2[k2] != u.b) return "degenerate quadrilateral";
  {
    const Eigen::Vector3d wa = s1_.vertex(u.a), wb = s1_.vertex(u.b);
    u.length = (wb - wa).norm();
    const Eigen::Vector3d dir = (wb - wa) / u.length;
    const auto lay = [&](const Eigen::Vector3d& w, double side) {
      const double x = (w - wa).dot(dir);
      return Vec2(x, side * ((w - wa) - x * dir).norm());
    };
    u.pa = Vec2(0.0, 0.0);
    u.pb = Vec2(u.length, 0.0);
    u.pc1 = lay(s1_.vertex(u.c1), 1.0);
    u.pc2 = lay(s1_.vertex(u.c2), -1.0);
  }
  u.corners1[k1] = u.pa, u.corners1[(k1 + 1) % 3] = u.pb, u.corners1[(k1 + 2) % 3] = u.pc1;
  u.corners2[k2] = u.pb, u.corners2[(k2 + 1) % 3] = u.pa, u.corners2[(k2 + 2) % 3] = u.pc2;
  // Convex (counter-clockwise A, C2, B, C1): then every straight segment between two points of
  // the closed quadrilateral stays in it, and Tutte/Floater applies.
  if (orient2d(u.pa, u.pc2, u.pb) <= 0 || orient2d(u.pc2, u.pb, u.pc1) <= 0 || orient2d(u.pb, u.pc1, u.pa) <= 0 ||
      orient2d(u.pc1, u.pa, u.pc2) <= 0)
    return "non-convex quadrilateral";
  return nullptr;
}

const char* QuadSmoother::merge(const Unfolding& u) {
  // The pieces of S2 edges in the quadrilateral, and the unknowns. The per-vertex and per-edge
  // marks of the previous step are cleared through its lists (a late coarse quadrilateral has
  // hundreds of unknowns and S2 edges, so looking them up by a linear search was quadratic).
  for (Index x : relevant_) edge_seen_[static_cast<std::size_t>(x)] = 0;
  for (Index v : unknown_vertex_) unknown_index_[static_cast<std::size_t>(v)] = -1;
  std::vector<Index>& relevant = relevant_;
  relevant.clear();
  for (Index t : {u.t1, u.t2})
    for (Index x : edges_in_element_[t])
      if (!edge_seen_[static_cast<std::size_t>(x)]) edge_seen_[static_cast<std::size_t>(x)] = 1, relevant.push_back(x);
  const auto movable = [&](const DomainPlace& p) {
    return (p.kind == DomainPlace::Kind::element && (p.where == u.t1 || p.where == u.t2)) ||
           (p.kind == DomainPlace::Kind::edge && p.where == u.e);
  };
  std::vector<Index>& unknown_vertex = unknown_vertex_;  // S2 vertex of each unknown
  unknown_vertex.clear();
  const auto unknown_of = [&](Index v) {
    int& index = unknown_index_[static_cast<std::size_t>(v)];
    if (index < 0) {
      index = static_cast<int>(unknown_vertex.size());
      unknown_vertex.push_back(v);
    }
    return index;
  };
  std::vector<QuadPiece>& pieces = w_.pieces;
  pieces.clear();
  std::vector<char>& inside = w_.inside;
  for (Index te : relevant) {
    const std::size_t n = polyline_size(g_, te);
    inside.assign(n - 1, 0);
    DomainPlace here = polyline_point(g_, s2_, te, 0);  // each point looked up once, not twice
    for (std::size_t i = 0; i + 1 < n; ++i) {
      bool along = false;
      const DomainPlace next = polyline_point(g_, s2_, te, i + 1);
      const Index t = common_element(s1_, here, next, &along);
      if (along) return "S2 edge along an S1 edge";
      inside[i] = (t == u.t1 || t == u.t2);
      here = next;
    }
    for (std::size_t i = 0; i + 1 < n;) {
      if (!inside[i]) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j + 1 < n && inside[j]) ++j;  // segments i .. j-1 inside: points i .. j
      for (std::size_t p = i + 1; p < j; ++p)
        if (g_.crossings[te][p - 1].domain_edge != u.e) return "S2 edge meets a triangle twice";
      if (j - i > 2) return "S2 edge crosses the shared edge twice";
      QuadPiece piece{te, i, j, {-1, -1}, {invalid_index, invalid_index}, {Vec2::Zero(), Vec2::Zero()}, {0.0, 0.0}};
      for (int end = 0; end < 2; ++end) {
        const std::size_t at = end == 0 ? i : j;
        const DomainPlace place = polyline_point(g_, s2_, te, at);
        piece.target_parameter[end] = polyline_target_parameter(g_, te, at);
        if (at == 0 || at == n - 1) piece.vertex[end] = s2_.edge_vertices(te)[at == 0 ? 0 : 1];
        if (piece.vertex[end] != invalid_index && movable(place)) {
          piece.unknown[end] = unknown_of(piece.vertex[end]);
        } else {
          const auto p = u.place(s1_, place);
          if (!p) return "S2 edge leaves the quadrilateral unexpectedly";
          piece.fixed[end] = *p;
        }
      }
      pieces.push_back(piece);
      i = j;
    }
  }
  return nullptr;
}

const char* QuadSmoother::solve_convex_combinations() {
  const std::vector<QuadPiece>& pieces = w_.pieces;
  const std::vector<Index>& unknown_vertex = unknown_vertex_;
  const int unknowns = static_cast<int>(unknown_vertex.size());
  auto& ring_of = w_.ring_of;  // (piece, end of the neighbour)
  auto& ordered_ring = w_.ordered_ring;
  auto& ring_world = w_.ring_world;
  for (auto* lists : {&ring_of, &ordered_ring}) {
    if (lists->size() < unknown_vertex.size()) lists->resize(unknown_vertex.size());
    for (std::size_t i = 0; i < unknown_vertex.size(); ++i) (*lists)[i].clear();
  }
  if (ring_world.size() < unknown_vertex.size()) ring_world.resize(unknown_vertex.size());
  for (int p = 0; p < static_cast<int>(pieces.size()); ++p)
    for (int end = 0; end < 2; ++end)
      if (pieces[p].unknown[end] >= 0) ring_of[pieces[p].unknown[end]].push_back({p, 1 - end});
  system_.reset(unknowns);
  for (int i = 0; i < unknowns; ++i) {
    const Index v = unknown_vertex[i];
    const std::vector<Index>* cycle = stars_->ring_edges(v);
    if (cycle == nullptr || ring_of[i].size() != cycle->size()) return "vertex preimage with an open S2 star";
    std::vector<Eigen::Vector3d>& ring = ring_world[i];
    ring.clear();
    bool whole_star = true;  // every ring point an S2 vertex: v's whole star (s2_stars.hpp)
    for (Index te : *cycle) {
      const auto it = std::find_if(ring_of[i].begin(), ring_of[i].end(), [&](const auto& pe) { return pieces[pe.first].edge == te; });
      if (it == ring_of[i].end()) return "vertex preimage with an open S2 star";
      ordered_ring[i].push_back(*it);
      const auto ends = s2_.edge_vertices(te);
      const double t = pieces[it->first].target_parameter[it->second];
      whole_star = whole_star && (t == 0.0 || t == 1.0);
      ring.push_back((1.0 - t) * s2_.vertex(ends[0]) + t * s2_.vertex(ends[1]));
    }
    bool fallback = false;
    const std::span<const double> w = stars_->weights(v, ring, whole_star, fallback);
    if (fallback) ++uniform_fallbacks_;
    system_.add(i, i, 1.0);
    for (std::size_t j = 0; j < ring.size(); ++j) {
      const auto [p, end] = ordered_ring[i][j];
      if (pieces[p].unknown[end] >= 0)
        system_.add(i, pieces[p].unknown[end], -w[j]);
      else
        system_.add_rhs(i, w[j] * pieces[p].fixed[end]);
    }
    if (g_.orientation < 0) {
      std::reverse(ordered_ring[i].begin(), ordered_ring[i].end());
      std::reverse(ring_world[i].begin(), ring_world[i].end());
    }
  }
  if (!system_.solve()) return "solver";
  return nullptr;
}

const char* QuadSmoother::place_unknowns(const Unfolding& u) {
  const int unknowns = static_cast<int>(unknown_vertex_.size());
  w_.position.resize(unknown_vertex_.size());
  w_.new_place.resize(unknown_vertex_.size());
  for (int i = 0; i < unknowns; ++i) {
    w_.position[i] = system_.solution(i);
    const int side = orient2d(u.pa, u.pb, w_.position[i]);
    if (side == 0) return "node on the shared edge";
    const Index t = side > 0 ? u.t1 : u.t2;
    const LocalPoint<2> local = u.local(t, w_.position[i]);
    const Barycentric<2> b = barycentric_from_local<2>(local);
    if (!(b.minCoeff() > clearance)) return "node leaves the quadrilateral";
    w_.new_place[i] = {DomainPlace::Kind::element, t, 0.0, local};
  }
  return nullptr;
}

Eigen::Vector2d QuadSmoother::end_position(const QuadPiece& p, int end) const {
  return p.unknown[end] >= 0 ? w_.position[p.unknown[end]] : p.fixed[end];
}

const char* QuadSmoother::check_no_fold_over() {
  const std::vector<QuadPiece>& pieces = w_.pieces;
  // all pairs of pieces, by a sweep (a late coarse quadrilateral carries hundreds of pieces)
  w_.segments.clear();
  w_.segment_ends.clear();
  for (const QuadPiece& p : pieces) {
    w_.segments.push_back({end_position(p, 0), end_position(p, 1)});
    w_.segment_ends.push_back(p.unknown);
  }
  // two spokes of one unknown are left to the winding check below (piece_crossings.hpp)
  if (pieces_apart_from_shared_ends_meet(w_.segments, w_.segment_ends, w_.boxes)) return "fold-over";
  const int unknowns = static_cast<int>(unknown_vertex_.size());
  for (int i = 0; i < unknowns; ++i) {
    // Each turn from one segment's direction to the next, counter-clockwise, is in (0, 2π]; they
    // add up to 2π times the number of turns that pass the +x direction, so the segments wind
    // once iff exactly one does (decided exactly, where a sum of atan2 angles was 6 % of a step).
    int wraps = 0;
    const auto& ring = w_.ordered_ring[i];
    for (std::size_t j = 0; j < ring.size(); ++j) {
      const Vec2 d0 = end_position(pieces[ring[j].first], ring[j].second) - w_.position[i];
      const auto& nx = ring[(j + 1) % ring.size()];
      const Vec2 d1 = end_position(pieces[nx.first], nx.second) - w_.position[i];
      if (d0 == Vec2::Zero()) return "fold-over";  // a segment of length zero
      const int turn = orient2d(Vec2::Zero(), d0, d1);
      if (turn == 0 && d0.dot(d1) > 0.0) return "fold-over";
      if (!direction_precedes(d0, d1, turn)) ++wraps;
    }
    if (wraps != 1) return "fold-over";
  }
  return nullptr;
}

const char* QuadSmoother::check_worst_condition(const Unfolding& u) {
  // The worst spoke triangle (v, neighbour j, neighbour j + 1) against its image: a step that
  // would make it worse is refused, so that sweeps do not trade the quadrilateral's worst piece
  // for a better average (without this, κ max creeps up again after a few sweeps).
  const std::vector<QuadPiece>& pieces = w_.pieces;
  const int unknowns = static_cast<int>(unknown_vertex_.size());
  const auto worst_spoke = [&](const std::vector<Vec2>& at) {
    double worst = 1.0;
    for (int i = 0; i < unknowns; ++i) {
      const auto& ring = w_.ordered_ring[i];
      const auto end_at = [&](std::pair<int, int> pe) {
        const QuadPiece& p = pieces[pe.first];
        return p.unknown[pe.second] >= 0 ? at[p.unknown[pe.second]] : p.fixed[pe.second];
      };
      for (std::size_t j = 0; j < ring.size(); ++j) {
        const std::size_t k = (j + 1) % ring.size();
        worst = std::max(worst, condition({at[i], end_at(ring[j]), end_at(ring[k])},
                                          {s2_.vertex(unknown_vertex_[i]), w_.ring_world[i][j], w_.ring_world[i][k]}));
      }
    }
    return worst;
  };
  w_.old_position.resize(unknown_vertex_.size());
  for (int i = 0; i < unknowns; ++i) w_.old_position[i] = *u.place(s1_, g_.vertex[unknown_vertex_[i]]);
  // the old positions' worst is needed only if the new one is above free_condition
  if (const double worst_new = worst_spoke(w_.position);
      worst_new > free_condition && worst_new > std::max(worst_spoke(w_.old_position), free_condition))
    return "would raise the worst condition number";
  return nullptr;
}

const char* QuadSmoother::cut_shared_edge(const Unfolding& u) {
  // the new crossings with e
  const std::vector<QuadPiece>& pieces = w_.pieces;
  w_.cut.assign(pieces.size(), std::nullopt);
  // per piece: bit 0 if it has a segment in T1 after the cut, bit 1 in T2 (an end off e lies on
  // e's side of its triangle; an end on e is A or B)
  w_.piece_sides.assign(pieces.size(), 0);
  const bool a_is_smaller = u.a < u.b;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const Vec2 s = end_position(pieces[p], 0), t = end_position(pieces[p], 1);
    const int ss = orient2d(u.pa, u.pb, s), st = orient2d(u.pa, u.pb, t);
    if (ss == 0 && st == 0) return "S2 edge along an S1 edge";
    for (const int side : {ss, st}) w_.piece_sides[p] |= side > 0 ? 1 : side < 0 ? 2 : 0;
    if (ss * st >= 0) continue;
    const double lambda = s.y() / (s.y() - t.y());
    const double along = (s.x() + lambda * (t.x() - s.x())) / u.length;
    if (!(along > clearance && along < 1.0 - clearance)) return "crossing next to a vertex";
    const double tp = pieces[p].target_parameter[0] + lambda * (pieces[p].target_parameter[1] - pieces[p].target_parameter[0]);
    w_.cut[p] = EdgeCrossing{u.e, a_is_smaller ? along : 1.0 - along, tp};
  }
  return nullptr;
}

QuadOutcome QuadSmoother::apply(const Unfolding& u, QuadStepRecord* record) {
  QuadOutcome out;
  const std::vector<QuadPiece>& pieces = w_.pieces;
  const int unknowns = static_cast<int>(unknown_vertex_.size());
  for (int i = 0; i < unknowns; ++i) {
    DomainPlace& old = g_.vertex[unknown_vertex_[i]];
    const double shift = (w_.position[i] - w_.old_position[i]).norm() / u.length;
    if (shift > 0.0) ++out.nodes_moved;
    if (old.kind != DomainPlace::Kind::element || old.where != w_.new_place[i].where) ++out.nodes_crossed;
    out.max_displacement = std::max(out.max_displacement, shift);
    old = w_.new_place[i];
  }
  // Pieces of one S2 edge from the last to the first, so that earlier point indices stay valid:
  // they were collected edge by edge, each edge's by increasing point index, so the pieces in
  // reverse order do that (without sorting them; each edge's list is edited on its own).
  for (std::size_t p = pieces.size(); p-- > 0;) {
    auto& list = g_.crossings[pieces[p].edge];
    const auto first = list.begin() + static_cast<std::ptrdiff_t>(pieces[p].first);  // crossing index of point first + 1
    list.erase(first, first + static_cast<std::ptrdiff_t>(pieces[p].last - pieces[p].first - 1));
    if (w_.cut[p]) list.insert(list.begin() + static_cast<std::ptrdiff_t>(pieces[p].first), *w_.cut[p]);
  }
  index_quadrilateral_from_pieces(edges_in_element_, u.t1, u.t2, relevant_, pieces, w_.piece_sides, position_in_relevant_,
                                  w_.edge_sides);
  if (record != nullptr) {
    record->wrote = true;
    record->places.clear();
    for (int i = 0; i < unknowns; ++i) record->places.emplace_back(unknown_vertex_[i], w_.new_place[i]);
    record->relevant = relevant_;
    record->sides = w_.edge_sides;
    record->cuts.clear();
    for (std::size_t p = 0; p < pieces.size(); ++p)
      if (w_.cut[p]) record->cuts.emplace_back(pieces[p].edge, *w_.cut[p]);
  }
  return out;
}

void QuadSmoother::replay(Index e, const QuadStepRecord& record) {
  uniform_fallbacks_ += record.uniform_fallbacks;
  if (!record.wrote) return;
  for (const auto& [v, place] : record.places) g_.vertex[v] = place;
  for (Index te : record.relevant) {
    auto& list = g_.crossings[te];
    std::erase_if(list, [e](const EdgeCrossing& c) { return c.domain_edge == e; });
    for (const auto& [cut_edge, crossing] : record.cuts) {
      if (cut_edge != te) continue;
      const auto at = std::upper_bound(list.begin(), list.end(), crossing.target_parameter,
                                       [](double t, const EdgeCrossing& c) { return t < c.target_parameter; });
      list.insert(at, crossing);
    }
  }
  // the lists the step made: the same graph around e gives the same lists (no polyline walk)
  const auto inc = s1_.edge_elements(e);
  std::vector<Index>& list1 = edges_in_element_[inc[0].element];
  std::vector<Index>& list2 = edges_in_element_[inc[1].element];
  list1.clear();
  list2.clear();
  for (std::size_t i = 0; i < record.relevant.size(); ++i) {
    if (record.sides[i] & 1) list1.push_back(record.relevant[i]);
    if (record.sides[i] & 2) list2.push_back(record.relevant[i]);
  }
}

QuadPassTally run_quadrilateral_pass(QuadSmoother& smoother, const Surface<2>& domain, const std::vector<char>& frozen,
                                     const std::vector<QuadStepRecord>* previous, const std::vector<char>* newly_frozen,
                                     std::vector<QuadStepRecord>& records) {
  QuadPassTally tally;
  records.resize(static_cast<std::size_t>(domain.edge_count()));
  // per S1 triangle: may differ from the previous pass at this point of the pass
  std::vector<char>& changed = tally.changed;
  changed.assign(static_cast<std::size_t>(domain.element_count()), 0);
  for (Index e = 0; e < domain.edge_count(); ++e) {
    const std::size_t ei = static_cast<std::size_t>(e);
    QuadStepRecord& record = records[ei];
    record.wrote = false;
    record.outcome = QuadOutcome{};
    record.uniform_fallbacks = 0;
    if (!smoother.has_quadrilateral(e)) continue;
    const auto inc = domain.edge_elements(e);
    const std::size_t t1 = static_cast<std::size_t>(inc[0].element), t2 = static_cast<std::size_t>(inc[1].element);
    if (frozen[ei]) {
      ++tally.skipped_by_reason["would raise the worst condition number of the rebuilt map"];
      if (previous != nullptr && (*newly_frozen)[ei] && (*previous)[ei].wrote) changed[t1] = changed[t2] = 1;
      continue;
    }
    QuadOutcome o;
    if (previous == nullptr || changed[t1] || changed[t2]) {
      o = smoother.smooth(e, &record);
      ++tally.solved;
      if (previous != nullptr) changed[t1] = changed[t2] = 1;
    } else {
      smoother.replay(e, (*previous)[ei]);
      record = (*previous)[ei];
      o = record.outcome;
      ++tally.replayed;
    }
    if (o.skipped != nullptr) {
      ++tally.skipped_by_reason[o.skipped];
      continue;
    }
    ++tally.smoothed;
    tally.nodes_moved += o.nodes_moved;
    tally.nodes_crossed += o.nodes_crossed;
    tally.max_displacement = std::max(tally.max_displacement, o.max_displacement);
  }
  return tally;
}

}  // namespace plmap::smoothing
