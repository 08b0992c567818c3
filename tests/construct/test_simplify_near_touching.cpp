// A simplification step whose straightened S2 edge passes within rounding of a vertex preimage.
// Found by the property SurfacesWithBoundaryOrNonManifoldStayValidParametrizations (random seed
// 13, "shared_corner over grid resolution=2"): on a 2 x 2 grid the plane-projection flattening
// put S2 vertex (0.5, 0.5) at a point that, in the next step's flattening, lay on the straight
// preimage of the S2 edge (0, 0.5)-(0.5, 1) up to the last bit. The exact crossing test on the
// rounded planar positions said "one side", the hand-over to the builder rounded it onto the
// edge, and the S2 triangle between them lost its region: the images covered 2.087 of S2's
// 2.212. A node that close to another edge's preimage is now refused like one on a new edge.

#include "simplify_test_support.hpp"

#include <plmap/construct/simplify.hpp>
#include <plmap/verify/check.hpp>

#include <gtest/gtest.h>

namespace plmap {
namespace {

// The failing case's surface: the unit square as a 2 x 2 grid (diagonals from the lower left),
// and a sheet of two triangles above [1, 2]^2 sharing the vertex (1, 1) with it.
std::shared_ptr<const Surface<2>> grid_with_a_sheet_at_its_corner() {
  std::vector<WorldPoint<2>> vertices = {
      {0, 0, 0},   {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0},   {1, 0, 0},   {1, 0.5, 0},
      {0.5, 1, 0}, {0, 1, 0},   {1, 1, 0},     {2, 1, 0.49},  {1, 2, 0.52}, {2, 2, 0.97}};
  std::vector<ElementCorners<2>> triangles = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}, {4, 5, 2}, {3, 2, 6},
                                              {3, 6, 7}, {2, 5, 6}, {5, 8, 6}, {8, 9, 10}, {9, 11, 10}};
  return std::make_shared<const Surface<2>>(std::move(vertices), std::move(triangles));
}

TEST(SimplifyNearTouching, NoVertexPreimageEndsOnAStraightenedEdge) {
  const auto fine = grid_with_a_sheet_at_its_corner();
  for (Index target : {4, 3, 2}) {
    SimplifyOptions options;
    options.target_elements = target;
    options.feature_angle_degrees = 180.0;
    options.hole_triangulation = "min-max-aspect";
    options.flattening = "plane-projection";
    options.oracles.add("long-edge", 1.0).add("self-intersection");
    const SimplifyResult result = simplify(fine, options);
    VerifyOptions v;
    v.expect_parametrization = true;
    const VerificationReport report = verify(result.map, v);
    EXPECT_TRUE(report.ok()) << "target " << target << "\n" << summary(report);
    EXPECT_NEAR(simplify_test::image_area(result.map), fine->measure(), 1e-9 * fine->measure()) << "target " << target;
    EXPECT_TRUE(simplify_test::vertices_without_one_preimage(result.map).empty()) << "target " << target;
  }
}

}  // namespace
}  // namespace plmap
