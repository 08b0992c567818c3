// finalize() for triangle surfaces (d = 2): the phases of finalize_phases.hpp in order, with the
// rounds that drop conflicting S2 edges (BuilderOptions::drop_conflicting_edges) and the vote on
// the map's orientation.

#include "finalize_assembly.hpp"
#include "finalize_buckets.hpp"
#include "finalize_closure.hpp"
#include "finalize_conflicts.hpp"
#include "finalize_joining.hpp"
#include "finalize_phases.hpp"
#include "finalize_rechecks.hpp"
#include "finalize_region_maps.hpp"
#include "finalize_reuse.hpp"
#include "map_arrays.hpp"

#include <plmap/core/parallel_ranges.hpp>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <atomic>
#include <exception>
#include <span>
#include <vector>
#include <utility>

namespace plmap::detail {

namespace {

using ElementFailures = std::vector<std::pair<Index, std::exception_ptr>>;

/// Closes and assembles every element, in blocks of consecutive elements, one part of the map
/// per block. Elements are independent, so the blocks run on all threads; errors are reported
/// for the smallest element that has one, whatever the thread count.
class ClosingPass {
 public:
  ClosingPass(BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where, unsigned threads,
              const ElementReuse* reuse)
      : in_(in), where_(where), threads_(threads), blocks_(block_count(in.s1.element_count(), threads)), reuse_(reuse) {}

  /// Closes and assembles every element with the given orientation. Returns the elements that
  /// could not be closed, in element order. Without drop_conflicting_edges it stops a block at
  /// its first failure (finalize then throws).
  ElementFailures run(int orientation) {
    const std::vector<Index> first = block_starts();
    const bool drop = in_.options.drop_conflicting_edges;
    workspaces_.clear();
    workspaces_.resize(blocks_);
    for (ClosureWorkspace& w : workspaces_) w.corner_maps_wanted = !deferred_region_maps();
    parts_.assign(blocks_, MapData<2>{});
    graph_elements_.assign(blocks_, {});
    face_counts_.assign(blocks_, FaceCounts{});
    std::vector<ElementFailures> failures(blocks_);
    // The first block's part becomes the joined map (join_parts): it takes room for all blocks.
    std::vector<PartBounds> bounds(blocks_);
    parallel_for_pieces(blocks_, blocks_, threads_, [&](std::size_t k, std::size_t, std::size_t) {
      bounds[k] = part_bounds(in_, where_, first[k], first[k + 1]);
    });
    PartBounds whole;
    for (const PartBounds& b : bounds) whole += b;
    omitted_weights_.assign(deferred_region_maps() ? blocks_ : 0, {});
    // After a failure in any block every part is discarded (finalize drops what failed and runs
    // the pass again, or throws): from then on every block only collects the failures, with
    // close_graph, which throws exactly where close_element does. (A block that went on
    // assembling after another block's failure took as long as a whole pass: on the femur pair
    // with two threads, the first block failed early and waited for the second.)
    std::atomic<bool> failed_somewhere{false};
    parallel_for_pieces(blocks_, blocks_, threads_, [&](std::size_t k, std::size_t, std::size_t) {
      const Index begin = first[k], end = first[k + 1];
      AssemblyCursor cursor;
      if (deferred_region_maps()) cursor.omitted_weights = &omitted_weights_[k];
      size_part(bounds[k], k == 0 ? whole : bounds[k], parts_[k], cursor);
      for (Index t = begin; t < end; ++t) {
        try {
          const bool assembling = !failed_somewhere.load(std::memory_order_relaxed);
          if (reuse_ != nullptr && reuse_->reuses(t)) {  // copied, not closed (finalize_reuse.hpp)
            if (assembling) reuse_->copy_element(in_, where_, t, parts_[k], cursor);
            continue;
          }
          if (assembling) {
            close_element(in_, where_, t, workspaces_[k], orientation);
            assemble_element(in_, workspaces_[k], orientation, parts_[k], cursor);
          } else {
            close_graph(in_, where_, t, workspaces_[k]);
          }
        } catch (...) {
          failures[k].emplace_back(t, std::current_exception());
          failed_somewhere.store(true, std::memory_order_relaxed);
          if (!drop) return;  // finalize throws: the part and its count are not used
        }
      }
      face_counts_[k] = {cursor.reversed_faces, cursor.unmapped_faces, cursor.left_out, std::move(cursor.split_targets),
                         std::move(cursor.outside_split_regions), static_cast<Index>(cursor.regions)};
      trim_part(cursor, parts_[k]);
      for (Index& t : cursor.graph_elements) t += begin;  // numbered in the block
      graph_elements_[k] = std::move(cursor.graph_elements);
    });
    ElementFailures failed;
    for (auto& list : failures) failed.insert(failed.end(), list.begin(), list.end());
    return failed;
  }

