// Builds the map from the unit square onto its midpoint refinement and prints its regions: for
// each, the coarse (S1) and fine (S2) triangle and the corners on both sides.
#include "refinement.hpp"

#include <plmap/core/regions.hpp>
#include <plmap/verify/check.hpp>

#include <Eigen/Core>

#include <iostream>

int main() {
  const Eigen::IOFormat point_format(Eigen::StreamPrecision, Eigen::DontAlignCols, ", ", ", ");
  const auto coarse = downstream::unit_square();
  const auto fine = downstream::midpoint_refine(*coarse);
  const plmap::PlMap<2> map = downstream::refinement_map(coarse, fine);

  for (const auto& region : plmap::remote_intersections(map)) {
    std::cout << "region " << region.region << ": S1 triangle " << region.domain_element
              << " -> S2 triangle " << region.target_element << ", area "
              << region.domain_measure() << "\n";
    for (int i = 0; i < 3; ++i)
      std::cout << "  (" << region.domain_world[i].transpose().format(point_format) << ") -> ("
                << region.target_world[i].transpose().format(point_format) << ")\n";
  }
  plmap::VerifyOptions options;
  options.expect_parametrization = true;
  const plmap::VerificationReport report = plmap::verify(map, options);
  std::cout << map.region_count() << " regions, verify: " << (report.ok() ? "ok" : "FAILED")
            << "\n";
  if (!report.ok()) std::cout << plmap::summary(report);
  return report.ok() ? 0 : 1;
}
