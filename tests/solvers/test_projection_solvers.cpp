// Both projection solvers (damped Newton, Ceres TinySolver) on the systems of paper eq. (3) and
// (4): known solutions for planar and curved direction fields, agreement between the two, and
// failure reports on systems that have no solution.
#include <plmap/core/errors.hpp>
#include <plmap/solvers/ceres_tiny_solver.hpp>
#include <plmap/solvers/damped_newton.hpp>
#include <plmap/solvers/projection_solver.hpp>
#include <plmap/solvers/projection_systems.hpp>
#include <plmap/solvers/solver_kind.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <functional>

using namespace plmap;

namespace {

/// Agreement between the two solvers on the same converged system: both stop at a residual of
/// 1e-12 x scale; with Jacobian condition numbers of the test systems below 1e3 the solutions
/// agree to this (relative to the element size).
constexpr double solver_agreement = 1e-8;

template <class Solver>
class ProjectionSolverTest : public ::testing::Test {};
using Solvers = ::testing::Types<DampedNewtonSolver, CeresTinySolver>;
TYPED_TEST_SUITE(ProjectionSolverTest, Solvers);

VertexProjectionSystem<2> planar_triangle(const Eigen::Vector3d& q) {
  VertexProjectionSystem<2> s;
  s.corners = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0, 2, 0)};
  s.directions = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 1)};
  s.target = q;
  return s;
}

/// A direction field fanning out from the focal point (0, 0, -1): nu(p) = p - focus at the
/// corners, so the linear interpolation is exact and the solution is known in closed form.
VertexProjectionSystem<2> radial_triangle(const Eigen::Vector3d& q) {
  VertexProjectionSystem<2> s;
  s.corners = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  const Eigen::Vector3d focus(0, 0, -1);
  for (int i = 0; i < 3; ++i) s.directions[i] = s.corners[i] - focus;
  s.target = q;
  return s;
}

}  // namespace

TYPED_TEST(ProjectionSolverTest, PlanarTriangleConstantNormals) {
  const TypeParam solver;
  const auto s = planar_triangle({0.5, 0.25, 0.3});
  const auto r = solver.solve(s, s.initial_guess());
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.x(0), 0.25, 1e-12);
  EXPECT_NEAR(r.x(1), 0.125, 1e-12);
  EXPECT_NEAR(r.x(2), 0.3, 1e-12);
  EXPECT_LE(r.relative_residual, 1e-12);
}

TYPED_TEST(ProjectionSolverTest, PlanarTriangleFromAPoorStart) {
  const TypeParam solver;
  const auto s = planar_triangle({0.5, 0.25, -0.7});
  const auto r = solver.solve(s, Eigen::Vector3d(5.0, -3.0, 2.0));
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.x(2), -0.7, 1e-12);  // a negative distance is a solution too; callers filter
}

TYPED_TEST(ProjectionSolverTest, CurvedFieldRadialProjection) {
  const TypeParam solver;
  // q = focus + s (p - focus) for p = (0.2, 0.3, 0) and s = 1.5: mu = s - 1 = 0.5.
  const Eigen::Vector3d focus(0, 0, -1), p(0.2, 0.3, 0.0);
  const auto s = radial_triangle(focus + 1.5 * (p - focus));
  const auto r = solver.solve(s, Eigen::Vector3d(1.0 / 3, 1.0 / 3, 0.0));
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.x(0), 0.2, 1e-10);
  EXPECT_NEAR(r.x(1), 0.3, 1e-10);
  EXPECT_NEAR(r.x(2), 0.5, 1e-10);
  EXPECT_GE(r.iterations, 1);
}

TYPED_TEST(ProjectionSolverTest, CurveSegmentCurvedField) {
  const TypeParam solver;
  // Segment (-1,0)-(1,0), directions (x, 1): rays fan out; q on the ray from (0.5, 0).
  VertexProjectionSystem<1> s;
  s.corners = {Eigen::Vector2d(-1, 0), Eigen::Vector2d(1, 0)};
  s.directions = {Eigen::Vector2d(-1, 1), Eigen::Vector2d(1, 1)};
  // p = (0.5, 0) <-> xi = 0.75, nu(xi) = (0.5, 1); mu = 2 -> q = (1.5, 2).
  s.target = Eigen::Vector2d(1.5, 2.0);
  const auto r = solver.solve(s, s.initial_guess());
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.x(0), 0.75, 1e-10);
  EXPECT_NEAR(r.x(1), 2.0, 1e-10);
}

