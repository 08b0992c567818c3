// orient2d's shortcuts (the static filter and the collinearity checks by comparison) must give
// the exact sign: checked against CGAL's exact predicate on triples built to be degenerate or
// nearly so, the kind the closure of an element meets on the sides of the reference triangle.
#include <plmap/core/predicates.hpp>

#include <gtest/gtest.h>

#include <random>

using namespace plmap;

namespace {
int exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return detail::orient2d_exact(a.x(), a.y(), b.x(), b.y(), c.x(), c.y());
}
}  // namespace

TEST(Predicates, PointsOnTheAntidiagonalAreRecognisedOnlyWhenExact) {
  // (1 - s, s) for s >= 1/2 lies exactly on x + y = 1 (1 - s is exact then).
  EXPECT_TRUE(detail::on_antidiagonal(Eigen::Vector2d(1.0 - 0.7, 0.7)));
  EXPECT_TRUE(detail::on_antidiagonal(Eigen::Vector2d(0.0, 1.0)));
  // 0.1 + 0.9 rounds to 1, but the doubles nearest 0.1 and 0.9 do not sum to 1 exactly.
  EXPECT_FALSE(detail::on_antidiagonal(Eigen::Vector2d(0.1, 0.9)));
  EXPECT_FALSE(detail::on_antidiagonal(Eigen::Vector2d(0.5, 0.5 + 1e-17 + 1e-16)));
}

TEST(Predicates, Orient2dAgreesWithTheExactPredicateOnDegenerateTriples) {
  std::mt19937_64 rng(20261201);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto on_antidiagonal_exactly = [&] {
    const double s = 0.5 + 0.5 * u(rng);
    return u(rng) < 0.5 ? Eigen::Vector2d(1.0 - s, s) : Eigen::Vector2d(s, 1.0 - s);
  };
  auto on_antidiagonal_rounded = [&] {
    const double x = u(rng);
    return Eigen::Vector2d(x, 1.0 - x);  // 1 - x rounds when x < 1/2
  };
  auto on_axis = [&](int axis, double value) {
    Eigen::Vector2d p(u(rng), u(rng));
    p(axis) = value;
    return p;
  };
  int zeros = 0;
  for (int i = 0; i < 200000; ++i) {
    std::array<Eigen::Vector2d, 3> p;
    const int kind = i % 5;
    const double value = u(rng);
    for (auto& q : p) {
      switch (kind) {
        case 0: q = on_antidiagonal_exactly(); break;
        case 1: q = on_antidiagonal_rounded(); break;
        case 2: q = on_axis(0, value); break;
        case 3: q = on_axis(1, value); break;
        default: q = Eigen::Vector2d(u(rng), u(rng)); break;
      }
    }
    if (i % 7 == 0) p[2] = on_axis(i % 2, p[0](i % 2));  // two on an axis line, one off or on it
    if (i % 11 == 0) p[i % 3] = p[(i + 1) % 3];          // two equal points
    const int o = orient2d(p[0], p[1], p[2]);
    ASSERT_EQ(o, exact(p[0], p[1], p[2])) << "case " << i << ": (" << p[0].transpose() << ") ("
                                          << p[1].transpose() << ") (" << p[2].transpose() << ")";
    zeros += o == 0;
  }
  EXPECT_GT(zeros, 100000);  // the collinear constructions really are collinear, and are seen so
}

TEST(Predicates, IncircleAgreesWithTheExactPredicateOnCocircularAndNearlyCocircularPoints) {
  // The static filter in front of CGAL's exact test must never decide a sign the exact test
  // would not: points on a lattice (squares and rectangles are cocircular), the same moved by a
  // few units in the last place, and points on the sides of the reference triangle, as the
  // Lawson flips of the closure meet them.
  std::mt19937_64 rng(20261202);
  std::uniform_int_distribution<int> cell(0, 8);
  std::uniform_int_distribution<int> ulps(-3, 3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto lattice = [&] { return Eigen::Vector2d(cell(rng) / 8.0, cell(rng) / 8.0); };
  auto nudged = [&](Eigen::Vector2d p) {
    for (int k = 0; k < 2; ++k)
      for (int n = ulps(rng); n != 0; n += n > 0 ? -1 : 1)
        p(k) = std::nextafter(p(k), n > 0 ? 2.0 : -2.0);
    return p;
  };
  int zeros = 0;
  for (int i = 0; i < 200000; ++i) {
    std::array<Eigen::Vector2d, 4> p;
    for (auto& q : p) q = lattice();
    if (i % 3 == 1) p[3] = nudged(p[3]);
    if (i % 3 == 2)
      for (auto& q : p) {
        const double s = u(rng);  // on x + y = 1, as the builder places edge nodes
        q = s >= 0.5 ? Eigen::Vector2d(1.0 - s, s) : Eigen::Vector2d(1.0 - s, 1.0 - (1.0 - s));
      }
    if (orient2d(p[0], p[1], p[2]) <= 0) continue;  // incircle is asked for counter-clockwise a, b, c
    const int filtered = incircle(p[0], p[1], p[2], p[3]);
    ASSERT_EQ(filtered, detail::incircle_exact(p[0], p[1], p[2], p[3])) << "case " << i;
    zeros += filtered == 0;
  }
  EXPECT_GT(zeros, 1000);  // cocircular quadruples do occur, and are seen exactly so
}

TEST(Predicates, FiltersDoNotDecideWhereTheirProductsUnderflow) {
  // Coordinates a few units of the smallest subnormal apart: every product underflows, so the
  // static error bounds (which assume it does not) must leave the decision to the exact tests.
  std::mt19937_64 rng(20261203);
  std::uniform_int_distribution<int> units(-6, 6);
  auto tiny_point = [&] { return Eigen::Vector2d(units(rng) * 0x1p-1074, units(rng) * 0x1p-1074); };
  int decided = 0;
  for (int i = 0; i < 20000; ++i) {
    std::array<Eigen::Vector2d, 4> p;
    for (auto& q : p) q = tiny_point();
    if (i % 2 == 0) p[3] = Eigen::Vector2d(units(rng) * 0x1p-1000, units(rng) * 0x1p-1000);
    ASSERT_EQ(orient2d(p[0], p[1], p[2]), exact(p[0], p[1], p[2])) << "case " << i;
    if (exact(p[0], p[1], p[2]) <= 0) continue;
    ASSERT_EQ(incircle(p[0], p[1], p[2], p[3]), detail::incircle_exact(p[0], p[1], p[2], p[3])) << "case " << i;
    ++decided;
  }
  EXPECT_GT(decided, 1000);
}
