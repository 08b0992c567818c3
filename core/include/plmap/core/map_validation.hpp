#pragma once
/// \file
/// The structural validation of a map from an untrusted source (a map file): everything the
/// queries rely on, checked in one linear pass, so that a map that passes is safe for every
/// command — point location by any locator, evaluation, the regions listing and measures,
/// drawing, export and plmap::verify.
///
/// Three levels of checking, from cheap to complete:
/// - the PlMap constructor: array sizes, monotone begin arrays and index ranges (every array
///   access through PlMap's accessors stays in bounds); it runs on every construction,
///   including MapBuilder::finalize;
/// - validate_map_structure (this file): what a walk or a listing assumes of the indices, that
///   the constructor cannot see: every node, neighbour, edge node and region corner of an
///   element belongs to that element, region neighbours are regions of the same element and
///   name each other, node types, locations and targets agree, numbers are finite. load_map and
///   parse_map run it on every file;
/// - plmap::verify (verify/): the invariants of DESIGN.md §4 (orientation, crossings, tiling,
///   continuity, coverage, ...), reported in full.
///
/// Maps built by the library's own algorithms satisfy the validation by construction, so it
/// is not repeated there; tests that corrupt a map in memory to exercise verify/ construct the
/// PlMap directly.

#include <plmap/core/pl_map.hpp>

namespace plmap {

/// Throws InvalidMapError naming the S1 element (and the node or region) of the first defect
/// found. Linear in the size of the map; see docs/robustness.md for its cost. The elements are
/// checked on up to `threads` threads (0: all cores); the defect reported is the one of the
/// lowest-numbered defective element, whatever the thread count.
template <int d>
void validate_map_structure(const PlMap<d>& map, unsigned threads = 0);

extern template void validate_map_structure<1>(const PlMap<1>&, unsigned);
extern template void validate_map_structure<2>(const PlMap<2>&, unsigned);

}  // namespace plmap
