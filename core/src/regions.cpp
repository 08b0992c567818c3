#include <plmap/core/element_transfer.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/regions.hpp>
#include <plmap/core/scaled_geometry.hpp>

#include "local_simplex_measure.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

namespace plmap {

namespace {

/// remote_intersection() for a region whose S1 element is already known.
template <int d>
RemoteIntersection<d> remote_intersection_on(const PlMap<d>& map, Index element, Index region) {
  const auto& m = map.stored();
  RemoteIntersection<d> ri;
  ri.region = region;
  ri.domain_element = element;
  ri.target_element = m.region_target[region];
  for (int i = 0; i <= d; ++i) {
    const Index n = m.region_corners[region][i];
    ri.domain_local[i] = m.node_position[n];
    ri.target_local[i] = corner_image_on_target(map, region, i);
    ri.domain_world[i] = map.domain().world_position(ri.domain_element, ri.domain_local[i]);
    ri.target_world[i] = map.target().world_position(ri.target_element, ri.target_local[i]);
  }
  return ri;
}

}  // namespace

template <int d>
double RemoteIntersection<d>::domain_measure() const {
  return simplex_measure<d>(domain_world);
}

template <int d>
double RemoteIntersection<d>::target_measure() const {
  return simplex_measure<d>(target_world);
}

template <int d>
RemoteIntersection<d> remote_intersection(const PlMap<d>& map, Index region) {
  return remote_intersection_on(map, map.node_element(map.stored().region_corners[region][0]), region);
}

// The lists run element by element, so no region needs the search for its element.
template <int d>
std::vector<RemoteIntersection<d>> remote_intersections(const PlMap<d>& map) {
  std::vector<RemoteIntersection<d>> out;
  out.reserve(map.region_count());
  for (Index t = 0; t < map.domain().element_count(); ++t)
    for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) out.push_back(remote_intersection_on(map, t, r));
  return out;
}

using detail::local_simplex_measure;

/// d! times the measure of region r's image in its S2 element's local coordinates (the image
/// corners moved onto that element exactly, as remote_intersection does).
template <int d>
double local_target_measure(const PlMap<d>& map, Index r) {
  std::array<LocalPoint<d>, d + 1> y;
  for (int i = 0; i <= d; ++i) y[i] = corner_image_on_target(map, r, i);
  return local_simplex_measure<d>(y);
}

// Elements are affine, so a region's measure is its measure in local coordinates times its
// element's, on either side: no world position of a corner is needed. Local measures are summed
// per element first (S1: consecutive regions; S2: one running sum per S2 element) and scaled once.
// With several threads, everything but the sums over elements is computed first, in parallel: the
// regions' target measures and each S1 element's scaled domain measure; then the sums run in the
// order and with the operations of one thread, so the result is the same to the last bit.
namespace {

/// The terms image_measures sums on several threads.
struct ImageMeasureTerms {
  std::vector<double> region_target;   ///< per region, d! times its image's local measure
  std::vector<double> element_domain;  ///< per S1 element with regions, its regions' measure
};

template <int d>
double domain_part(const PlMap<d>& map, Index t) {
  return detail::element_regions_measure(map.stored(), map.domain(), t);
}

/// The terms of element t: its regions' target measures and its scaled domain measure.
template <int d>
void element_terms(const PlMap<d>& map, Index t, ImageMeasureTerms& terms) {
  if (map.regions_begin(t) == map.regions_end(t)) {
    terms.element_domain[static_cast<std::size_t>(t)] = 0.0;  // not summed
    return;
  }
  for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r)
    terms.region_target[static_cast<std::size_t>(r)] = local_target_measure(map, r);
  terms.element_domain[static_cast<std::size_t>(t)] = domain_part(map, t);
}

/// The sums over the terms, in the order of the one-thread loop (the S2 elements' measures, a
/// scaled cross product each, in that loop as well).
template <int d>
ImageMeasures sum_terms(const PlMap<d>& map, unsigned threads, const ImageMeasureTerms& terms) {
  const auto& m = map.stored();
  const Surface<d>& s2 = map.target();
  const Index n1 = map.domain().element_count(), n2 = s2.element_count();
  ImageMeasures out;
  assign_on_huge_pages(out.per_target, static_cast<std::size_t>(n2), 0.0, threads);
  for (Index t = 0; t < n1; ++t) {
    if (map.regions_begin(t) == map.regions_end(t)) continue;
    for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r)
      out.per_target[static_cast<std::size_t>(m.region_target[r])] += terms.region_target[static_cast<std::size_t>(r)];
    out.covered.domain += terms.element_domain[static_cast<std::size_t>(t)];
  }
  out.covered.target = detail::covered_target_measure(out.per_target, s2);
  return out;
}

