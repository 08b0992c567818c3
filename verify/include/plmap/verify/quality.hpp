#pragma once
/// \file
/// The quality of a map (DESIGN.md §4.7): the condition number kappa of each region's linear
/// piece, its maximum and its distribution.
///
/// For a region with world triangle P on S1 and image triangle Q on S2, A is the linear map that
/// takes P to Q, written in orthonormal frames of the two triangles' planes (2x2 for d = 2;
/// for d = 1 the scalar length ratio, so kappa = 1 and only the stretch is informative).
/// kappa = ||A||_2 ||A^-1||_2 = sigma_max / sigma_min.

#include <plmap/core/pl_map.hpp>
#include <plmap/verify/options.hpp>

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace plmap {

struct QualityReport {
  Index region_count = 0;
  /// Regions with zero measure on either side (kappa is infinite); not part of the statistics.
  Index degenerate_count = 0;
  double kappa_max = 1.0;
  Index kappa_max_region = invalid_index;
  double kappa_mean = 1.0;
  /// Quantiles of kappa over the non-degenerate regions, at the levels in `quantile_levels`.
  std::vector<double> quantile_levels;
  std::vector<double> quantiles;
  /// Histogram of log10 kappa: bin i counts regions with log10 kappa in
  /// [i * histogram_bin_width, (i + 1) * histogram_bin_width); the last bin is open-ended.
  double histogram_bin_width = 0.25;
  std::vector<std::size_t> histogram;
  /// Extremes of the singular values of A over all regions: how much the map stretches (max) and
  /// shrinks (min) lengths.
  double stretch_min = 1.0;
  double stretch_max = 1.0;
};

/// Condition number and singular values of one region's linear piece (infinite kappa and zero
/// sigma_min for a degenerate region).
struct RegionConditioning {
  double kappa = 1.0;
  double sigma_min = 1.0;
  double sigma_max = 1.0;
};

template <int d>
RegionConditioning region_conditioning(const PlMap<d>& map, Index region);

/// The same for the linear map taking the world triangle `domain` to the world triangle `image`
/// (corner i to corner i): what region_conditioning computes for a region, available to code
/// that holds a map in another form (the peer benchmarks measure PSurface's regions with it).
RegionConditioning triangle_conditioning(const std::array<WorldPoint<2>, 3>& domain,
                                         const std::array<WorldPoint<2>, 3>& image);

/// Kappa of every region and the summary. Linear in the number of regions (the quantiles use
/// selection, not a full sort).
template <int d>
QualityReport compute_quality(const PlMap<d>& map);

/// compute_quality's κ statistics (all but the stretch, left at 1) from the κ of every region, in
/// region order (infinite for a degenerate region), for callers that have them already (the
/// smoothing computes them for its guards: SmoothOptions::summarize_kappa).
QualityReport kappa_statistics(std::span<const double> region_kappas);

}  // namespace plmap
