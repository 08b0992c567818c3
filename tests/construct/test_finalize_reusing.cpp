// MapBuilder::finalize_reusing (core/src/finalize_reuse.hpp), as the smoothing's repeated
// quadrilateral pass uses it through PreimageGraph::to_map_reusing: after steps that edit the
// graph on a few S1 elements, the map built with every other element copied from the map of the
// graph before must equal the map built from scratch, array for array (stored arrays and stored
// graph). And a reuse the graph contradicts by an element's node count is refused.

#include "preimage_graph.hpp"
#include "quad_smoothing.hpp"
#include "simplified_spheres.hpp"

#include <plmap/construct/simplify.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <vector>

namespace plmap {
namespace {

using smoothing::PreimageGraph;
using smoothing::QuadSmoother;
using simplify_test::simplified_sphere;

struct EditedGraph {
  SimplifyResult s;
  PreimageGraph before, after;
  std::vector<char> changed;  ///< per S1 element: a kept step edited it
};

/// A random simplified sphere's graph, and the graph after steps on random edges.
EditedGraph random_edited_graph() {
  EditedGraph g{simplified_sphere(*rc::gen::inRange(1, 3), *rc::gen::inRange(0, 25) / 100.0,
                                  *rc::gen::arbitrary<std::uint32_t>(), *rc::gen::inRange(10, 60)),
                {}, {}, {}};
  std::string why;
  auto graph = PreimageGraph::from_map(g.s.map, &why);
  RC_ASSERT(graph.has_value());
  g.before = *graph;
  const Surface<2>& s1 = g.s.map.domain();
  g.changed.assign(static_cast<std::size_t>(s1.element_count()), 0);
  QuadSmoother smoother(*graph, s1, g.s.map.target(), make_smoothing_weights("mean-value"));
  const int steps = *rc::gen::inRange(1, 12);
  for (int i = 0; i < steps; ++i) {
    const Index e = *rc::gen::inRange<Index>(0, s1.edge_count());
    if (!smoother.has_quadrilateral(e)) continue;
    if (smoother.smooth(e).skipped != nullptr) continue;
    for (const auto& inc : s1.edge_elements(e)) g.changed[static_cast<std::size_t>(inc.element)] = 1;
  }
  g.after = *graph;
  return g;
}

RC_GTEST_PROP(FinalizeReusing, CopiedElementsGiveTheMapBuiltFromScratch, ()) {
  const EditedGraph g = random_edited_graph();
  const auto& s = g.s.map;
  const PlMap<2> previous = g.before.to_map(s.domain_ptr(), s.target_ptr(), nullptr);
  const PlMap<2> scratch = g.after.to_map(s.domain_ptr(), s.target_ptr(), nullptr);
  // every unchanged element may be copied; some of them are closed anyway (a subset is reused)
  std::vector<char> reuse(g.changed.size());
  for (std::size_t t = 0; t < reuse.size(); ++t) reuse[t] = !g.changed[t] && *rc::gen::inRange(0, 4) != 0;
  RC_CLASSIFY(std::count(g.changed.begin(), g.changed.end(), 1) > 0, "edited");
  const PlMap<2> reused = g.after.to_map_reusing(s.domain_ptr(), s.target_ptr(), previous, reuse, nullptr);
  RC_ASSERT(reused.stored() == scratch.stored());
  RC_ASSERT(reused.stored_graph() == scratch.stored_graph());
}

RC_GTEST_PROP(FinalizeReusing, AnElementWhoseNodeCountChangedIsNotCopied, ()) {
  const EditedGraph g = random_edited_graph();
  const auto& s = g.s.map;
  const PlMap<2> previous = g.before.to_map(s.domain_ptr(), s.target_ptr(), nullptr);
  const PlMap<2> scratch = g.after.to_map(s.domain_ptr(), s.target_ptr(), nullptr);
  const auto& a = previous.stored().node_begin;
  const auto& b = scratch.stored().node_begin;
  bool differs = false;
  for (std::size_t t = 0; t + 1 < a.size(); ++t) differs = differs || a[t + 1] - a[t] != b[t + 1] - b[t];
  RC_PRE(differs);
  const std::vector<char> all(g.changed.size(), 1);
  RC_ASSERT_THROWS_AS(g.after.to_map_reusing(s.domain_ptr(), s.target_ptr(), previous, all, nullptr), BuilderError);
}

}  // namespace
}  // namespace plmap
