// The seed walks of the vertex preimage search stop once no element on which a nearer preimage
// could be accepted is left unsolved (construct/src/preimage_rank_floor.hpp). That is only an
// economy if it never changes a preimage. Checked here in three steps:
//  - distance_floor never exceeds the distance from a point to a segment or triangle (and is
//    that distance for most well-shaped ones, else the rule would rarely stop anything);
//  - no solution that a walk accepts on an element ranks below the element's rank floor, for
//    solutions near the floor (targets placed along the element's own direction field), curved
//    fields, wide inside tolerances and both signs of the distance;
//  - on random surface pairs (manifold or not, curves and triangle surfaces, averaged normals or
//    random directions, Newton and Ceres) the search that stops gives every S2 vertex the
//    preimage that walking from every seed gives, bit for bit, with no more solver calls.
#include "curve_solution_side.hpp"
#include "preimage_rank_floor.hpp"
#include "projection_context.hpp"
#include "projection_fixtures.hpp"
#include "projection_ghost_rays.hpp"
#include "projection_vertex_preimages.hpp"
#include "simplex_distance.hpp"

#include <plmap/solvers/ceres_tiny_solver.hpp>
#include <plmap/solvers/damped_newton.hpp>
#include <plmap/solvers/projection_systems.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <random>

using namespace plmap;
using namespace plmap::projection;
namespace gen = plmap::generators;

