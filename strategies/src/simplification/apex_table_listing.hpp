#pragma once
/// \file
/// Reading a triangulation of a hole polygon off its apex table: the one canonical listing that
/// both hole triangulations (min-max-aspect and constrained Delaunay) report, so that the same
/// set of triangles always comes out in the same order.

#include <plmap/strategies/simplification/hole_triangulation.hpp>

#include <array>
#include <vector>

namespace plmap::detail {

/// Appends to `out` the triangles (i, m, j), i < m < j, of the triangulation of the polygon
/// 0, 1, ..., n-1 in which the chord i-j has apex m = split[i * n + j], read from the chord
/// 0-(n-1) inwards, depth first. `stack` is the caller's reused buffer. Returns false if a chord
/// that must be split has no apex (-1).
inline bool list_from_apex_table(const std::vector<int>& split, int n, std::vector<std::array<int, 2>>& stack,
                                 HoleTriangles& out) {
  stack.assign(1, {0, n - 1});
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int m = split[static_cast<std::size_t>(i * n + j)];
    if (m < 0) return false;
    out.push_back({i, m, j});
    stack.push_back({i, m});
    stack.push_back({m, j});
  }
  return true;
}

}  // namespace plmap::detail
