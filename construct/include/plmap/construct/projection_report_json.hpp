#pragma once
/// \file
/// The projection's report as JSON: one form, with one set of names, for `plmap project --json`
/// and for Python's `Map.report`, so that a script can move between the two.

#include <plmap/construct/projection_result.hpp>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <limits>

namespace plmap {

/// The measures, counts, left-out measures by reason, the first `max_listed_edges` entries of
/// `edges_not_inserted` (as `edges_not_inserted_list`; `edges_not_inserted` is their number),
/// whether each surface was renumbered (`renumbered.S1`, `renumbered.S2`) and the seconds
/// (`seconds`: the total, `seconds_by_phase`: each phase), in that order. What only the caller
/// knows (the output file, the thread count it asked for, the solver's name) the caller adds.
template <int d>
nlohmann::ordered_json projection_report_json(const ProjectionResult<d>& result,
                                              std::size_t max_listed_edges = std::numeric_limits<std::size_t>::max());

}  // namespace plmap
