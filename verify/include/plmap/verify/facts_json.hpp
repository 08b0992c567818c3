#pragma once
/// \file
/// The facts about a surface or a map that `plmap info` reports, as JSON: one form for the
/// command line and for Python's `Map.info()`.

#include <plmap/core/pl_map.hpp>

#include <nlohmann/json.hpp>

namespace plmap {

/// Counts, measure, bounding box, boundary and non-manifold counts, coincident vertices.
template <int d>
nlohmann::ordered_json surface_facts_json(const Surface<d>& surface);

/// How many vertices lie exactly where a vertex with a smaller index does: seams whose sides
/// were not stitched together (each side's elements keep their own vertices).
template <int d>
Index coincident_vertex_count(const Surface<d>& surface);

/// Both surfaces, node counts by type, regions, covered measure; with `with_quality` also the
/// distribution of the condition number kappa.
template <int d>
nlohmann::ordered_json map_facts_json(const PlMap<d>& map, bool with_quality);

}  // namespace plmap
