// DESIGN.md §4.7: kappa = ||A||_2 ||A^-1||_2 per region, A the linear piece in orthonormal
// frames of the region's world triangle on S1 and its image on S2.

#include <plmap/core/regions.hpp>
#include <plmap/core/scaled_geometry.hpp>
#include <plmap/verify/quality.hpp>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace plmap {

namespace {

/// The edge vectors u, v of a triangle in an orthonormal frame of its plane: an upper
/// triangular 2x2 matrix [[|u|, v.e1], [0, v.e2]].
Eigen::Matrix2d frame_coordinates_of(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const double lu = u.norm();
  Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
  if (lu == 0.0) return m;
  const Eigen::Vector3d e1 = u / lu;
  m(0, 0) = lu;
  m(0, 1) = v.dot(e1);
  m(1, 1) = (v - m(0, 1) * e1).norm();  // the frame's second axis points towards p2
  return m;
}

/// frame_coordinates_of(p1 - p0, p2 - p0), computed on the edge vectors divided by a power of
/// two near their size (exact), so that the squares inside the norms stay in range at every
/// scale of the surfaces.
Eigen::Matrix2d frame_coordinates(const std::array<WorldPoint<2>, 3>& p) {
  const double scale = power_of_two_scale<2>({p[1] - p[0], p[2] - p[0]});
  return scale * frame_coordinates_of((p[1] - p[0]) / scale, (p[2] - p[0]) / scale);
}

/// Singular values of a 2x2 matrix in closed form (no iteration).
std::pair<double, double> singular_values(const Eigen::Matrix2d& a) {
  const double e = 0.5 * (a(0, 0) + a(1, 1)), f = 0.5 * (a(0, 0) - a(1, 1));
  const double g = 0.5 * (a(1, 0) + a(0, 1)), h = 0.5 * (a(1, 0) - a(0, 1));
  const double q = std::hypot(e, h), r = std::hypot(f, g);
  return {q + r, std::abs(q - r)};
}

}  // namespace

template <int d>
RegionConditioning region_conditioning(const PlMap<d>& map, Index region) {
  const RemoteIntersection<d> ri = remote_intersection(map, region);
  RegionConditioning c;
  if constexpr (d == 1) {
    const double domain = ri.domain_measure(), image = ri.target_measure();
    if (!(domain > 0) || !(image > 0)) {
      c.kappa = std::numeric_limits<double>::infinity();
      c.sigma_min = domain > 0 ? 0.0 : std::numeric_limits<double>::infinity();
      c.sigma_max = c.sigma_min;
      return c;
    }
    c.sigma_min = c.sigma_max = image / domain;
    c.kappa = 1.0;
  } else {
    c = triangle_conditioning(ri.domain_world, ri.target_world);
  }
  return c;
}

RegionConditioning triangle_conditioning(const std::array<WorldPoint<2>, 3>& domain,
                                         const std::array<WorldPoint<2>, 3>& image) {
  RegionConditioning c;
  const Eigen::Matrix2d p = frame_coordinates(domain);
  const Eigen::Matrix2d q = frame_coordinates(image);
  const double det_p = p(0, 0) * p(1, 1);
  if (!(det_p > 0)) {
    c.kappa = std::numeric_limits<double>::infinity();
    c.sigma_min = 0.0;
    c.sigma_max = std::numeric_limits<double>::infinity();
    return c;
  }
  // A maps the domain frame coordinates to the image frame coordinates: A P = Q.
  const Eigen::Matrix2d a = q * p.inverse();
  const auto [smax, smin] = singular_values(a);
  c.sigma_max = smax;
  c.sigma_min = smin;
  c.kappa = smin > 0 ? smax / smin : std::numeric_limits<double>::infinity();
  return c;
}

QualityReport kappa_statistics(std::span<const double> region_kappas) {
  QualityReport report;
  report.region_count = static_cast<Index>(region_kappas.size());
  report.quantile_levels = {0.5, 0.9, 0.99, 0.999, 1.0};
  report.histogram.assign(17, 0);  // log10 kappa in steps of 0.25 up to 4, then open-ended
  std::vector<double> kappas;
  kappas.reserve(region_kappas.size());
  double sum = 0.0;
  report.kappa_max = 0.0;
  for (Index r = 0; r < report.region_count; ++r) {
    const double kappa = region_kappas[static_cast<std::size_t>(r)];
    if (!std::isfinite(kappa)) {
      ++report.degenerate_count;
      report.kappa_max = std::numeric_limits<double>::infinity();
      report.kappa_max_region = r;
      continue;
    }
    kappas.push_back(kappa);
    sum += kappa;
    if (kappa > report.kappa_max && std::isfinite(report.kappa_max)) {
      report.kappa_max = kappa;
      report.kappa_max_region = r;
    }
    const double bin = std::log10(std::max(kappa, 1.0)) / report.histogram_bin_width;
    const auto index = std::min<std::size_t>(static_cast<std::size_t>(bin), report.histogram.size() - 1);
    ++report.histogram[index];
  }
  if (kappas.empty()) {
    if (report.degenerate_count == 0) report.kappa_max = 1.0;
    report.quantiles.assign(report.quantile_levels.size(), report.kappa_max);
    return report;
  }
  report.kappa_mean = sum / static_cast<double>(kappas.size());
  for (double level : report.quantile_levels) {
    const auto k = static_cast<std::size_t>(std::ceil(level * static_cast<double>(kappas.size()))) ;
    const std::size_t index = std::min(kappas.size() - 1, k == 0 ? 0 : k - 1);
    std::nth_element(kappas.begin(), kappas.begin() + static_cast<std::ptrdiff_t>(index), kappas.end());
    report.quantiles.push_back(kappas[index]);
  }
  return report;
}

template <int d>
QualityReport compute_quality(const PlMap<d>& map) {
  std::vector<double> kappas(static_cast<std::size_t>(map.region_count()));
  double stretch_min = std::numeric_limits<double>::infinity(), stretch_max = 0.0;
  bool any_finite = false;
  for (Index r = 0; r < map.region_count(); ++r) {
    const RegionConditioning c = region_conditioning(map, r);
    kappas[static_cast<std::size_t>(r)] = c.kappa;
    if (!std::isfinite(c.kappa)) continue;
    any_finite = true;
    stretch_min = std::min(stretch_min, c.sigma_min);
    stretch_max = std::max(stretch_max, c.sigma_max);
  }
  QualityReport report = kappa_statistics(kappas);
  report.stretch_min = any_finite ? stretch_min : 1.0;
  report.stretch_max = any_finite ? stretch_max : 1.0;
  return report;
}

template RegionConditioning region_conditioning(const PlMap<1>&, Index);
template RegionConditioning region_conditioning(const PlMap<2>&, Index);
template QualityReport compute_quality(const PlMap<1>&);
template QualityReport compute_quality(const PlMap<2>&);

}  // namespace plmap