TYPED_TEST(ProjectionSolverTest, EdgeCrossingPlanar) {
  const TypeParam solver;
  EdgeCrossingSystem e;
  e.edge = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  e.directions = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 1)};
  e.target = {Eigen::Vector3d(0.3, -1, 0.2), Eigen::Vector3d(0.3, 1, 0.2)};
  const auto r = solver.solve(e, e.initial_guess());
  ASSERT_TRUE(r.converged);
  EXPECT_NEAR(r.x(0), 0.3, 1e-12);
  EXPECT_NEAR(r.x(1), 0.2, 1e-12);
  EXPECT_NEAR(r.x(2), 0.5, 1e-12);
}

TYPED_TEST(ProjectionSolverTest, EdgeCrossingCurvedField) {
  const TypeParam solver;
  // Directions fan out from (0.5, 0, -1) in the x-z plane; the S2 edge runs along y at height 1
  // above x = 0.8: crossing point p(lambda) with p + mu nu = (0.8, 0, 1).
  EdgeCrossingSystem e;
  const Eigen::Vector3d focus(0.5, 0, -1);
  e.edge = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  e.directions = {e.edge[0] - focus, e.edge[1] - focus};
  e.target = {Eigen::Vector3d(0.8, -1, 1), Eigen::Vector3d(0.8, 3, 1)};
  const auto r = solver.solve(e, Eigen::Vector3d(0.5, 0.0, 0.5));
  ASSERT_TRUE(r.converged);
  // (0.8, 0, 1) = focus + 2 (p - focus) -> p = (0.65, 0, 0), mu = 1
  EXPECT_NEAR(r.x(0), 0.65, 1e-10);
  EXPECT_NEAR(r.x(1), 1.0, 1e-10);
  EXPECT_NEAR(r.x(2), 0.25, 1e-10);
}

TYPED_TEST(ProjectionSolverTest, DirectionsParallelToTheElementHaveNoSolution) {
  const TypeParam solver;
  auto s = planar_triangle({0.5, 0.5, 1.0});
  for (auto& n : s.directions) n = Eigen::Vector3d(1, 0, 0);  // in the plane: q unreachable
  const auto r = solver.solve(s, Eigen::Vector3d(0.3, 0.3, 0.0));
  EXPECT_FALSE(r.converged);
  EXPECT_GT(r.relative_residual, 1e-3);
}

TYPED_TEST(ProjectionSolverTest, CurvedFieldWithoutRealSolution) {
  const TypeParam solver;
  // Segment (-1,0)-(1,0) with nu(xi) = (1, 1 - 2 xi): the system for q = (0, -1) reduces to
  // s^2 + 1 = 0 in s = 1 - 2 xi, which has no real root.
  VertexProjectionSystem<1> s;
  s.corners = {Eigen::Vector2d(-1, 0), Eigen::Vector2d(1, 0)};
  s.directions = {Eigen::Vector2d(1, 1), Eigen::Vector2d(1, -1)};
  s.target = Eigen::Vector2d(0, -1);
  const auto r = solver.solve(s, Eigen::Vector2d(0.5, 0.0));
  EXPECT_FALSE(r.converged);
}

TYPED_TEST(ProjectionSolverTest, ScaleInvariantConvergence) {
  const TypeParam solver;
  for (double scale : {1e-6, 1.0, 1e6}) {
    auto s = radial_triangle({0.1, 0.2, 0.4});
    for (auto& c : s.corners) c *= scale;
    s.target *= scale;
    // directions stay unit-free; mu scales with the geometry
    const auto r = solver.solve(s, s.initial_guess());
    ASSERT_TRUE(r.converged) << "scale " << scale;
    EXPECT_NEAR(r.relative_residual, 0.0, 1e-12);
  }
}

RC_GTEST_PROP(ProjectionSolvers, NewtonAndCeresAgreeOnRandomCurvedSystems, ()) {
  const auto coord = [] { return *rc::gen::inRange(-1000, 1001) / 1000.0; };
  VertexProjectionSystem<2> s;
  s.corners = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  // Directions near the normal, tilted by up to 0.3: a well-behaved field.
  for (auto& n : s.directions) n = Eigen::Vector3d(0.3 * coord(), 0.3 * coord(), 1.0);
  const Eigen::Vector3d xi(0.5 * (coord() + 1) * 0.5, 0.5 * (coord() + 1) * 0.5, coord());
  typename VertexProjectionSystem<2>::Vector x(xi(0), xi(1), xi(2));
  s.target = s.point(x) + x(2) * (s.directions[0] + x(0) * (s.directions[1] - s.directions[0]) +
                                  x(1) * (s.directions[2] - s.directions[0]));
  const auto a = DampedNewtonSolver{}.solve(s, s.initial_guess());
  const auto b = CeresTinySolver{}.solve(s, s.initial_guess());
  RC_ASSERT(a.converged);
  RC_ASSERT(b.converged);
  RC_ASSERT((a.x - x).norm() < solver_agreement);
  RC_ASSERT((a.x - b.x).norm() < solver_agreement);
}

