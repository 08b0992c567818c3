// farther_overlapping_regions (image_overlaps.hpp).

#include "image_overlaps.hpp"
#include "element_set_connectivity.hpp"

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/core/parallel_sort.hpp>
#include <plmap/core/triangle_overlap.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>
#include <utility>

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

/// The corners of a region's image in its S2 element's local coordinates, as covered_measure and
/// remote_intersection take them (corner_image_on_target).
template <int d>
std::array<LocalPoint<d>, d + 1> image_corners(const PlMap<d>& map, Index r) {
  std::array<LocalPoint<d>, d + 1> y;
  for (int i = 0; i <= d; ++i) y[i] = corner_image_on_target(map, r, i);
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
  const auto& m = map.stored();
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

/// Per S2 element, the S1 elements with a region on it, each once and in increasing order, as a
/// compressed list: elements[first[t2], first[t2 + 1]).
struct ElementsPerTarget {
  std::vector<Index> first, elements;
};

/// Calls f(t, t2) once for every S1 element t in [begin, end) and S2 element t2 that t has a
/// region on, in the order of t's regions. The regions of one element are consecutive, so its
/// repeats are found among its own targets (`seen`); an element with many regions (a coarse S1
/// over a fine S2) uses a stamp per S2 element instead (`last_seen`, sized on first need: one
/// index per S2 element and piece was a quarter of the sheet selection's memory on the femur
/// pair, where elements hold a few regions each).
template <int d, class F>
void for_each_element_and_target(const PlMap<d>& map, Index begin, Index end, std::vector<Index>& seen,
                                 std::vector<Index>& last_seen, F&& f) {
  constexpr Index few = 32;
  const auto& target = map.stored().region_target;
  std::fill(last_seen.begin(), last_seen.end(), invalid_index);  // (stamps of an earlier call)
  for (Index t = begin; t < end; ++t) {
    const Index first = map.regions_begin(t), last = map.regions_end(t);
    if (last - first <= few) {
      seen.clear();
      for (Index r = first; r < last; ++r)
        if (const Index t2 = target[r]; std::find(seen.begin(), seen.end(), t2) == seen.end()) {
          seen.push_back(t2);
          f(t, t2);
        }
      continue;
    }
    if (last_seen.empty()) last_seen.assign(static_cast<std::size_t>(map.target().element_count()), invalid_index);
    for (Index r = first; r < last; ++r)
      if (const Index t2 = target[r]; last_seen[t2] != t) {
        last_seen[t2] = t;
        f(t, t2);
      }
  }
}

/// The lists by a counting sort over contiguous pieces of S1 elements, on all threads: each piece
/// counts its own elements per S2 element, and then writes them after the pieces before it, so
/// every list is in element order whatever the number of pieces.
template <int d>
ElementsPerTarget elements_per_target(const PlMap<d>& map, unsigned threads) {
  const Index n2 = map.target().element_count(), nt = map.domain().element_count();
  const std::size_t pieces = std::min<std::size_t>(resolve_thread_count(threads), static_cast<std::size_t>(std::max<Index>(1, nt / 4096)));
  const std::size_t size = (static_cast<std::size_t>(nt) + pieces - 1) / pieces;
  ElementsPerTarget lists;
  std::vector<std::vector<Index>> seen(pieces), last_seen(pieces);
  if (pieces == 1) {
    // One piece (one thread, or a small S1): the counts go into `first` itself, one place on,
    // whose prefix sums are then each list's end; writing each list from its start moves that
    // start to the next list's, so `first` is shifted back after. (A separate array of write
    // positions, one index per S2 element, is saved: on the femur pair part of the projection's
    // peak memory.)
    assign_on_huge_pages(lists.first, static_cast<std::size_t>(n2) + 1, 0);
    for_each_element_and_target(map, 0, nt, seen[0], last_seen[0], [&](Index, Index t2) { ++lists.first[t2 + 1]; });
    for (Index t2 = 0; t2 < n2; ++t2) lists.first[t2 + 1] += lists.first[t2];
    assign_on_huge_pages(lists.elements, static_cast<std::size_t>(lists.first[n2]), invalid_index);
    for_each_element_and_target(map, 0, nt, seen[0], last_seen[0], [&](Index t, Index t2) { lists.elements[lists.first[t2]++] = t; });
    for (Index t2 = n2; t2 > 0; --t2) lists.first[t2] = lists.first[t2 - 1];
    lists.first[0] = 0;
    return lists;
  }
  // each piece's arrays made (first touched) by the thread that counts it
  std::vector<std::vector<Index>> at(pieces);
  parallel_for_pieces_of_size(static_cast<std::size_t>(nt), size, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    assign_on_huge_pages(at[k], static_cast<std::size_t>(n2), 0);  // pages backed in one call
    for_each_element_and_target(map, static_cast<Index>(begin), static_cast<Index>(end), seen[k], last_seen[k],
                                [&](Index, Index t2) { ++at[k][t2]; });
  });
  assign_on_huge_pages(lists.first, static_cast<std::size_t>(n2) + 1, 0);
  for (Index t2 = 0; t2 < n2; ++t2) {  // counts become where each piece writes
    Index next = lists.first[t2];
    for (auto& piece : at)
      if (!piece.empty()) next += std::exchange(piece[t2], next);  // (a piece with no elements has no counts)
    lists.first[t2 + 1] = next;
  }
  assign_on_huge_pages(lists.elements, static_cast<std::size_t>(lists.first[n2]), invalid_index);
  parallel_for_pieces_of_size(static_cast<std::size_t>(nt), size, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    for_each_element_and_target(map, static_cast<Index>(begin), static_cast<Index>(end), seen[k], last_seen[k],
                                [&](Index t, Index t2) { lists.elements[at[k][t2]++] = t; });
  });
  return lists;
}

