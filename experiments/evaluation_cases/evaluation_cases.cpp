// The evaluation benchmarks' shared cases (evaluation_cases.hpp).

#include "evaluation_cases.hpp"

#include <plmap/core/io/surface_reader.hpp>
#include <plmap/verify/generators/simplified_surface.hpp>

#include <random>

namespace plmap::bench {

std::shared_ptr<const Surface<2>> coarse_femur(const std::string& path, std::size_t faces) {
  return std::make_shared<const Surface<2>>(generators::simplify_by_edge_collapse(read_surface<2>(path), faces));
}

std::vector<SurfacePoint<2>> random_queries(const Surface<2>& s1, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<Index> element(0, s1.element_count() - 1);
  std::vector<SurfacePoint<2>> q(n);
  for (auto& p : q) {
    double x = u(rng), y = u(rng);
    if (x + y > 1) x = 1 - x, y = 1 - y;
    p = {element(rng), LocalPoint<2>(x, y)};
  }
  return q;
}

}  // namespace plmap::bench
