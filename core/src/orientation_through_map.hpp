#pragma once
// finalize(), phase 2: whether a closure triangle's affine map keeps its image's orientation at
// the corners without computing the map. Private to the builder.
//
// judge_face_orientation (finalize_closure.cpp) judges each closure triangle twice: by the
// orientation of its corners' images, and by that of the corners as the region's affine map
// reproduces them (what verify sees: a nearly flat image may become exactly flat through the
// map). The map's corners differ from the images only by its rounding, so for all but nearly
// flat images the second judgement is the first; this filter says when that is certain, and the
// map (affine_through in long double, a third of the judgement's cost) is then not computed
// where the regions' maps are written later anyway (finalize_region_maps.hpp).

#include <plmap/core/types.hpp>

#include <array>
#include <cmath>

namespace plmap::detail {

/// Whether the affine map through the corners `from` -> `image` (affine_through, rounded to
/// doubles), applied to `from`, surely gives a triangle of the same orientation as `image`.
/// The map's corners differ from the images by its rounding, at most
///     b = 1e-14 (1 + |T| |F| / |det F|)
/// (F, T the corners' differences; their Frobenius norms bound the linear part's by
/// |F^-1| = |F| / |det F| for 2 x 2; local coordinates are at most about 1, and the rounding of
/// affine_through and of applying the map is a few 1e-16 of that: a margin of five). Moving the
/// corners of a triangle with sides u, v from one corner by b changes u x v by at most
/// 2 b (|u| + |v|) + 4 b^2.
inline bool orientation_survives_the_map(const std::array<LocalPoint<2>, 3>& from,
                                         const std::array<LocalPoint<2>, 3>& image) {
  const LocalPoint<2> f1 = from[1] - from[0], f2 = from[2] - from[0];
  const LocalPoint<2> u = image[1] - image[0], v = image[2] - image[0];
  const double det = std::abs(f1(0) * f2(1) - f1(1) * f2(0));
  if (!(det > 0.0)) return false;
  const double f_norm = std::sqrt(f1.squaredNorm() + f2.squaredNorm());
  const double t_norm = std::sqrt(u.squaredNorm() + v.squaredNorm());
  const double b = 1e-14 * (1.0 + t_norm * f_norm / det);
  const double cross = std::abs(u(0) * v(1) - u(1) * v(0));
  // (the cross product's own rounding: a few ulps of |u| |v|)
  return cross > 2.0 * b * (u.norm() + v.norm()) + 4.0 * b * b + 1e-15 * u.norm() * v.norm();
}

}  // namespace plmap::detail
