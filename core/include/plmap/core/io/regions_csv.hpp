#pragma once
/// \file
/// The regions of a map (its remote intersections, see regions.hpp) as a CSV table, for
/// spreadsheets, pandas and mortar-assembly prototypes.
///
/// One header row, then one row per region in region order. Columns (d = 2 shown; for d = 1 the
/// local coordinates have one component `xi0`, the world points two, `x` and `y`, and there are
/// two corners):
/// - `region`, `domain_element`, `target_element`;
/// - `domain_local_C_xiI`: local coordinate I of corner C on the S1 element;
/// - `target_local_C_xiI`: local coordinate I of the image of corner C on the S2 element;
/// - `domain_world_C_x` (`_y`, `_z`): world position of corner C on S1;
/// - `target_world_C_x` (`_y`, `_z`): world position of its image on S2;
/// - `domain_measure`, `target_measure`: length / area of the region on S1 and of its image.
/// Corners are listed in the same order on both sides. Numbers are written in the shortest
/// decimal form that parses back to the same double, so the table is exact.

#include <plmap/core/pl_map.hpp>

#include <filesystem>
#include <iosfwd>

namespace plmap {

/// Writes the table to `out`.
template <int d>
void write_regions_csv(std::ostream& out, const PlMap<d>& map);

/// Writes the table to `path` atomically. Throws plmap::Error naming the file on failure.
template <int d>
void write_regions_csv(const std::filesystem::path& path, const PlMap<d>& map);

}  // namespace plmap
