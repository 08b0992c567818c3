#pragma once
// Normal projection, after finalize: D leaves out where the rays fold (folded_regions.hpp) and
// the split regions that the rays do not back (split_region_rays.hpp). Regions with a folded and
// an unfolded corner are cut along the fold (d = 2, with cut_folded_regions), the others leave
// whole. Private to the projection (project.cpp).

#include <plmap/construct/projection_result.hpp>
#include <plmap/core/map_builder.hpp>
#include <plmap/core/pl_map.hpp>
#include <plmap/core/regions.hpp>

#include <vector>

namespace plmap::projection {

/// Takes the folded and unbacked regions out of `map` (and cuts the partly folded ones), on up to
/// `threads` threads; `directions` and `focal_free_reach` are the projection's direction per S1
/// vertex and focal-free distance per S1 element, `dropped` what finalize reported (its image
/// measures, if finalize took them, are moved out and kept up to date). Counts what left in
/// `report` (folded_faces, folded_regions, folded_regions_cut, unbacked_regions, left_out.folded
/// and left_out.unbacked) and returns the image measures of the map left (covered.domain to the
/// last bit; covered.target and per_target to rounding where finalize measured them).
template <int d>
ImageMeasures leave_out_folds(PlMap<d>& map, bool cut_folded_regions, unsigned threads,
                              const std::vector<WorldPoint<d>>& directions, const std::vector<double>& focal_free_reach,
                              FinalizeReport& dropped, ProjectionReport<d>& report);

}  // namespace plmap::projection
