#include <plmap/construct/direction_field.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <fmt/format.h>

#include <cmath>

namespace plmap {

template <int d>
  requires SurfaceDimension<d>
std::vector<WorldPoint<d>> averaged_vertex_normals(const Surface<d>& surface, unsigned threads) {
  // Each element's measure and normal once (a vertex star shares every element with d others, and
  // each is a scaled cross product: computed per star they were most of the projection's set-up
  // on the real-mesh pairs); the sums below add the same products in the same order.
  const auto elements = static_cast<std::size_t>(surface.element_count());
  // per element and per vertex, millions on large surfaces: on huge pages (huge_page_allocator.hpp)
  std::vector<double> measure;
  std::vector<WorldPoint<d>> normal;
  assign_on_huge_pages(measure, elements);
  assign_on_huge_pages(normal, elements, WorldPoint<d>::Zero());
  parallel_for_chunks(elements, 4096, threads, [&](std::size_t begin, std::size_t end) {
    for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t) {
      measure[t] = surface.element_measure(t);
      normal[t] = surface.element_normal(t);
    }
  });
  std::vector<WorldPoint<d>> out;
  assign_on_huge_pages(out, static_cast<std::size_t>(surface.vertex_count()), WorldPoint<d>::Zero());
  parallel_for_chunks(static_cast<std::size_t>(surface.vertex_count()), 4096, threads, [&](std::size_t begin, std::size_t end) {
    for (auto v = static_cast<Index>(begin); v < static_cast<Index>(end); ++v) {
      const auto star = surface.vertex_elements(v);
      if (star.empty()) continue;
      WorldPoint<d> sum = WorldPoint<d>::Zero();
      for (Index t : star) sum += measure[t] * normal[t];
      const double norm = sum.norm();
      // Cancellation is judged relative to the weights, so the rule does not depend on the scale.
      double weight = 0.0;
      for (Index t : star) weight += measure[t];
      out[v] = norm > 1e-12 * weight ? WorldPoint<d>(sum / norm) : normal[star.front()];
    }
  });
  return out;
}

template <int d>
  requires SurfaceDimension<d>
std::vector<WorldPoint<d>> directions_from_values(const Surface<d>& surface, std::span<const double> values) {
  const std::size_t n = static_cast<std::size_t>(surface.vertex_count());
  if (values.size() != (d + 1) * n)
    throw Error(fmt::format("projection directions: expected {} numbers ({} per vertex for {} vertices), got {}",
                            (d + 1) * n, d + 1, n, values.size()));
  std::vector<WorldPoint<d>> out(n);
  for (std::size_t v = 0; v < n; ++v) {
    for (int k = 0; k <= d; ++k) out[v](k) = values[(d + 1) * v + k];
    // scaled by its largest coordinate first: the norm of (1e200, 0, 0) overflows, that of
    // (1e-200, 0, 0) underflows to 0, yet both give a direction
    const double largest = out[v].allFinite() ? out[v].cwiseAbs().maxCoeff() : 0.0;
    if (largest == 0.0)
      throw Error(fmt::format("projection direction at S1 vertex {} is zero or not finite", v));
    out[v] /= largest;
    out[v] /= out[v].norm();
  }
  return out;
}

template std::vector<WorldPoint<1>> averaged_vertex_normals<1>(const Surface<1>&, unsigned);
template std::vector<WorldPoint<2>> averaged_vertex_normals<2>(const Surface<2>&, unsigned);
template std::vector<WorldPoint<1>> directions_from_values<1>(const Surface<1>&, std::span<const double>);
template std::vector<WorldPoint<2>> directions_from_values<2>(const Surface<2>&, std::span<const double>);

}  // namespace plmap
