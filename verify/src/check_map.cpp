// DESIGN.md §4.4: node images are where node_target says, region corners map into the common S2
// element, no region folds over, and every S2 vertex has at most one preimage.

#include "check_context.hpp"

namespace plmap::detail {

namespace {

template <int d>
double distance_to_segment(const WorldPoint<d>& p, const WorldPoint<d>& a, const WorldPoint<d>& b) {
  const WorldPoint<d> ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

/// Identifies the S1 point a vertex-preimage node sits on, so that copies of one node count as
/// one preimage: an S1 vertex, a point on an S1 edge (with its parameter), or the node itself.
struct PreimageKey {
  Index target_vertex;
  int place;  // 0: S1 vertex, 1: S1 edge, 2: interior node
  Index id;
  double parameter;
  Index node;
  friend bool operator<(const PreimageKey& x, const PreimageKey& y) {
    return std::tie(x.target_vertex, x.place, x.id, x.parameter) <
           std::tie(y.target_vertex, y.place, y.id, y.parameter);
  }
};

}  // namespace

template <int d>
void run_map(const MapContext<d>& ctx, ViolationSink& sink) {
  const auto& m = ctx.data;
  const auto& map = ctx.map;
  const auto& s2 = ctx.s2;
  const double local_tol = ctx.options.local_tolerance;
  const double world_tol = ctx.world_tolerance_s2;
  const Index nn = static_cast<Index>(m.node_type.size());

  // ---- node images --------------------------------------------------------------------------
  std::vector<PreimageKey> preimages;
  for (Index n = 0; n < nn; ++n) {
    const Index t = ctx.node_element[n];
    const SurfacePoint<d> img = m.node_image(n);
    const double inside = min_barycentric<d>(img.local);
    if (inside < -local_tol)
      sink.add("node_image_outside_element", {t, n, invalid_index, img.element}, [&] {
        return fmt::format("node {} has image {} on S2 element {}, outside it (barycentric {:.3g})",
                           n, fmt_point<d>(img.local), img.element, inside);
      });
    const NodeType type = m.node_type[n];
    const WorldPoint<d> world = map.node_target_world(n);
    if (is_target_vertex_preimage(type)) {
      const double dist = (world - s2.vertex(m.node_target[n])).norm();
      if (!(dist <= world_tol))
        sink.add("node_image_on_target", {t, n, invalid_index, img.element}, [&] {
          return fmt::format("node {} ({}) is the preimage of S2 vertex {}, but its image is {:.3g} "
                             "away from it (tolerance {:.3g})",
                             n, to_string(type), m.node_target[n], dist, world_tol);
        });
      PreimageKey key{m.node_target[n], 2, n, 0.0, n};
      if (type == NodeType::corner) {
        key.place = 0;
        key.id = ctx.s1.element(t)[m.node_location[n]];
      } else if constexpr (d == 2) {
        if (type == NodeType::touching) {
          key.place = 1;
          key.id = ctx.s1.element_edge(t, m.node_location[n]);
          key.parameter = global_edge_parameter(ctx.s1, t, m.node_location[n], m.node_position[n]);
        }
      }
      preimages.push_back(key);
    } else if (type == NodeType::intersection || (is_on_rim(type) && m.node_target[n] != invalid_index)) {
      if constexpr (d == 2) {
        const auto ends = s2.edge_vertices(m.node_target[n]);
        const double dist = distance_to_segment<d>(world, s2.vertex(ends[0]), s2.vertex(ends[1]));
        if (!(dist <= world_tol))
          sink.add("node_image_on_target", {t, n, invalid_index, img.element}, [&] {
            return fmt::format("{} node {} lies on S2 edge {}, but its image is {:.3g} "
                               "away from it (tolerance {:.3g})",
                               to_string(type), n, m.node_target[n], dist, world_tol);
          });
      }
    }
  }

  // ---- at most one preimage per S2 vertex ---------------------------------------------------
  std::sort(preimages.begin(), preimages.end());
  for (std::size_t i = 0; i < preimages.size();) {
    std::size_t j = i + 1;
    std::size_t distinct = 1;
    Index second = invalid_index;
    while (j < preimages.size() && preimages[j].target_vertex == preimages[i].target_vertex) {
      const PreimageKey& a = preimages[j - 1];
      const PreimageKey& b = preimages[j];
      if (a.place != b.place || a.id != b.id || std::abs(a.parameter - b.parameter) > local_tol) {
        ++distinct;
        if (second == invalid_index) second = b.node;
      }
      ++j;
    }
    if (distinct > 1)
      sink.add("vertex_preimage_unique", {ctx.node_element[second], second}, [&] {
        return fmt::format("S2 vertex {} has {} distinct preimages (nodes {} and {}, among others)",
                           preimages[i].target_vertex, distinct, preimages[i].node, second);
      });
    i = j;
  }

  // ---- region corners map into region_target onto the node images; no fold-over ------------
  for (Index t = 0; t < ctx.element_count(); ++t) {
    for (Index r = ctx.regions_begin(t); r < ctx.regions_end(t); ++r) {
      const auto& c = m.region_corners[r];
      const Index target = m.region_target[r];
      const double rounding = region_map_rounding<d>(m.region_map[r]);
      const double region_tol = local_tol + rounding;
      const double region_world_tol = world_tol + rounding_in_space(rounding, s2);
      std::array<LocalPoint<d>, d + 1> image;
      for (int i = 0; i <= d; ++i) {
        const Index n = c[i];
        image[i] = apply<d>(m.region_map[r], m.node_position[n]);
        const double inside = min_barycentric<d>(image[i]);
        if (!(inside >= -region_tol))
          sink.add("region_corner_image", {t, n, r, target}, [&] {
            return fmt::format("region {} maps its corner {} to {} on S2 element {}, outside it "
                               "(barycentric {:.3g})",
                               r, n, fmt_point<d>(image[i]), target, inside);
          });
        const double dist = (s2.world_position(target, image[i]) - map.node_target_world(n)).norm();
        if (!(dist <= region_world_tol))
          sink.add("region_corner_image", {t, n, r, target}, [&] {
            return fmt::format("region {} maps its corner {} {:.3g} away from the node's image "
                               "(tolerance {:.3g})",
                               r, n, dist, region_world_tol);
          });
      }
      int domain_sign, image_sign;
      if constexpr (d == 1) {
        const double dx = m.node_position[c[1]](0) - m.node_position[c[0]](0);
        const double dy = image[1](0) - image[0](0);
        domain_sign = (dx > 0) - (dx < 0);
        image_sign = (dy > 0) - (dy < 0);
      } else {
        domain_sign = orient2d(m.node_position[c[0]], m.node_position[c[1]], m.node_position[c[2]]);
        image_sign = orient2d(image[0], image[1], image[2]);
      }
      if (domain_sign != 0 && domain_sign * image_sign != m.orientation)
        sink.add("fold_over", {t, invalid_index, r, target}, [&] {
          return image_sign == 0
                     ? fmt::format("region {} is mapped onto a degenerate image", r)
                     : fmt::format("region {} is mapped with orientation {}, the map's is {} "
                                   "(fold-over)",
                                   r, domain_sign * image_sign, m.orientation);
        });
    }
  }
}

template void run_map(const MapContext<1>&, ViolationSink&);
template void run_map(const MapContext<2>&, ViolationSink&);

}  // namespace plmap::detail
