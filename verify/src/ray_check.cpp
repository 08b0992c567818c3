// The ray check of ray_check.hpp: samples on S1, rays along the interpolated direction field,
// CGAL's AABB tree for the hits on S2, and a comparison with the map's regions.

#include <plmap/verify/ray_check.hpp>

#include "cgal_triangles.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/evaluation.hpp>

#include <Eigen/Dense>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

namespace plmap {

std::string_view to_string(MissedReason reason) {
  switch (reason) {
    case MissedReason::nearer_sheet: return "nearer_sheet";
    case MissedReason::farther_sheet: return "farther_sheet";
    case MissedReason::not_covered: return "not_covered";
    case MissedReason::domain_in_between: return "domain_in_between";
    case MissedReason::target_seen_twice: return "target_seen_twice";
    case MissedReason::target_crosses_itself: return "target_crosses_itself";
    case MissedReason::in_folding_element: return "in_folding_element";
    case MissedReason::next_to_fold: return "next_to_fold";
    case MissedReason::inside_target_boundary: return "inside_target_boundary";
  }
  return "unknown";
}

std::string_view to_string(ExtraReason reason) {
  switch (reason) {
    case ExtraReason::beyond_target_boundary: return "beyond_target_boundary";
    case ExtraReason::unexplained: return "unexplained";
    case ExtraReason::behind_domain: return "behind_domain";
    case ExtraReason::beyond_distance_limit: return "beyond_distance_limit";
    case ExtraReason::against_normal_check: return "against_normal_check";
    case ExtraReason::past_focal_point: return "past_focal_point";
    case ExtraReason::folded_region: return "folded_region";
  }
  return "unknown";
}

namespace {

using namespace verify_detail;

/// Barycentric coordinates of x with respect to the simplex with the given corners (local
/// coordinates of dimension d).
template <int d>
Eigen::Matrix<double, d + 1, 1> barycentric_in(const std::array<LocalPoint<d>, d + 1>& c, const LocalPoint<d>& x) {
  Eigen::Matrix<double, d, d> m;
  for (int i = 0; i < d; ++i) m.col(i) = c[i + 1] - c[0];
  const LocalPoint<d> y = m.fullPivLu().solve(x - c[0]);
  Eigen::Matrix<double, d + 1, 1> b;
  b(0) = 1.0 - y.sum();
  b.template tail<d>() = y;
  return b;
}

/// Local coordinates of a world point (on or next to the element) on S2 element t: the least
/// squares solution of c0 + sum_i y_i (c_{i+1} - c0) = p.
template <int d>
LocalPoint<d> local_on(const Surface<d>& s, Index t, const WorldPoint<d>& p) {
  Eigen::Matrix<double, d + 1, d> m;
  for (int i = 0; i < d; ++i) m.col(i) = s.corner(t, i + 1) - s.corner(t, 0);
  return (m.transpose() * m).ldlt().solve(m.transpose() * (p - s.corner(t, 0)));
}

template <int d>
double mean_edge_length(const Surface<d>& s, Index t) {
  if constexpr (d == 1)
    return (s.corner(t, 1) - s.corner(t, 0)).norm();
  else
    return ((s.corner(t, 1) - s.corner(t, 0)).norm() + (s.corner(t, 2) - s.corner(t, 1)).norm() +
            (s.corner(t, 0) - s.corner(t, 2)).norm()) / 3.0;
}

/// True if the ray p(xi) + t nu(xi) of the element passes a focal point for t strictly between
/// 0 and mu: J(t) = det[dp/dxi_i + t dnu/dxi_i ..., nu(xi)] changes sign or touches zero there.
/// Values within 1e-9 of J's scale on the interval count as zero, so a hit exactly at a focal
/// point is not rejected.
template <int d>
bool passes_focal_point(const std::array<WorldPoint<d>, d + 1>& corners, const std::array<WorldPoint<d>, d + 1>& nus,
                        const WorldPoint<d>& nu, double mu) {
  std::array<double, 3> a{0.0, 0.0, 0.0};  // J(t) = a0 + a1 t + a2 t^2
  if constexpr (d == 1) {
    const Eigen::Vector2d e = corners[1] - corners[0], f = nus[1] - nus[0];
    a[0] = e.x() * nu.y() - e.y() * nu.x();
    a[1] = f.x() * nu.y() - f.y() * nu.x();
  } else {
    const Eigen::Vector3d e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
    const Eigen::Vector3d f1 = nus[1] - nus[0], f2 = nus[2] - nus[0];
    // the determinant is linear in each column: expand (e1 + t f1, e2 + t f2, nu) in t
    a[0] = e1.cross(e2).dot(nu);
    a[1] = (f1.cross(e2) + e1.cross(f2)).dot(nu);
    a[2] = f1.cross(f2).dot(nu);
  }
  if (mu == 0.0) return false;
  const double m = std::abs(mu);
  const double scale = std::max({std::abs(a[0]), std::abs(a[1]) * m, std::abs(a[2]) * m * m});
  if (!(scale > 0.0)) return false;
  const double zero = 1e-9 * scale;
  const auto J = [&](double t) { return a[0] + t * (a[1] + t * a[2]); };
  const auto sign = [&](double v) { return v > zero ? 1 : (v < -zero ? -1 : 0); };
  const int s0 = sign(J(0.0)), s1 = sign(J(mu));
  if (s0 != 0 && s1 != 0 && s0 != s1) return true;
  if (a[2] != 0.0) {
    const double vertex = -a[1] / (2.0 * a[2]);
    const double lo = std::min(0.0, mu), hi = std::max(0.0, mu);
    if (vertex > lo && vertex < hi) {
      const int sv = sign(J(vertex));
      const int reference = s0 != 0 ? s0 : s1;
      if (sv == 0 || (reference != 0 && sv != reference)) return true;
    }
  }
  return false;
}

struct Hit {
  Index element = invalid_index;
  double mu = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

template <int d>
class RayChecker {
 public:
  RayChecker(const PlMap<d>& map, const RayCheckOptions<d>& o)
      : map_(map), s1_(map.domain()), s2_(map.target()), o_(o), triangles_(s2_), domain_triangles_(s1_) {
    if (o_.directions.size() != static_cast<std::size_t>(s1_.vertex_count()))
      throw Error(fmt::format("the ray check needs one direction per S1 vertex: {} given, S1 has {} vertices",
                              o_.directions.size(), s1_.vertex_count()));
    const double diagonal = (s1_.bounding_box_max() - s1_.bounding_box_min()).norm();
    limit_ = o_.max_distance_is_relative ? o_.max_distance * diagonal : o_.max_distance;
    if (!(limit_ >= 0.0)) throw Error(fmt::format("max_distance {} is not >= 0", o_.max_distance));
    // a segment long enough to reach every point of the box around S1 and S2, or the limit
    WorldPoint<d> lo = s1_.bounding_box_min().cwiseMin(s2_.bounding_box_min());
    WorldPoint<d> hi = s1_.bounding_box_max().cwiseMax(s2_.bounding_box_max());
    const double extent = (hi - lo).norm();
    reach_ = extent > 0.0 ? 3.0 * extent : 1.0;
    if (std::isfinite(limit_)) reach_ = std::min(reach_, 2.0 * limit_ + 1e-6 * reach_);
    tree_.insert(triangles_.triangles.cbegin(), triangles_.triangles.cend());
    tree_.build();
    domain_tree_.insert(domain_triangles_.triangles.cbegin(), domain_triangles_.triangles.cend());
    domain_tree_.build();
    regions_of_target_.resize(s2_.element_count());
    for (Index r = 0; r < map_.region_count(); ++r) regions_of_target_[map_.data().region_target[r]].push_back(r);
  }

