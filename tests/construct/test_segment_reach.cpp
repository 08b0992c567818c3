// The restart searches skip S1 edges and elements that lie out of reach of the rest of an S2
// edge under the distance limit (construct/src/segment_reach.hpp). The skip must never drop a
// crossing the search would accept: an edge crossing whose |mu| is within the limit, or a pierce
// of an element moved to a distance within the limit. Checked on constructed configurations
// where such a crossing exists by design, and against the solvers' own answers on random ones.
#include "segment_reach.hpp"

#include <plmap/solvers/projection_systems.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>

using namespace plmap;
using namespace plmap::projection;

namespace {

double uniform(double lo, double hi) {
  return lo + (hi - lo) * (*rc::gen::inRange(0, 1 << 20)) / double(1 << 20);
}

WorldPoint<2> random_point(double range) {
  return WorldPoint<2>(uniform(-range, range), uniform(-range, range), uniform(-range, range));
}

WorldPoint<2> random_unit() {
  for (;;) {
    const WorldPoint<2> v = random_point(1.0);
    if (v.norm() > 0.1) return v.normalized();
  }
}

}  // namespace

TEST(SegmentReach, WithoutADistanceLimitNothingIsOutOfReach) {
  const SegmentReach<2> rest(std::numeric_limits<double>::infinity(), 0.0, WorldPoint<2>(0, 0, 0),
                             WorldPoint<2>(1, 0, 0));
  EXPECT_FALSE(rest.out_of_reach(WorldPoint<2>(0, 1e9, 0), 1.0));
}

TEST(SegmentReach, ABallIsOutOfReachOnlyBeyondItsRadiusAndTheBandsReach) {
  // the segment along the x axis from 0 to 1, reach 0.5: a ball of radius 0.25 around a point at
  // distance 0.75 touches the band; farther, it is out of reach
  const SegmentReach<2> rest(0.5, 0.0, WorldPoint<2>(0, 0, 0), WorldPoint<2>(1, 0, 0));
  EXPECT_FALSE(rest.out_of_reach(WorldPoint<2>(0.5, 0.75, 0), 0.25));
  EXPECT_FALSE(rest.out_of_reach(WorldPoint<2>(0.5, 0.7, 0), 0.25));
  EXPECT_TRUE(rest.out_of_reach(WorldPoint<2>(0.5, 0.76, 0), 0.25));
  // beyond the segment's end, the distance is to the end point
  EXPECT_FALSE(rest.out_of_reach(WorldPoint<2>(1.7, 0, 0), 0.25));
  EXPECT_TRUE(rest.out_of_reach(WorldPoint<2>(1.8, 0, 0), 0.25));
  EXPECT_TRUE(rest.out_of_reach(WorldPoint<2>(-0.8, 0, 0), 0.25));
}

// An S2 edge built to cross the S1 edge's ray at (lambda, mu, eta): where |mu| is within the
// limit, the S1 edge (the ball around its midpoint through its ends) is never out of reach; and
// wherever it is, the closed-form crossing the fold-exit search uses has no admissible root.
RC_GTEST_PROP(SegmentReachProperties, NoEdgeCrossingWithinTheLimitIsOutOfReach, ()) {
  const double scale = std::pow(10.0, uniform(-3.0, 3.0));
  EdgeCrossingSystem sys;
  sys.edge = {scale * random_point(1.0), scale * random_point(1.0)};
  // the tight cases too: rays along the S1 edge from one of its ends, and mu at the limit
  const bool along_the_edge = *rc::gen::element(false, false, true);
  const WorldPoint<2> e = (sys.edge[1] - sys.edge[0]).normalized();
  sys.directions = along_the_edge ? std::array<WorldPoint<2>, 2>{e, e} : std::array<WorldPoint<2>, 2>{random_unit(), random_unit()};
  const double lambda = *rc::gen::element(0.0, 1.0, uniform(0.0, 1.0)), eta = uniform(0.0, 1.0);
  const double mu = scale * uniform(-2.0, 2.0);
  const WorldPoint<2> hit = sys.edge[0] + lambda * (sys.edge[1] - sys.edge[0]) +
                            mu * (sys.directions[0] + lambda * (sys.directions[1] - sys.directions[0]));
  const WorldPoint<2> g = scale * random_point(1.0);
  sys.target = {hit - eta * g, hit + (1.0 - eta) * g};
  const double limit = std::abs(mu) * *rc::gen::element(1.0, uniform(0.5, 2.0));
  // the whole edge, or the stretch after a stop somewhere before the hit
  const double after = *rc::gen::element(0.0, eta * uniform(0.0, 1.0));
  const WorldPoint<2> from = sys.target[0] + after * (sys.target[1] - sys.target[0]);
  const SegmentReach<2> rest(limit, 1e-12 * 3.0 * scale, from, sys.target[1]);
  const WorldPoint<2> mid = 0.5 * (sys.edge[0] + sys.edge[1]);
  const bool out = rest.out_of_reach(mid, 0.5 * (sys.edge[1] - sys.edge[0]).norm());
  RC_CLASSIFY(out, "out of reach");
  if (std::abs(mu) <= limit) RC_ASSERT(!out);
  if (out)
    if (const auto root = sys.root_on_the_edges()) RC_ASSERT(std::abs((*root)(1)) > limit);
}

// A segment built to pierce an S1 triangle moved to a distance within the limit: the ball
// around the unmoved triangle (centroid, farthest corner) is never out of its reach.
RC_GTEST_PROP(SegmentReachProperties, NoPierceOfAMovedElementWithinTheLimitIsOutOfReach, ()) {
  const double scale = std::pow(10.0, uniform(-3.0, 3.0));
  std::array<WorldPoint<2>, 3> corners{scale * random_point(1.0), scale * random_point(1.0), scale * random_point(1.0)};
  const double limit = scale * uniform(0.01, 2.0);
  const double mu = limit * uniform(-1.0, 1.0);
  std::array<WorldPoint<2>, 3> moved;
  for (int k = 0; k < 3; ++k) moved[k] = corners[k] + mu * random_unit();
  const double b0 = uniform(0.01, 0.98), b1 = uniform(0.01, 0.99 - b0);
  const WorldPoint<2> x = b0 * moved[0] + b1 * moved[1] + (1.0 - b0 - b1) * moved[2];
  const WorldPoint<2> g = scale * random_point(1.0);
  const double s = uniform(0.0, 1.0);
  const WorldPoint<2> a = x - s * g, b = x + (1.0 - s) * g;
  WorldPoint<2> centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
  double radius = 0.0;
  for (const auto& c : corners) radius = std::max(radius, (c - centroid).norm());
  const SegmentReach<2> rest(limit, 1e-12 * 3.0 * scale, a, b);
  RC_ASSERT(!rest.out_of_reach(centroid, radius));
}
