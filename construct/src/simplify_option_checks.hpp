#pragma once
// The checks of SimplifyOptions that surfaces and curves share (construct/src only).

#include <plmap/construct/simplify.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/surface.hpp>

#include <fmt/format.h>

#include <cmath>
#include <string_view>

namespace plmap::detail {

/// Throws Error naming the option when `options` cannot be run on an input of `elements`
/// elements and `vertices` vertices; `element_noun` names the elements in the plural
/// ("triangles", "segments"; the message drops the "s" for one)
/// and `input_noun` the input ("surface", "curve") in the messages.
inline void check_simplify_options(const SimplifyOptions& options, Index elements, Index vertices,
                                   std::string_view input_noun, std::string_view element_noun) {
  if (options.target_elements < 0 || options.target_vertices < 0)
    throw Error("simplify: the element and vertex targets must not be negative");
  if (options.target_elements > 0 && options.target_elements >= elements)
    throw Error(fmt::format("simplify: the target of {} elements is not below the {}'s {} {}", options.target_elements,
                            input_noun, elements,
                            elements == 1 ? element_noun.substr(0, element_noun.size() - 1) : element_noun));
  if (options.target_vertices > 0 && options.target_vertices >= vertices)
    throw Error(fmt::format("simplify: the target of {} vertices is not below the {}'s {} vertices",
                            options.target_vertices, input_noun, vertices));
  if (options.target_elements == 0 && options.target_vertices == 0 && !std::isfinite(options.max_error))
    throw Error("simplify: give a target element or vertex count, or an error bound");
  if (!(options.max_error > 0.0))
    throw Error(fmt::format("simplify: the error bound must be positive, not {}", options.max_error));
  if (!(options.feature_angle_degrees >= 0.0 && options.feature_angle_degrees <= 180.0))
    throw Error(fmt::format("simplify: the feature angle must be between 0 and 180 degrees, not {}",
                            options.feature_angle_degrees));
}

/// Throws Error naming the first vertex of the fine input that is a corner of none of its
/// elements: a parametrization gives every vertex a preimage, and such a vertex can have none
/// (the builder would find it only after the whole run, and call it an S1 vertex).
template <int d>
void check_no_isolated_vertices(const Surface<d>& s, std::string_view input_noun, std::string_view element_noun) {
  for (Index v = 0; v < s.vertex_count(); ++v)
    if (s.vertex_elements(v).empty())
      throw Error(fmt::format("simplify: vertex {} of the {} is isolated (a corner of none of its {}); a "
                              "parametrization gives every vertex a preimage: remove isolated vertices first",
                              v, input_noun, element_noun));
}

}  // namespace plmap::detail
