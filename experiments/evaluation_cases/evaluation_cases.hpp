#pragma once
// The maps and queries the evaluation benchmarks share (bench_point_location, psurface_eval), so
// that their figures are taken on the same cases: CGAL's femur simplified by edge collapse, and
// query points uniform over the elements from a fixed seed.

#include <plmap/core/surface.hpp>
#include <plmap/core/types.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace plmap::bench {

/// The mesh at `path` (CGAL's femur in the benchmarks) simplified to about `faces` triangles by
/// CGAL's edge collapse.
std::shared_ptr<const Surface<2>> coarse_femur(const std::string& path, std::size_t faces);

/// `n` points uniform over the elements of `s1` (an element uniformly, then a point uniform in
/// its reference triangle); the same seed gives the same points.
std::vector<SurfacePoint<2>> random_queries(const Surface<2>& s1, std::size_t n, std::uint64_t seed);

}  // namespace plmap::bench
