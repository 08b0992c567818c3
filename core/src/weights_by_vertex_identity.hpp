#pragma once
// A point given on one S2 element re-expressed on another that contains it, exactly: its weights
// move with the vertices they belong to. Shared by the region maps finalize writes
// (finalize_region_maps.cpp) and those the binary map file derives (io/region_map_derivation.hpp),
// so that both give the same bits. Private to core.

#include <plmap/core/surface.hpp>

namespace plmap::detail {

/// The local coordinates on the element with corners `to` of a point whose barycentric weights on
/// the element with corners `from` are omitted() for corner 0 and `local` for corners 1 .. d: the
/// weights of to's corners 1 .. d, moved by vertex identity (+0.0 for a corner of `to` that is no
/// corner of `from`). `omitted` is called only where corner 0 of `from` is one of those corners.
template <int d, class OmittedWeight>
LocalPoint<d> weights_by_vertex_identity(const ElementCorners<d>& from, const ElementCorners<d>& to,
                                         const LocalPoint<d>& local, OmittedWeight&& omitted) {
  LocalPoint<d> y = LocalPoint<d>::Zero();
  for (int k = 1; k <= d; ++k)
    for (int j = 0; j <= d; ++j)
      if (from[j] == to[k]) y(k - 1) = j == 0 ? omitted() : local(j - 1);
  return y;
}

}  // namespace plmap::detail
