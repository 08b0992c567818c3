#pragma once
// Whether a nearer sheet of S2 hides a point the projection reaches: the ray from the S1 point
// meets another part of S2 first (the offset copies of the bones of a joint, which interpenetrate
// where the gap is smaller than the offset), so the points there take that nearer hit.
//  - The rim of D at a bound of the band of distances (projection_rim.cpp) is where the rays'
//    distance to one sheet reaches the bound; it bounds D only where no nearer sheet hides it
//    (under a loose distance limit one bone's level set runs beside the next bone, whose pieces
//    the rim edges would cross and cost faces): hidden_by_nearer_sheet, exact.
//  - A walk along an S2 edge's preimage ends where the crossing it reaches is hidden
//    (EdgeFailureReason::hidden), instead of running on under the nearer sheet, crossing its
//    pieces and costing both their stretches there: hidden_along_sheet, a walk on S2 from the
//    nearer sheet's triangle that a ray from a vertex close by hit, cheap enough for the walks.

#include "projection_context.hpp"
#include "rim_geometry.hpp"

#include <plmap/core/surface.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace plmap::projection {

/// A hit counts as hiding a point only where it lies inside its triangle by more than this
/// (barycentric), and nearer than the point by more than this fraction of its rank: decisions
/// at a tie (a ray through an S2 edge or a fin's foot, two sheets that meet) would go either
/// way with the rounding of the input, and the map would depend on the unit of length. (So a
/// sheet whose edges lie exactly over the ray, as in a copy of S1's own grid, hides nothing.)
inline constexpr double inside_margin = 1e-9;
inline constexpr double nearer_margin = 1e-6;

/// Whether the ray from local point xi of S1 element t meets an S2 triangle other than `skip`
/// at an admissible distance of smaller rank (ProjectionContext::rank) than mu: within the band,
/// facing the ray as the normal check asks, and before a focal point of t's direction field.
/// Candidates come from the S2 centroid index around the stretch of the ray that such distances
/// cover; each is tested exactly by where the ray pierces it.
template <class Context>
bool hidden_by_nearer_sheet(const Context& ctx, Index t, const LocalPoint<2>& xi, double mu, Index skip) {
  const Barycentric<2> b = barycentric_from_local<2>(xi);
  WorldPoint<2> nu = WorldPoint<2>::Zero();
  for (int k = 0; k < 3; ++k) nu += b(k) * ctx.vertex_directions[ctx.s1.element(t)[k]];
  const WorldPoint<2> x = ctx.s1.world_position(t, xi);
  // every distance of smaller rank lies between `from` and mu along the ray
  const double from = ctx.options.allow_negative_distance ? -std::abs(mu) : 0.0;
  const WorldPoint<2> p0 = x + from * nu, p1 = x + mu * nu;
  const double reach = 0.5 * (p1 - p0).norm() + 1.01 * ctx.s2_index->radius;
  const double rank_of_bound = ctx.rank(mu);
  return ctx.s2_index->any_within(0.5 * (p0 + p1), reach, [&](Index c) {
    if (c == skip) return false;
    const std::array<WorldPoint<2>, 3> tri = {ctx.s2.corner(c, 0), ctx.s2.corner(c, 1), ctx.s2.corner(c, 2)};
    const std::optional<Pierce> p = segment_through_triangle(p0, p1, tri);
    if (!p || !strictly_inside(p->barycentric, inside_margin)) return false;
    const double mu_c = from + p->s * (mu - from);
    if (!(ctx.rank(mu_c) < (1.0 - nearer_margin) * rank_of_bound)) return false;
    return ctx.normal_ok(nu, ctx.s2.element_normal(c)) && ctx.unfolded_in(t, xi, mu_c);
  });
}