  /// The given elements (sorted) that cannot be closed, in element order; nothing is assembled.
  ElementFailures failures_among(std::span<const Index> elements) {
    if (workspaces_.size() < blocks_) workspaces_.resize(blocks_);
    std::vector<ElementFailures> failures(blocks_);
    parallel_for_pieces(elements.size(), blocks_, threads_, [&](std::size_t k, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        try {
          close_graph(in_, where_, elements[i], workspaces_[k]);
        } catch (...) {
          failures[k].emplace_back(elements[i], std::current_exception());
        }
      }
    });
    ElementFailures failed;
    for (auto& list : failures) failed.insert(failed.end(), list.begin(), list.end());
    return failed;
  }

  /// The orientation the closed elements vote for (triangles along minus against).
  int voted_orientation() const {
    long long votes = 0;
    for (const auto& w : workspaces_) votes += w.votes;
    return votes >= 0 ? 1 : -1;
  }
  /// FinalizeReport::reversed_faces, unmapped_faces, left_out, split_targets and
  /// regions_split_off_outside_faces of the last run, over all blocks.
  struct FaceCounts {
    Index reversed = 0, unmapped = 0;
    AssemblyCursor::LeftOutTally left_out;
    std::vector<Index> split_targets;  // sorted, each once
    std::vector<Index> outside_split_regions;  // sorted; per block: numbered in the block
    Index regions = 0;  // per block: the regions it assembled
  };
  FaceCounts face_counts() const {
    FaceCounts sum;
    for (const FaceCounts& c : face_counts_) {  // in block order: the same sums for every thread count
      sum.reversed += c.reversed;
      sum.unmapped += c.unmapped;
      sum.left_out += c.left_out;
      sum.split_targets.insert(sum.split_targets.end(), c.split_targets.begin(), c.split_targets.end());
      // the parts are joined in block order: a block's regions follow those of the blocks before
      for (Index r : c.outside_split_regions) sum.outside_split_regions.push_back(sum.regions + r);
      sum.regions += c.regions;
    }
    std::sort(sum.split_targets.begin(), sum.split_targets.end());
    sum.split_targets.erase(std::unique(sum.split_targets.begin(), sum.split_targets.end()), sum.split_targets.end());
    return sum;
  }
  std::vector<MapData<2>>& parts() { return parts_; }
  /// The elements that keep their graph (AssembledMap), over all blocks of the last run.
  std::vector<Index> graph_elements() const {
    std::vector<Index> all;
    for (const auto& list : graph_elements_) all.insert(all.end(), list.begin(), list.end());
    return all;
  }
  unsigned threads() const { return threads_; }

  /// Whether the assembly leaves region_map out (finalize_region_maps.hpp): not where elements
  /// are copied from a previous map, whose region maps are copied with them.
  bool deferred_region_maps() const { return reuse_ == nullptr; }
  /// The omitted image weights of the last run, joined in the order of the parts' nodes (the
  /// first part's array has room for all of them, as its map arrays do).
  std::vector<double> joined_omitted_weights() {
    if (omitted_weights_.empty()) return {};
    std::vector<double> all = std::move(omitted_weights_[0]);
    for (std::size_t k = 1; k < omitted_weights_.size(); ++k) {
      all.insert(all.end(), omitted_weights_[k].begin(), omitted_weights_[k].end());
      std::vector<double>().swap(omitted_weights_[k]);
    }
    omitted_weights_.clear();
    return all;
  }
  /// Frees the closure workspaces (slot_of_node alone has an entry per builder node) once the
  /// pass will not run again.
  void release_workspaces() { std::vector<ClosureWorkspace>().swap(workspaces_); }

