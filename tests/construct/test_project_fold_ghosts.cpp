// Ghost rays where one element at a vertex folds and the others do not (walk_acceptance.hpp,
// folded_regions.hpp): the vertex keeps its image for the fold-free elements, and the faces on
// the folding element stay outside D.
#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/verify/ray_check.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace plmap;
using namespace plmap::test;

TEST(ProjectFoldGhosts, AValleyCreaseCostsOnlyItsOwnColumns) {
  // S1: a valley z = |x - 0.5| of 6 x 10 cells over [0.2, 0.8] x [0, 1], with its averaged
  // normals; S2 a plane at z = 0.7 facing it. The normals of the two columns at the crease turn
  // by 45 degrees over one cell, so their rays meet about 0.2 above the crease and every ray of
  // those columns is folded before S2; the four flank columns are planar, their rays parallel.
  // The vertices between a crease column and a flank column have a folded ray in the one and an
  // unfolded ray in the other: judged per element, they keep their images, and the flanks are
  // covered whole (2/3 of S1), with nothing missed and nothing extra. Judged by all elements at
  // the vertex, they had none, and the flank faces next to the crease were lost (36 % of S1
  // missed).
  auto s1 = transformed<2>(*grid(6, 10, 0.2, 0.8, 0, 1, 0.0),
                           [](const WorldPoint<2>& p) { return WorldPoint<2>(p.x(), p.y(), std::abs(p.x() - 0.5)); });
  auto s2 = grid(40, 13, -1, 2, -0.2, 1.2, 0.7, true);
  const auto r = project<2>(s1, s2);
  EXPECT_EQ(verify_violations(r.map), "");
  EXPECT_NEAR(r.measures.covered_domain / r.measures.domain, 2.0 / 3.0, 1e-3);
  RayCheckOptions<2> o;
  o.directions = averaged_vertex_normals(*s1);
  o.samples = 20000;
  const auto rays = check_against_rays(r.map, o);
  EXPECT_EQ(rays.missed, 0u);
  EXPECT_EQ(rays.extra, 0u);
  EXPECT_NEAR(rays.fraction(rays.in_domain_with_hit), 2.0 / 3.0, 0.02);
}