namespace {

template <int d>
WorldPoint<d> random_point(std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> g(0.0, spread);
  WorldPoint<d> p;
  for (int k = 0; k <= d; ++k) p(k) = g(rng);
  return p;
}

/// A random simplex: well shaped, or a sliver (one corner almost on the opposite side).
template <int d>
std::array<WorldPoint<d>, d + 1> random_simplex(std::mt19937_64& rng, bool sliver) {
  std::array<WorldPoint<d>, d + 1> c;
  const WorldPoint<d> centre = random_point<d>(rng, 10.0);
  for (auto& p : c) p = centre + random_point<d>(rng, 1.0);
  if (sliver) c[d] = 0.5 * (c[0] + c[1]) + 1e-7 * random_point<d>(rng, 1.0);
  return c;
}

template <int d>
void check_distance_floor(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int tight = 0, shaped = 0;
  for (int i = 0; i < 20000; ++i) {
    const bool sliver = d == 2 && i % 5 == 0;
    const auto c = random_simplex<d>(rng, sliver);
    // points near the simplex (on it, just off it, beyond its sides) and far from it
    WorldPoint<d> x = c[0];
    double rest = 1.0;
    for (int k = 1; k <= d; ++k) {
      const double b = (1.0 + 0.2) * unit(rng) * rest - 0.1;
      x += b * (c[k] - c[0]);
      rest -= std::max(b, 0.0);
    }
    x += std::pow(10.0, -8.0 + 9.0 * unit(rng)) * random_point<d>(rng, 1.0);
    const double distance = simplex_distance<d>(x, c);
    const double floor = distance_floor<d>(x, c, longest_edge<d>(c));
    ASSERT_LE(floor, distance) << "case " << i << " sliver " << sliver;
    if (!sliver) {
      ++shaped;
      if (floor >= distance - 1e-8 * (distance + longest_edge<d>(c))) ++tight;
    }
  }
  // for well-shaped simplices the floor is the distance up to its margins, but where the
  // nearest point is a corner of a triangle (the side lines bound it from below only)
  EXPECT_GE(tight, (d == 1 ? 99 : 80) * shaped / 100) << tight << " of " << shaped;
}

/// Unit directions at the corners: the simplex's normal tilted by random amounts (up to
/// `spread`), so the field is curved.
template <int d>
std::array<WorldPoint<d>, d + 1> random_directions(std::mt19937_64& rng, const std::array<WorldPoint<d>, d + 1>& c,
                                                   double spread) {
  WorldPoint<d> normal;
  if constexpr (d == 1)
    normal = WorldPoint<1>((c[1] - c[0]).y(), -(c[1] - c[0]).x());
  else
    normal = (c[1] - c[0]).cross(c[2] - c[0]);
  normal.normalize();
  std::array<WorldPoint<d>, d + 1> n;
  for (auto& direction : n) direction = (normal + spread * random_point<d>(rng, 1.0)).normalized();
  return n;
}

template <int d, class Solver>
void check_rank_floor(const Solver& solver, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int accepted = 0, near_floor = 0;
  for (int i = 0; i < 20000; ++i) {
    PreimageAcceptance accept;
    accept.solver_tolerance = solver.options.relative_tolerance;
    accept.inside_tolerance = std::array<double, 3>{1e-9, 1e-4, 0.05}[i % 3];
    accept.allow_negative_distance = i % 2 == 0;
    VertexProjectionSystem<d> sys;
    sys.corners = random_simplex<d>(rng, false);
    sys.directions = random_directions<d>(rng, sys.corners, std::array<double, 3>{0.0, 0.1, 0.6}[i % 3]);
    // the target: a point of the element (or just outside it) moved along the field by mu
    Barycentric<d> b;
    double sum = 0.0;
    for (int k = 0; k <= d; ++k) sum += (b(k) = unit(rng) + 0.01);
    b /= sum;
    if (i % 4 == 0) {  // just outside a side, within the inside tolerance
      const int k = i / 4 % (d + 1);
      const double outside = accept.inside_tolerance * unit(rng);
      b *= (1.0 + outside) / (1.0 - b(k));
      b(k) = -outside;
    }
    const double h = longest_edge<d>(sys.corners);
    const double mu = (i % 7 == 0 ? -1e-9 * unit(rng) : std::pow(10.0, -6.0 + 7.0 * unit(rng))) * h;
    WorldPoint<d> p = WorldPoint<d>::Zero(), nu = WorldPoint<d>::Zero();
    for (int k = 0; k <= d; ++k) {
      p += b(k) * sys.corners[k];
      nu += b(k) * sys.directions[k];
    }
    sys.target = p + mu * nu;
    const auto r = solver.solve(sys, sys.initial_guess());
    if (!r.converged) continue;
    const Barycentric<d> found = barycentric_from_local<d>(r.x.template head<d>());
    if (!(found.minCoeff() >= -accept.inside_tolerance)) continue;
    const double found_mu = r.x(d);
    if (!accept.allow_negative_distance && found_mu < -1e-9 * sys.scale()) continue;
    const double rank = accept.allow_negative_distance ? std::abs(found_mu) : std::max(found_mu, 0.0);
    const double floor = preimage_rank_floor<d>(sys.target, sys.corners, accept);
    ++accepted;
    ASSERT_GE(rank, floor) << "case " << i << ": mu " << found_mu << " floor " << floor;
    if (floor > 0.5 * rank) ++near_floor;
  }
  EXPECT_GT(accepted, 10000);
  EXPECT_GT(near_floor, accepted / 10);  // the floor is not trivially 0
}

/// What the two searches gave: the first difference (empty if none) and the solver calls.
struct Comparison {
  std::string difference;
  long long all_calls = 0, stopping_calls = 0;
};

/// The preimages of both searches, compared bit for bit.
template <int d, class Solver>
Comparison compare_searches(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
                            const ProjectionOptions& options, const Solver& solver) {
  ProjectionContext<d> ctx(s1, s2, options);
  const auto hits = cast_rays_from_s1_vertices(ctx);
  Comparison out;
  ctx.solver_calls = 0;
  const VertexPreimages<d> all = find_vertex_preimages(ctx, solver, hits, SeedWalks::all);
  out.all_calls = ctx.solver_calls.exchange(0);
  const VertexPreimages<d> stopping = find_vertex_preimages(ctx, solver, hits, SeedWalks::until_no_rival_left);
  out.stopping_calls = ctx.solver_calls.load();
  auto describe = [](const std::optional<SurfacePoint<d>>& p) {
    return p ? fmt::format("element {} at ({:.17g}, {:.17g})", p->element, p->local(0), p->local(d - 1)) : "nothing";
  };
  for (std::size_t q = 0; q < all.preimage.size() && out.difference.empty(); ++q) {
    const auto& a = all.preimage[q];
    const auto& b = stopping.preimage[q];
    if (a.has_value() != b.has_value() || (a && (a->element != b->element || a->local != b->local)))
      out.difference = fmt::format("S2 vertex {}: all seeds give {}, the stopping search {}", q, describe(a), describe(b));
  }
  if (out.difference.empty() && all.found_by_ray_hits != stopping.found_by_ray_hits)
    out.difference = "the second search maps another number of vertices";
  if (out.difference.empty() && out.stopping_calls > out.all_calls)
    out.difference = fmt::format("more solver calls when stopping: {} > {}", out.stopping_calls, out.all_calls);
  return out;
}

/// Random directions (d + 1 numbers per vertex, not normalised), as ProjectionOptions wants them.
template <int d>
std::vector<double> random_direction_values(const Surface<d>& s1) {
  std::vector<double> out;
  for (Index v = 0; v < s1.vertex_count(); ++v) {
    WorldPoint<d> n;
    do {
      for (int k = 0; k <= d; ++k) n(k) = *rc::gen::inRange(-100, 101) / 100.0;
    } while (n.norm() < 0.1);
    for (int k = 0; k <= d; ++k) out.push_back(n(k));
  }
  return out;
}

/// Options as the properties vary them: directions, distance rules, tolerances.
template <int d>
ProjectionOptions random_options(const Surface<d>& s1, std::string& what) {
  ProjectionOptions o;
  const int directions = *rc::gen::inRange(0, 3);
  if (directions == 1) o.directions = random_direction_values<d>(s1);
  if (directions == 2) o.directions = test::constant_directions<d>(s1, WorldPoint<d>::UnitX());
  o.allow_negative_distance = *rc::gen::arbitrary<bool>();
  o.search_limits.inside_tolerance = *rc::gen::element(1e-9, 1e-6, 1e-3);
  o.solver = *rc::gen::element(std::string("newton"), std::string("ceres"));
  what += fmt::format(" directions {} negative {} inside {} {}", directions, o.allow_negative_distance,
                      o.search_limits.inside_tolerance, o.solver);
  return o;
}

template <int d>
Comparison compare_with_solver(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
                               const ProjectionOptions& o) {
  if (o.solver == "ceres") {
    CeresTinySolver solver;
    solver.options.relative_tolerance = o.solver_tolerance;
    return compare_searches<d>(s1, s2, o, solver);
  }
  DampedNewtonSolver solver;
  solver.options.relative_tolerance = o.solver_tolerance;
  return compare_searches<d>(s1, s2, o, solver);
}

/// The property: the same preimages.
template <int d>
void assert_same_preimages(std::shared_ptr<const Surface<d>> s1, std::shared_ptr<const Surface<d>> s2,
                           const ProjectionOptions& o, const std::string& what) {
  const Comparison c = compare_with_solver<d>(s1, s2, o);
  if (!c.difference.empty()) RC_FAIL(what + ": " + c.difference);
  RC_CLASSIFY(c.stopping_calls < c.all_calls, "fewer solves");
}

template <int d>
std::shared_ptr<const Surface<d>> moved(const Surface<d>& s, double scale, const WorldPoint<d>& shift) {
  return test::transformed<d>(s, [&](const WorldPoint<d>& p) { return WorldPoint<d>(scale * p + shift); });
}

}  // namespace

