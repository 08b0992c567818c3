// SmoothOptions::summarize_kappa: the smoothing hands over the κ of every region that its guards
// computed, for the input and after each sweep, instead of the caller evaluating the map again
// (`plmap smooth --json` did, a tenth of the command). The values must be exactly those of
// verify's region_conditioning on the map at that point, region by region, also after a
// quadrilateral pass that ran more than once (its κ is then moved over from the previous run's
// rebuilt map for the elements that run did not change).

#include <plmap/construct/simplify.hpp>
#include <plmap/construct/smooth.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>
#include <plmap/verify/generators/rc_generators.hpp>
#include <plmap/verify/quality.hpp>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace plmap {
namespace {

std::vector<double> quality_report_kappas(const PlMap<2>& map) {
  std::vector<double> k;
  for (Index r = 0; r < map.region_count(); ++r) k.push_back(region_conditioning(map, r).kappa);
  return k;
}

/// Equal bit for bit, infinities included.
bool same_values(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i])) return false;
  return true;
}

RC_GTEST_PROP(SmoothKappaReport, HandsOverTheQualityReportsKappaOfEveryRegion, ()) {
  const int subdivisions = *rc::gen::inRange(1, 3);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  generators::Rng rng(seed);
  auto fine = std::make_shared<const Surface<2>>(generators::icosphere({subdivisions, *rc::gen::inRange(0, 30) / 100.0}, rng));
  SimplifyOptions so;
  so.target_elements = std::max<Index>(8, fine->element_count() * *rc::gen::inRange(3, 40) / 100);
  so.feature_angle_degrees = 180.0;
  so.oracles.add("hausdorff", 1.0);
  so.oracles.add("aspect-ratio", *rc::gen::element(0.0, 1.0));
  const SimplifyResult s = simplify(fine, so);

  SmoothOptions options;
  options.weights = *rc::gen::element<std::string>("floater", "mean-value", "uniform");
  options.quadrilaterals = *rc::gen::arbitrary<bool>();
  options.sweeps = *rc::gen::inRange(1, 4);
  std::vector<std::vector<double>> handed;  // input, then after each sweep
  options.summarize_kappa = [&handed](std::span<const double> k) {
    handed.emplace_back(k.begin(), k.end());
    KappaSummary summary;
    summary.max = kappa_statistics(k).kappa_max;
    return summary;
  };
  std::vector<std::vector<double>> measured;  // after each sweep, by the quality report
  options.after_sweep = [&measured](int, const PlMap<2>& map) { measured.push_back(quality_report_kappas(map)); };
  const SmoothResult r = smooth(s.map, options);

  RC_ASSERT(handed.size() == static_cast<std::size_t>(options.sweeps) + 1);
  RC_ASSERT(same_values(handed.front(), quality_report_kappas(s.map)));
  int repeated_runs = 0;
  for (int i = 0; i < options.sweeps; ++i) {
    RC_ASSERT(same_values(handed[static_cast<std::size_t>(i) + 1], measured[static_cast<std::size_t>(i)]));
    RC_ASSERT(r.report.sweeps[static_cast<std::size_t>(i)].kappa->max == kappa_statistics(measured[static_cast<std::size_t>(i)]).kappa_max);
    repeated_runs += r.report.sweeps[static_cast<std::size_t>(i)].quadrilateral_attempts > 1 ? 1 : 0;
  }
  RC_ASSERT(same_values(handed.back(), quality_report_kappas(r.map)));
  RC_CLASSIFY(repeated_runs > 0, "a quadrilateral pass ran more than once");
}

// kappa_statistics on given values is compute_quality's κ part.
TEST(SmoothKappaReport, StatisticsOfGivenValuesEqualTheQualityReport) {
  generators::Rng rng(7);
  auto fine = std::make_shared<const Surface<2>>(generators::icosphere({2, 0.2}, rng));
  SimplifyOptions so;
  so.target_elements = 40;
  so.feature_angle_degrees = 180.0;
  const SimplifyResult s = simplify(fine, so);
  const QualityReport q = compute_quality(s.map);
  const QualityReport k = kappa_statistics(quality_report_kappas(s.map));
  EXPECT_EQ(k.kappa_max, q.kappa_max);
  EXPECT_EQ(k.kappa_mean, q.kappa_mean);
  EXPECT_EQ(k.kappa_max_region, q.kappa_max_region);
  EXPECT_EQ(k.quantiles, q.quantiles);
  EXPECT_EQ(k.histogram, q.histogram);
  EXPECT_EQ(k.degenerate_count, q.degenerate_count);
  EXPECT_EQ(k.region_count, q.region_count);
  EXPECT_GT(q.kappa_max, 1.0);
  const std::vector<double> with_degenerate = {2.0, std::numeric_limits<double>::infinity(), 1.5};
  const QualityReport d = kappa_statistics(with_degenerate);
  EXPECT_EQ(d.degenerate_count, 1);
  EXPECT_TRUE(std::isinf(d.kappa_max));
  EXPECT_EQ(d.kappa_mean, 1.75);
}

}  // namespace
}  // namespace plmap
