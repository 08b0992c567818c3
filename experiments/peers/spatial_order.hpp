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

#include <plmap/core/spatial_order.hpp>

#include <algorithm>
#include <array>
#include <span>
#include <vector>

namespace plmap::peers {

/// The mesh with its cells in Morton order of their centroids (plmap::morton_order) and its
/// points in first-use order.
template <int d>
PlainMesh<d> spatially_ordered(const PlainMesh<d>& mesh) {
  constexpr int n = d + 1;
  WorldPoint<d> low = WorldPoint<d>::Zero(), high = WorldPoint<d>::Zero();
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    for (int k = 0; k < n; ++k) {
      low(k) = i == 0 ? mesh.points[i][k] : std::min(low(k), mesh.points[i][k]);
      high(k) = i == 0 ? mesh.points[i][k] : std::max(high(k), mesh.points[i][k]);
    }
  std::vector<WorldPoint<d>> centroids(mesh.cells.size(), WorldPoint<d>::Zero());
  for (std::size_t c = 0; c < mesh.cells.size(); ++c)
    for (int corner : mesh.cells[c])
      for (int k = 0; k < n; ++k) centroids[c](k) += mesh.points[corner][k] / n;
  const std::vector<Index> order = morton_order<d>(std::span<const WorldPoint<d>>(centroids), low, high);
  PlainMesh<d> out;
  std::vector<int> renumbered(mesh.points.size(), -1);
  out.cells.reserve(mesh.cells.size());
  for (const Index c : order) {
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