/// Where the line x + m nu pierces the plane of S2 triangle c: the barycentric coordinates of the
/// pierce and m, or nothing where the line runs parallel to the plane. The sides are divided by
/// their length first, so that no product of lengths under- or overflows (any unit of length).
struct LinePierce {
  std::array<double, 3> barycentric{};
  double m = 0.0;
  double scale = 0.0;  // the longer of the sides at corner 0
};
inline std::optional<LinePierce> line_through_plane(const Surface<2>& s2, Index c, const WorldPoint<2>& x,
                                                    const WorldPoint<2>& nu) {
  const WorldPoint<2> c0 = s2.corner(c, 0);
  const double scale = std::max((s2.corner(c, 1) - c0).norm(), (s2.corner(c, 2) - c0).norm());
  if (!(scale > 0.0)) return std::nullopt;
  const WorldPoint<2> e1 = (s2.corner(c, 1) - c0) / scale, e2 = (s2.corner(c, 2) - c0) / scale;
  const WorldPoint<2> n = e1.cross(e2);
  const double along = n.dot(nu);
  if (!(std::abs(along) > 1e-12 * n.norm() * nu.norm())) return std::nullopt;
  LinePierce p;
  p.scale = scale;
  p.m = n.dot(c0 - x) / along;
  const WorldPoint<2> hit = (x + p.m * nu - c0) / scale;
  const double nn = n.squaredNorm();
  const double y1 = n.dot(hit.cross(e2)) / nn, y2 = n.dot(e1.cross(hit)) / nn;
  p.barycentric = {1.0 - y1 - y2, y1, y2};
  return p;
}

/// The smallest barycentric coordinate of that pierce (positive: inside), -inf if there is none.
inline double pierce_depth(const Surface<2>& s2, Index a, const WorldPoint<2>& x, const WorldPoint<2>& nu) {
  const std::optional<LinePierce> p = line_through_plane(s2, a, x, nu);
  return p ? std::min({p->barycentric[0], p->barycentric[1], p->barycentric[2]}) : -std::numeric_limits<double>::infinity();
}

/// Where the pierce of the ray x + m nu lies beyond the side of S2 triangle c opposite corner k,
/// the triangle across that side to step to, other than `previous`: at a manifold edge the one
/// across; at an edge of three or more triangles (a fin on a sheet) the one whose plane the ray
/// pierces deepest inside (the largest smallest barycentric coordinate), so that the walk does
/// not depend on the triangle it came from; at S2's boundary none.
template <class Context>
Index across_toward(const Context& ctx, Index c, int k, const WorldPoint<2>& x, const WorldPoint<2>& nu, Index previous) {
  const Surface<2>& s2 = ctx.s2;
  const auto around = s2.edge_elements(s2.element_edge(c, (k + 1) % 3));
  if (around.size() == 2) {
    const Index other = around[0].element == c ? around[1].element : around[0].element;
    return other == previous ? invalid_index : other;
  }
  Index best = invalid_index;
  double best_depth = -std::numeric_limits<double>::infinity();
  for (const auto& incidence : around) {
    const Index a = incidence.element;
    if (a == c || a == previous) continue;
    const double depth = pierce_depth(s2, a, x, nu);
    if (best == invalid_index || depth > best_depth) {
      best = a;
      best_depth = depth;
    }
  }
  return best;
}

/// Of the S2 triangles around vertex q, the one whose plane the ray x + m nu pierces deepest
/// inside: where a walk starts if the nearest hit of an S1 vertex's ray is q itself (a lifted
/// copy, a corner shared with S1), which any triangle of the star would stand for.
template <class Context>
Index deepest_around_vertex(const Context& ctx, Index q, const WorldPoint<2>& x, const WorldPoint<2>& nu) {
  Index best = invalid_index;
  double best_depth = -std::numeric_limits<double>::infinity();
  for (const Index a : ctx.s2.vertex_elements(q)) {
    const double depth = pierce_depth(ctx.s2, a, x, nu);
    if (best == invalid_index || depth > best_depth) {
      best = a;
      best_depth = depth;
    }
  }
  return best;
}