  RayCheckReport<d> run() {
    RayCheckReport<d> report;
    report.samples = o_.samples;
    report.domain_measure = s1_.measure();
    if (s1_.element_count() == 0 || o_.samples == 0) return report;
    std::vector<double> cumulative(s1_.element_count());
    double sum = 0.0;
    for (Index t = 0; t < s1_.element_count(); ++t) cumulative[t] = sum += s1_.element_measure(t);
    std::mt19937_64 rng(o_.seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<double> errors;
    for (std::size_t i = 0; i < o_.samples; ++i) {
      const double u = uniform(rng) * sum;
      const Index t = std::min<Index>(
          static_cast<Index>(std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin()),
          s1_.element_count() - 1);
      LocalPoint<d> xi;
      if constexpr (d == 1) {
        xi(0) = uniform(rng);
      } else {
        const double r1 = std::sqrt(uniform(rng)), r2 = uniform(rng);
        xi = LocalPoint<2>(r1 * (1.0 - r2), r1 * r2);
      }
      sample(t, xi, report, errors);
    }
    if (!errors.empty()) {
      std::sort(errors.begin(), errors.end());
      const auto at = [&](double q) {
        return errors[std::min(errors.size() - 1, static_cast<std::size_t>(q * static_cast<double>(errors.size())))];
      };
      report.error_median = at(0.5);
      report.error_p99 = at(0.99);
      report.error_max = errors.back();
    }
    return report;
  }

 private:
  void sample(Index t, const LocalPoint<d>& xi, RayCheckReport<d>& report, std::vector<double>& errors) {
    const WorldPoint<d> x = s1_.world_position(t, xi);
    const WorldPoint<d> nu = direction_at(t, xi);
    const std::optional<Hit> hit = cast(t, x, nu);
    const Index region = region_containing(t, xi);
    if (region != invalid_index && hit) {
      ++report.in_domain_with_hit;
      const Evaluation<d> e = evaluate_in_region(map_, region, xi);
      errors.push_back((lifted<d>(e.world) - hit->point).norm() / mean_edge_length(s2_, hit->element));
      if (errors.back() > 1.0) {
        ++report.error_above_one_edge;
        const MissedReason reason = classify_missed(x, *hit);
        ++report.above_one_by_reason[static_cast<std::size_t>(reason)];
        if (reason != MissedReason::nearer_sheet && report.in_domain_defect_examples.size() < o_.max_listed) {
          RaySample<d> s{t, x, hit->element, hit->mu, reason};
          s.image_element = e.image.element;
          s.image_error = errors.back();
          report.in_domain_defect_examples.push_back(s);
        }
      }
    } else if (region != invalid_index) {
      ++report.extra;
      const Evaluation<d> e = evaluate_in_region(map_, region, xi);
      const std::optional<double> sliver = beyond_target_boundary(x, nu, e);
      const ExtraReason reason = sliver ? ExtraReason::beyond_target_boundary : rule_rejecting_image(t, x, nu, e);
      if (sliver) errors.push_back(*sliver);
      ++report.extra_by_reason[static_cast<std::size_t>(reason)];
      if (report.extra_examples.size() < o_.max_listed)
        report.extra_examples.push_back(
            RaySample<d>{t, x, e.image.element, 0.0, MissedReason::not_covered, reason});
    } else if (hit) {
      ++report.missed;
      MissedReason reason = classify_missed(x, *hit);
      if (reason == MissedReason::not_covered)
        reason = explain_not_covered(t, x, nu, *hit);
      else if (beside_target_boundary_preimage(t, x, *hit))
        reason = MissedReason::inside_target_boundary;
      ++report.missed_by_reason[static_cast<std::size_t>(reason)];
      if (report.missed_examples.size() < o_.max_listed)
        report.missed_examples.push_back(RaySample<d>{t, x, hit->element, hit->mu, reason});
    } else {
      ++report.neither;
    }
  }

  /// For a sample in D without a hit: if Xi(x) lies on an S2 element next to S2's boundary and
  /// the ray meets the plane of that element, or of an element around one of its boundary
  /// vertices, outside it only across boundary facets of S2, the distance of Xi(x) from the ray
  /// relative to the image element's mean edge length (the smallest over those elements).
  /// Near a boundary corner of S2 the ray may leave S2 across a neighbour's boundary facet while
  /// Xi(x) lies on the element next to it, which is the same interpolation error.
  std::optional<double> beyond_target_boundary(const WorldPoint<d>& x, const WorldPoint<d>& nu,
                                               const Evaluation<d>& e) const {
    const Index tau = e.image.element;
    std::optional<double> nearest = plane_point_beyond_boundary(x, nu, e, tau);
    for (Index v : s2_.element(tau)) {
      if (!s2_.is_boundary_vertex(v)) continue;
      for (Index sigma : s2_.vertex_elements(v)) {
        if (sigma == tau) continue;
        const std::optional<double> distance = plane_point_beyond_boundary(x, nu, e, sigma);
        if (distance && (!nearest || *distance < *nearest)) nearest = distance;
      }
    }
    if (!nearest) return std::nullopt;
    return *nearest / mean_edge_length(s2_, tau);
  }

  /// If the ray meets S2 element sigma's plane at a point outside sigma only across boundary
  /// facets of S2: the distance of Xi(x) from the ray.
  std::optional<double> plane_point_beyond_boundary(const WorldPoint<d>& x, const WorldPoint<d>& nu,
                                                    const Evaluation<d>& e, Index sigma) const {
    const WorldPoint<d> n = s2_.element_normal(sigma);
    const double along = n.dot(nu);
    if (!(std::abs(along) > 1e-12 * nu.norm() * n.norm())) return std::nullopt;
    const WorldPoint<d> q = x + (n.dot(s2_.corner(sigma, 0) - x) / along) * nu;
    const LocalPoint<d> y = local_on<d>(s2_, sigma, q);
    Eigen::Matrix<double, d + 1, 1> b;
    b(0) = 1.0 - y.sum();
    b.template tail<d>() = y;
    bool outside = false;
    for (int k = 0; k <= d; ++k) {
      if (!(b(k) < 0.0)) continue;
      outside = true;
      // the facet opposite corner k bounds the part of S2 the rays may hit: no other element
      // lies across it, or only elements the normal test rejects (S2's silhouette along the rays)
      if constexpr (d == 2) {
        for (const EdgeIncidence& across : s2_.edge_elements(s2_.element_edge(sigma, (k + 1) % 3)))
          if (across.element != sigma && faces_the_rays(nu, across.element)) return std::nullopt;
      } else {
        for (Index across : s2_.vertex_elements(s2_.element(sigma)[1 - k]))
          if (across != sigma && faces_the_rays(nu, across)) return std::nullopt;
      }
    }
    if (!outside) return std::nullopt;
    // The distance of Xi(x) from the ray, not from q: a ray that grazes the plane meets it far
    // away (203 edge lengths on a generated pair, seed 113 of the projection properties) while
    // Xi(x) lies beside the ray. (q lies on the ray, so this is never more.)
    const WorldPoint<d> w = e.world - x;
    return (w - (w.dot(nu) / nu.squaredNorm()) * nu).norm();
  }

  /// Whether `cast` rejects hits past a focal point of the direction field.
  enum class FocalRule { apply, ignore };

  /// For a sample in D without an admissible hit: if Xi(x) lies on the ray (within half the
  /// mean edge length of its S2 element), the acceptance rule of the check that rejects it as a
  /// hit (negative distance, the distance limit, the normal test, or a focal point of the
  /// direction field between x and Xi(x), or between x and the ray's own hit next to Xi(x));
  /// else unexplained.
  ExtraReason rule_rejecting_image(Index t, const WorldPoint<d>& x, const WorldPoint<d>& nu,
                                   const Evaluation<d>& e) const {
    const double nn = nu.squaredNorm();
    if (!(nn > 0.0)) return ExtraReason::unexplained;
    const double mu = (e.world - x).dot(nu) / nn;
    const double edge = mean_edge_length(s2_, e.image.element);
    if (!((e.world - (x + mu * nu)).norm() <= 0.5 * edge)) return ExtraReason::unexplained;
    const double slack = 1e-9 * edge;
    if (!o_.allow_negative_distance && mu < -slack) return ExtraReason::behind_domain;
    if (!(std::abs(mu) <= limit_ + slack)) return ExtraReason::beyond_distance_limit;
    if (o_.normal_check != RayNormalCheck::none) {
      const double c = nu.dot(s2_.element_normal(e.image.element));
      if (o_.normal_check == RayNormalCheck::facing ? !(c < 0.0) : !(c > 0.0))
        return ExtraReason::against_normal_check;
    }
    // Past a focal point: the interpolation at a fold only if the region's corners are unfolded.
    const auto at_fold = [&] {
      return has_folded_corner(t, e.region) ? ExtraReason::folded_region : ExtraReason::past_focal_point;
    };
    if (passes_focal_point_in(t, nu, mu)) return at_fold();
    // Xi(x) is the interpolation of the ray's hit, a little off the ray: where S2 crosses the
    // focal surface, Xi(x) can lie just before the focal point while the ray's own hit lies just
    // past it. The hit, not the foot of Xi(x) on the ray, decides.
    if (const auto past = cast(t, x, nu, FocalRule::ignore);
        past && (past->point - lifted<d>(e.world)).norm() <= 0.5 * edge && passes_focal_point_in(t, nu, past->mu))
      return at_fold();
    return ExtraReason::unexplained;
  }

  /// The direction field at local point xi of element t: the corners' directions interpolated
  /// linearly (not normalised), as the projection's rays take it.
  WorldPoint<d> direction_at(Index t, const LocalPoint<d>& xi) const {
    const auto corners = s1_.element(t);
    WorldPoint<d> nu = o_.directions[corners[0]];
    for (int i = 0; i < d; ++i) nu += xi(i) * (o_.directions[corners[i + 1]] - o_.directions[corners[0]]);
    return nu;
  }

  /// Whether the ray of a corner of region r (on element t), from the corner's point along the
  /// element's field to the corner's image, passes a focal point of the element.
  bool has_folded_corner(Index t, Index r) const {
    const auto& m = map_.stored();
    for (const Index n : m.region_corners[r]) {
      const LocalPoint<d>& xi = m.node_position[n];
      const WorldPoint<d> nu = direction_at(t, xi);
      const double nn = nu.squaredNorm();
      if (!(nn > 0.0)) continue;
      const SurfacePoint<d> image = m.node_image(n);
      const WorldPoint<d> y = s2_.world_position(image.element, image.local);
      const double mu = (y - s1_.world_position(t, xi)).dot(nu) / nn;
      if (passes_focal_point_in(t, nu, mu)) return true;
    }
    return false;
  }

  /// The admissible hit with the smallest mu (|mu| with negative distances), if any.
  std::optional<Hit> cast(Index t, const WorldPoint<d>& x, const WorldPoint<d>& nu,
                          FocalRule focal = FocalRule::apply) const {
    const double nn = nu.squaredNorm();
    if (!(nn > 0.0)) return std::nullopt;
    const Eigen::Vector3d origin = lifted<d>(x), direction = lifted<d>(nu);
    const Eigen::Vector3d unit = direction / std::sqrt(nn);
    std::optional<Hit> best;
    const auto consider = [&](const Eigen::Vector3d& p, Index tau) {
      const double mu = (p - origin).dot(direction) / nn;
      if (!admissible(t, nu, mu, tau, focal)) return;
      if (best && rank(mu) >= rank(best->mu)) return;
      best = Hit{tau, mu, p};
    };
    const auto cast_segment = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
      using Query = Kernel::Segment_3;
      const Query segment(cgal_point(from), cgal_point(to));
      std::vector<Tree::Intersection_and_primitive_id<Query>::Type> hits;
      tree_.all_intersections(segment, std::back_inserter(hits));
      for (const auto& [where, id] : hits) {
        const Index tau = triangles_.element[triangles_.index_of(id)];
        if (const Point3* p = boost::get<Point3>(&where)) consider(eigen_point(*p), tau);
        // a segment: the ray runs inside the element's plane (grazing); its nearer end counts
        else if (const auto* s = boost::get<Kernel::Segment_3>(&where)) {
          const Eigen::Vector3d a = eigen_point(s->source()), b = eigen_point(s->target());
          consider((a - origin).norm() < (b - origin).norm() ? a : b, tau);
        }
      }
    };
    // Where S1 and S2 meet (a surface projected onto a copy of itself, or touching bodies), the
    // hit is x itself; but x is S1's rounding of that point and may lie a rounding step behind
    // S2's plane, where a segment from x misses it (the ray then found only the far side of a
    // closed surface, and the check reported up to half of S1 as "extra"). So the segment
    // starts a little behind x; `admissible` judges the hits found there by their distance.
    const Eigen::Vector3d start = origin - 1e-9 * mean_edge_length(s1_, t) * unit;
    cast_segment(start, origin + reach_ * unit);
    if (o_.allow_negative_distance) cast_segment(origin, origin - reach_ * unit);
    return best;
  }

