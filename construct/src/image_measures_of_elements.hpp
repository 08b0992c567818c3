#pragma once
// Image measures kept up to date across a change of a few S1 elements (normal projection, after
// finalize): the removals and cuts that leave folded and occluded parts out of D change only the
// elements of the regions they name (a removal takes a named region, its face or its element,
// core/face_removal.hpp; a cut changes the cut regions' elements and those across an S1 edge
// where a cut ends, core/region_clipping.hpp). Their regions' images are taken off the measures
// before the change and what is left of them is added back after, instead of measuring every
// image of the map again (5 ms of the femur pair's projection, 40 ms of the armadillo pair's,
// per measure). covered.target and per_target follow to rounding; covered.domain is left to the
// caller, who measures it exactly without moving any image (covered_domain_measure).

#include <plmap/core/pl_map.hpp>
#include <plmap/core/regions.hpp>

#include <algorithm>
#include <span>
#include <vector>

namespace plmap::projection {

/// The S1 elements of the given regions (any order, repeats kept).
template <int d>
std::vector<Index> elements_of_regions(const PlMap<d>& map, std::span<const Index> regions) {
  std::vector<Index> elements;
  elements.reserve(regions.size());
  for (const Index r : regions) elements.push_back(map.node_element(map.stored().region_corners[r][0]));
  return elements;
}

template <int d>
class ImageMeasuresOfElements {
 public:
  /// For a change of `elements` (any order, repeats allowed) of a map whose measures `images`
  /// are; with no measures (nullptr: none are kept), take_off and add_back do nothing.
  ImageMeasuresOfElements(ImageMeasures* images, std::vector<Index> elements)
      : images_(images), elements_(std::move(elements)) {
    std::sort(elements_.begin(), elements_.end());
    elements_.erase(std::unique(elements_.begin(), elements_.end()), elements_.end());
  }

  /// Before the change: the elements' images leave the measures.
  void take_off(const PlMap<d>& before) { shift(before, -1.0); }
  /// After the change: what the elements' regions now cover comes back.
  void add_back(const PlMap<d>& after) { shift(after, 1.0); }

 private:
  void shift(const PlMap<d>& map, double sign) {
    if (images_ == nullptr) return;
    const MapData<d>& m = map.stored();
    for (const Index t : elements_)
      for (Index r = map.regions_begin(t); r < map.regions_end(t); ++r) {
        const Index t2 = m.region_target[r];
        const double image = sign * local_image_measure(map, r);
        images_->per_target[static_cast<std::size_t>(t2)] += image;
        images_->covered.target += image * map.target().element_measure(t2);
      }
  }

  ImageMeasures* images_;
  std::vector<Index> elements_;  // sorted, each once
};

}  // namespace plmap::projection