 private:
  /// One block per thread, and at least 64 elements per block. (More blocks than threads would
  /// balance by taking turns, but the smaller parts fall under malloc's mmap threshold, and the
  /// memory they give back after the join stays in the process: 170 MiB more peak on the 200k
  /// planes with four blocks per thread.)
  static unsigned block_count(Index elements, unsigned threads) {
    return std::max(1u, std::min<unsigned>(resolve_thread_count(threads),
                                           static_cast<unsigned>(std::max<Index>(1, elements / 64))));
  }

  /// The first element of each block, and the element count at the end: blocks of about the same
  /// work, measured by the nodes and graph pieces in and around each element (halves by element
  /// count cost 0.52 and 0.63 s of CPU on the 200k planes).
  std::vector<Index> block_starts() const {
    const Index n1 = in_.s1.element_count();
    std::vector<Index> first(blocks_ + 1, n1);
    first[0] = 0;
    if (blocks_ == 1) return first;
    auto work = [&](Index t) {
      std::size_t w = 1 + where_.interior_nodes[t].size() + where_.element_segments[t].size();
      for (int k = 0; k < 3; ++k) w += where_.edge_nodes[in_.s1.element_edge(t, k)].size();
      return w;
    };
    std::size_t total = 0;
    for (Index t = 0; t < n1; ++t) total += work(t);
    std::size_t done = 0;
    unsigned k = 1;
    for (Index t = 0; t < n1 && k < blocks_; ++t) {
      done += work(t);
      while (k < blocks_ && done * blocks_ >= total * k) first[k++] = t + 1;
    }
    return first;
  }

  BuilderContents<2>& in_;
  const NodesAndSegmentsByPlace<2>& where_;
  unsigned threads_;
  unsigned blocks_;
  std::vector<ClosureWorkspace> workspaces_;
  std::vector<MapData<2>> parts_;
  std::vector<FaceCounts> face_counts_;  // per block
  std::vector<std::vector<Index>> graph_elements_;  // per block
  std::vector<std::vector<double>> omitted_weights_;  // per block, with deferred region maps
  const ElementReuse* reuse_;
};

}  // namespace

/// The closing pass first-touches the whole map while the builder is still alive: that is the
/// peak of a projection. What the callers freed before it (the projection's plans, the buckets'
/// cursors, the sample's workspace) stays with malloc, scattered over the heap, where the map's
/// large arrays (mmap'ed) cannot use it: glibc gives it back to the system (2.3 MiB of the 200k
/// plane pair's peak, 2.7 MiB of the armadillo pair's).
void give_freed_heap_back() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

namespace {

/// The orientation guess: the vote of up to 64 elements spread over S1.
int sampled_orientation(const BuilderContents<2>& in, const NodesAndSegmentsByPlace<2>& where) {
  ClosureWorkspace w;
  w.corner_maps_wanted = false;  // only the faces' signs vote
  const Index n1 = in.s1.element_count();
  const Index stride = std::max<Index>(1, n1 / 64);
  for (Index t = 0; t < n1; t += stride) {
    try {
      close_element(in, where, t, w, 0);
    } catch (...) {
      // an element that cannot be closed does not vote; the full pass reports it
    }
  }
  return w.votes >= 0 ? 1 : -1;
}

}  // namespace

