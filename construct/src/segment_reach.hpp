#pragma once
// Normal projection, restart searches: which parts of S1 cannot reach a stretch of an S2 edge
// under the distance limit.
//
// After a walk stops (at a fold, on the rim, at the distance limit), fold_reentry.hpp and
// rim_reentry.hpp look for where the S2 edge comes back, by solving for a crossing on every S1
// edge, or piercing every S1 element, within a few rings around the stop. A crossing there has
// |mu| <= distance_limit, and its ray moves |mu| |nu| <= ctx.band_reach from its point of S1, so
// an S1 edge or element that lies farther than band_reach from the rest of the S2 edge cannot
// give one. With a distance limit most of them do (on the armadillo pair at --max-distance 0.35,
// 76k S2 edges stop at the limit and the searches after them took a third of the projection),
// and the test is far cheaper than the solve it saves. The answers are the same: only candidates
// that the searches would reject are skipped.

#include "projection_context.hpp"

#include <algorithm>
#include <cmath>

namespace plmap::projection {

/// The stretch [a, b] of an S2 edge that a restart search may find a crossing on, and the test
/// whether a ball of S1 lies out of its reach.
template <int d>
class SegmentReach {
 public:
  /// `band_reach` and `coordinate_rounding` as in ProjectionContext (infinite reach: no limit).
  SegmentReach(double band_reach, double coordinate_rounding, const WorldPoint<d>& a, const WorldPoint<d>& b)
      : a_(a), ab_(b - a), squared_length_(ab_.squaredNorm()), band_reach_(band_reach) {
    // Margins: 1e-5 of the lengths involved covers the slack with which the crossing solvers
    // accept parameters just outside [0, 1] (1e-6), far above rounding; the coordinates' own
    // rounding is added for segments and balls near a point.
    margin_ = 1e-5 * (band_reach_ + std::sqrt(squared_length_)) + coordinate_rounding;
  }
  SegmentReach(const ProjectionContext<d>& ctx, const WorldPoint<d>& a, const WorldPoint<d>& b)
      : SegmentReach(ctx.band_reach, ctx.coordinate_rounding, a, b) {}

  /// Whether no point within `radius` of `center` has an admissible hit on the stretch. Always
  /// false without a distance limit.
  bool out_of_reach(const WorldPoint<d>& center, double radius) const {
    if (!std::isfinite(band_reach_)) return false;
    const double s = squared_length_ > 0.0 ? std::clamp((center - a_).dot(ab_) / squared_length_, 0.0, 1.0) : 0.0;
    const double reach = (radius + band_reach_) * (1.0 + 1e-5) + margin_;
    return (a_ + s * ab_ - center).squaredNorm() > reach * reach;
  }

 private:
  WorldPoint<d> a_, ab_;
  double squared_length_, band_reach_, margin_ = 0.0;
};

}  // namespace plmap::projection
