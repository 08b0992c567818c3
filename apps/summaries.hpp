#pragma once
/// \file
/// The facts `plmap info` reports about a surface or a map, as JSON (also used by `build` and
/// `convert` to describe what they wrote).

#include <plmap/core/pl_map.hpp>

#include "cli_common.hpp"

namespace plmap::cli {

/// Counts, measure, bounding box, boundary and non-manifold counts, coincident vertices.
template <int d>
Json surface_summary(const Surface<d>& surface);

/// How many vertices lie exactly where a vertex with a smaller index does: seams whose sides
/// were not stitched together (each side's elements keep their own vertices).
template <int d>
Index coincident_vertex_count(const Surface<d>& surface);

/// Both surfaces, node counts by type, regions, covered measure; with `with_quality` also the
/// distribution of the condition number kappa.
template <int d>
Json map_summary(const PlMap<d>& map, bool with_quality);

}  // namespace plmap::cli
