// finalize() cuts every face of an element's graph into triangles (ear clipping, then Lawson
// flips, or a constrained Delaunay triangulation where the fast path declines). Either way each
// face's triangulation must end up constrained Delaunay: every closure edge between two regions
// is locally Delaunay under the exact in-circle test. This matters beyond looks: Xi is
// interpolated on each closure triangle, and slivers would carry ill-conditioned affine maps.

#include <plmap/core/predicates.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>

namespace plmap {
namespace {

bool is_closure_edge(const MapData<2>& m, Index a, Index b) {
  for (Index i = m.neighbor_begin[a]; i < m.neighbor_begin[a + 1]; ++i)
    if (m.neighbor[i] == b) return m.neighbor_edge_kind[i] == GraphEdgeKind::closure;
  return false;
}

RC_GTEST_PROP(Closure, ClosureEdgesOfOverlayMapsAreLocallyDelaunay, ()) {
  const auto c = *rc::gen::scale(0.6, generators::overlay_maps<2>());
  const MapData<2>& m = c.map->data();
  int closure_sides = 0;
  for (Index r = 0; r < c.map->region_count(); ++r) {
    for (int i = 0; i < 3; ++i) {
      const Index s = m.region_neighbors[r][i];
      if (s == invalid_index || s < r) continue;
      const auto& rc = m.region_corners[r];
      const Index p = rc[i], a = rc[(i + 1) % 3], b = rc[(i + 2) % 3];
      if (!is_closure_edge(m, a, b)) continue;
      const auto& sc = m.region_corners[s];
      const Index q = *std::find_if(sc.begin(), sc.end(), [&](Index n) { return n != a && n != b; });
      ++closure_sides;
      RC_ASSERT(incircle(m.node_position[p], m.node_position[a], m.node_position[b],
                         m.node_position[q]) <= 0);
    }
  }
  RC_CLASSIFY(closure_sides > 0, "with closure edges between regions");
}

}  // namespace
}  // namespace plmap