TEST(PreimageRankFloor, DistanceFloorIsAtMostTheDistanceToASegment) { check_distance_floor<1>(11); }
TEST(PreimageRankFloor, DistanceFloorIsAtMostTheDistanceToATriangle) { check_distance_floor<2>(12); }

TEST(PreimageRankFloor, NoAcceptedSolutionRanksBelowTheFloorOnSegments) {
  check_rank_floor<1>(DampedNewtonSolver{}, 21);
  check_rank_floor<1>(CeresTinySolver{}, 22);
}

TEST(PreimageRankFloor, NoAcceptedSolutionRanksBelowTheFloorOnTriangles) {
  check_rank_floor<2>(DampedNewtonSolver{}, 23);
  check_rank_floor<2>(CeresTinySolver{}, 24);
}

TEST(VertexPreimageWalkStop, OffsetGridNeedsFarFewerSolves) {
  // S2 a little above S1, vertical directions: each S2 vertex's first walk finds its preimage,
  // and nothing else lies as near, so the other seven walks are not needed. S1's cells narrow
  // towards x = 0 (uneven sizes: the box hierarchy the rule needs is built).
  auto s1 = test::transformed<2>(*test::grid(20, 20, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2), [](const WorldPoint<2>& p) {
    return WorldPoint<2>(p.x() * p.x(), p.y(), p.z());
  });
  auto s2 = test::grid(26, 26, 0.1, 0.9, 0.1, 0.9, 0.02, true, 0.2);
  ProjectionOptions o;
  o.directions = test::constant_directions<2>(*s1, WorldPoint<2>(0.0, 0.0, 1.0));
  const Comparison c = compare_with_solver<2>(s1, s2, o);
  EXPECT_EQ(c.difference, "");
  EXPECT_LT(4 * c.stopping_calls, c.all_calls) << c.stopping_calls << " solves against " << c.all_calls;
}

