#pragma once
// What the quadrilateral steps (quad_smoothing.hpp) ask about S2's vertex stars, which do not
// change during a smoothing: per S2 vertex, its edges in S2's cyclic order (following its
// triangles), and the smoothing weights of its whole star.
//
// A step's unknown v gets weights from its ring: per S2 edge at v, the point where the edge's
// segment ends in the quadrilateral, which is the edge's other vertex when that lies in the
// quadrilateral too. When every ring point is such a vertex the ring is v's whole star on S2,
// the same in every step that has v among its unknowns (a vertex preimage is an unknown of the
// three quadrilaterals of its element, and again in a repeated run), so its weights are computed
// once. The weights are a function of the ring alone, so the cached ones are the ones a fresh
// computation gives, bit for bit. Femur → 500: about a third of the steps' weight computations.
//
// One object per smoothing sweep, shared by the runs of its quadrilateral pass.

#include <plmap/core/surface.hpp>
#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>

#include <Eigen/Core>

#include <span>
#include <vector>

namespace plmap::smoothing {

class S2Stars {
 public:
  S2Stars(const Surface<2>& target, AnySmoothingWeights weights);
  const Surface<2>& target() const { return s2_; }

  /// The S2 edges at v in S2's cyclic order around v, or nullptr if v's triangles do not close
  /// one fan around it. Computed on the first call for v.
  const std::vector<Index>* ring_edges(Index v);

  /// Weights of v for `ring` (world positions of its ring points, in ring_edges(v)'s order);
  /// `whole_star`: every ring point is the other vertex of its edge, so the weights are cached.
  /// Falls back to uniform weights where the model refuses the star, and then sets `fallback`.
  std::span<const double> weights(Index v, std::span<const Eigen::Vector3d> ring, bool whole_star, bool& fallback);

 private:
  struct CachedWeights {
    bool known = false;
    bool fallback = false;
    std::vector<double> values;
  };
  std::vector<double> compute(Index v, std::span<const Eigen::Vector3d> ring, bool& fallback) const;

  const Surface<2>& s2_;
  AnySmoothingWeights weights_;
  std::vector<signed char> ring_known_;            ///< per S2 vertex: 0 not yet, 1 closed fan, -1 open
  std::vector<std::vector<Index>> ring_edges_;     ///< per S2 vertex with a closed fan
  std::vector<CachedWeights> star_weights_;        ///< per S2 vertex: its whole star's weights
  std::vector<double> scratch_;                    ///< the last uncached weights
};

}  // namespace plmap::smoothing
