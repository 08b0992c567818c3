#pragma once
/// \file
/// Uniform refinement of a surface, for `plmap build refine`: every segment split into 2^levels
/// equal pieces (d = 1), every triangle into 4^levels similar triangles (d = 2), together with
/// where each new vertex lies on the original surface, so that the inclusion map can be built.

#include <plmap/verify/generators/random_maps.hpp>

namespace plmap::cli {

/// Throws plmap::Error if the result would exceed `max_elements` elements.
template <int d>
generators::Refinement<d> uniform_refinement(const Surface<d>& surface, int levels,
                                             Index max_elements);

}  // namespace plmap::cli
