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

#include <plmap/core/freed_heap.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
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
  /// could not be closed, in element order. Without drop_conflicting_edges it stops a part at its
  /// first failure (finalize then throws).
  ///
  /// Each thread starts with one block of elements (block_starts: about equal work) and writes it
  /// into a part of its own. A thread whose block is done takes the back half of what is left of
  /// the part with the most elements left, as a new part (work stealing): the two virtual CPUs of
  /// the machines we measure on differ in speed by up to a third, and with fixed halves the faster
  /// one waited for the slower. The parts are joined in element order, and what each element
  /// writes depends on nothing but the element, so the map is the same however the elements were
  /// split.
  ElementFailures run(int orientation) {
    const std::vector<Index> first = block_starts();
    workspaces_.clear();
    workspaces_.resize(blocks_);
    for (ClosureWorkspace& w : workspaces_) w.corner_maps_wanted = !deferred_region_maps();
    // room for every part a thread may take; a part takes half of the largest range left, so a
    // few per thread suffice
    const std::size_t capacity = blocks_ == 1 ? 1 : 16 * static_cast<std::size_t>(blocks_);
    std::vector<Part> parts(capacity);
    // The first block's part becomes the joined map (join_parts): it takes room for all blocks.
    std::vector<PartBounds> bounds(blocks_);
    parallel_for_pieces(blocks_, blocks_, threads_, [&](std::size_t k, std::size_t, std::size_t) {
      bounds[k] = part_bounds(in_, where_, first[k], first[k + 1]);
    });
    PartBounds whole;
    for (const PartBounds& b : bounds) whole += b;
    for (unsigned k = 0; k < blocks_; ++k) parts[k].start(first[k], first[k + 1]);
    std::atomic<std::size_t> part_count{blocks_};
    // After a failure in any part every part is discarded (finalize drops what failed and runs
    // the pass again, or throws): from then on every part only collects the failures, with
    // close_graph, which throws exactly where close_element does. (A block that went on
    // assembling after another block's failure took as long as a whole pass: on the femur pair
    // with two threads, the first block failed early and waited for the second.)
    std::atomic<bool> failed_somewhere{false};
    parallel_for_pieces(blocks_, blocks_, threads_, [&](std::size_t k, std::size_t, std::size_t) {
      Part* part = &parts[k];
      PartBounds own = bounds[k];
      while (part != nullptr) {
        if (!close_part(*part, own, k == 0 && part == &parts[0] ? whole : own, workspaces_[k], orientation,
                        failed_somewhere))
          return;  // finalize throws: no more parts
        part = steal(parts, part_count, own);
      }
    });
    // the parts in element order (a part taken from another lies after it)
    std::vector<Part*> used;
    for (std::size_t i = 0; i < std::min(part_count.load(), capacity); ++i)
      if (parts[i].begin != invalid_index) used.push_back(&parts[i]);
    std::sort(used.begin(), used.end(), [](const Part* a, const Part* b) { return a->begin < b->begin; });
    parts_.clear();
    face_counts_.clear();
    graph_elements_.clear();
    kept_omitted_weights_.clear();
    ElementFailures failed;
    for (Part* p : used) {
      parts_.push_back(std::move(p->data));
      face_counts_.push_back(std::move(p->counts));
      graph_elements_.push_back(std::move(p->graph_elements));
      if (deferred_region_maps()) kept_omitted_weights_.push_back(std::move(p->kept_omitted_weights));
      failed.insert(failed.end(), p->failures.begin(), p->failures.end());
    }
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
  /// The kept omitted weights of the last run (finalize_region_maps.hpp), joined in the order of
  /// the parts, their nodes numbered as in the joined map; to be called before the parts are
  /// joined (their node counts give the numbers).
  std::vector<KeptOmittedWeight> joined_kept_omitted_weights() {
    std::size_t total = 0, first_node = 0;
    for (const auto& kept : kept_omitted_weights_) total += kept.size();
    std::vector<KeptOmittedWeight> all;
    all.reserve(total);
    for (std::size_t k = 0; k < kept_omitted_weights_.size(); ++k) {
      for (const KeptOmittedWeight& w : kept_omitted_weights_[k])
        all.push_back({static_cast<Index>(first_node + static_cast<std::size_t>(w.node)), w.weight});
      first_node += parts_[k].node_type.size();
    }
    kept_omitted_weights_.clear();
    return all;
  }
  /// Frees the closure workspaces (slot_of_node alone has an entry per builder node) once the
  /// pass will not run again.
  void release_workspaces() { std::vector<ClosureWorkspace>().swap(workspaces_); }

 private:
  /// A range of elements closed by one thread into a part of the map of its own.
  struct Part {
    Index begin = invalid_index;  // invalid_index: not used
    /// (next element to close, end of the range), 32 bits each, in one word: the owner takes the
    /// next element and a thief cuts the end with one compare-and-swap each
    std::atomic<std::uint64_t> range{0};
    MapData<2> data;
    FaceCounts counts;
    std::vector<Index> graph_elements;  // numbered from begin
    std::vector<KeptOmittedWeight> kept_omitted_weights;
    ElementFailures failures;

    static std::uint64_t pack(Index next, Index end) {
      return static_cast<std::uint64_t>(static_cast<std::uint32_t>(next)) << 32 | static_cast<std::uint32_t>(end);
    }
    static Index next_of(std::uint64_t r) { return static_cast<Index>(r >> 32); }
    static Index end_of(std::uint64_t r) { return static_cast<Index>(r & 0xffffffffu); }
    void start(Index from, Index to) {
      begin = from;
      range.store(pack(from, to), std::memory_order_release);
    }
    /// The next element of the range, or invalid_index when none is left.
    Index take_next() {
      std::uint64_t r = range.load(std::memory_order_acquire);
      while (next_of(r) < end_of(r))
        if (range.compare_exchange_weak(r, pack(next_of(r) + 1, end_of(r)), std::memory_order_acq_rel)) return next_of(r);
      return invalid_index;
    }
    /// Ends the range at the next element (after a failure that stops the pass).
    void stop() {
      std::uint64_t r = range.load(std::memory_order_acquire);
      while (next_of(r) < end_of(r) && !range.compare_exchange_weak(r, pack(next_of(r), next_of(r)), std::memory_order_acq_rel)) {
      }
    }
  };

  /// Closes and assembles the elements of `part` as they are taken, into its data, sized by
  /// `own` with the capacity of `room`. False after a failure that ends the pass (without
  /// drop_conflicting_edges).
  bool close_part(Part& part, const PartBounds& own, const PartBounds& room, ClosureWorkspace& w, int orientation,
                  std::atomic<bool>& failed_somewhere) {
    const bool drop = in_.options.drop_conflicting_edges;
    AssemblyCursor cursor;
    cursor.spare_room = in_.options.spare_room;
    if (deferred_region_maps()) cursor.kept_omitted_weights = &part.kept_omitted_weights;
    size_part(own, room, part.data, cursor);
    bool go_on = true;
    for (Index t = part.take_next(); t != invalid_index; t = part.take_next()) {
      try {
        const bool assembling = !failed_somewhere.load(std::memory_order_relaxed);
        if (reuse_ != nullptr && reuse_->reuses(t)) {  // copied, not closed (finalize_reuse.hpp)
          if (assembling) reuse_->copy_element(in_, where_, t, part.data, cursor);
          continue;
        }
        if (assembling) {
          close_element(in_, where_, t, w, orientation);
          assemble_element(in_, w, orientation, part.data, cursor);
        } else {
          close_graph(in_, where_, t, w);
        }
      } catch (...) {
        part.failures.emplace_back(t, std::current_exception());
        failed_somewhere.store(true, std::memory_order_relaxed);
        if (!drop) {  // finalize throws: the part and its count are not used
          part.stop();
          go_on = false;
          break;
        }
      }
    }
    part.counts = {cursor.reversed_faces, cursor.unmapped_faces, cursor.left_out, std::move(cursor.split_targets),
                   std::move(cursor.outside_split_regions), static_cast<Index>(cursor.regions)};
    trim_part(cursor, part.data);
    for (Index& t : cursor.graph_elements) t += part.begin;  // numbered in the part
    part.graph_elements = std::move(cursor.graph_elements);
    return go_on;
  }

  /// A new part with the back half of the range left to the part with the most elements left
  /// (its bounds in `own`), or null when no part has enough left to be worth splitting, or no
  /// room is left for another part.
  Part* steal(std::vector<Part>& parts, std::atomic<std::size_t>& part_count, PartBounds& own) {
    // below this many elements the split costs more (bounds, sizing, a part to join) than it saves
    constexpr Index least_taken = 16;
    // the slot first: a range cut from its owner must have a part to go to
    const std::size_t slot = part_count.fetch_add(1, std::memory_order_acq_rel);
    if (slot >= parts.size()) return nullptr;
    for (;;) {
      Part* victim = nullptr;
      std::uint64_t seen = 0;
      const std::size_t count = std::min(part_count.load(std::memory_order_acquire), parts.size());
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint64_t r = parts[i].range.load(std::memory_order_acquire);
        const Index left = Part::end_of(r) - Part::next_of(r);
        if (left >= 2 * least_taken && (victim == nullptr || left > Part::end_of(seen) - Part::next_of(seen))) {
          victim = &parts[i];
          seen = r;
        }
      }
      if (victim == nullptr) return nullptr;  // the slot stays unused
      const Index next = Part::next_of(seen), end = Part::end_of(seen);
      const Index middle = next + (end - next) / 2;
      if (victim->range.compare_exchange_strong(seen, Part::pack(next, middle), std::memory_order_acq_rel)) {
        own = part_bounds(in_, where_, middle, end);
        parts[slot].start(middle, end);
        return &parts[slot];
      }
      // the owner took an element meanwhile, or another thief cut the range: look again
    }
  }

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
  std::vector<std::vector<KeptOmittedWeight>> kept_omitted_weights_;  // per part, with deferred region maps
  const ElementReuse* reuse_;
};

}  // namespace

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
  // The closing pass first-touches the whole map while the builder is still alive: that is the
  // peak of a projection. What the callers freed before it (the projection's plans, the buckets'
  // cursors, the sample's workspace) stays with malloc, scattered over the heap, where the map's
  // large arrays (mmap'ed) cannot use it (2.3 MiB of the 200k plane pair's peak, 2.7 MiB of the
  // armadillo pair's).
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
    // rim edges on a failed element go (a conflict with a rim edge costs the rim there, not an
    // S2 edge's stretch), and so do the stretches of S2 edges in conflict among themselves or
    // with a node: both in the same round, which closes every element again. What goes is found
    // on all threads (from the buckets, which the round's drops do not change), and dropped in
    // element order.
    std::vector<ElementConflicts> conflicts(failed.size());
    parallel_for_chunks(failed.size(), 8, in.options.threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) conflicts[i] = conflicts_on_element(in, where, failed[i].first);
    });
    bool any = false;
    std::vector<Index> failed_elements;
    for (std::size_t i = 0; i < failed.size(); ++i) {
      failed_elements.push_back(failed[i].first);
      any = drop_conflicts_on_element(in, where, failed[i].first, conflicts[i], dropped) || any;
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
  std::vector<KeptOmittedWeight> kept;  // (numbered as in the joined map)
  if (pass.deferred_region_maps()) kept = pass.joined_kept_omitted_weights();
  join_parts(pass.parts(), n1, pass.threads(), m);
  // The arrays sized by bounds are final now: their slack goes before the region maps are written
  // (shrink_stored_form), not after, and so do the originals the copies leave in the heap (on the
  // femur pair 1.3 MiB, 86k regions of a 92k bound, was on top of the region maps).
  shrink_stored_form(m, pass.threads(), in.options.spare_room);
  give_freed_heap_back();
  assembled.graph_elements = pass.graph_elements();
  if (pass.deferred_region_maps()) {
    if (in.options.measure_images) {
      ImageMeasures images = write_region_maps_and_measure(in.s1, in.s2, kept, m, pass.threads(), in.options.spare_room);
      if (report) report->images = std::move(images);
    } else {
      write_region_maps(in.s2, kept, m, pass.threads(), in.options.spare_room);
    }
  }
  return assembled;
}

}  // namespace plmap::detail
