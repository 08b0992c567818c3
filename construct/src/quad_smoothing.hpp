#pragma once
// Smoothing over the quadrilateral of two S1 triangles that share an edge (paper 3.3.2), on the
// PreimageGraph form of a parametrization. One step, for the S1 edge e = AB with triangles
// T1 = (A, B, C1) and T2 = (B, A, C2):
//  1. unfold: T1 and T2 are laid isometrically into one plane, e on the x axis;
//  2. merge: the crossings of S2 edges with e are dropped, so every S2 edge that meets the
//     quadrilateral Q is one straight segment in it; the S2 vertex preimages inside T1, T2 or on
//     e are the unknowns, every point on ∂Q is fixed;
//  3. solve: each unknown is the convex combination of its S2 neighbours (the other ends of its
//     segments, in S2's cyclic order) with weights from its star on S2; a dense LU for small systems, else Eigen's
//     SparseLU (convex_combination_system.hpp);
//  4. check, with exact predicates in the plane: Q is convex, every unknown is strictly inside
//     Q and off e (by a relative clearance), no two segments meet except at a common end, and
//     the segments around every unknown keep S2's cyclic order and wind once (no fold-over),
//     and the worst condition number of the spoke triangles (unknown, two consecutive
//     neighbours) against their images does not grow (so that sweeps converge instead of
//     trading the worst piece for a better average);
//  5. cut: each segment that crosses e gets a new crossing there (its image interpolated along
//     the S2 edge, linearly along the segment: the map stays linear on it), each unknown goes to
//     the triangle on its side of e. A refused step changes nothing.

#include "convex_combination_system.hpp"
#include "preimage_graph.hpp"
#include "quad_step_workspace.hpp"
#include "quad_unfolding.hpp"
#include "s2_stars.hpp"

#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace plmap::smoothing {

struct QuadOutcome {
  const char* skipped = nullptr;  ///< why the step was refused, or nullptr
  Index nodes_moved = 0;          ///< vertex preimages whose position changed
  Index nodes_crossed = 0;        ///< of these, those now in the other triangle (or off e)
  double max_displacement = 0.0;  ///< largest move, relative to the length of e
};

/// What a step decided and wrote into the graph, so that the same step on the same input can be
/// replayed without solving again (a repeated quadrilateral pass, smooth.cpp): its outcome, and
/// if it wrote, the new places of its unknowns and, per S2 edge it saw, the new crossings of
/// the shared edge e (a written step replaces all of that edge's crossings of these S2 edges).
struct QuadStepRecord {
  QuadOutcome outcome;
  Index uniform_fallbacks = 0;  ///< counted by this step
  bool wrote = false;
  std::vector<std::pair<Index, DomainPlace>> places;  ///< (S2 vertex, new place)
  std::vector<Index> relevant;                         ///< S2 edges with a segment in T1 or T2
  std::vector<std::pair<Index, EdgeCrossing>> cuts;    ///< (S2 edge, new crossing of e)
  /// per S2 edge of `relevant`: bit 0 if it is in edges_in_element() of e's first triangle
  /// (edge_elements(e) order) after the step, bit 1 of the second (their lists are `relevant`
  /// filtered by these, in its order)
  std::vector<std::uint8_t> sides;
};

/// Per S1 triangle, the S2 edges that have a segment in it (the order matters: it is the order
/// of a step's pieces and unknowns, hence of its solve's rounding).
using EdgesInElement = std::vector<std::vector<Index>>;

class QuadSmoother {
 public:
  /// `graph` is edited in place; the surfaces must be those of the map it came from. `index`,
  /// if given, is edges_in_element() of a smoother on an identical graph (saves indexing).
  QuadSmoother(PreimageGraph& graph, const Surface<2>& domain, const Surface<2>& target, AnySmoothingWeights weights,
               const EdgesInElement* index = nullptr);
  /// The same, reading S2's stars (cyclic orders, whole-star weights) from `stars`, which
  /// outlives the smoother and may be shared with other smoothers on the same S2 and weights.
  QuadSmoother(PreimageGraph& graph, const Surface<2>& domain, S2Stars& stars, const EdgesInElement* index = nullptr);
  /// True if S1 edge e has exactly two triangles, oriented consistently across it.
  bool has_quadrilateral(Index e) const;
  /// One step; with `record`, what it decided and wrote goes there.
  QuadOutcome smooth(Index e, QuadStepRecord* record = nullptr);
  /// Does what a recorded smooth(e) did, without solving: exactly that, provided the graph in
  /// and around e's quadrilateral (T1, T2, their edges) is what it was when the step was recorded.
  void replay(Index e, const QuadStepRecord& record);
  const EdgesInElement& edges_in_element() const { return edges_in_element_; }
  /// Vertex preimages that got uniform weights because the model refused their star.
  Index uniform_fallbacks() const { return uniform_fallbacks_; }

