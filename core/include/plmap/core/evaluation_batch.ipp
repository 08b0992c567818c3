#pragma once
// Implementation of evaluate_batch (included from evaluation.hpp).

#include <plmap/core/errors.hpp>
#include <plmap/core/parallel_ranges.hpp>

namespace plmap {

template <int d, class Locator>
  requires PointLocator<Locator, d>
void evaluate_batch(const PlMap<d>& map, std::span<const SurfacePoint<d>> points,
                    std::span<Evaluation<d>> out, const Locator& locator, unsigned threads) {
  if (out.size() != points.size())
    throw Error("evaluate_batch: output span size differs from the number of points");
  const Index elements = map.domain().element_count();
  for (const auto& p : points)
    if (p.element < 0 || p.element >= elements)
      throw Error("evaluate_batch: query point on element " + std::to_string(p.element) +
                  ", but S1 has " + std::to_string(elements) + " elements");
  // Threads work on copies; preparing one first lets the copies share its table.
  Locator prepared = locator;
  prepare_point_locator<d>(prepared, map);
  parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end) {
    Locator local_locator = prepared;
    if constexpr (PreparedEvaluatingPointLocator<Locator, d>) {
      for (std::size_t i = begin; i < end; ++i) out[i] = local_locator.evaluate_prepared(points[i]);
    } else {
      for (std::size_t i = begin; i < end; ++i) out[i] = evaluate(map, points[i], local_locator);
    }
  });
}

}  // namespace plmap