TEST(VertexPreimageWalkStop, ConcentricCirclesNeedAboutOneSolvePerVertex) {
  // Segments of even length build no box hierarchy, so the rivals' rule cannot stop the walks;
  // the closed form of curve_solution_side.hpp does: once the first walk has found the preimage,
  // each other seed's segment holds no solution and its walk would step into a solved segment.
  // S2 lies 300 segment lengths outside S1, where every seed walks towards the same segment.
  auto s1 = test::circle(2000, 1.0);
  auto s2 = test::circle(2600, 1.1, 0.3);
  const Comparison c = compare_with_solver<1>(s1, s2, ProjectionOptions{});
  EXPECT_EQ(c.difference, "");
  EXPECT_GE(c.all_calls, 8 * 2600) << "every seed walked and solved";
  EXPECT_LT(c.stopping_calls, 2 * 2600) << c.stopping_calls << " solves against " << c.all_calls;
}

TEST(CurveSolutionSide, AgreesWithTheSolverOnRandomSegments) {
  // Wherever the closed form names a side, the solver started as the search starts it either
  // fails or converges on that side, beyond the margin; and it names a side for most segments
  // that hold no solution (a third here, with directions turning at random; on smooth curves,
  // whose other solution lies far away, nearly all).
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  DampedNewtonSolver solver;
  int decided = 0, outside = 0;
  for (int i = 0; i < 20000; ++i) {
    VertexProjectionSystem<1> sys;
    sys.corners = {WorldPoint<1>(unit(rng), unit(rng)), WorldPoint<1>(unit(rng), unit(rng))};
    const WorldPoint<1> e = sys.corners[1] - sys.corners[0];
    const WorldPoint<1> normal(-e.y(), e.x());
    for (auto& n : sys.directions) n = normal + 0.5 * WorldPoint<1>(unit(rng), unit(rng));
    sys.target = WorldPoint<1>(4.0 * unit(rng), 4.0 * unit(rng));
    const double margin = 1e-6;
    const int side = curve_solution_side(sys.corners[0], sys.corners[1], sys.directions[0], sys.directions[1],
                                         sys.target, margin);
    const auto r = solver.solve(sys, sys.initial_guess());
    if (!r.converged) continue;
    const double xi = r.x(0);
    if (xi >= -margin && xi <= 1.0 + margin) {
      ASSERT_EQ(side, 0) << "case " << i << ": a solution at xi " << xi << " on the segment";
      continue;
    }
    ++outside;
    if (side == 0) continue;
    ++decided;
    ASSERT_EQ(side, xi > 1.0 ? 1 : -1) << "case " << i << ": the solver converged at xi " << xi;
  }
  EXPECT_GT(outside, 5000);
  EXPECT_GT(decided, outside / 4);
}

