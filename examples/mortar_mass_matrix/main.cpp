// Mortar mass matrix between two non-matching P1 discretizations, from the regions of a map.
//
//   plmap_mortar_mass_matrix [seed]
//
// d = 2: S1 is a 6 x 6 grid of the unit square, S2 a Delaunay triangulation of random points in
// it; the overlay map (Xi = identity of the plane) is built with the generators of plmap::verify.
// d = 1: two random subdivisions of one polyline. For both, the program assembles
// M_ij = integral of phi_i psi_j over the regions and checks it against exact values:
//   sum of all entries = |domain|, row sums = integral of phi_i, column sums = integral of psi_j,
// and, for two identical grids, M = the standard P1 mass matrix. Exit status 1 if a check fails.

#include "mortar_mass_matrix.hpp"

#include <plmap/verify/generators/random_maps.hpp>

#include <fmt/format.h>

#include <cstdlib>
#include <string>

using namespace plmap;

namespace {

constexpr double tolerance = 1e-12;

bool report(const char* what, double error) {
  const bool ok = error <= tolerance;
  fmt::print("  {:<44} error {:.2e}  {}\n", what, error, ok ? "ok" : "FAILED");
  return ok;
}

template <int d>
bool check_mortar(const generators::MapCase<d>& c) {
  const auto regions = remote_intersections(*c.map);
  fmt::print("{}: |S1| = {} elements, |S2| = {} elements, {} regions\n", c.description,
             c.domain->element_count(), c.target->element_count(), regions.size());
  for (std::size_t r = 0; r < std::min<std::size_t>(regions.size(), 3); ++r)
    fmt::print("  region {}: S1 element {} x S2 element {}, measure {:.4g}\n", r, regions[r].domain_element,
               regions[r].target_element, regions[r].domain_measure());
  if (regions.size() > 3) fmt::print("  ...\n");

  const Eigen::MatrixXd m = mortar::mortar_mass_matrix(*c.map);
  const auto e = mortar::mortar_identity_errors<d>(m, *c.domain, *c.target);
  bool ok = report("sum of all entries = measure of the domain", e.total);
  ok &= report("row sums = integrals of the S1 hat functions", e.row_sums);
  ok &= report("column sums = integrals of the S2 hat functions", e.column_sums);
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t seed = argc > 1 ? std::stoull(argv[1]) : 2026;
  generators::Rng rng(seed);
  bool ok = true;

  // d = 2, non-matching: a structured grid against an unstructured Delaunay mesh.
  auto grid = std::make_shared<const Surface<2>>(generators::grid_triangulation({.cells = 6}, rng));
  auto delaunay = std::make_shared<const Surface<2>>(
      generators::delaunay_triangulation({.interior_points = 40, .boundary_points = 8, .grid_points = 6}, rng));
  ok &= check_mortar<2>(generators::plane_overlay_map(grid, delaunay, "grid 6x6 -> Delaunay (d = 2)"));

  // d = 2, matching: the mortar matrix of a grid with itself is its P1 mass matrix.
  const auto same = generators::plane_overlay_map(grid, grid, "grid 6x6 -> itself (d = 2)");
  ok &= check_mortar<2>(same);
  ok &= report("identical grids: M = P1 mass matrix (max entry)",
               (mortar::mortar_mass_matrix(*same.map) - mortar::p1_mass_matrix(*grid)).cwiseAbs().maxCoeff());

  // d = 1: two subdivisions of a random polyline.
  auto base = std::make_shared<const Surface<1>>(generators::random_open_polyline(4, rng));
  ok &= check_mortar<1>(generators::polyline_overlay_map(generators::random_subdivisions(base, 3, rng),
                                                         "two subdivisions of a polyline (d = 1)"));

  fmt::print("{}\n", ok ? "all mortar identities hold" : "SOME CHECKS FAILED");
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
