#pragma once
// What the commands do with a map that loads: evaluate it with every registered point locator
// (plmap eval), list and measure its regions (plmap regions, info), check it (plmap check) and
// draw it (plmap draw). Shared by the fuzz targets that produce maps. A map the loader accepts
// must be safe for all of these: they may throw a plmap::Error, nothing else.

#include <plmap/core/errors.hpp>
#include <plmap/core/evaluation.hpp>
#include <plmap/core/io/regions_csv.hpp>
#include <plmap/core/io/svg_drawing.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/strategies/point_locator_registry.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/quality.hpp>
#include <plmap/verify/report.hpp>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string_view>
#include <vector>

namespace plmap::fuzz {

// Large maps only make the fuzzer slow; a few elements show every code path.
inline constexpr Index max_elements_used = 32;

/// Query points on the first elements: corners, edge midpoints, the centroid, points just
/// inside and just outside the reference element.
template <int d>
std::vector<SurfacePoint<d>> query_points(const Surface<d>& s1) {
  std::vector<SurfacePoint<d>> points;
  const Index elements = std::min(s1.element_count(), max_elements_used);
  for (Index t = 0; t < elements; ++t) {
    auto add = [&](double x, double y) {
      SurfacePoint<d> p;
      p.element = t;
      p.local(0) = x;
      if constexpr (d == 2) p.local(1) = y;
      points.push_back(p);
    };
    for (double x : {0.0, 0.5, 1.0, 1.0 / 3, 1e-17, -1e-9, 1 + 1e-9})
      for (double y : {0.0, 0.5, 1.0 / 3, 0.25})
        if (d == 2 || y == 0.0) add(x, y);
  }
  return points;
}

/// Runs every command on the map; throws only what the commands throw.
template <int d>
void exercise_map(const PlMap<d>& map) {
  // plmap eval, with every locator the registry knows.
  const std::vector<SurfacePoint<d>> points = query_points(map.domain());
  std::vector<Evaluation<d>> out(points.size());
  for (const std::string_view name : point_locator_names<d>()) {
    with_point_locator<d>(name, [&](auto& locator) {
      evaluate_batch<d>(map, points, out, locator, 1);
      for (std::size_t i = 0; i < out.size(); ++i) {
        // A region found must be one of the query element's.
        if (out[i].in_domain && (out[i].region < map.regions_begin(points[i].element) ||
                                 out[i].region >= map.regions_end(points[i].element)))
          std::abort();
      }
    });
  }
  // plmap regions, plmap info.
  (void)remote_intersections(map);
  std::ostringstream csv;
  write_regions_csv(csv, map);
  (void)image_measures(map);
  (void)compute_quality(map);
  // plmap check.
  (void)summary(verify(map));
  // plmap draw: the element pictures of the first elements and the whole view.
  const Index elements = std::min(map.domain().element_count(), max_elements_used);
  for (Index t = 0; t < elements; ++t) (void)draw_element_graph_svg(map, t);
  (void)draw_map_view_svg(map);
}

}  // namespace plmap::fuzz