/// The walks' cheaper form of the same question, for the ray from local point xi of S1 element t
/// at the crossing of a walk at distance mu: it walks on S2 from triangle `start` (the nearest
/// hit of a ray from an S1 vertex close by; if that hit is S2 vertex `start_vertex`, from the
/// triangle of its star the ray pierces deepest) towards the ray's pierce of that sheet, across the
/// side of the most negative barycentric coordinate, for up to `steps` triangles, and answers
/// whether the ray meets the triangle it arrives in at an admissible distance of smaller rank
/// than mu. A sheet that the start does not lead to is not seen: the test only finds the sheets
/// the rays of the S1 vertices around the crossing meet first.
template <class Context>
bool hidden_along_sheet(const Context& ctx, Index t, const LocalPoint<2>& xi, double mu, Index start,
                        Index start_vertex, int steps = 16) {
  const Barycentric<2> b = barycentric_from_local<2>(xi);
  WorldPoint<2> nu = WorldPoint<2>::Zero();
  for (int k = 0; k < 3; ++k) nu += b(k) * ctx.vertex_directions[ctx.s1.element(t)[k]];
  const WorldPoint<2> x = ctx.s1.world_position(t, xi);
  const Surface<2>& s2 = ctx.s2;
  Index c = start_vertex != invalid_index ? deepest_around_vertex(ctx, start_vertex, x, nu) : start;
  Index previous = invalid_index;
  for (int step = 0; step < steps && c != invalid_index; ++step) {
    const std::optional<LinePierce> pierce = line_through_plane(s2, c, x, nu);
    if (!pierce) return false;  // parallel to the ray
    const std::array<double, 3>& bary = pierce->barycentric;
    const double m = pierce->m, scale = pierce->scale;
    std::array<int, 3> order{0, 1, 2};  // the sides by the barycentric coordinate opposite them
    std::sort(order.begin(), order.end(), [&](int i, int j) { return bary[i] < bary[j]; });
    if (bary[order[0]] >= 0.0) {
      return bary[order[0]] > inside_margin && ctx.rank(m) < (1.0 - nearer_margin) * ctx.rank(mu) &&
             ctx.distance_ok(m, scale) && ctx.normal_ok(nu, s2.element_normal(c)) && ctx.unfolded_in(t, xi, m);
    }
    // Across the side the pierce lies farthest beyond; where S2 ends there, or the walk would go
    // back, across the other side it lies beyond (so that which of two triangles at an edge or
    // vertex the walk starts from does not decide whether it arrives).
    Index next = invalid_index;
    for (const int k : order) {
      if (bary[k] >= 0.0) break;
      const Index across = across_toward(ctx, c, k, x, nu, previous);
      if (across != invalid_index) {
        next = across;
        break;
      }
    }
    previous = c;
    c = next;
  }
  return false;
}

/// The walks' question (EdgeWalker::walk, EdgeFailureReason::hidden): whether a nearer sheet of
/// S2 hides the crossing at place p of S1, distance mu. Where mu's rank exceeds the nearest hit
/// of an S1 vertex of p's edge (or element, or p itself; ProjectionState::nearest_hit_rank) by
/// more than `hidden_slack` times that edge's length, the ray from p is followed on S2 from
/// that vertex's hit (hidden_along_sheet). On one smooth sheet the distance moves less than
/// that between a crossing and the vertices around it, so few crossings are followed (the walks
/// of the armadillo pair take 0.013 s longer, 1 % of its projection).
template <class Context, class State, int d>
bool crossing_hidden_by_nearer_sheet(const Context& ctx, const State& state, const Place<d>& p, double mu) {
  if constexpr (d == 2) {
    if (state.nearest_hit_rank.empty()) return false;
    constexpr double hidden_slack = 0.05;
    const Surface<2>& s1 = ctx.s1;
    std::array<Index, 3> around{invalid_index, invalid_index, invalid_index};
    double length = 0.0;
    Index t = invalid_index;
    LocalPoint<2> xi;
    if (p.kind == PlaceKind::edge) {
      const auto ev = s1.edge_vertices(p.index);
      around = {ev[0], ev[1], invalid_index};
      length = (s1.vertex(ev[1]) - s1.vertex(ev[0])).norm();
      t = s1.edge_elements(p.index).front().element;
      xi = local_on_edge_of(s1, t, p.index, p.t);
    } else if (p.kind == PlaceKind::vertex) {
      around[0] = p.index;
      t = s1.vertex_elements(p.index).front();
      xi = local_of_corner(s1, t, p.index);
      for (int k = 0; k < 3; ++k) length = std::max(length, (s1.corner(t, k) - s1.vertex(p.index)).norm());
    } else {
      t = p.index;
      xi = p.local;
      for (int k = 0; k < 3; ++k) {
        around[k] = s1.element(t)[k];
        length = std::max(length, (s1.corner(t, (k + 1) % 3) - s1.corner(t, k)).norm());
      }
    }
    const double rank = ctx.rank(mu);
    for (const Index v : around) {
      if (v == invalid_index || state.nearest_hit_element[v] == invalid_index) continue;
      if (!(rank > state.nearest_hit_rank[v] + hidden_slack * length)) continue;
      if (hidden_along_sheet(ctx, t, xi, mu, state.nearest_hit_element[v], state.nearest_hit_vertex[v])) return true;
    }
  }
  return false;
}

}  // namespace plmap::projection
