#pragma once
// The rim of D at a bound of the band of distances (projection_rim.cpp) is where the rays'
// distance to one sheet of S2 reaches the bound. It bounds D only where no nearer sheet of S2
// hides it: otherwise the points on both sides of it take the nearer hit (the bones of a joint
// under a loose distance limit, where one bone's level set runs beside the next bone, whose
// pieces the rim edges would cross and cost faces).

#include "rim_geometry.hpp"

#include <plmap/core/surface.hpp>

#include <array>
#include <cmath>
#include <optional>

namespace plmap::projection {

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
  for (const Index c : ctx.s2_index->within(0.5 * (p0 + p1), reach)) {
    if (c == skip) continue;
    const std::array<WorldPoint<2>, 3> tri = {ctx.s2.corner(c, 0), ctx.s2.corner(c, 1), ctx.s2.corner(c, 2)};
    const std::optional<Pierce> p = segment_through_triangle(p0, p1, tri);
    if (!p || p->barycentric[0] < 0.0 || p->barycentric[1] < 0.0 || p->barycentric[2] < 0.0) continue;
    const double mu_c = from + p->s * (mu - from);
    if (!(ctx.rank(mu_c) < (1.0 - 1e-9) * rank_of_bound)) continue;
    if (ctx.normal_ok(nu, ctx.s2.element_normal(c)) && ctx.unfolded_in(t, xi, mu_c)) return true;
  }
  return false;
}

}  // namespace plmap::projection