  double rank(double mu) const { return o_.allow_negative_distance ? std::abs(mu) : mu; }

  /// S2 element tau passes the check's normal test for rays along nu.
  bool faces_the_rays(const WorldPoint<d>& nu, Index tau) const {
    if (o_.normal_check == RayNormalCheck::none) return true;
    const double c = nu.dot(s2_.element_normal(tau));
    return o_.normal_check == RayNormalCheck::facing ? c < 0.0 : c > 0.0;
  }

  bool admissible(Index t, const WorldPoint<d>& nu, double mu, Index tau, FocalRule focal = FocalRule::apply) const {
    const double slack = 1e-9 * mean_edge_length(s2_, tau);
    if (!o_.allow_negative_distance && mu < -slack) return false;
    if (!(std::abs(mu) <= limit_ + slack)) return false;
    if (!faces_the_rays(nu, tau)) return false;
    return focal == FocalRule::ignore || !passes_focal_point_in(t, nu, mu);
  }

  /// The ray along nu from a point of S1 element t passes a focal point of the element's field
  /// before distance mu.
  bool passes_focal_point_in(Index t, const WorldPoint<d>& nu, double mu) const {
    std::array<WorldPoint<d>, d + 1> corners, nus;
    for (int k = 0; k <= d; ++k) {
      corners[k] = s1_.corner(t, k);
      nus[k] = o_.directions[s1_.element(t)[k]];
    }
    return passes_focal_point<d>(corners, nus, nu, mu);
  }

