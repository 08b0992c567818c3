#pragma once
// Normal projection, edge walks: where an S2 edge comes back into the admissible band of
// distances after a walk stopped on the rim (the edge passed behind S1 there, or beyond the
// distance limit).
//
// The first point beyond the rim point, and before `before`, at which the edge pierces an S1
// element from behind (or, for a bound mu = m of the band, the element moved to distance m, from
// beyond it: rim_geometry.hpp), searched in the elements within search_limits.fold_exit_reach
// rings (sharing a vertex) around the rim point's element. Between the two pierces the edge lies
// outside the band; beyond the second, its preimage goes on from a rim node inside that element. The
// S1-edge crossings that the fold-exit search (fold_reentry.hpp) looks for lie one element
// farther on, and a walk from that crossing that reaches the second vertex leaves no walk back
// from there to find the stretch between the pierce and the crossing: the faces next to it
// mapped into two S2 triangles and left D (on the bones pair, a fifth of the area not covered).

#include "fold_reentry.hpp"
#include "projection_edge_walks.hpp"
#include "rim_geometry.hpp"
#include "seen_indices.hpp"
#include "segment_reach.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

namespace plmap::projection {

/// The re-entry of the S2 edge qa -> qb (oriented as the walk ran; its parameters measured from
/// qa) beyond `rim`, the rim point where the walk stopped, and before `before`; none if the edge
/// does not come back into the band (for mu = 0: out in front of S1) within the search's reach.
inline std::optional<RimPoint<2>> rim_reentry(const ProjectionContext<2>& ctx, const RimPoint<2>& rim,
                                              const WorldPoint<2>& qa, const WorldPoint<2>& qb, double before) {
  const auto& limits = ctx.options.search_limits;
  const double after = rim.eta;
  const WorldPoint<2> from = qa + after * (qb - qa);
  const SegmentReach<2> rest(ctx, from, qa + std::min(before, 1.0) * (qb - qa));  // no pierce beyond is kept
  // the rings of elements around the rim point's element
  SeenIndices seen;
  seen.insert(rim.element);
  std::vector<Index> all{rim.element}, ring{rim.element}, next;
  const int rings = static_cast<int>(std::ceil(limits.fold_exit_reach));
  for (int r = 0; r < rings; ++r) {
    next.clear();
    for (Index t : ring)
      for (Index v : ctx.s1.element(t))
        for (Index n : ctx.s1.vertex_elements(v)) next.push_back(n);
    take_unseen_into(next, seen, ring);
    all.insert(all.end(), ring.begin(), ring.end());
  }
  // in element order: of two pierces at the same parameter, the element first in it wins
  std::sort(all.begin(), all.end());
  std::optional<RimPoint<2>> best;
  for (Index t : all) {
    // the rim point's element holds the edge's rim node already (one per element and S2 edge)
    if (t == rim.element) continue;
    // no level of the band (|mu| <= distance_limit) reaches the rest of the edge from t
    WorldPoint<2> centroid = WorldPoint<2>::Zero();
    for (int k = 0; k < 3; ++k) centroid += ctx.s1.corner(t, k);
    centroid /= 3.0;
    double radius = 0.0;
    for (int k = 0; k < 3; ++k) radius = std::max(radius, (ctx.s1.corner(t, k) - centroid).norm());
    if (rest.out_of_reach(centroid, radius)) continue;
    for (int level = 0; level < ctx.rim_level_count(); ++level) {
      const auto tri = ctx.corners_at_distance(t, ctx.rim_level(level).mu);
      const std::optional<Pierce> p = segment_through_triangle(from, qb, tri);
      if (!p || !strictly_inside(p->barycentric, 1e3 * ctx.options.snap_tolerance)) continue;
      const double at = after + p->s * (1.0 - after);
      if (!(at > after + limits.edge_parameter_slack) || !(at < before - limits.edge_parameter_slack) ||
          !(at < 1.0 - limits.end_parameter_slack))
        continue;
      if (best && best->eta <= at) continue;
      // into the band (for mu = 0: from behind S1 to its front)
      const LocalPoint<2> xi(p->barycentric[1], p->barycentric[2]);
      if (ctx.direction_into_band(t, level, xi, qa, qb) != 1) continue;
      best = RimPoint<2>{t, xi, at, level};
    }
  }
  return best;
}

}  // namespace plmap::projection
