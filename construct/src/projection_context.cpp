// Normal projection, the set-up phase: the direction field, the focal-free distance of every S1
// element, the kd-trees of both surfaces, and the limits the options give.

#include "projection_context.hpp"

#include "projection_seeds.hpp"

#include <plmap/construct/direction_field.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace plmap::projection {

template <int d>
ProjectionContext<d>::ProjectionContext(std::shared_ptr<const Surface<d>> s1_surface,
                                        std::shared_ptr<const Surface<d>> s2_surface,
                                        const ProjectionOptions& projection_options)
    : s1_shared(std::move(s1_surface)), s2_shared(std::move(s2_surface)), s1(*s1_shared), s2(*s2_shared),
      options(projection_options) {
  const unsigned setup_threads = resolve_thread_count(options.threads);
  vertex_directions = options.directions.empty() ? averaged_vertex_normals(s1, setup_threads)
                                : directions_from_values(s1, std::span<const double>(options.directions));
  if (options.normal_check != TargetNormalCheck::none) s2_vertex_normals = averaged_vertex_normals(s2, setup_threads);
  const double diagonal = (s1.bounding_box_max() - s1.bounding_box_min()).norm();
  distance_limit = options.max_distance_is_relative ? options.max_distance * diagonal : options.max_distance;
  if (!(distance_limit >= 0.0)) throw Error(fmt::format("max_distance {} is not >= 0", options.max_distance));
  if (std::isfinite(distance_limit)) {
    double longest_direction = 0.0;
    for (const auto& nu : vertex_directions) longest_direction = std::max(longest_direction, nu.norm());
    band_reach = distance_limit * longest_direction;
  }
  for (const Surface<d>* s : {&s1, &s2})
    coordinate_rounding = std::max({coordinate_rounding, 1e-12 * s->bounding_box_min().cwiseAbs().maxCoeff(),
                                    1e-12 * s->bounding_box_max().cwiseAbs().maxCoeff()});
  seed_count = std::clamp(options.search_seeds, 1, max_search_seeds);
  threads = resolve_thread_count(options.threads);
  // Independent indexes, the box index first: it takes about as long as both kd-trees, so with
  // two threads one builds it while the other builds the kd-trees (started last, it ran alone for
  // a third of the set-up on the 200k plane pair).
  parallel_for_pieces(3, 3, threads, [&](std::size_t k, std::size_t, std::size_t) {
    if (k == 0)
      s1_boxes = std::make_unique<ElementBoxIndex<d>>(s1);
    else
      (k == 1 ? s1_index : s2_index) = std::make_unique<ElementIndex<d>>(k == 1 ? s1 : s2);
  });
  const ProjectionSearchLimits& limits = options.search_limits;
  if (!(limits.seed_walk_steps > 0) || !(limits.edge_walk_steps >= 0) || !(limits.inside_tolerance >= 0.0) ||
      !(limits.inside_tolerance < 0.5) || !(limits.edge_parameter_slack >= 0.0) ||
      !(limits.edge_parameter_slack < 0.5) || !(limits.second_search_hits > 0) ||
      !(limits.second_search_hits <= 32) || !(limits.second_search_reach >= 0.0) ||
      !(limits.farther_hit_retry >= 0.0) || !(limits.retry_seeds > 0) || !(limits.retry_seeds <= max_search_seeds) ||
      !(limits.piece_parameter_slack >= 0.0) || !(limits.piece_parameter_slack < 0.5) ||
      !(limits.end_parameter_slack >= 0.0) || !(limits.end_parameter_slack < 0.5) || !(limits.rim_walk_rounds >= 0))
    throw Error(fmt::format(
        "projection search limits out of range (seed_walk_steps {} > 0, edge_walk_steps {} >= 0, "
        "inside_tolerance {}, edge_parameter_slack {}, piece_parameter_slack {} and end_parameter_slack {} "
        "in [0, 0.5), second_search_hits {} and retry_seeds {} in 1..32, second_search_reach {} and "
        "farther_hit_retry {} >= 0, rim_walk_rounds {} >= 0)",
        limits.seed_walk_steps, limits.edge_walk_steps, limits.inside_tolerance, limits.edge_parameter_slack,
        limits.piece_parameter_slack, limits.end_parameter_slack, limits.second_search_hits, limits.retry_seeds,
        limits.second_search_reach, limits.farther_hit_retry, limits.rim_walk_rounds));
  retry_seed_count = limits.retry_seeds;
  edge_walk_steps = limits.edge_walk_steps > 0 ? limits.edge_walk_steps : 2 * static_cast<int>(s1.element_count()) + 16;
  assign_on_huge_pages(focal_free_reach, static_cast<std::size_t>(s1.element_count()));
  parallel_ranges(s1.element_count(), threads, [&](std::size_t begin, std::size_t end) {
    for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t) {
      std::array<WorldPoint<d>, d + 1> corners, directions;
      for (int k = 0; k <= d; ++k) {
        corners[k] = s1.corner(t, k);
        directions[k] = vertex_directions[s1.element(t)[k]];
      }
      focal_free_reach[t] = focal_free_distance<d>(corners, directions);
    }
  });
}

template <int d>
void ProjectionContext<d>::release_search_data() {
  s1_index.reset();
  s2_index.reset();
  s1_boxes.reset();
  auto release = [](auto& v) { std::decay_t<decltype(v)>().swap(v); };
  release(focal_free_reach);
  release(vertex_directions);
  release(s2_vertex_normals);
}

// Only the members defined here: an explicit instantiation of the whole class would instantiate
// the members constrained to d == 2 for d = 1 as well (clang 14 does).
template ProjectionContext<1>::ProjectionContext(std::shared_ptr<const Surface<1>>, std::shared_ptr<const Surface<1>>,
                                                 const ProjectionOptions&);
template ProjectionContext<2>::ProjectionContext(std::shared_ptr<const Surface<2>>, std::shared_ptr<const Surface<2>>,
                                                 const ProjectionOptions&);
template void ProjectionContext<1>::release_search_data();
template void ProjectionContext<2>::release_search_data();

}  // namespace plmap::projection