 private:
  QuadOutcome step(Index e, QuadStepRecord* record);
  // The phases of a step (see the top of this file). Each returns why it refuses the step, or
  // nullptr; they hand their results on in w_ and in relevant_ and unknown_vertex_.
  const char* unfold(Index e, Unfolding& u) const;     ///< 1.
  const char* merge(const Unfolding& u);               ///< 2. the pieces and the unknowns
  const char* solve_convex_combinations();             ///< 3.
  const char* place_unknowns(const Unfolding& u);      ///< 4. inside Q, off e
  const char* check_no_fold_over();                    ///< 4. no crossing, each ring winds once
  const char* check_worst_condition(const Unfolding& u);  ///< 4. the worst spoke no worse
  const char* cut_shared_edge(const Unfolding& u);     ///< 5. the new crossings of e
  QuadOutcome apply(const Unfolding& u, QuadStepRecord* record);  ///< 5. written into the graph
  /// Plane position of an end of a piece: the unknown's new position, or the fixed point.
  Eigen::Vector2d end_position(const QuadPiece& p, int end) const;
  void index_edges(const EdgesInElement* index);
  void index_edge(Index target_edge);
  PreimageGraph& g_;
  const Surface<2>& s1_;
  const Surface<2>& s2_;
  /// S2's cyclic orders and whole-star weights, computed once per vertex (S2 does not change;
  /// every step with v among its unknowns asked again: a tenth of a step): the smoother's own,
  /// or shared (stars_ points to one or the other).
  std::optional<S2Stars> own_stars_;
  S2Stars* stars_;
  EdgesInElement edges_in_element_;
  ConvexCombinationSystem system_;
  std::vector<Index> relevant_, unknown_vertex_;  ///< of the current step: S2 edges in T1 ∪ T2, unknowns
  std::vector<int> unknown_index_;                ///< per S2 vertex: its unknown in the current step, or -1
  std::vector<char> edge_seen_;                   ///< per S2 edge: in relevant_
  std::vector<Index> position_in_relevant_;       ///< per S2 edge in relevant_: its index there
  QuadStepWorkspace w_;                           ///< of the current step: what its phases hand on
  Index uniform_fallbacks_ = 0;
};

/// What one pass over all quadrilaterals did.
struct QuadPassTally {
  Index smoothed = 0, nodes_moved = 0, nodes_crossed = 0;
  double max_displacement = 0.0;
  std::map<std::string, Index> skipped_by_reason;
  Index solved = 0;    ///< steps solved
  Index replayed = 0;  ///< steps replayed from the previous pass's records
  /// With previous records: per S1 triangle, 1 if its part of the graph may differ from the
  /// previous pass's result (elsewhere it is the same, bit for bit).
  std::vector<char> changed;
};

/// One pass: the step of every S1 edge with a quadrilateral, in index order, each seeing the
/// previous ones, except the `frozen` edges. `records` gets, per S1 edge, what its step did.
/// With `previous` (the records of a pass on the same starting graph whose frozen edges were
/// `frozen` minus `newly_frozen`), the result is the one of a pass from scratch, but a step is
/// solved only where that result can differ from the previous pass's: a step reads and writes
/// only its quadrilateral (T1, T2 and their edges; an edge's crossings and touching preimages
/// change only in the step on that edge), so a step whose triangles no earlier step of this pass
/// changed differently (a newly frozen edge that wrote before, or a step solved again) sees
/// exactly what it saw in the previous pass and is replayed from its record.
QuadPassTally run_quadrilateral_pass(QuadSmoother& smoother, const Surface<2>& domain, const std::vector<char>& frozen,
                                     const std::vector<QuadStepRecord>* previous, const std::vector<char>* newly_frozen,
                                     std::vector<QuadStepRecord>& records);

}  // namespace plmap::smoothing
