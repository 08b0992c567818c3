#pragma once
/// \file
/// Forward evaluation at points that lie on element boundaries, as points computed elsewhere do
/// (the image of another map, the nearest surface point to a world point): such a point may be
/// given on an element whose regions do not reach it, or lie outside its element by a rounding.

#include <plmap/core/element_transfer.hpp>
#include <plmap/core/evaluation.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <vector>

namespace plmap {

/// Xi at a point of S1 that may lie on the boundary of its element or just outside it (by
/// rounding), e.g. the image of another map or the nearest point of S1 to a world point:
/// 1. clamped into the element (negative barycentric weights set to zero) and evaluated;
/// 2. if that misses, moved towards the element's centroid by 1e-14 of the element's size (a
///    point on the element's boundary may be outside it in exact arithmetic after the rounding of
///    its coordinates; the locators decide exactly) and evaluated again;
/// 3. if that misses and the point lies on an edge or vertex (weights within `tolerance` of zero),
///    evaluated on the elements sharing that edge or vertex (D may end at the edge on this side).
template <int d, class Locator>
  requires PointLocator<Locator, d>
Evaluation<d> evaluate_on_any_incident_element(const PlMap<d>& map, SurfacePoint<d> p, Locator& locator,
                                               double tolerance = 1e-10) {
  Barycentric<d> b = barycentric_from_local<d>(p.local).cwiseMax(0.0);
  if (!(b.sum() > 0.0)) return {};  // NaN
  b /= b.sum();
  p.local = local_from_barycentric<d>(b);
  Evaluation<d> e = evaluate(map, p, locator);
  if (e.in_domain) return e;
  auto nudged = [](const LocalPoint<d>& x) {
    constexpr double step = 1e-14;
    return LocalPoint<d>((1.0 - step) * x + step * LocalPoint<d>::Constant(1.0 / (d + 1)));
  };
  e = evaluate(map, SurfacePoint<d>{p.element, nudged(p.local)}, locator);
  if (e.in_domain) return e;
  const Surface<d>& s = map.domain();
  for (Index t : elements_sharing_boundary_point(s, p, tolerance)) {
    const auto local = transfer_to_element(s, p, t, tolerance);
    if (!local) continue;
    e = evaluate(map, SurfacePoint<d>{t, *local}, locator);
    if (e.in_domain) return e;
    e = evaluate(map, SurfacePoint<d>{t, nudged(*local)}, locator);
    if (e.in_domain) return e;
  }
  return {};
}

/// Evaluates many points as evaluate_batch does (same checks, locator copies and threads), each
/// through evaluate_on_any_incident_element: for points that may lie on element boundaries, such
/// as the user's points or nearest surface points of world points (`plmap eval --points`).
template <int d, class Locator>
  requires PointLocator<Locator, d>
void evaluate_points_batch(const PlMap<d>& map, std::span<const SurfacePoint<d>> points, std::span<Evaluation<d>> out,
                           const Locator& locator, unsigned threads = 0) {
  if (out.size() != points.size())
    throw Error("evaluate_points_batch: output span size differs from the number of points");
  const Index elements = map.domain().element_count();
  for (const auto& p : points)
    if (p.element < 0 || p.element >= elements)
      throw Error("evaluate_points_batch: query point on element " + std::to_string(p.element) + ", but S1 has " +
                  std::to_string(elements) + " elements");
  Locator prepared = locator;
  prepare_point_locator<d>(prepared, map);
  parallel_ranges(points.size(), threads, [&](std::size_t begin, std::size_t end) {
    Locator local_locator = prepared;
    for (std::size_t i = begin; i < end; ++i) out[i] = evaluate_on_any_incident_element(map, points[i], local_locator);
  });
}

}  // namespace plmap
