// Mortar mass matrix between two non-matching P1 discretizations, from the regions of a map.
//
//   plmap_mortar_mass_matrix [seed] [--write DIR]
//
// d = 2: S1 is a 6 x 6 grid of the unit square, S2 a Delaunay triangulation of random points in
// it; the overlay map (Xi = identity of the plane) is built with the generators of plmap::verify.
// d = 1: two random subdivisions of one polyline. For both, the program assembles
// M_ij = integral of phi_i psi_j over the regions and checks it against exact values:
//   sum of all entries = |domain|, row sums = integral of phi_i, column sums = integral of psi_j,
// and, for two identical grids, M = the standard P1 mass matrix. Exit status 1 if a check fails.
// With --write DIR it also writes each non-matching case's map (DIR/<case>.plmap) and matrix
// (DIR/<case>.mortar.txt: "rows columns", then one "i j value" line per nonzero entry, with
// doubles that read back exactly), so that other implementations, such as the Python example
// examples/python/mortar_mass_matrix.py, can be compared with this one.

#include "mortar_mass_matrix.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/verify/generators/random_maps.hpp>

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

using namespace plmap;

namespace {

constexpr double tolerance = 1e-12;

bool report(const char* what, double error) {
  const bool ok = error <= tolerance;
  fmt::print("  {:<44} error {:.2e}  {}\n", what, error, ok ? "ok" : "FAILED");
  return ok;
}

/// The map and its mortar matrix, for comparisons with other implementations (see the top).
template <int d>
void write_case(const std::filesystem::path& dir, const std::string& name, const PlMap<d>& map) {
  std::filesystem::create_directories(dir);
  save_map(dir / (name + ".plmap"), map);
  const Eigen::MatrixXd m = mortar::mortar_mass_matrix(map);
  std::ofstream out(dir / (name + ".mortar.txt"));
  out << m.rows() << ' ' << m.cols() << '\n';
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      if (m(i, j) != 0.0) out << fmt::format("{} {} {}\n", i, j, m(i, j));  // shortest exact form
  if (!out.flush()) throw Error((dir / (name + ".mortar.txt")).string() + ": cannot write");
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
  std::uint64_t seed = 2026;
  std::optional<std::filesystem::path> write_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--write" && i + 1 < argc)
      write_dir = argv[++i];
    else
      seed = std::stoull(arg);
  }
  generators::Rng rng(seed);
  bool ok = true;

  // d = 2, non-matching: a structured grid against an unstructured Delaunay mesh.
  auto grid = std::make_shared<const Surface<2>>(generators::grid_triangulation({.cells = 6}, rng));
  auto delaunay = std::make_shared<const Surface<2>>(
      generators::delaunay_triangulation({.interior_points = 40, .boundary_points = 8, .grid_points = 6}, rng));
  const auto non_matching = generators::plane_overlay_map(grid, delaunay, "grid 6x6 -> Delaunay (d = 2)");
  ok &= check_mortar<2>(non_matching);
  if (write_dir) write_case(*write_dir, "grid_delaunay", *non_matching.map);

  // d = 2, matching: the mortar matrix of a grid with itself is its P1 mass matrix.
  const auto same = generators::plane_overlay_map(grid, grid, "grid 6x6 -> itself (d = 2)");
  ok &= check_mortar<2>(same);
  ok &= report("identical grids: M = P1 mass matrix (max entry)",
               (mortar::mortar_mass_matrix(*same.map) - mortar::p1_mass_matrix(*grid)).cwiseAbs().maxCoeff());

  // d = 1: two subdivisions of a random polyline.
  auto base = std::make_shared<const Surface<1>>(generators::random_open_polyline(4, rng));
  const auto polylines = generators::polyline_overlay_map(generators::random_subdivisions(base, 3, rng),
                                                          "two subdivisions of a polyline (d = 1)");
  ok &= check_mortar<1>(polylines);
  if (write_dir) write_case(*write_dir, "polylines", *polylines.map);

  fmt::print("{}\n", ok ? "all mortar identities hold" : "SOME CHECKS FAILED");
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
