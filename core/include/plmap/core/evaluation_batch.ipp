#pragma once
// Implementation of evaluate_batch (included from evaluation.hpp).

#include <plmap/core/errors.hpp>

#include <algorithm>
#include <thread>
#include <vector>

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
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t n = points.size();
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(n, 1)));
  // Threads work on copies; preparing one first lets the copies share its table.
  Locator prepared = locator;
  prepare_point_locator<d>(prepared, map);
  auto work = [&](std::size_t begin, std::size_t end) {
    Locator local_locator = prepared;
    for (std::size_t i = begin; i < end; ++i) out[i] = evaluate(map, points[i], local_locator);
  };
  if (threads <= 1) {
    work(0, n);
    return;
  }
  std::vector<std::jthread> pool;
  pool.reserve(threads);
  const std::size_t chunk = (n + threads - 1) / threads;
  for (unsigned k = 0; k < threads; ++k) {
    const std::size_t begin = std::min(n, k * chunk), end = std::min(n, begin + chunk);
    pool.emplace_back(work, begin, end);
  }
}

}  // namespace plmap