AssembledMap finalize_triangles(BuilderContents<2>& in, FinalizeReport* report, const ElementReuse* reuse) {
  const Index n1 = in.s1.element_count();
  DroppedEdges dropped(in.edge_inserted, report, in.segments.size());
  NodesAndSegmentsByPlace<2> where;
  where.build(in, dropped);
  if (report) *report = FinalizeReport{};
  // An element whose graph has crossing edges (or an edge through another node) cannot be
  // closed. Unless asked to drop the S2 edges involved, that is an error; otherwise their
  // stretches on that element are dropped and the elements where something changed are closed
  // again (each round removes at least one segment; see the loop below). The rest of each
  // preimage stays: it ends at the element's boundary.
  const bool drop = in.options.drop_conflicting_edges;
  // Minimal embedding (DESIGN §4.3): the preimage of an S2 edge meets an S1 element in at most
  // one connected piece; with drop_conflicting_edges an edge that does not loses its stretch on
  // that element, like one that crosses another.
  if (drop && drop_split_preimages(in, where, dropped)) where.build(in, dropped);
  // Only faces mapped with the map's orientation become regions, and that orientation is voted
  // on by all elements: the pass assembles with a guess (the vote of a sample of elements, or
  // the orientation given in the options) and runs again in the rare case the full vote differs.
  const int guess = in.options.orientation != 0 ? in.options.orientation : sampled_orientation(in, where);
  give_freed_heap_back();
  ClosingPass pass(in, where, in.options.threads, reuse);
  // A failure in the full pass makes every later element's graph be closed once more for
  // nothing (a quarter of the femur pair's projection); the elements where failures arise are
  // closed first, and the full pass usually meets none (finalize_rechecks.hpp).
  ElementFailures failed;
  if (drop) failed = pass.failures_among(elements_next_to_partial_preimages(in, reuse));
  if (failed.empty()) failed = pass.run(guess);
  for (int round = 0; !failed.empty(); ++round) {
    // failed.front() is the smallest element that failed
    if (!drop || round == 16) std::rethrow_exception(failed.front().second);
    bool any = false;
    std::vector<Index> failed_elements;
    for (const auto& [t, error] : failed) {
      failed_elements.push_back(t);
      // rim edges on a failed element go (a conflict with a rim edge costs the rim there, not an
      // S2 edge's stretch), and so do the stretches of S2 edges in conflict among themselves or
      // with a node: both in the same round, which closes every element again
      any = drop_rim_edges_on_element(in, where, t, dropped) || any;
      for (Index e : conflicting_edges(in, where, t)) any = drop_stretch_on_element(in, where, e, t, dropped) || any;
    }
    if (!any) std::rethrow_exception(failed.front().second);
    // rim nodes whose rim went with it go too (their images would spoil the faces around them)
    drop_rim_nodes_left_without_rim(in, dropped);
    where.build(in, dropped);
    // Only the elements the drops touched, and those that failed, can fail now
    // (finalize_rechecks.hpp): their graphs alone are closed until none fails, and then every
    // element is closed and assembled once more.
    failed = pass.failures_among(elements_to_close_again(in, dropped.take_changes(), failed_elements));
    if (failed.empty()) failed = pass.run(guess);
  }
  AssembledMap assembled;
  MapData<2>& m = assembled.map;
  m.orientation = in.options.orientation != 0 ? in.options.orientation : pass.voted_orientation();
  if (m.orientation != guess) {
    const ElementFailures failed = pass.run(m.orientation);  // the same graphs: they close again
    if (!failed.empty()) std::rethrow_exception(failed.front().second);
  }
  if (report) {
    ClosingPass::FaceCounts counts = pass.face_counts();  // summed over the blocks once
    report->reversed_faces += counts.reversed;
    report->unmapped_faces += counts.unmapped;
    report->left_out += counts.left_out.measures(in.s1.measure());
    report->split_targets = std::move(counts.split_targets);
    report->regions_split_off_outside_faces = std::move(counts.outside_split_regions);
  }
  // Everything is closed: the builder's nodes and segments and their buckets are not read again.
  // Freed before the join, which with several blocks first-touches the later blocks' share of the
  // map once more (31 MiB of the 200k plane pair's peak with two threads), and before the region
  // maps are written (finalize_region_maps.hpp).
  pass.release_workspaces();
  BuilderSegments<2>().swap(in.segments);
  BuilderNodes<2>().swap(in.nodes);
  where.release();
  join_parts(pass.parts(), n1, pass.threads(), m);
  // The arrays sized by bounds are final now: their slack goes before the region maps are written
  // (shrink_stored_form), not after, and so do the originals the copies leave in the heap (on the
  // femur pair 1.3 MiB, 86k regions of a 92k bound, was on top of the region maps).
  shrink_stored_form(m, pass.threads());
  give_freed_heap_back();
  assembled.graph_elements = pass.graph_elements();
  if (pass.deferred_region_maps()) write_region_maps(in.s2, pass.joined_omitted_weights(), m, pass.threads());
  return assembled;
}

}  // namespace plmap::detail