/// image_measures on several threads: the terms in parallel, then their sums in order.
template <int d>
ImageMeasures measured_on_threads(const PlMap<d>& map, unsigned threads) {
  const Index n1 = map.domain().element_count();
  ImageMeasureTerms terms;
  // per region and per element of large surfaces: on huge pages (huge_page_allocator.hpp)
  assign_on_huge_pages(terms.region_target, static_cast<std::size_t>(map.region_count()), 0.0, threads);
  assign_on_huge_pages(terms.element_domain, static_cast<std::size_t>(n1), 0.0, threads);
  parallel_for_chunks(static_cast<std::size_t>(n1), 1024, threads, [&](std::size_t begin, std::size_t end) {
    for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t) element_terms(map, t, terms);
  });
  return sum_terms(map, threads, terms);
}

}  // namespace

template <int d>
ImageMeasures image_measures(const PlMap<d>& map, unsigned threads) {
  if (resolve_thread_count(threads) > 1) return measured_on_threads(map, threads);
  const auto& m = map.stored();
  const Surface<d>& s2 = map.target();
  const Index n1 = map.domain().element_count(), n2 = s2.element_count();
  ImageMeasures out;
  assign_on_huge_pages(out.per_target, static_cast<std::size_t>(n2), 0.0, threads);
  for (Index t = 0; t < n1; ++t) {
    if (map.regions_begin(t) == map.regions_end(t)) continue;
    for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r)
      out.per_target[static_cast<std::size_t>(m.region_target[r])] += local_target_measure(map, r);
    out.covered.domain += domain_part(map, t);
  }
  out.covered.target = detail::covered_target_measure(out.per_target, s2);
  return out;
}

template <int d>
double covered_domain_measure(const PlMap<d>& map, unsigned threads) {
  const Index n1 = map.domain().element_count();
  double covered = 0.0;
  if (resolve_thread_count(threads) <= 1) {
    for (Index t = 0; t < n1; ++t)
      if (map.regions_begin(t) != map.regions_end(t)) covered += domain_part(map, t);
    return covered;
  }
  // the elements' parts in parallel, summed in element order as above
  std::vector<double> part(static_cast<std::size_t>(n1), 0.0);
  parallel_for_chunks(static_cast<std::size_t>(n1), 1024, threads, [&](std::size_t begin, std::size_t end) {
    for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t)
      if (map.regions_begin(t) != map.regions_end(t)) part[static_cast<std::size_t>(t)] = domain_part(map, t);
  });
  for (Index t = 0; t < n1; ++t)
    if (map.regions_begin(t) != map.regions_end(t)) covered += part[static_cast<std::size_t>(t)];
  return covered;
}

template <int d>
double local_image_measure(const PlMap<d>& map, Index r) {
  return local_target_measure(map, r);
}

template <int d>
CoveredMeasure covered_measure(const PlMap<d>& map) {
  return image_measures(map).covered;
}

template struct RemoteIntersection<1>;
template struct RemoteIntersection<2>;
template RemoteIntersection<1> remote_intersection(const PlMap<1>&, Index);
template RemoteIntersection<2> remote_intersection(const PlMap<2>&, Index);
template std::vector<RemoteIntersection<1>> remote_intersections(const PlMap<1>&);
template std::vector<RemoteIntersection<2>> remote_intersections(const PlMap<2>&);
template CoveredMeasure covered_measure(const PlMap<1>&);
template CoveredMeasure covered_measure(const PlMap<2>&);
template ImageMeasures image_measures(const PlMap<1>&, unsigned);
template ImageMeasures image_measures(const PlMap<2>&, unsigned);
template double covered_domain_measure(const PlMap<1>&, unsigned);
template double covered_domain_measure(const PlMap<2>&, unsigned);
template double local_image_measure(const PlMap<1>&, Index);
template double local_image_measure(const PlMap<2>&, Index);

}  // namespace plmap
