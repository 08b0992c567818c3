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

#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>

namespace plmap::smoothing {

struct QuadOutcome {
  const char* skipped = nullptr;  ///< why the step was refused, or nullptr
  Index nodes_moved = 0;          ///< vertex preimages whose position changed
  Index nodes_crossed = 0;        ///< of these, those now in the other triangle (or off e)
  double max_displacement = 0.0;  ///< largest move, relative to the length of e
};

class QuadSmoother {
 public:
  /// `graph` is edited in place; the surfaces must be those of the map it came from.
  QuadSmoother(PreimageGraph& graph, const Surface<2>& domain, const Surface<2>& target, AnySmoothingWeights weights);
  /// True if S1 edge e has exactly two triangles, oriented consistently across it.
  bool has_quadrilateral(Index e) const;
  QuadOutcome smooth(Index e);
  /// Vertex preimages that got uniform weights because the model refused their star.
  Index uniform_fallbacks() const { return uniform_fallbacks_; }

 private:
  void index_edge(Index target_edge);
  PreimageGraph& g_;
  const Surface<2>& s1_;
  const Surface<2>& s2_;
  AnySmoothingWeights weights_;
  std::vector<std::vector<Index>> edges_in_element_;  ///< S2 edges with a segment in each S1 triangle
  ConvexCombinationSystem system_;
  Index uniform_fallbacks_ = 0;
};

}  // namespace plmap::smoothing
