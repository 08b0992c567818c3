// A repeated quadrilateral pass (smooth.cpp redoes the pass with more frozen edges when the
// rebuilt map raised κ somewhere) solves only near the newly frozen edges and replays the other
// steps from the previous pass's records (run_quadrilateral_pass, construct/src/quad_smoothing).
// It must give exactly, bit for bit, the graph of a pass from scratch with the same frozen edges.

#include "preimage_graph.hpp"
#include "quad_smoothing.hpp"
#include "region_condition.hpp"
#include "simplified_spheres.hpp"

#include <plmap/construct/simplify.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>
#include <plmap/verify/generators/random_maps.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>

namespace plmap {
namespace {

using smoothing::DomainPlace;
using smoothing::PreimageGraph;
using smoothing::QuadPassTally;
using smoothing::QuadSmoother;
using smoothing::QuadStepRecord;

bool same_graph(const PreimageGraph& a, const PreimageGraph& b) {
  if (a.vertex.size() != b.vertex.size() || a.crossings.size() != b.crossings.size()) return false;
  for (std::size_t v = 0; v < a.vertex.size(); ++v) {
    const DomainPlace &p = a.vertex[v], &q = b.vertex[v];
    if (p.kind != q.kind || p.where != q.where || p.edge_parameter != q.edge_parameter || p.local != q.local) return false;
  }
  for (std::size_t e = 0; e < a.crossings.size(); ++e) {
    if (a.crossings[e].size() != b.crossings[e].size()) return false;
    for (std::size_t i = 0; i < a.crossings[e].size(); ++i) {
      const EdgeCrossing &c = a.crossings[e][i], &d = b.crossings[e][i];
      if (c.domain_edge != d.domain_edge || c.domain_parameter != d.domain_parameter ||
          c.target_parameter != d.target_parameter)
        return false;
    }
  }
  return true;
}

bool same_tally(const QuadPassTally& a, const QuadPassTally& b) {
  return a.smoothed == b.smoothed && a.nodes_moved == b.nodes_moved && a.nodes_crossed == b.nodes_crossed &&
         a.max_displacement == b.max_displacement && a.skipped_by_reason == b.skipped_by_reason;
}

RC_GTEST_PROP(QuadrilateralPassReplay, RepeatedPassEqualsAPassFromScratch, ()) {
  const int subdivisions = *rc::gen::inRange(1, 3);
  const int jitter_percent = *rc::gen::inRange(0, 25);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const int percent = *rc::gen::inRange(10, 60);
  RC_LOG() << "icosphere " << subdivisions << " jitter " << jitter_percent << "% seed " << seed << " to " << percent << "%\n";
  const SimplifyResult s = simplify_test::simplified_sphere(subdivisions, jitter_percent / 100.0, seed, percent);
  std::string why;
  const auto start = PreimageGraph::from_map(s.map, &why);
  RC_ASSERT(start.has_value());
  const Surface<2>& s1 = s.map.domain();
  const auto weights = make_smoothing_weights(*rc::gen::elementOf(std::vector<std::string>{"floater", "mean-value", "uniform"}));
  const std::size_t edges = static_cast<std::size_t>(s1.edge_count());

  // the first pass, with some edges frozen already
  std::vector<char> frozen(edges, 0);
  for (std::size_t e = 0; e < edges; ++e) frozen[e] = *rc::gen::inRange(0, 100) < 5;
  PreimageGraph first = *start;
  QuadSmoother first_smoother(first, s1, s.map.target(), weights);
  const smoothing::EdgesInElement start_index = first_smoother.edges_in_element();
  std::vector<QuadStepRecord> records;
  const QuadPassTally first_tally = smoothing::run_quadrilateral_pass(first_smoother, s1, frozen, nullptr, nullptr, records);

  // freeze a few more, as smooth.cpp does around an element whose κ rose
  std::vector<char> newly(edges, 0);
  const int more = *rc::gen::inRange(1, 4);
  for (int k = 0; k < more; ++k) {
    const std::size_t e = static_cast<std::size_t>(*rc::gen::inRange<Index>(0, s1.edge_count()));
    if (!frozen[e]) newly[e] = frozen[e] = 1;
  }
  PreimageGraph scratch = *start, replayed = *start;
  QuadSmoother scratch_smoother(scratch, s1, s.map.target(), weights);
  QuadSmoother replay_smoother(replayed, s1, s.map.target(), weights, &start_index);
  std::vector<QuadStepRecord> scratch_records, replay_records;
  const QuadPassTally from_scratch =
      smoothing::run_quadrilateral_pass(scratch_smoother, s1, frozen, nullptr, nullptr, scratch_records);
  const QuadPassTally repeated = smoothing::run_quadrilateral_pass(replay_smoother, s1, frozen, &records, &newly, replay_records);
  RC_CLASSIFY(repeated.replayed > 0, "some steps replayed");
  RC_CLASSIFY(first_tally.smoothed != from_scratch.smoothed, "the frozen edges changed the result");
  RC_ASSERT(same_graph(scratch, replayed));
  RC_ASSERT(same_tally(from_scratch, repeated));
  RC_ASSERT(scratch_smoother.uniform_fallbacks() == replay_smoother.uniform_fallbacks());
  RC_ASSERT(repeated.solved + repeated.replayed == from_scratch.solved);
  // MapBuilder closes each element from its own part of the graph: where the repeated pass says
  // nothing changed, the rebuilt maps have the same κ (smooth.cpp re-evaluates only the others)
  FinalizeReport built;
  const PlMap<2> first_map = first.to_map(s.map.domain_ptr(), s.map.target_ptr(), &built);
  const PlMap<2> repeated_map = replayed.to_map(s.map.domain_ptr(), s.map.target_ptr(), &built);
  for (Index t = 0; t < s1.element_count(); ++t) {
    if (!repeated.changed[static_cast<std::size_t>(t)]) {
      RC_ASSERT(smoothing::worst_condition_of_element(first_map, t) == smoothing::worst_condition_of_element(repeated_map, t));
    }
  }
  // and the records it leaves serve the next repetition just as well
  for (std::size_t e = 0; e < edges; ++e) {
    RC_ASSERT(replay_records[e].wrote == scratch_records[e].wrote);
    const char* a = replay_records[e].outcome.skipped;
    const char* b = scratch_records[e].outcome.skipped;
    const bool same_reason = (a == nullptr && b == nullptr) || (a != nullptr && b != nullptr && std::string(a) == b);
    RC_ASSERT(same_reason);
  }
}

}  // namespace
}  // namespace plmap