TEST(SolverKind, NamesRoundTripAndUnknownNamesThrow) {
  for (const auto& name : solver_names()) EXPECT_EQ(to_string(solver_kind_from_string(name)), name);
  EXPECT_THROW(solver_kind_from_string("gauss"), Error);
  const int iterations = with_solver(SolverKind::ceres, 1e-12, [](const auto& solver) {
    const auto s = planar_triangle({0.5, 0.25, 0.3});
    return solver.solve(s, Eigen::Vector3d(0, 0, 0)).iterations;
  });
  EXPECT_GE(iterations, 1);
}

namespace {
/// Eq. (4) with two real roots: the S1 edge from (0,0,0) to (1,0,0) with directions (0,-1,1) and
/// (0,1,1) sweeps the saddle y = z (2x - 1); the S2 edge q(eta) = (eta, 0.3, eta) meets it where
/// 2 eta^2 - eta - 0.3 = 0, at eta = (1 + sqrt(3.4)) / 4 ~ 0.711 (on both edges) and at
/// eta = (1 - sqrt(3.4)) / 4 ~ -0.211 (off both).
EdgeCrossingSystem saddle_crossing() {
  EdgeCrossingSystem s;
  s.edge = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  s.directions = {Eigen::Vector3d(0, -1, 1), Eigen::Vector3d(0, 1, 1)};
  s.target = {Eigen::Vector3d(0, 0.3, 0), Eigen::Vector3d(1, 0.3, 1)};
  return s;
}
}  // namespace

TEST(EdgeCrossingSystem, TheStartIsTheRootOnBothEdges) {
  const auto s = saddle_crossing();
  const double root = (1.0 + std::sqrt(3.4)) / 4.0;
  const auto start = s.root_on_the_edges();
  ASSERT_TRUE(start.has_value());
  EXPECT_NEAR((*start)(0), root, 1e-12);  // lambda = x
  EXPECT_NEAR((*start)(1), root, 1e-12);  // mu = z
  EXPECT_NEAR((*start)(2), root, 1e-12);  // eta
  EXPECT_LE(s.residual(*start).norm(), 1e-12);
  EXPECT_EQ(s.initial_guess(), *start);
  // an S2 edge that misses the S1 edge's sweep has no such root: the frozen-midpoint start
  EdgeCrossingSystem apart = s;
  apart.target = {Eigen::Vector3d(3, 0.3, 0), Eigen::Vector3d(4, 0.3, 1)};
  EXPECT_FALSE(apart.root_on_the_edges().has_value());
  EXPECT_EQ(apart.initial_guess(), apart.frozen_midpoint_guess());
}

TYPED_TEST(ProjectionSolverTest, BothSolversFindTheCrossingOnTheEdgesOfAQuadraticSystem) {
  const TypeParam solver;
  const auto s = saddle_crossing();
  const auto r = solver.solve(s, s.initial_guess());
  ASSERT_TRUE(r.converged);
  const double root = (1.0 + std::sqrt(3.4)) / 4.0;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.x(k), root, 1e-10) << k;
}

// misses_the_edge lets the projection skip eq. (4) on S1 edges the S2 edge's projection does not
// cross. It must never skip a system with a solution on the edge, also when that solution lies
// just inside the edge's ends or the field is curved, and it must skip the clear misses.
TEST(EdgeCrossingSystem, MissesTheEdgeOnlyWithoutASolutionOnIt) {
  const auto s = saddle_crossing();
  EXPECT_FALSE(s.misses_the_edge(1e-12, 1e-9));  // the root at lambda ~ 0.711
  // q(eta) = (3 + eta, 0.3, eta) meets the sweep of the edge's line at lambda ~ 3.06 and at
  // lambda ~ 0.44 with eta ~ -2.56: off the S2 edge, but a solution with lambda on the S1 edge
  EdgeCrossingSystem beside = s;
  beside.target = {Eigen::Vector3d(3, 0.3, 0), Eigen::Vector3d(4, 0.3, 1)};
  EXPECT_FALSE(beside.root_on_the_edges().has_value());
  EXPECT_FALSE(beside.misses_the_edge(1e-12, 1e-9));
  // q(eta) = (3, 0.3 + eta, 0.4 eta): P(lambda) = (lambda - 3)(0.8 lambda - 1.4), roots off the edge
  EdgeCrossingSystem apart = s;
  apart.target = {Eigen::Vector3d(3, 0.3, 0), Eigen::Vector3d(3, 1.3, 0.4)};
  EXPECT_TRUE(apart.misses_the_edge(1e-12, 1e-9));
  // an S2 edge along the S1 edge's sweep: P vanishes identically, nothing can be excluded
  EdgeCrossingSystem along;
  along.edge = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  along.directions = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 1)};
  along.target = {Eigen::Vector3d(-1, 0, 0.5), Eigen::Vector3d(2, 0, 0.5)};
  EXPECT_FALSE(along.misses_the_edge(1e-12, 1e-9));
}

