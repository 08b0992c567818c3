// The grid cells of InverseIndex: where an S2 element has many regions, a query looks only at its
// cell's candidates, also for points in no image (the rounding gaps between images and the
// border of Xi(D)). These tests check that the cells list every image within the tolerance of a
// point, and that the answers equal those of a scan of all the element's images.

#include "fine_onto_coarse_overlays.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/verify/generators/random_maps.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace plmap;

namespace {

/// Xi^{-1} at y by the rule of inverse_evaluate, but scanning every image of y's element: the
/// image that contains y, else the one with the largest margin if it is within the tolerance.
/// Returns whether y was found and the world point.
std::pair<bool, WorldPoint<2>> scan_all_images(const InverseIndex<2>& index, const SurfacePoint<2>& y) {
  const double tolerance = index.options().tolerance;
  double best_margin = -tolerance;
  const InverseIndex<2>::Entry* best = nullptr;
  std::array<double, 3> best_w{};
  for (const auto& e : index.entries(y.element)) {
    const auto& c = e.image_corners;
    std::array<double, 3> w{};
    double margin = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
      const LocalPoint<2> a = c[(i + 1) % 3], b = c[(i + 2) % 3];
      w[i] = (b.x() - a.x()) * (y.local.y() - a.y()) - (b.y() - a.y()) * (y.local.x() - a.x());
      margin = std::min(margin, w[i] / (b - a).norm());
    }
    if (margin >= best_margin) best = &e, best_margin = margin, best_w = w;
  }
  if (best == nullptr) return {false, WorldPoint<2>::Zero()};
  double sum = 0;
  for (double& x : best_w) sum += x = std::max(x, 0.0);
  WorldPoint<2> world = WorldPoint<2>::Zero();
  for (int j = 0; j < 3; ++j) world += (best_w[j] / sum) * best->preimage_world[j];
  return {true, world};
}

}  // namespace

RC_GTEST_PROP(InverseGridCells, ListEveryImageWithinTheToleranceAndAnswerLikeAFullScan, (std::uint64_t seed)) {
  // a 1x1 coarse grid: every fine region lies on one of its two triangles
  const generators::MapCase<2> c = test::fine_onto_coarse_overlay(1);
  const InverseIndex<2> index(*c.map);
  const double tolerance = index.options().tolerance;
  generators::Rng rng(seed);
  int checked = 0;
  for (Index element = 0; element < c.target->element_count(); ++element) {
    if (!index.has_grid(element)) continue;
    const auto entries = index.entries(element);
    for (int k = 0; k < 40; ++k) {
      // A point on a side of a random image, moved outward across it by up to 0.9 tolerance
      // (still within the tolerance of that image), or by 2 tolerances (within it only if another
      // image is near): the cases that the cells must list for the rounding-gap rule.
      const auto& e = entries[static_cast<std::size_t>(generators::uniform_index(rng, static_cast<int>(entries.size())))];
      const int side = static_cast<int>(generators::uniform_index(rng, 3));
      const LocalPoint<2> a = e.image_corners[static_cast<std::size_t>(side)];
      const LocalPoint<2> b = e.image_corners[static_cast<std::size_t>((side + 1) % 3)];
      const double t = generators::uniform_unit(rng);
      const LocalPoint<2> outward = LocalPoint<2>(b.y() - a.y(), a.x() - b.x()).normalized();
      const double push = (k % 2 == 0 ? 0.9 : 2.0) * tolerance;
      const SurfacePoint<2> y{element, a + t * (b - a) + push * outward};
      if (k % 2 == 0) {
        const auto listed = index.cell_candidates(element, y.local);
        const auto position = static_cast<Index>(&e - entries.data());
        RC_ASSERT(std::find(listed.begin(), listed.end(), position) != listed.end());
      }
      // Only points inside the reference triangle: the rest are also searched in the
      // neighbouring elements, which the full scan here does not do.
      if (y.local.x() < 0 || y.local.y() < 0 || y.local.x() + y.local.y() > 1) continue;
      const InverseEvaluation<2> got = inverse_evaluate(index, y);
      const auto [found, world] = scan_all_images(index, y);
      RC_ASSERT(got.in_image == found);
      if (found) {
        RC_ASSERT((got.world - world).norm() <= 1e-12 * (1.0 + world.norm()));
      }
      ++checked;
    }
  }
  RC_CLASSIFY(checked == 0, "no element with a grid");
}