  /// The region of element t that contains the local point, or invalid_index (outside D).
  Index region_containing(Index t, const LocalPoint<d>& xi) const {
    const auto& m = map_.data();
    for (Index r = map_.regions_begin(t); r < map_.regions_end(t); ++r) {
      std::array<LocalPoint<d>, d + 1> c;
      for (int k = 0; k <= d; ++k) c[k] = m.node_position[m.region_corners[r][k]];
      if (barycentric_in<d>(c, xi).minCoeff() >= -1e-12) return r;
    }
    return invalid_index;
  }

  MissedReason classify_missed(const WorldPoint<d>& x, const Hit& hit) const {
    const std::optional<WorldPoint<d>> y = covering_preimage(hit);
    if (!y) return MissedReason::not_covered;
    const WorldPoint<d> q = hit_point(hit);
    return (q - *y).norm() <= (q - x).norm() ? MissedReason::nearer_sheet : MissedReason::farther_sheet;
  }

  /// The hit in S1's world space (for curves, without the extrusion's z).
  static WorldPoint<d> hit_point(const Hit& hit) {
    if constexpr (d == 2)
      return hit.point;
    else
      return hit.point.template head<2>();
  }

  /// The point of D that the map sends to the hit, if a region covers it.
  std::optional<WorldPoint<d>> covering_preimage(const Hit& hit) const {
    const auto& m = map_.data();
    const LocalPoint<d> on_target = local_on<d>(s2_, hit.element, hit_point(hit));
    for (Index r : regions_of_target_[hit.element]) {
      std::array<LocalPoint<d>, d + 1> image;
      for (int k = 0; k <= d; ++k) image[k] = apply<d>(m.region_map[r], m.node_position[m.region_corners[r][k]]);
      const auto b = barycentric_in<d>(image, on_target);
      if (!(b.minCoeff() >= -1e-9)) continue;
      LocalPoint<d> preimage = LocalPoint<d>::Zero();
      for (int k = 0; k <= d; ++k) preimage += b(k) * m.node_position[m.region_corners[r][k]];
      return s1_.world_position(map_.node_element(m.region_corners[r][0]), preimage);
    }
    return std::nullopt;
  }

