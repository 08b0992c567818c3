#pragma once
// Normal projection, edge walks: where the preimage of an S2 edge comes out of a fold again.
//
// A walk stops at the last crossing before a fold (walk_acceptance.hpp). But the S2 edge may
// only cross a narrow folded band of S1 and come out over an unfolded part beyond it. Without a
// new start there, that stretch is reached only by the walk back from the edge's second vertex,
// and lost when that vertex has no preimage or its own walk fails: the faces of both S2
// triangles at the edge then stay outside D on unfolded elements next to the fold (the
// `next_to_fold` class of the ray check). So after a walk stops at a fold, the S1 edges near
// the stop are solved for crossings of the S2 edge (eq. 4) farther along it, and the nearest
// one along the S2 edge whose ray is unfolded starts a new piece, as a boundary entry does.
// The same holds where a walk stops because the edge passes behind S1 or beyond the distance
// limit (a ridge of S1 through S2), or finds no continuation: it may come out again beyond.
// Every walk that stops so is restarted: the walk from the first vertex, the walks
// from boundary entries (both on towards the second vertex) and the walks backwards from the
// second vertex or from where the edge leaves S1 (on towards the first vertex, short of what
// the forward walks covered), since each of them may be the only walk that reaches a stretch.

#include <plmap/core/types.hpp>

#include <algorithm>
#include <optional>
#include <span>
#include <vector>

namespace plmap::projection {

/// A solution of eq. (4) on one S1 edge: S1 edge parameter lambda, S2 edge parameter eta, and
/// the distance mu along the ray.
struct FoldExitCandidate {
  Index domain_edge = invalid_index;
  double lambda = 0.0, eta = 0.0, mu = 0.0;
};

/// Of the crossings that `solve(edge)` finds on the given S1 edges, the one nearest along the
/// S2 edge in (after, before), by more than `eta_slack` from both (`before` is 1, the edge's
/// end, or where a walk from the other end has come), that `accept` takes. Candidates are judged nearest first, so that `accept` (the fold test, the
/// costly part) runs only until one passes. `found` is scratch.
template <class Solve, class Accept>
std::optional<FoldExitCandidate> nearest_fold_exit(double after, double before, double eta_slack,
                                                   std::span<const Index> domain_edges,
                                                   std::vector<FoldExitCandidate>& found, Solve&& solve,
                                                   Accept&& accept) {
  found.clear();
  for (Index edge : domain_edges)
    if (const std::optional<FoldExitCandidate> c = solve(edge); c && c->eta > after + eta_slack && c->eta < before - eta_slack)
      found.push_back(*c);
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return a.eta < b.eta || (a.eta == b.eta && a.domain_edge < b.domain_edge);
  });
  for (const FoldExitCandidate& c : found)
    if (accept(c)) return c;
  return std::nullopt;
}

}  // namespace plmap::projection