/// Marks as crowded every S2 element whose regions lie on S1 elements that do not form one
/// edge-connected set. The preimage of an S2 element on one sheet is connected; it falls apart
/// where two sheets map onto the element (and, harmlessly, where S1's boundary or a vertex it
/// passes cuts it: those elements are then checked pairwise for nothing). The S2 elements are
/// searched independently, in pieces on all threads (two per thread, for balance), each piece
/// with its own search (element_set_connectivity.hpp).
template <int d>
void mark_disconnected_preimages(const PlMap<d>& map, std::vector<char>& crowded, unsigned threads) {
  const Index n2 = map.target().element_count();
  const ElementsPerTarget lists = elements_per_target(map, threads);
  const unsigned used = resolve_thread_count(threads);
  const std::size_t pieces = used == 1 ? 1 : 2 * std::size_t{used};
  parallel_for_pieces(static_cast<std::size_t>(n2), pieces, threads, [&](std::size_t, std::size_t begin, std::size_t end) {
    ElementSetConnectivity<d> search(map.domain());
    for (auto t2 = static_cast<Index>(begin); t2 < static_cast<Index>(end); ++t2) {
      const Index list_begin = lists.first[t2], list_end = lists.first[t2 + 1];
      if (crowded[t2] || list_end - list_begin < 2) continue;
      const std::span<const Index> list(lists.elements.data() + list_begin, static_cast<std::size_t>(list_end - list_begin));
      if (!search.connected(list)) crowded[t2] = 1;
    }
  });
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
std::vector<Index> farther_overlapping_regions(const PlMap<d>& map, const ImageMeasures& images,
                                               const OverlapTolerances& tolerances, unsigned threads,
                                               std::span<const Index> also_compared) {
  const auto& m = map.stored();
  const Index n2 = map.target().element_count();
  const Index nt = map.domain().element_count();

  std::vector<char> crowded;
  assign_on_huge_pages(crowded, static_cast<std::size_t>(n2), char{0});  // per S2 element: on huge pages
  // Where the preimage of an S2 element tau on one sheet of S1 is bounded by the preimages of
  // tau's own edges, its images tile tau exactly once: they are positively oriented and their
  // boundary runs once around tau, so the map has degree 1 on all of tau (the builder has
  // dropped the edges where a sheet folds). Their measures then add up to the whole element
  // (per_target is d! times the measure: 1 for the whole element). So images can overlap only
  // - where they add up to more than the element;
  // - where they add up to less: part of the preimage's boundary is the boundary of D (S1's
  //   boundary, an edge not inserted), whose image is not tau's boundary, and one connected
  //   sheet can then reach over itself: a region of ghost nodes on a curved S1 with averaged
  //   normals overlapping a neighbour's image where no ray crosses another inside an element
  //   (the rays of elements some way apart cross on a flat S2 element that S1's footprint
  //   only partly covers);
  // - where they come from parts of S1 that are not connected through elements mapping onto
  //   it: two sheets, each covering only part of the element.
  for (Index t2 = 0; t2 < n2; ++t2) {
    const double sum = images.per_target[static_cast<std::size_t>(t2)];
    if (sum > 1.0 + tolerances.measure_tolerance || (sum > 0.0 && sum < 1.0 - tolerances.measure_tolerance))
      crowded[static_cast<std::size_t>(t2)] = 1;
  }
  // - and where regions split off unmapped faces map (their images end inside the element).
  for (const Index t2 : also_compared) crowded[static_cast<std::size_t>(t2)] = 1;
  mark_disconnected_preimages(map, crowded, threads);
  if (std::find(crowded.begin(), crowded.end(), 1) == crowded.end()) return {};
  // The images on the crowded elements, compared pairwise per element. The crowded regions are
  // listed with their S2 element first (12 bytes each), grouped by it, and each group's images
  // are made when it is compared: all images gathered at once (120 bytes each) were the largest
  // array the sheet selection held, 0.9 MiB for 7.7k crowded regions on the femur pair, where
  // the sheet selection set the projection's memory peak. (One list sorted by element, not one
  // list per S2 element, whose million empty lists on a large S2 cost a serial first touch of
  // their memory for the few elements crowded; counted first, so that it is not copied while it
  // grows.)
  struct CrowdedRegion {
    Index target, region, element;
  };
  // Listed and compared on all threads. Listed in contiguous pieces of S1 elements: each piece
  // counts its crowded regions, then writes them after the pieces before it into one list (no
  // second copy of it); then the groups are compared in pieces, each with its own list of the
  // farther regions. The result (sorted, each region once) is the same for every thread count.
  const unsigned used = resolve_thread_count(threads);
  const std::size_t pieces = used == 1 ? 1 : 4 * std::size_t{used};
  const std::size_t piece_size = (static_cast<std::size_t>(nt) + pieces - 1) / pieces;
  std::vector<std::size_t> piece_start(pieces + 1, 0);
  parallel_for_pieces_of_size(static_cast<std::size_t>(nt), piece_size, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    std::size_t count = 0;
    for (Index r = map.regions_begin(static_cast<Index>(begin)); r < map.regions_begin(static_cast<Index>(end)); ++r)
      count += static_cast<std::size_t>(crowded[static_cast<std::size_t>(m.region_target[r])]);
    piece_start[k + 1] = count;
  });
  for (std::size_t k = 0; k < pieces; ++k) piece_start[k + 1] += piece_start[k];
  std::vector<CrowdedRegion> listed(piece_start[pieces]);
  parallel_for_pieces_of_size(static_cast<std::size_t>(nt), piece_size, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    std::size_t at = piece_start[k];
    for (auto t = static_cast<Index>(begin); t < static_cast<Index>(end); ++t)
      for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r)
        if (crowded[static_cast<std::size_t>(m.region_target[r])]) listed[at++] = {m.region_target[r], r, t};
  });
  // (target, region) is unique: the sorted list is the same whichever sort made it
  parallel_sort(listed.begin(), listed.end(), threads, [](const CrowdedRegion& a, const CrowdedRegion& b) {
    return std::tie(a.target, a.region) < std::tie(b.target, b.region);
  });
  std::vector<std::size_t> group_first;  // where each S2 element's group starts in `listed`
  for (std::size_t i = 0; i < listed.size(); ++i)
    if (i == 0 || listed[i].target != listed[i - 1].target) group_first.push_back(i);
  group_first.push_back(listed.size());
  const std::size_t groups = group_first.size() - 1;
  std::vector<std::vector<Index>> farther_in_piece(pieces);
  parallel_for_pieces(groups, pieces, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    std::vector<Image<d>> group;
    auto& farther = farther_in_piece[k];
    for (std::size_t g = begin; g < end; ++g) {
      group.clear();
      for (std::size_t i = group_first[g]; i < group_first[g + 1]; ++i)
        group.push_back(image_of(map, listed[i].element, listed[i].region));
      // Pairs by a sweep along the first coordinate: an element may carry thousands of regions
      // where S1 is much finer than S2. (The region number orders ties, so that the pairs are
      // compared in an order that does not depend on the sort.)
      std::sort(group.begin(), group.end(), [](const Image<d>& a, const Image<d>& b) {
        return std::tie(a.low(0), a.region) < std::tie(b.low(0), b.region);
      });
      for (std::size_t i = 0; i < group.size(); ++i)
        for (std::size_t j = i + 1; j < group.size() && group[j].low(0) <= group[i].high(0); ++j) {
          const Image<d>& a = group[i];
          const Image<d>& b = group[j];
          const double explained = tolerances.position_tolerance * std::min(a.boundary, b.boundary);
          if (!(overlap(a, b) > std::max(tolerances.measure_tolerance * std::min(a.measure, b.measure), explained))) continue;
          const bool a_farther = a.distance > b.distance || (a.distance == b.distance && a.region > b.region);
          farther.push_back(a_farther ? a.region : b.region);
        }
    }
  });
  std::vector<Index> farther;
  for (const auto& list : farther_in_piece) farther.insert(farther.end(), list.begin(), list.end());
  std::sort(farther.begin(), farther.end());
  farther.erase(std::unique(farther.begin(), farther.end()), farther.end());
  return farther;
}

template std::vector<Index> farther_overlapping_regions<1>(const PlMap<1>&, const ImageMeasures&,
                                                           const OverlapTolerances&, unsigned, std::span<const Index>);
template std::vector<Index> farther_overlapping_regions<2>(const PlMap<2>&, const ImageMeasures&,
                                                           const OverlapTolerances&, unsigned, std::span<const Index>);

}  // namespace plmap::projection