  /// For a missed sample in S1 element t whose hit a region covers: the hit lies on an S2
  /// element with a corner on S2's boundary, and its preimage lies within the mean edge length
  /// of t from x (MissedReason::inside_target_boundary).
  bool beside_target_boundary_preimage(Index t, const WorldPoint<d>& x, const Hit& hit) const {
    bool at_boundary = false;
    for (Index v : s2_.element(hit.element)) at_boundary |= s2_.is_boundary_vertex(v);
    if (!at_boundary) return false;
    const std::optional<WorldPoint<d>> y = covering_preimage(hit);
    return y && (*y - x).norm() <= mean_edge_length(s1_, t);
  }

  /// Why a sample that no region covers lies outside D: a stated reason (domain_in_between,
  /// target_seen_twice, target_crosses_itself), else the defect class that says where it lies
  /// (in_folding_element, next_to_fold), tried in that order; else not_covered.
  MissedReason explain_not_covered(Index t, const WorldPoint<d>& x, const WorldPoint<d>& nu, const Hit& hit) const {
    if (domain_between(lifted<d>(x), hit.point)) return MissedReason::domain_in_between;
    if (target_seen_again(lifted<d>(nu), hit)) return MissedReason::target_seen_twice;
    if (target_crosses_itself_near(hit)) return MissedReason::target_crosses_itself;
    if (folds_within(t, hit.mu)) return MissedReason::in_folding_element;
    if (fold_next_to(t, hit.mu)) return MissedReason::next_to_fold;
    return MissedReason::not_covered;
  }