namespace {
/// A random edge pair (curved field, any scale and offset) whose projection crosses at the given
/// lambda, with eta = 0.4 and mu = 0.3 (times the scale).
EdgeCrossingSystem crossing_at(double lambda, double scale, const Eigen::Vector3d& offset,
                               const std::function<double()>& coord) {
  EdgeCrossingSystem s;
  s.edge = {offset, offset + scale * Eigen::Vector3d(1.0, 0.2 * coord(), 0.2 * coord())};
  for (auto& n : s.directions) n = Eigen::Vector3d(0.5 * coord(), 0.5 * coord(), 1.0).normalized();
  const Eigen::Vector3d p = s.edge[0] + lambda * (s.edge[1] - s.edge[0]);
  const Eigen::Vector3d nu = s.directions[0] + lambda * (s.directions[1] - s.directions[0]);
  const Eigen::Vector3d q = p + 0.3 * scale * nu;
  const Eigen::Vector3d g = scale * Eigen::Vector3d(0.3 * coord(), 1.0, 0.3 * coord());
  s.target = {q - 0.4 * g, q + 0.6 * g};
  return s;
}
}  // namespace

RC_GTEST_PROP(EdgeCrossingSystem, NeverMissesACrossingTheSolversFind, ()) {
  const auto coord = [] { return *rc::gen::inRange(-1000, 1001) / 1000.0; };
  const double scale = std::pow(10.0, *rc::gen::inRange(-6, 7));
  const Eigen::Vector3d offset = std::pow(10.0, *rc::gen::inRange(-6, 4)) * Eigen::Vector3d(coord(), coord(), coord());
  // crossings at the ends of the edge, just inside and outside the slack, and well away
  const double lambda = *rc::gen::element(0.0, 1.0, -1e-9, 1.0 + 1e-9, -1e-7, 1.0 + 1e-7, 0.5, -0.3, 1.7,
                                          -1e-12, 1.0 + 1e-12);
  const auto s = crossing_at(lambda, scale, offset, coord);
  const bool missed = s.misses_the_edge(1e-12, 1e-9);
  for (const bool newton : {true, false}) {
    const auto r =
        newton ? DampedNewtonSolver{}.solve(s, s.initial_guess()) : CeresTinySolver{}.solve(s, s.initial_guess());
    if (r.converged && r.x(0) >= -1e-9 && r.x(0) <= 1.0 + 1e-9) RC_ASSERT(!missed);
  }
  if (lambda >= -1e-9 && lambda <= 1.0 + 1e-9) RC_ASSERT(!missed);
}

TEST(EdgeCrossingSystem, MissesTheEdgeWhenTheOnlyCrossingIsClearlyOffIt) {
  // constant directions: P is linear, its one root is the crossing
  const auto one = [] { return 0.0; };
  for (double scale : {1e-6, 1.0, 1e6}) {
    const Eigen::Vector3d offset(3 * scale, -2 * scale, 0.5 * scale);
    EXPECT_TRUE(crossing_at(1.7, scale, offset, one).misses_the_edge(1e-12, 1e-9)) << scale;
    EXPECT_TRUE(crossing_at(-0.3, scale, offset, one).misses_the_edge(1e-12, 1e-9)) << scale;
    EXPECT_TRUE(crossing_at(1.0 + 1e-6, scale, offset, one).misses_the_edge(1e-12, 1e-9)) << scale;
    EXPECT_FALSE(crossing_at(1.0, scale, offset, one).misses_the_edge(1e-12, 1e-9)) << scale;
    EXPECT_FALSE(crossing_at(-1e-9, scale, offset, one).misses_the_edge(1e-12, 1e-9)) << scale;
    EXPECT_FALSE(crossing_at(1.0 + 1e-9 + 1e-13, scale, offset, one).misses_the_edge(1e-12, 1e-9)) << scale;
  }
}
