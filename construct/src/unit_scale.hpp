#pragma once
// Normal projection computes on copies of S1 and S2 scaled by one power of two to unit size
// (longest edge in [1/2, 1)) when they are very large or very small, and reports in the user's
// units (issue 12, DESIGN §6).
//
// Why: its solvers, focal-point polynomials and determinant tests form products of three or four
// lengths, which overflow from coordinates of about 1e77 on and underflow below 1e-77; a
// tolerance written relative to a length still fails there. Scaling by a power of two is exact,
// so a surface pair scaled by 2^k gives bit-for-bit the same map, and one scaled by 10^k the map
// of inputs rounded once. The map stores only local and barycentric coordinates, so its arrays
// are attached unchanged to the caller's surfaces; world quantities of the report (measures,
// points where walks stopped) and the absolute distance limit are converted.

#include <plmap/construct/projection_options.hpp>
#include <plmap/construct/projection_result.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

namespace plmap::projection {

template <int d>
struct UnitScaledPair {
  std::shared_ptr<const Surface<d>> s1, s2;
  int exponent = 0;  ///< world coordinates of the copies = user coordinates * 2^exponent
};

/// Surfaces whose longest edge lies within 2^-40 .. 2^40 (about 1e-12 .. 1e12) are used as they
/// are: there every product the projection forms is far inside the range of doubles, and its
/// tolerances are relative, so the copies (which would add the surfaces' size to the memory
/// peak of large projections) would change nothing.
inline constexpr int unit_scale_free_exponent = 40;

template <int d>
UnitScaledPair<d> unit_scaled(const std::shared_ptr<const Surface<d>>& s1,
                              const std::shared_ptr<const Surface<d>>& s2) {
  const double longest = std::max(s1->max_edge_length(), s2->max_edge_length());
  if (!(longest > 0.0) || std::abs(std::ilogb(longest)) <= unit_scale_free_exponent) return {s1, s2, 0};
  const int exponent = -std::ilogb(longest) - 1;
  auto scaled1 = std::make_shared<const Surface<d>>(s1->scaled_by_power_of_two(exponent));
  // S1 = S2 as one object stays one object: the projection recognises the identity by it.
  auto scaled2 = s2 == s1 ? scaled1 : std::make_shared<const Surface<d>>(s2->scaled_by_power_of_two(exponent));
  return {std::move(scaled1), std::move(scaled2), exponent};
}

/// The options for the scaled copies: only an absolute distance limit is a length.
inline ProjectionOptions options_for_unit_scale(ProjectionOptions options, int exponent) {
  if (!options.max_distance_is_relative) options.max_distance = std::ldexp(options.max_distance, exponent);
  return options;
}

/// The result on the scaled copies, expressed on the caller's surfaces and in their units.
template <int d>
ProjectionResult<d> in_user_units(ProjectionResult<d> r, const std::shared_ptr<const Surface<d>>& s1,
                                  const std::shared_ptr<const Surface<d>>& s2, int exponent) {
  if (exponent == 0) return r;
  PlMap<d> map(s1, s2, std::move(r.map).release_data());
  for (auto& failure : r.report.edges_not_inserted)
    for (int i = 0; i <= d; ++i) failure.domain_point(i) = std::ldexp(failure.domain_point(i), -exponent);
  auto& left_out = r.report.left_out;
  for (const auto& [name, measure] : left_out.fields()) left_out.*measure = std::ldexp(left_out.*measure, -d * exponent);
  ProjectionMeasures m;
  m.domain = s1->measure();
  m.target = s2->measure();
  m.covered_domain = std::ldexp(r.measures.covered_domain, -d * exponent);
  m.covered_target = std::ldexp(r.measures.covered_target, -d * exponent);
  return ProjectionResult<d>{std::move(map), std::move(r.report), m};
}

}  // namespace plmap::projection