  /// Another part of S1 meets the open segment between x and its hit. Intersections within a
  /// millionth of the segment's length of either end are x's own element (and its neighbours
  /// when x lies on an edge) or S1 touching S2 at the hit.
  bool domain_between(const Eigen::Vector3d& x, const Eigen::Vector3d& hit) const {
    const double length = (hit - x).norm();
    if (!(length > 0.0)) return false;
    const double end_slack = 1e-6 * length;
    using Query = Kernel::Segment_3;
    const Query segment(cgal_point(x), cgal_point(hit));
    std::vector<Tree::Intersection_and_primitive_id<Query>::Type> hits;
    domain_tree_.all_intersections(segment, std::back_inserter(hits));
    for (const auto& [where, id] : hits) {
      std::array<Eigen::Vector3d, 2> points;
      int n = 0;
      if (const Point3* p = boost::get<Point3>(&where)) {
        points[n++] = eigen_point(*p);
      } else if (const auto* s = boost::get<Kernel::Segment_3>(&where)) {
        points[n++] = eigen_point(s->source());
        points[n++] = eigen_point(s->target());
      }
      for (int i = 0; i < n; ++i)
        if ((points[i] - x).norm() > end_slack && (points[i] - hit).norm() > end_slack) return true;
    }
    return false;
  }

