#pragma once
/// \file
/// The invariant checks of DESIGN.md §4 for a finalized map.
///
/// `verify` runs all of them; each check_* runs one and is usable alone (it first makes sure
/// the indices it dereferences are in range, and otherwise reports that under "structure" and
/// marks itself skipped). Every check is linear or n log n in the size of the map, apart from
/// the per-element pairwise tests, which are pruned by a sweep over x.
///
/// What each check covers:
/// - structure: indices in range; neighbour lists symmetric, free of repeats, in ccw order
///   (d = 1: by increasing position); node type agrees with the position (snap tolerance);
///   edge arrays complete, ordered along the edge, starting/ending at the corner/ghost nodes;
///   copies on shared S1 edges and corners agree in parameter, type, node_target and image.
/// - plane_graph: no two graph edges of an element cross (exact predicates); regions are
///   positively oriented, their sides are graph edges, region_neighbors is symmetric and
///   matches shared sides; region areas sum to at most the element area, and to exactly it when
///   the element is fully covered (all corners present, boundary covered).
/// - minimal_embedding: each graph edge marked as an S2-edge preimage can be labelled with one
///   S2 edge (from its endpoints' node_target / images), and per element the graph edges of one
///   label form a single chain.
/// - map: node images lie in their S2 element and on their node_target; every region corner,
///   mapped by region_map, lands in region_target and on the node's image; image and domain
///   orientation agree with MapData::orientation (no fold-over); each S2 vertex has at most one
///   preimage (copies count once).
/// - continuity: Xi evaluated at sample points of each shared S1 edge (d = 1: shared vertex)
///   from every incident element agrees.
/// - coverage: per S2 element, image regions do not overlap (area sum and pairwise clipped
///   overlap); with expect_parametrization, regions cover S1 and images cover S2.
/// - quality: kappa above VerifyOptions::max_condition (and the distribution in
///   VerificationReport::quality).

#include <plmap/core/pl_map.hpp>
#include <plmap/verify/options.hpp>
#include <plmap/verify/report.hpp>

namespace plmap {

template <int d>
VerificationReport verify(const PlMap<d>& map, const VerifyOptions& options = {});

template <int d>
VerificationReport check_structure(const PlMap<d>& map, const VerifyOptions& options = {});
template <int d>
VerificationReport check_plane_graph(const PlMap<d>& map, const VerifyOptions& options = {});
template <int d>
VerificationReport check_minimal_embedding(const PlMap<d>& map,
                                           const VerifyOptions& options = {});
template <int d>
VerificationReport check_map(const PlMap<d>& map, const VerifyOptions& options = {});
template <int d>
VerificationReport check_continuity(const PlMap<d>& map, const VerifyOptions& options = {});
template <int d>
VerificationReport check_coverage(const PlMap<d>& map, const VerifyOptions& options = {});
/// Violations of VerifyOptions::max_condition, plus the distribution in report.quality.
template <int d>
VerificationReport check_quality(const PlMap<d>& map, const VerifyOptions& options = {});

}  // namespace plmap
