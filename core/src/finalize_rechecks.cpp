// finalize(): the elements to close again after drops (finalize_rechecks.hpp).

#include "finalize_rechecks.hpp"

#include <algorithm>
#include <numeric>

namespace plmap::detail {

std::vector<Index> elements_to_close_again(const BuilderContents<2>& in, const DroppedEdges::Changes& changes,
                                           std::span<const Index> failed) {
  std::vector<Index> elements;
  if (changes.whole_edges) {  // the intersection nodes of those edges went everywhere
    elements.resize(static_cast<std::size_t>(in.s1.element_count()));
    std::iota(elements.begin(), elements.end(), Index{0});
    return elements;
  }
  elements.assign(failed.begin(), failed.end());
  auto around_edge = [&](Index edge) {
    for (const EdgeIncidence& incidence : in.s1.edge_elements(edge)) elements.push_back(incidence.element);
  };
  for (const Index s : changes.segments) {
    const Segment& seg = in.segments[s];
    if (seg.along_edge)
      around_edge(seg.where);
    else
      elements.push_back(seg.where);
  }
  for (const Index n : changes.nodes) {
    const Place<2>& place = in.nodes[n].place;
    if (place.kind == PlaceKind::element) {
      elements.push_back(place.index);
    } else if (place.kind == PlaceKind::edge) {
      around_edge(place.index);
    } else {
      const auto star = in.s1.vertex_elements(place.index);
      elements.insert(elements.end(), star.begin(), star.end());
    }
  }
  std::sort(elements.begin(), elements.end());
  elements.erase(std::unique(elements.begin(), elements.end()), elements.end());
  return elements;
}

}  // namespace plmap::detail