  /// S2 crosses the ray again within one mean edge length of the element hit, seen from the
  /// other side (its normal's component along the ray has the opposite sign).
  bool target_seen_again(const Eigen::Vector3d& direction, const Hit& hit) const {
    const double reach = mean_edge_length(s2_, hit.element);
    const double n = direction.norm();
    if (!(reach > 0.0) || !(n > 0.0)) return false;
    const Eigen::Vector3d unit = direction / n;
    const double side = facing_sign(hit.element, unit);
    if (side == 0.0) return false;
    using Query = Kernel::Segment_3;
    const Query segment(cgal_point(hit.point - reach * unit), cgal_point(hit.point + reach * unit));
    std::vector<Tree::Intersection_and_primitive_id<Query>::Type> hits;
    tree_.all_intersections(segment, std::back_inserter(hits));
    for (const auto& [where, id] : hits) {
      const Point3* p = boost::get<Point3>(&where);
      if (!p || (eigen_point(*p) - hit.point).norm() <= 1e-6 * reach) continue;
      const Index tau = triangles_.element[triangles_.index_of(id)];
      if (facing_sign(tau, unit) == -side) return true;
    }
    return false;
  }

  /// S2 crosses itself within one mean edge length of the hit: the hit lies that close to a
  /// point where an S2 element meets another with which it shares no vertex
  /// (MissedReason::target_crosses_itself).
  bool target_crosses_itself_near(const Hit& hit) const {
    const double reach = mean_edge_length(s2_, hit.element);
    if (!(reach > 0.0)) return false;
    const Point3 c = cgal_point(hit.point);
    const Kernel::Iso_cuboid_3 box(c.x() - reach, c.y() - reach, c.z() - reach, c.x() + reach, c.y() + reach,
                                   c.z() + reach);
    std::vector<TriangleIterator> near;
    tree_.all_intersected_primitives(box, std::back_inserter(near));
    for (const TriangleIterator it : near)
      for (const Segment3& crossing : crossings_.of(triangles_.index_of(it)))
        if (CGAL::squared_distance(c, crossing) <= reach * reach) return true;
    return false;
  }

  /// The sign of the S2 element's normal along the unit direction (0 for curves, whose
  /// extruded segments have no orientation here, and for grazing elements).
  double facing_sign(Index tau, const Eigen::Vector3d& unit) const {
    if constexpr (d == 2) {
      const double c = s2_.element_normal(tau).dot(unit);
      return c > 0.0 ? 1.0 : (c < 0.0 ? -1.0 : 0.0);
    } else {
      WorldPoint<1> tangent = s2_.corner(tau, 1) - s2_.corner(tau, 0);
      const double c = tangent.x() * unit.y() - tangent.y() * unit.x();
      return c > 0.0 ? 1.0 : (c < 0.0 ? -1.0 : 0.0);
    }
  }

  /// The ray from some corner of an element sharing a vertex with t passes a focal point before
  /// distance mu.
  bool fold_next_to(Index t, double mu) const {
    for (int k = 0; k <= d; ++k)
      for (Index u : s1_.vertex_elements(s1_.element(t)[k]))
        if (folds_within(u, mu)) return true;
    return false;
  }

  /// The ray from some corner of element u passes a focal point before distance mu: the fold
  /// line at that distance runs through u (or u lies wholly beyond it).
  bool folds_within(Index u, double mu) const {
    std::array<WorldPoint<d>, d + 1> corners, nus;
    for (int k = 0; k <= d; ++k) {
      corners[k] = s1_.corner(u, k);
      nus[k] = o_.directions[s1_.element(u)[k]];
    }
    for (int k = 0; k <= d; ++k)
      if (passes_focal_point<d>(corners, nus, nus[k], mu)) return true;
    return false;
  }

