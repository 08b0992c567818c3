#pragma once
// finalize(): which S1 elements to close first, and which to close again after conflicting
// stretches were dropped (BuilderOptions::drop_conflicting_edges). An element's closure depends
// only on the live nodes and segments inside it and along its edges, so only the elements where
// something was dropped, and those that failed before, can fail or stop failing in the next
// round: closing them alone finds the same failures as closing every element. Private to the
// builder.

#include "builder_nodes.hpp"
#include "finalize_phases.hpp"

#include <span>
#include <vector>

namespace plmap::detail {

/// The elements whose graph `changes` touched (a dropped segment's element, or the elements
/// around the S1 edge it lies along; the same for a dropped node's place), together with
/// `failed`, sorted, each once. Every element when whole S2 edges were dropped.
std::vector<Index> elements_to_close_again(const BuilderContents<2>& in, const DroppedEdges::Changes& changes,
                                           std::span<const Index> failed);

/// The elements that hold, inside or along an edge, a segment of a rim edge or of a partly
/// inserted S2 edge one of whose pieces ends inside S1 (not at a vertex preimage or on S1's
/// boundary), sorted, each once, except those `reuse` copies (may be null). Preimages conflict
/// (an element whose graph cannot be closed) where the projection folds or overlaps, which is
/// where walks stop: on the femur and bones pairs every element that failed was one of these.
/// finalize closes their graphs before the first full pass, so that the pass meets no failure;
/// an element outside them that fails is still found by the pass.
std::vector<Index> elements_next_to_partial_preimages(const BuilderContents<2>& in, const ElementReuse* reuse);

}  // namespace plmap::detail
