// Normal projection, phase 3: sheet selection (projection_sheet_selection.hpp).

#include "projection_sheet_selection.hpp"

#include "image_measures_of_elements.hpp"
#include "image_overlaps.hpp"

#include <plmap/core/face_removal.hpp>
#include <plmap/core/freed_heap.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/regions.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <span>
#include <utility>

namespace plmap::projection {

template <int d>
std::vector<bool> coincident_preimage_losers(const ProjectionContext<d>& ctx,
                                             const std::vector<std::optional<Place<d>>>& target_place) {
  // Group the preimages by the S1 edge or element they lie on (a counting sort: almost every
  // group has a single member, which keeps its place without further work).
  const Index n2v = static_cast<Index>(target_place.size());
  const Index edge_keys = d == 2 ? ctx.s1.edge_count() : 0;
  auto key = [&](const Place<d>& p) { return p.kind == PlaceKind::edge ? p.index : edge_keys + p.index; };
  std::vector<Index> group_begin;  // per S1 edge and element: on huge pages (huge_page_allocator.hpp)
  assign_on_huge_pages(group_begin, static_cast<std::size_t>(edge_keys + ctx.s1.element_count()) + 1, Index{0});
  auto grouped = [&](Index q) { return target_place[q] && target_place[q]->kind != PlaceKind::vertex; };
  for (Index q = 0; q < n2v; ++q)
    if (grouped(q)) ++group_begin[key(*target_place[q]) + 1];
  for (std::size_t k = 1; k < group_begin.size(); ++k) group_begin[k] += group_begin[k - 1];
  std::vector<Index> members;
  assign_on_huge_pages(members, static_cast<std::size_t>(group_begin.back()));
  {
    std::vector<Index> cursor;
    reserve_for_writing(cursor, group_begin.size() - 1);
    cursor.assign(group_begin.begin(), group_begin.end() - 1);
    for (Index q = 0; q < n2v; ++q)
      if (grouped(q)) members[cursor[key(*target_place[q])]++] = q;
  }
  std::vector<bool> loses(target_place.size(), false);
  struct Item {
    double distance;
    Index q;
  };
  std::vector<Item> group;
  std::vector<const Place<d>*> kept;
  for (std::size_t g = 0; g + 1 < group_begin.size(); ++g) {
    if (group_begin[g + 1] - group_begin[g] < 2) continue;
    // within one S1 edge or element, nearest first (then the smallest q): a point loses if it
    // coincides with a kept one
    group.clear();
    for (Index i = group_begin[g]; i < group_begin[g + 1]; ++i) {
      const Index q = members[i];
      group.push_back({(ctx.s2.vertex(q) - ctx.world_of(*target_place[q])).norm(), q});
    }
    std::sort(group.begin(), group.end(), [](const Item& a, const Item& b) {
      return a.distance != b.distance ? a.distance < b.distance : a.q < b.q;
    });
    kept.clear();
    for (const Item& item : group) {
      const Place<d>& place = *target_place[item.q];
      const bool same = std::any_of(kept.begin(), kept.end(), [&](const Place<d>* w) {
        const double gap = place.kind == PlaceKind::edge
                               ? std::abs(place.t - w->t)
                               : (place.local - w->local).template lpNorm<Eigen::Infinity>();
        return gap <= ctx.options.snap_tolerance;
      });
      if (same)
        loses[item.q] = true;
      else
        kept.push_back(&place);
    }
  }
  return loses;
}

template <int d>
void keep_nearer_sheet(PlMap<d>& map, ImageMeasures& images, unsigned threads,
                       ProjectionReport<d>& report, std::span<const Index> split_targets) {
  const std::vector<Index> farther = farther_overlapping_regions(map, images, {}, threads, split_targets);
  // The search's working arrays (S1 elements by target, the regions on crowded targets) are
  // freed into malloc's heap by now and would stay resident under the removal, where the femur
  // pair had its peak (0.4 MiB above the finished map's): given back first.
  give_freed_heap_back();
  if (farther.empty()) return;
  // The measures after the removal without measuring every image again
  // (image_measures_of_elements.hpp): S1's side is measured again without moving any image.
  ImageMeasuresOfElements<d> changed(&images, elements_of_regions(map, std::span<const Index>(farther)));
  changed.take_off(map);
  FaceRemovalReport removal;
  map = remove_regions(std::move(map), std::span<const Index>(farther), &removal, threads);
  report.occluded_faces = removal.removed_faces;
  report.occluded_regions = removal.removed_regions;
  changed.add_back(map);
  images.covered.domain = covered_domain_measure(map, threads);
}

template std::vector<bool> coincident_preimage_losers<1>(const ProjectionContext<1>&,
                                                         const std::vector<std::optional<Place<1>>>&);
template std::vector<bool> coincident_preimage_losers<2>(const ProjectionContext<2>&,
                                                         const std::vector<std::optional<Place<2>>>&);
template void keep_nearer_sheet<1>(PlMap<1>&, ImageMeasures&, unsigned, ProjectionReport<1>&,
                                   std::span<const Index>);
template void keep_nearer_sheet<2>(PlMap<2>&, ImageMeasures&, unsigned, ProjectionReport<2>&,
                                   std::span<const Index>);

}  // namespace plmap::projection
