#pragma once
// Normal projection, phase 4 (projection_edge_walks.hpp): where the projection of one S2 edge
// crosses one S1 edge (paper eq. 4), and for curves where the ray of an S1 vertex meets the line
// of an S2 segment. The walks ask these equations at every step; what counts as a crossing
// (inside the edge up to its slack, within the distance limit, isolated) is decided here.

#include "projection_context.hpp"

#include <plmap/solvers/projection_systems.hpp>
#include <plmap/solvers/small_lu.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace plmap::projection {

/// One answer of the crossing equations: valid when a crossing was found, else why not.
struct CrossingCandidate {
  bool valid = false;
  bool solver_failed = false;
  bool beyond_limit = false;
  double lambda = 0.0, mu = 0.0, eta = 0.0;
};

/// The answers of eq. (4) for the S2 edge of one walk, by S1 edge. Consecutive steps of a walk
/// share an element whose other edges were solved in the step before, and a walk from an S1
/// vertex meets each edge at the vertex in two elements: the answer depends only on the two
/// edges, so it is looked up instead of solved again. The last `capacity` answers are kept,
/// enough for a step from a vertex of any usual valence and the step after it.
struct CrossingMemo {
  static constexpr int capacity = 16;
  std::array<Index, capacity> edges;
  std::array<CrossingCandidate, capacity> answers;
  int size = 0, next = 0;

  template <class Solve>
  const CrossingCandidate& get(Index edge, Solve&& solve) {
    for (int i = 0; i < size; ++i)
      if (edges[i] == edge) return answers[i];
    const int slot = next;
    next = (next + 1) % capacity;
    if (size < capacity) ++size;
    edges[slot] = edge;
    answers[slot] = solve();
    return answers[slot];
  }
};

/// The crossing equations of one projection, solved with `Solver`.
template <int d, class Solver>
class EdgeCrossings {
 public:
  EdgeCrossings(const ProjectionContext<d>& ctx, const Solver& solver) : ctx_(ctx), solver_(solver) {}

  /// Eq. (4): where the projection of S2 edge (qa, qb) crosses S1 edge `edge` (d = 2).
  CrossingCandidate solve(Index edge, const WorldPoint<d>& qa, const WorldPoint<d>& qb,
                                   long long& calls, long long& failures) const
    requires(d == 2)
  {
    CrossingCandidate c;
    const auto ev = ctx_.s1.edge_vertices(edge);
    EdgeCrossingSystem sys;
    sys.edge = {ctx_.s1.vertex(ev[0]), ctx_.s1.vertex(ev[1])};
    sys.directions = {ctx_.vertex_directions[ev[0]], ctx_.vertex_directions[ev[1]]};
    sys.target = {qa, qb};
    // A crossing outside [-slack, 1 + slack] is rejected below whatever the solver returns.
    const double crossing_lambda_slack = ctx_.options.search_limits.edge_parameter_slack;
    if (sys.misses_the_edge(ctx_.options.solver_tolerance, crossing_lambda_slack)) return c;
    ++calls;
    const auto r = solver_.solve(sys, sys.initial_guess());
    if (!r.converged) {
      ++failures;
      c.solver_failed = true;
      return c;
    }
    c.lambda = r.x(0);
    c.mu = r.x(1);
    c.eta = r.x(2);
    // A (nearly) singular Jacobian at the solution means the S2 edge runs along the projection
    // of the S1 edge: there is no isolated crossing (the walk passes the edge's end vertices).
    {
      const Eigen::Matrix3d j = sys.jacobian(r.x);
      const double s = sys.scale();
      if (!(std::abs(j.determinant()) > 1e-10 * s * s * j.col(1).norm())) return c;
    }
    if (c.lambda < -crossing_lambda_slack || c.lambda > 1.0 + crossing_lambda_slack) return c;
    if (!ctx_.distance_ok(c.mu, sys.scale())) {
      c.beyond_limit = true;
      return c;
    }
    c.lambda = std::clamp(c.lambda, 0.0, 1.0);
    c.valid = true;
    return c;
  }

  /// Eq. (3) on S1 element t: the local point of t, strictly inside it (by `margin` in
  /// barycentric coordinates), whose ray reaches world point q within the distance limit and
  /// before any focal point of t's field, and the distance along that ray; nullopt if there is
  /// none.
  struct ElementPreimage {
    LocalPoint<d> local;
    double mu;
  };
  std::optional<ElementPreimage> unfolded_preimage_in(Index t, const WorldPoint<d>& q, double margin, long long& calls,
                                                     long long& failures) const {
    const VertexProjectionSystem<d> sys = ctx_.element_system(t, q);
    ++calls;
    const auto r = solver_.solve(sys, sys.initial_guess());
    if (!r.converged) {
      ++failures;
      return std::nullopt;
    }
    const LocalPoint<d> xi = r.x.template head<d>();
    const double mu = r.x(d);
    if (!(barycentric_from_local<d>(xi).minCoeff() > margin) || !ctx_.distance_ok(mu, sys.scale()) ||
        !ctx_.unfolded_in(t, xi, mu))
      return std::nullopt;
    return ElementPreimage{xi, mu};
  }

  /// For d = 1: the ray from S1 vertex w meets the line of the S2 segment (qa, qb).
  CrossingCandidate ray(Index w, const WorldPoint<d>& qa, const WorldPoint<d>& qb) const
    requires(d == 1)
  {
    CrossingCandidate c;
    Eigen::Matrix2d a;
    a.col(0) = ctx_.vertex_directions[w];
    a.col(1) = qa - qb;
    const double scale = (qb - qa).norm();
    if (!(std::abs(a.determinant()) > 1e-12 * scale)) return c;
    const Eigen::Vector2d x = solve_with_partial_pivoting<2>(a, qa - ctx_.s1.vertex(w));
    c.mu = x(0);
    c.eta = x(1);
    c.lambda = 0.0;
    if (!ctx_.distance_ok(c.mu, scale)) {
      c.beyond_limit = true;
      return c;
    }
    c.valid = true;
    return c;
  }

 private:
  const ProjectionContext<d>& ctx_;
  const Solver& solver_;
};

}  // namespace plmap::projection
