// leave_out_folds (projection_fold_removal.hpp).

#include "projection_fold_removal.hpp"
#include "element_set_connectivity.hpp"
#include "folded_regions.hpp"
#include "image_measures_of_elements.hpp"
#include "split_region_rays.hpp"

#include <plmap/core/face_removal.hpp>
#include <plmap/core/region_clipping.hpp>

#include <algorithm>
#include <iterator>
#include <optional>
#include <span>
#include <utility>

namespace plmap::projection {

namespace {

std::vector<Index> clip_regions_named(std::span<const RegionClip> clips) {
  std::vector<Index> regions;
  regions.reserve(clips.size());
  for (const RegionClip& c : clips) regions.push_back(c.region);
  return regions;
}

}  // namespace

template <int d>
ImageMeasures leave_out_folds(PlMap<d>& map, bool cut_folded_regions, unsigned threads,
                              const std::vector<WorldPoint<d>>& directions, const std::vector<double>& focal_free_reach,
                              FinalizeReport& dropped, ProjectionReport<d>& report) {
  // The images' measures as finalize took them (BuilderOptions::measure_images), kept up to date
  // through the removals and the cut below (image_measures_of_elements.hpp); where finalize did
  // not measure them (curves), they are measured once the folds are out.
  std::optional<ImageMeasures> images = std::move(dropped.images);
  dropped.images.reset();
  ImageMeasures* kept = images ? &*images : nullptr;
  // What the fold removals and cuts below take is the difference of the covered measures of D.
  const double before_folded = images ? images->covered.domain : covered_domain_measure(map, threads);
  // faces closed on an element where the ray of a ghost node accepted from another element at
  // its vertex is folded (folded_regions.hpp), and regions split off faces at a corner without a
  // node that the rays do not back (split_region_rays.hpp): one removal for both. A region with
  // a folded and an unfolded corner is cut along the fold instead (d = 2), after the removal.
  std::vector<Index> folded;
  std::vector<RegionClip> fold_clips;
  if constexpr (d == 2) {
    FoldCuts cuts = fold_cuts(map, directions, focal_free_reach, threads);
    folded = std::move(cuts.whole);
    fold_clips = std::move(cuts.clips);
    if (!cut_folded_regions) {  // every region with a folded corner leaves whole
      for (const RegionClip& clip : fold_clips) folded.push_back(clip.region);
      std::sort(folded.begin(), folded.end());
      fold_clips.clear();
    }
  } else {
    folded = regions_with_folded_corners<d>(map, directions, focal_free_reach, threads);
  }
  std::vector<Index> unbacked;
  if constexpr (d == 2) {
    const std::vector<Index> off =
        split_regions_off_their_rays(map, directions, focal_free_reach, dropped.regions_split_off_outside_faces, threads);
    std::set_difference(off.begin(), off.end(), folded.begin(), folded.end(), std::back_inserter(unbacked));
  }
  // the elements to cut, in the map's element numbers (which a removal keeps); an unbacked region
  // leaves whole, cut or not
  std::vector<Index> cut_elements;
  for (const RegionClip& clip : fold_clips)
    if (!std::binary_search(unbacked.begin(), unbacked.end(), clip.region))
      cut_elements.push_back(map.node_element(map.stored().region_corners[clip.region][0]));
  cut_elements.erase(std::unique(cut_elements.begin(), cut_elements.end()), cut_elements.end());
  double unbacked_measure = 0.0;
  if (!folded.empty() || !unbacked.empty()) {
    for (Index r : unbacked) unbacked_measure += remote_intersection(map, r).domain_measure();
    std::vector<Index> named;
    std::set_union(folded.begin(), folded.end(), unbacked.begin(), unbacked.end(), std::back_inserter(named));
    FaceRemovalReport removal;
    ImageMeasuresOfElements<d> changed(kept, elements_of_regions(map, std::span<const Index>(named)));
    changed.take_off(map);
    map = remove_regions(std::move(map), std::span<const Index>(named), &removal, threads);
    changed.add_back(map);
    report.folded_faces = removal.removed_faces;
    report.unbacked_regions = static_cast<Index>(unbacked.size());
    report.folded_regions = removal.removed_regions - report.unbacked_regions;
  }
  if constexpr (d == 2)
    if (!cut_elements.empty()) {
      // the removal renumbered the regions: the cuts are found again on the elements concerned
      // (and if that names regions to leave whole, which a removal can make, again after those)
      FoldCuts cuts = fold_cuts(map, directions, focal_free_reach, threads, cut_elements);
      for (int round = 0; !cuts.whole.empty(); ++round) {
        FaceRemovalReport removal;
        ImageMeasuresOfElements<d> changed(kept, elements_of_regions(map, std::span<const Index>(cuts.whole)));
        changed.take_off(map);
        map = remove_regions(std::move(map), std::span<const Index>(cuts.whole), &removal, threads);
        changed.add_back(map);
        report.folded_faces += removal.removed_faces;
        report.folded_regions += removal.removed_regions;
        cuts = fold_cuts(map, directions, focal_free_reach, threads, cut_elements);
        if (round == 3) cuts.whole.clear();  // (never seen: what is left is cut where it can be)
      }
      RegionClipReport clipping;
      // the cut regions' elements, and those across an S1 edge where a cut may end
      std::vector<Index> around = elements_of_regions(map, std::span<const Index>(clip_regions_named(cuts.clips)));
      for (std::size_t i = 0, n = around.size(); i < n; ++i)
        for_each_neighbour(map.domain(), around[i], [&](Index u) { around.push_back(u); });
      ImageMeasuresOfElements<d> changed(kept, std::move(around));
      changed.take_off(map);
      map = clip_regions(std::move(map), std::span<const RegionClip>(cuts.clips), &clipping, threads);
      changed.add_back(map);
      report.folded_regions_cut = clipping.clipped_regions;
      report.folded_regions += clipping.removed_regions;
    }
  // The image measures give the covered measures and show where images overlap on S2: two sheets
  // of S1 whose rays reach the same part of S2, of which the farther one leaves D. (No term per
  // region is kept between the removals: a double per region stood on the femur pair's peak
  // through them, 0.7 MiB; the elements a change touches are measured before and after it.)
  if (images)
    images->covered.domain = covered_domain_measure(map, threads);
  else
    images = image_measures(map, threads);
  report.left_out.unbacked = unbacked_measure;
  report.left_out.folded = std::max(0.0, before_folded - images->covered.domain - unbacked_measure);
  return std::move(*images);
}

template ImageMeasures leave_out_folds<1>(PlMap<1>&, bool, unsigned, const std::vector<WorldPoint<1>>&,
                                          const std::vector<double>&, FinalizeReport&, ProjectionReport<1>&);
template ImageMeasures leave_out_folds<2>(PlMap<2>&, bool, unsigned, const std::vector<WorldPoint<2>>&,
                                          const std::vector<double>&, FinalizeReport&, ProjectionReport<2>&);

}  // namespace plmap::projection
