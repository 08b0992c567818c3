#include "refinement.hpp"

#include <plmap/core/map_builder.hpp>

#include <utility>
#include <vector>

namespace downstream {

using plmap::ElementCorners;
using plmap::Index;
using plmap::Surface;
using plmap::WorldPoint;

std::shared_ptr<const Surface<2>> midpoint_refine(const Surface<2>& coarse) {
  const Index vertex_count = coarse.vertex_count();
  std::vector<WorldPoint<2>> vertices = coarse.vertices();
  for (Index e = 0; e < coarse.edge_count(); ++e) {
    const auto [a, b] = coarse.edge_vertices(e);
    vertices.push_back(0.5 * (coarse.vertex(a) + coarse.vertex(b)));
  }
  std::vector<ElementCorners<2>> elements;
  for (Index t = 0; t < coarse.element_count(); ++t) {
    const auto& c = coarse.element(t);
    // Local edge k joins corners k and k+1, so m[k] lies between c[k] and c[k+1]; the four
    // children keep the parent's counter-clockwise orientation.
    Index m[3];
    for (int k = 0; k < 3; ++k) m[k] = vertex_count + coarse.element_edge(t, k);
    elements.push_back({c[0], m[0], m[2]});
    elements.push_back({m[0], c[1], m[1]});
    elements.push_back({m[2], m[1], c[2]});
    elements.push_back({m[0], m[1], m[2]});
  }
  return std::make_shared<const Surface<2>>(std::move(vertices), std::move(elements));
}

plmap::PlMap<2> refinement_map(std::shared_ptr<const Surface<2>> coarse,
                               std::shared_ptr<const Surface<2>> fine) {
  const Index vertex_count = coarse->vertex_count();
  plmap::MapBuilder<2> builder(coarse, fine);
  for (Index v = 0; v < vertex_count; ++v) builder.add_vertex_preimage_at_vertex(v, v);
  for (Index e = 0; e < coarse->edge_count(); ++e)
    builder.add_vertex_preimage_on_edge(vertex_count + e, e, 0.5);
  // Every fine edge lies inside one coarse triangle or along a coarse edge.
  for (Index t = 0; t < fine->element_count(); ++t) builder.add_target_element(t);
  return std::move(builder).finalize();
}

std::shared_ptr<const Surface<2>> unit_square() {
  return std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
      std::vector<ElementCorners<2>>{{0, 1, 2}, {0, 2, 3}});
}

std::shared_ptr<const Surface<2>> tetrahedron() {
  // Outward normals: each face lists its corners counter-clockwise seen from outside.
  return std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
      std::vector<ElementCorners<2>>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

}  // namespace downstream
