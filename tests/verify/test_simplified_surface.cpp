// generators::simplify_by_edge_collapse: the coarse meshes of the femur-kind experiments.
#include <plmap/core/errors.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/simplified_surface.hpp>

#include <gtest/gtest.h>


namespace plmap {
namespace {

TEST(SimplifiedSurface, ReachesAboutTheAskedSizeDeterministically) {
  generators::Rng rng(3);
  generators::GridOptions grid;
  grid.cells = 16;  // 512 triangles
  grid.jitter = 0.1;
  const Surface<2> fine = generators::lift_to_height_field(generators::grid_triangulation(grid, rng),
                                                           generators::HeightField{.amplitude = 0.05});
  const Surface<2> coarse = generators::simplify_by_edge_collapse(fine, 100);
  EXPECT_LT(coarse.element_count(), fine.element_count() / 2);
  EXPECT_GT(coarse.element_count(), 40);
  for (const auto& v : coarse.vertices()) EXPECT_TRUE(v.allFinite());
  // deterministic: the same input gives the same output
  const Surface<2> again = generators::simplify_by_edge_collapse(fine, 100);
  EXPECT_EQ(again.elements(), coarse.elements());
  EXPECT_EQ(again.vertices(), coarse.vertices());
}

TEST(SimplifiedSurface, RejectsANonManifoldMesh) {
  generators::Rng rng(5);
  generators::GridOptions grid;
  grid.cells = 4;
  const Surface<2> fin = generators::add_fins(generators::grid_triangulation(grid, rng), 1, rng);
  EXPECT_THROW((void)generators::simplify_by_edge_collapse(fin, 10), Error);
}

}  // namespace
}  // namespace plmap