  const PlMap<d>& map_;
  const Surface<d>& s1_;
  const Surface<d>& s2_;
  const RayCheckOptions<d>& o_;
  TargetTriangles<d> triangles_;
  Tree tree_;
  TargetTriangles<d> domain_triangles_;  ///< S1's elements, for domain_in_between
  Tree domain_tree_;
  double limit_ = 0.0, reach_ = 0.0;
  std::vector<std::vector<Index>> regions_of_target_;
  mutable SelfCrossings<d> crossings_{s2_, triangles_, tree_};  ///< where S2 meets itself, memoized
};

}  // namespace

template <int d>
RayCheckReport<d> check_against_rays(const PlMap<d>& map, const RayCheckOptions<d>& options) {
  return RayChecker<d>(map, options).run();
}

template <int d>
nlohmann::json to_json(const RayCheckReport<d>& r) {
  const auto examples = [](const std::vector<RaySample<d>>& list, bool with_reason) {
    nlohmann::json a = nlohmann::json::array();
    for (const RaySample<d>& s : list) {
      nlohmann::json e{{"element", s.element}, {"point", std::vector<double>(s.point.data(), s.point.data() + d + 1)}};
      if (s.hit_element != invalid_index) e[with_reason ? "hit_element" : "image_element"] = s.hit_element;
      if (with_reason) e["mu"] = s.mu;
      e["reason"] = with_reason ? std::string(to_string(s.reason)) : std::string(to_string(s.extra_reason));
      if (with_reason && s.image_element != invalid_index) {
        e["image_element"] = s.image_element;
        e["error"] = s.image_error;
      }
      a.push_back(e);
    }
    return a;
  };
  nlohmann::json by_reason = nlohmann::json::object();
  for (MissedReason reason : {MissedReason::nearer_sheet, MissedReason::farther_sheet, MissedReason::not_covered,
                              MissedReason::domain_in_between, MissedReason::target_seen_twice,
                              MissedReason::target_crosses_itself, MissedReason::in_folding_element,
                              MissedReason::next_to_fold, MissedReason::inside_target_boundary}) {
    const std::size_t n = r.missed_by_reason[static_cast<std::size_t>(reason)];
    by_reason[std::string(to_string(reason))] = {{"samples", n}, {"fraction", r.fraction(n)}};
  }
  nlohmann::json j;
  j["samples"] = r.samples;
  j["domain_measure"] = r.domain_measure;
  j["missed"] = {{"samples", r.missed},
                 {"fraction", r.fraction(r.missed)},
                 {"defect_fraction", r.fraction(r.missed_defects())},
                 {"by_reason", by_reason},
                 {"examples", examples(r.missed_examples, true)}};
  nlohmann::json extra_by_reason = nlohmann::json::object();
  for (ExtraReason reason : {ExtraReason::beyond_target_boundary, ExtraReason::unexplained, ExtraReason::behind_domain,
                             ExtraReason::beyond_distance_limit, ExtraReason::against_normal_check,
                             ExtraReason::past_focal_point, ExtraReason::folded_region}) {
    const std::size_t n = r.extra_by_reason[static_cast<std::size_t>(reason)];
    extra_by_reason[std::string(to_string(reason))] = {{"samples", n}, {"fraction", r.fraction(n)}};
  }
  j["extra"] = {{"samples", r.extra},
                {"fraction", r.fraction(r.extra)},
                {"defect_fraction", r.fraction(r.extra_defects())},
                {"by_reason", extra_by_reason},
                {"examples", examples(r.extra_examples, false)}};
  j["in_domain_with_hit"] = r.in_domain_with_hit;
  j["neither"] = r.neither;
  nlohmann::json above_one_by_reason = nlohmann::json::object();
  for (MissedReason reason : {MissedReason::nearer_sheet, MissedReason::farther_sheet, MissedReason::not_covered}) {
    const std::size_t n = r.above_one_by_reason[static_cast<std::size_t>(reason)];
    above_one_by_reason[std::string(to_string(reason))] = {{"samples", n}, {"fraction", r.fraction(n)}};
  }
  j["image_error_relative_to_edge"] = {{"median", r.error_median},
                                       {"p99", r.error_p99},
                                       {"max", r.error_max},
                                       {"samples_above_one", r.error_above_one_edge},
                                       {"fraction_above_one", r.fraction(r.error_above_one_edge)},
                                       {"above_one_by_reason", above_one_by_reason},
                                       {"defect_fraction", r.fraction(r.in_domain_defects())},
                                       {"examples", examples(r.in_domain_defect_examples, true)}};
  return j;
}

template RayCheckReport<1> check_against_rays<1>(const PlMap<1>&, const RayCheckOptions<1>&);
template RayCheckReport<2> check_against_rays<2>(const PlMap<2>&, const RayCheckOptions<2>&);
template nlohmann::json to_json<1>(const RayCheckReport<1>&);
template nlohmann::json to_json<2>(const RayCheckReport<2>&);

}  // namespace plmap
