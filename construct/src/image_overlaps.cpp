// farther_overlapping_regions (image_overlaps.hpp).

#include "image_overlaps.hpp"

#include <plmap/core/element_transfer.hpp>
#include <plmap/core/triangle_overlap.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace plmap::projection {

namespace {

/// A region's image on its S2 element, in that element's local coordinates, and how far its
/// corners lie from their images.
template <int d>
struct Image {
  Index region = invalid_index;
  std::array<LocalPoint<d>, d + 1> corner;  // d = 2: counter-clockwise
  double measure = 0.0;                     // in local coordinates
  double boundary = 0.0;                    // length of the boundary (d = 1: 2, its two ends)
  double distance = 0.0;                    // mean distance between corners and their images
  LocalPoint<d> low, high;                  // bounding box
};

/// The corners of a region's image in its S2 element's local coordinates: moved there exactly
/// through shared S2 vertices and edges, as covered_measure and remote_intersection do.
template <int d>
std::array<LocalPoint<d>, d + 1> image_corners(const PlMap<d>& map, Index r) {
  const auto& m = map.data();
  std::array<LocalPoint<d>, d + 1> y;
  for (int i = 0; i <= d; ++i) {
    const Index n = m.region_corners[r][i];
    y[i] = transfer_to_element(map.target(), m.node_image[n], m.region_target[r])
               .value_or(apply<d>(m.region_map[r], m.node_position[n]));
  }
  return y;
}

/// d! times the measure of a simplex in local coordinates, and its orientation.
template <int d>
double signed_local_measure(const std::array<LocalPoint<d>, d + 1>& y) {
  if constexpr (d == 1) {
    return y[1](0) - y[0](0);
  } else {
    const LocalPoint<2> u = y[1] - y[0], v = y[2] - y[0];
    return u(0) * v(1) - u(1) * v(0);
  }
}

template <int d>
Image<d> image_of(const PlMap<d>& map, Index element, Index r) {
  const auto& m = map.data();
  Image<d> im;
  im.region = r;
  im.corner = image_corners(map, r);
  for (int i = 0; i <= d; ++i)
    im.distance += (map.domain().world_position(element, m.node_position[m.region_corners[r][i]]) -
                    map.target().world_position(m.region_target[r], im.corner[i]))
                       .norm();
  im.distance /= d + 1;
  const double signed_measure = signed_local_measure<d>(im.corner);
  if constexpr (d == 1) {
    im.measure = std::abs(signed_measure);
    im.boundary = 2.0;
  } else {
    if (signed_measure < 0) std::swap(im.corner[1], im.corner[2]);
    im.measure = 0.5 * std::abs(signed_measure);
    for (int i = 0; i < 3; ++i) im.boundary += (im.corner[(i + 1) % 3] - im.corner[i]).norm();
  }
  im.low = im.high = im.corner[0];
  for (int i = 1; i <= d; ++i) {
    im.low = im.low.cwiseMin(im.corner[i]);
    im.high = im.high.cwiseMax(im.corner[i]);
  }
  return im;
}

template <int d>
double overlap(const Image<d>& a, const Image<d>& b) {
  if constexpr (d == 1) {
    return std::min(a.high(0), b.high(0)) - std::max(a.low(0), b.low(0));
  } else {
    if ((a.high.array() < b.low.array()).any() || (b.high.array() < a.low.array()).any()) return 0.0;
    return triangle_intersection_area({a.corner[0], a.corner[1], a.corner[2]},
                                      {b.corner[0], b.corner[1], b.corner[2]});
  }
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
std::vector<Index> farther_overlapping_regions(const PlMap<d>& map, const ImageMeasures& images,
                                               const OverlapTolerances& tolerances) {
  const auto& m = map.data();
  const Index n2 = map.target().element_count();
  const Index nt = map.domain().element_count();

  // The images on one S2 element tile part of it, so they can only overlap where they add up to
  // more than the element (per_target is d! times the measure: 1 for the whole element).
  std::vector<char> crowded(static_cast<std::size_t>(n2), 0);
  bool any = false;
  for (Index t2 = 0; t2 < n2; ++t2)
    if (images.per_target[static_cast<std::size_t>(t2)] > 1.0 + tolerances.measure_tolerance)
      crowded[static_cast<std::size_t>(t2)] = any = true;
  if (!any) return {};

  // The images on the crowded elements, grouped by element, compared pairwise.
  std::vector<std::vector<Image<d>>> on_target(static_cast<std::size_t>(n2));
  for (Index t = 0; t < nt; ++t)
    for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r)
      if (crowded[static_cast<std::size_t>(m.region_target[r])])
        on_target[static_cast<std::size_t>(m.region_target[r])].push_back(image_of(map, t, r));
  // Pairs by a sweep along the first coordinate: an element may carry thousands of regions
  // where S1 is much finer than S2.
  std::vector<Index> farther;
  for (auto& list : on_target) {
    std::sort(list.begin(), list.end(), [](const Image<d>& a, const Image<d>& b) { return a.low(0) < b.low(0); });
    for (std::size_t i = 0; i < list.size(); ++i)
      for (std::size_t j = i + 1; j < list.size() && list[j].low(0) <= list[i].high(0); ++j) {
        const Image<d>& a = list[i];
        const Image<d>& b = list[j];
        const double explained = tolerances.position_tolerance * std::min(a.boundary, b.boundary);
        if (!(overlap(a, b) > std::max(tolerances.measure_tolerance * std::min(a.measure, b.measure), explained)))
          continue;
        const bool a_farther = a.distance > b.distance || (a.distance == b.distance && a.region > b.region);
        farther.push_back(a_farther ? a.region : b.region);
      }
  }
  std::sort(farther.begin(), farther.end());
  farther.erase(std::unique(farther.begin(), farther.end()), farther.end());
  return farther;
}

template std::vector<Index> farther_overlapping_regions<1>(const PlMap<1>&, const ImageMeasures&,
                                                           const OverlapTolerances&);
template std::vector<Index> farther_overlapping_regions<2>(const PlMap<2>&, const ImageMeasures&,
                                                           const OverlapTolerances&);

}  // namespace plmap::projection
