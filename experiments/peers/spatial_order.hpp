#pragma once
// The benchmark's inputs renumbered in space-filling-curve order (bench_projection_peers
// --order spatial): cells sorted by the Morton code of their centroid, points numbered in the
// order the sorted cells first use them. Each cell keeps its corners in their order, so the
// geometry, the orientation and every measure stay those of the input; only the numbering
// changes. It measures how much a tool depends on the order its input comes in: CGAL's meshes
// and the remeshed copies of the real-mesh pairs list their triangles in no spatial order (the
// centroids of consecutive triangles lie about 50 edge lengths apart), the generated planes and
// spheres row by row.

#include "inputs.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <vector>

namespace plmap::peers {

/// Interleaves the low `bits` bits of the coordinates' cells (x first).
template <int n>
std::uint64_t morton_code(const std::array<std::uint32_t, n>& cell, int bits) {
  std::uint64_t code = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (int k = 0; k < n; ++k) code = (code << 1) | ((cell[k] >> b) & 1u);
  return code;
}

/// The mesh with its cells in Morton order of their centroids and its points in first-use order.
template <int d>
PlainMesh<d> spatially_ordered(const PlainMesh<d>& mesh) {
  constexpr int n = d + 1;
  constexpr int bits = 63 / n;
  std::array<double, n> low, high;
  low.fill(0.0);
  high.fill(0.0);
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    for (int k = 0; k < n; ++k) {
      low[k] = i == 0 ? mesh.points[i][k] : std::min(low[k], mesh.points[i][k]);
      high[k] = i == 0 ? mesh.points[i][k] : std::max(high[k], mesh.points[i][k]);
    }
  std::vector<std::uint64_t> code(mesh.cells.size());
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    std::array<std::uint32_t, n> cell;
    for (int k = 0; k < n; ++k) {
      double centroid = 0.0;
      for (int corner : mesh.cells[c]) centroid += mesh.points[corner][k] / n;
      const double extent = high[k] - low[k];
      const double unit = extent > 0.0 ? (centroid - low[k]) / extent : 0.0;
      cell[k] = static_cast<std::uint32_t>(std::clamp(unit, 0.0, 1.0) * double((1u << bits) - 1));
    }
    code[c] = morton_code<n>(cell, bits);
  }
  std::vector<std::size_t> order(mesh.cells.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return code[a] < code[b]; });
  PlainMesh<d> out;
  std::vector<int> renumbered(mesh.points.size(), -1);
  out.cells.reserve(mesh.cells.size());
  for (std::size_t c : order) {
    std::array<int, n> cell = mesh.cells[c];
    for (int& corner : cell) {
      if (renumbered[corner] < 0) {
        renumbered[corner] = static_cast<int>(out.points.size());
        out.points.push_back(mesh.points[corner]);
      }
      corner = renumbered[corner];
    }
    out.cells.push_back(cell);
  }
  return out;
}

}  // namespace plmap::peers
