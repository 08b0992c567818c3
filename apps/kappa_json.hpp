#pragma once
// κ_Ξ's distribution as the commands that change a map's quality print it (`plmap simplify`,
// `plmap smooth`): one writer, so that scripts read both the same way.

#include "cli_common.hpp"

#include <plmap/construct/smooth.hpp>
#include <plmap/verify/quality.hpp>

namespace plmap::cli {

/// The κ part of verify's quality report, in the form smoothing reports it per sweep.
KappaSummary kappa_summary(const QualityReport& quality);

/// kappa_max, kappa_mean, kappa_p99 (flat, for scripts), kappa_quantiles ("p50", "p90", "p99",
/// "p99.9", "p100"), log10_kappa_histogram {bin_width, counts} and degenerate_regions.
Json kappa_json(const KappaSummary& kappa);

}  // namespace plmap::cli
