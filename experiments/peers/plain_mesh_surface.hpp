#pragma once
// A PlainMesh of the peer benchmark's input pairs (inputs.hpp) as a plmap Surface: for the plmap
// tool of the benchmark and for the experiment runner's contact-pair inputs.

#include "inputs.hpp"

#include <plmap/core/surface.hpp>

#include <memory>
#include <vector>

namespace plmap::peers {

template <int d>
std::shared_ptr<const Surface<d>> to_surface(const PlainMesh<d>& mesh) {
  std::vector<WorldPoint<d>> points;
  points.reserve(mesh.points.size());
  for (const auto& p : mesh.points) {
    WorldPoint<d> x;
    for (int k = 0; k <= d; ++k) x(k) = p[k];
    points.push_back(x);
  }
  std::vector<ElementCorners<d>> cells;
  cells.reserve(mesh.cells.size());
  for (const auto& c : mesh.cells) {
    ElementCorners<d> corners;
    for (int k = 0; k <= d; ++k) corners[k] = static_cast<Index>(c[k]);
    cells.push_back(corners);
  }
  return std::make_shared<const Surface<d>>(std::move(points), std::move(cells));
}

}  // namespace plmap::peers
