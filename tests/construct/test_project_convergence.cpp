// The image error of a projection map against an independent ray cast shrinks like the error of
// piecewise-linear interpolation: Xi is the PL interpolant, over its regions, of the curved map
// p + mu(p) nu(p), so on smooth surfaces |Xi(x) - hit| = O(h^2) for mesh size h.

#include "projection_fixtures.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/construct/project.hpp>
#include <plmap/verify/ray_check.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace plmap {
namespace {

using namespace plmap::test;

double mean_edge_length(const Surface<2>& s) {
  double sum = 0.0;
  for (Index e = 0; e < s.edge_count(); ++e) {
    const auto v = s.edge_vertices(e);
    sum += (s.vertex(v[0]) - s.vertex(v[1])).norm();
  }
  return sum / static_cast<double>(s.edge_count());
}

struct LevelError {
  double h = 0.0;               ///< mean S2 edge length
  double median = 0.0, p99 = 0.0;  ///< absolute image error |Xi(x) - hit|
};

/// Concentric spheres (radius 1 and 1.05, S2 rotated so that the meshes are unrelated), both
/// refined `level` times, projected along S1's averaged normals and checked against rays.
LevelError image_error_at(int level) {
  auto s1 = sphere(level, 1.0);
  auto s2 = sphere(level, 1.05, true, 0.3);
  const auto r = project<2>(s1, s2, {.normal_check = TargetNormalCheck::facing});
  RayCheckOptions<2> rays;
  rays.directions = averaged_vertex_normals(*s1);
  rays.samples = 20000;
  rays.normal_check = RayNormalCheck::facing;
  const auto check = check_against_rays(r.map, rays);
  EXPECT_EQ(check.missed, 0u) << "level " << level;
  EXPECT_EQ(check.extra, 0u) << "level " << level;
  EXPECT_EQ(check.in_domain_with_hit, check.samples) << "level " << level;
  const double h = mean_edge_length(*s2);
  // the report gives the error relative to the edge length of the S2 triangle hit, which is
  // within a factor of about 1.5 of the mean on these meshes at every level
  return {h, check.error_median * h, check.error_p99 * h};
}

TEST(ProjectConvergence, ImageErrorAgainstRaysShrinksQuadraticallyWithMeshSize) {
  std::vector<LevelError> levels;
  // (level 2, 128 triangles, misses 2.6 % of S1 against the rays: too coarse to start from)
  for (int level = 3; level <= 6; ++level) levels.push_back(image_error_at(level));
  for (std::size_t i = 1; i < levels.size(); ++i) {
    const double h_ratio = levels[i - 1].h / levels[i].h;  // about 2 per refinement
    ASSERT_GT(h_ratio, 1.8);
    // O(h^2): the error falls by at least about h_ratio^2 (4) per refinement; O(h) would give 2.
    // (The median falls faster, by about 8: on concentric spheres the averaged normals are
    // nearly radial and the map nearly affine on each region.)
    const double median_ratio = levels[i - 1].median / levels[i].median;
    const double p99_ratio = levels[i - 1].p99 / levels[i].p99;
    EXPECT_GT(median_ratio, 0.75 * h_ratio * h_ratio) << "refinement " << i << ": median error "
                                                      << levels[i - 1].median << " -> " << levels[i].median;
    EXPECT_GT(p99_ratio, 0.75 * h_ratio * h_ratio) << "refinement " << i << ": p99 error " << levels[i - 1].p99
                                                   << " -> " << levels[i].p99;
  }
}

}  // namespace
}  // namespace plmap
