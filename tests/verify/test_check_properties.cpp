// Properties of plmap::verify on families of valid maps: any identity map of a grid, at any
// scale, passes every check; moving any single touching node off its edge is always caught.

#include "test_check_support.hpp"

#include <plmap/core/map_builder.hpp>
#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

namespace plmap {
namespace {

using namespace plmap::test;

std::shared_ptr<const Surface<2>> jittered_grid(int n, double scale, const std::vector<double>& jitter) {
  std::vector<WorldPoint<2>> v;
  std::vector<ElementCorners<2>> e;
  std::size_t k = 0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool inner = i > 0 && j > 0 && i < n && j < n;
      const double dx = inner ? jitter[k++ % jitter.size()] : 0.0;
      const double dy = inner ? jitter[k++ % jitter.size()] : 0.0;
      v.push_back(WorldPoint<2>((i + dx) / n, (j + dy) / n, 0.1 * std::sin(i + 2.0 * j) / n) * scale);
    }
  auto id = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      e.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      e.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return make_surface<2>(std::move(v), std::move(e));
}

RC_GTEST_PROP(VerifyProperties, IdentityMapOfAnyGridAtAnyScalePasses, ()) {
  const int n = *rc::gen::inRange(1, 6);
  const int exponent = *rc::gen::inRange(-6, 7);
  const auto jitter_percent = *rc::gen::container<std::vector<int>>(8, rc::gen::inRange(-30, 31));
  std::vector<double> jitter;
  for (int p : jitter_percent) jitter.push_back(p / 100.0);
  auto s = jittered_grid(n, std::pow(10.0, exponent), jitter);
  MapBuilder<2> b(s, s);
  for (Index v = 0; v < s->vertex_count(); ++v) b.add_vertex_preimage_at_vertex(v, v);
  for (Index t = 0; t < s->element_count(); ++t) b.add_target_element(t);
  const PlMap<2> map = std::move(b).finalize();
  VerifyOptions o;
  o.expect_parametrization = true;
  const VerificationReport report = verify(map, o);
  RC_ASSERT(report.ok());
  RC_ASSERT(std::abs(report.quality->kappa_max - 1.0) < 1e-9);
}

RC_GTEST_PROP(VerifyProperties, TouchingNodeMovedInsideIsCaught, ()) {
  const PlMap<2> base = midpoint_refinement();
  const Index target = *rc::gen::inRange<Index>(3, 6);
  const double inward = *rc::gen::inRange(1, 1000) * 1e-4;  // well beyond the snap tolerance
  const Index n = node_with_target(base, 0, target, NodeType::touching);
  const PlMap<2> bad = modified<2>(base, [&](MapData<2>& m) {
    // Towards the centroid of the reference triangle.
    const LocalPoint<2> centre = lp<2>(1.0 / 3, 1.0 / 3);
    m.node_position[n] += inward * (centre - m.node_position[n]);
  });
  RC_ASSERT(check_structure(bad).violation_count("structure", "node_position") > 0u);
}

}  // namespace
}  // namespace plmap