RC_GTEST_PROP(VertexPreimageWalkStop, SamePreimagesOnRandomTriangleSurfacePairs, ()) {
  const auto s1 = *gen::triangle_surfaces();
  const auto s2_shape = *gen::triangle_surfaces();
  const double scale = *rc::gen::element(0.5, 1.0, 2.0);
  const WorldPoint<2> shift(*rc::gen::inRange(-30, 31) / 100.0, *rc::gen::inRange(-30, 31) / 100.0,
                            *rc::gen::inRange(-30, 31) / 100.0);
  std::string what = fmt::format("scale {} shift ({}, {}, {})", scale, shift.x(), shift.y(), shift.z());
  const auto o = random_options<2>(*s1, what);
  const auto s2 = moved<2>(*s2_shape, scale, shift);
  assert_same_preimages<2>(s1, s2, o, what);
}

RC_GTEST_PROP(VertexPreimageWalkStop, SamePreimagesOnOffsetHeightFields, ()) {
  const auto r1 = *gen::planar_recipes();
  const auto r2 = *gen::planar_recipes();
  const auto field_seed = *rc::gen::noShrink(rc::gen::arbitrary<std::uint64_t>());
  gen::Rng rng(field_seed);
  const gen::HeightField field = gen::random_height_field(rng);
  const double offset = *rc::gen::inRange(-100, 301) / 1000.0;
  std::string what = fmt::format("S1 {} / S2 {} field seed {} offset {}", gen::describe(r1), gen::describe(r2),
                                 field_seed, offset);
  auto s1 = std::make_shared<const Surface<2>>(gen::lift_to_height_field(gen::make_planar(r1), field));
  auto s2 = test::transformed<2>(gen::make_planar(r2), [&](const WorldPoint<2>& p) {
    return WorldPoint<2>(p.x() + 0.1, p.y() - 0.05, field(p.x() + 0.1, p.y() - 0.05) + offset);
  });
  const auto o = random_options<2>(*s1, what);
  assert_same_preimages<2>(s1, s2, o, what);
}

RC_GTEST_PROP(VertexPreimageWalkStop, SamePreimagesOnRandomCurvePairs, ()) {
  const auto s1 = *gen::curves();
  const auto s2_shape = *gen::curves();
  const double scale = *rc::gen::element(0.5, 1.0, 2.0);
  const WorldPoint<1> shift(*rc::gen::inRange(-30, 31) / 100.0, *rc::gen::inRange(-30, 31) / 100.0);
  std::string what = fmt::format("scale {} shift ({}, {})", scale, shift.x(), shift.y());
  const auto o = random_options<1>(*s1, what);
  const auto s2 = moved<1>(*s2_shape, scale, shift);
  assert_same_preimages<1>(s1, s2, o, what);
}

RC_GTEST_PROP(VertexPreimageWalkStop, SamePreimagesOnConcentricCircles, ()) {
  const int n = *rc::gen::inRange(12, 200), m = *rc::gen::inRange(12, 200);
  const double ratio = *rc::gen::element(0.7, 0.99, 1.0, 1.01, 1.3);
  const double phase = *rc::gen::inRange(0, 6283) / 1000.0;
  std::string what = fmt::format("circles {} / {} ratio {} phase {}", n, m, ratio, phase);
  auto s1 = test::circle(n, 1.0);
  auto s2 = test::circle(m, ratio, phase);
  const auto o = random_options<1>(*s1, what);
  assert_same_preimages<1>(s1, s2, o, what);
}
