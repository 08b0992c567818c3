// The mortar mass matrix (examples/mortar_mass_matrix) over random overlays: on every generated
// overlay (Xi = identity of the plane, D = S1, Xi(D) = S2) the exact identities hold:
// sum of all entries = |S1|, row sums = integrals of the S1 hat functions, column sums = those
// of S2; and the overlay of a triangulation with itself gives its P1 mass matrix.

#include "../../examples/mortar_mass_matrix/mortar_mass_matrix.hpp"

#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

namespace plmap {
namespace {

template <int d>
void check_identities(const generators::MapCase<d>& c) {
  const Eigen::MatrixXd m = mortar::mortar_mass_matrix(*c.map);
  const auto e = mortar::mortar_identity_errors<d>(m, *c.domain, *c.target);
  const double tol = 1e-12 * c.domain->measure();
  RC_ASSERT(e.total <= tol);
  RC_ASSERT(e.row_sums <= tol);
  RC_ASSERT(e.column_sums <= tol);
}

RC_GTEST_PROP(GeneratedMapsMortar, OverlaysOfTriangulationsSatisfyTheMortarIdentities, ()) {
  check_identities<2>(*generators::overlay_maps<2>());
}

RC_GTEST_PROP(GeneratedMapsMortar, OverlaysOfPolylinesSatisfyTheMortarIdentities, ()) {
  check_identities<1>(*generators::overlay_maps<1>());
}

RC_GTEST_PROP(GeneratedMapsMortar, OverlayWithItselfGivesTheP1MassMatrix, ()) {
  const auto recipe = *generators::planar_recipes();
  auto s = std::make_shared<const Surface<2>>(generators::make_planar(recipe));
  const auto c = generators::plane_overlay_map(s, s, "self-overlay of " + generators::describe(recipe));
  RC_ASSERT(c.map->region_count() == s->element_count());
  const Eigen::MatrixXd difference = mortar::mortar_mass_matrix(*c.map) - mortar::p1_mass_matrix(*s);
  RC_ASSERT(difference.cwiseAbs().maxCoeff() <= 1e-14);
}

}  // namespace
}  // namespace plmap
