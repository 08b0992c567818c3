#pragma once
// A parametrization the smoothing tests start from: an icosphere (subdivisions, jitter as a
// fraction of the edge length, seed) simplified to `percent` % of its triangles (at least 8),
// features off.

#include <plmap/construct/simplify.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>

namespace plmap::simplify_test {

inline SimplifyResult simplified_sphere(int subdivisions, double jitter, std::uint32_t seed, int percent) {
  generators::Rng rng(seed);
  auto fine = std::make_shared<const Surface<2>>(generators::icosphere({subdivisions, jitter}, rng));
  SimplifyOptions options;
  options.target_elements = std::max<Index>(8, fine->element_count() * percent / 100);
  options.feature_angle_degrees = 180.0;
  return simplify(fine, options);
}

}  // namespace plmap::simplify_test
