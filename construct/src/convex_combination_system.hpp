#pragma once
// The linear system of one smoothing solve (an element or a quadrilateral, paper 3.3.2): each
// unknown position is the convex combination of its neighbours, x_i - Σ_j w_ij x_j = Σ_k w_ik p_k
// over its free (j) and fixed (k) neighbours. The matrix is an M-matrix (diagonally dominant,
// strictly in rows next to a fixed point) but not symmetric for geometric weights.
//
// Almost every system is small (a coarse element carries a handful to a few dozen free S2
// vertex preimages), and for those Eigen's SparseLU spends more time on its symbolic analysis,
// ordering and allocations than on the numbers: a dense Gaussian elimination with partial
// pivoting in reused buffers is several times faster. Above `dense_limit` unknowns (a late coarse quadrilateral of a large mesh) the fill-in
// of the dense form costs more than the sparse factorization saves, so SparseLU takes over.
// One object per smoother: its buffers are reused from solve to solve (no allocation once they
// have grown to the largest system).

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace plmap::smoothing {

class ConvexCombinationSystem {
 public:
  /// Largest system solved densely: the break-even with SparseLU measured on the armadillo -> 500
  /// map (callgrind: 64 -> 160 saves 4.5 % of the smoothing, 256 is worse again).
  static constexpr int dense_limit = 160;

  /// Starts a system of `unknowns` rows, all zero.
  void reset(int unknowns);
  /// matrix(row, col) += value; each (row, col) pair may be added more than once.
  void add(int row, int col, double value);
  /// right-hand side row += value.
  void add_rhs(int row, const Eigen::Vector2d& value);
  /// Solves; false if the matrix is singular or the result is not finite. The solution stays
  /// valid until the next reset.
  bool solve();
  const Eigen::Vector2d& solution(int row) const { return solution_[static_cast<std::size_t>(row)]; }
  int unknowns() const { return n_; }

 private:
  bool solve_dense();
  bool solve_sparse();

  int n_ = 0;
  bool dense_ = true;
  std::vector<double> matrix_;  ///< dense: row-major n × n
  std::vector<Eigen::Triplet<double>> triplets_;  ///< sparse
  std::vector<Eigen::Vector2d> rhs_, solution_;
};

}  // namespace plmap::smoothing
