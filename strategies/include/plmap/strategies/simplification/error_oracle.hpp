#pragma once
/// \file
/// Strategy family "error oracle" (DESIGN.md §2, paper 3.3.1): ranks or vetoes one planned
/// vertex removal of the simplification. A model looks at the plan (old and new triangles,
/// where the star's nodes went and their images) and returns a cost (lower is removed first)
/// or a veto. Costs are scale-free (lengths divided by the mean S2 edge length), so weights
/// mean the same on every mesh. Oracles compose: WeightedOracles (weighted_oracles.hpp) sums
/// weighted costs and vetoes if any member vetoes.
///
/// A model that keeps state about S1 (a spatial index) also provides
/// `void on_applied(const EditableMap&, const VertexRemovalPlan&)`, called after every step.
///
/// Models: HausdorffOracle, AspectRatioOracle, LongEdgeOracle, NormalDeviationOracle,
/// SelfIntersectionVeto.

#include <plmap/core/editable_map.hpp>

#include <concepts>

namespace plmap {

/// What an oracle is asked about.
struct RemovalCandidate {
  const EditableMap& map;
  const VertexRemovalPlan& plan;
  double length_scale = 1.0;  ///< mean edge length of S2
};

struct OracleVerdict {
  double cost = 0.0;
  bool veto = false;
  static OracleVerdict vetoed() { return {0.0, true}; }
};

template <class O>
concept ErrorOracle = requires(const O& o, const RemovalCandidate& c) {
  { o.evaluate(c) } -> std::same_as<OracleVerdict>;
};

template <class O>
concept StatefulErrorOracle = ErrorOracle<O> && requires(O& o, const EditableMap& m, const VertexRemovalPlan& p) {
  o.on_applied(m, p);
};

}  // namespace plmap
