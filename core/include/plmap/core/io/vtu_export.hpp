#pragma once
/// \file
/// Export of a map to ParaView: a set of VTK XML UnstructuredGrid files (ASCII) and a `.pvd`
/// collection that opens them together.
///
/// Files written into the target directory (created if missing), each atomically:
///   domain.vtu   S1: vertices, elements; cell data `element`, `node_count`, `region_count`.
///   target.vtu   S2: vertices, elements; cell data `element`.
///   graph.vtu    the graph on S1: one point per node (per-element copies included) in S1 world
///                coordinates with point data `node` (id), `node_type` (0 corner, 1 touching,
///                2 intersection, 3 ghost, 4 interior), `element`, `node_target`; one line cell
///                per graph edge with cell data `edge_kind` (0 closure, 1 target_edge) and
///                `element`.
///   regions.vtu  one triangle (d = 2) / segment (d = 1) per region in S1 world coordinates with
///                cell data `region`, `domain_element`, `target_element`, `domain_measure`,
///                `target_measure`.
///   images.vtu   the same cells placed at the regions' images on S2.
///   map.pvd      the collection of the five files.
/// For d = 1 the points are padded with z = 0 (VTK points are always three-dimensional).

#include <plmap/core/pl_map.hpp>

#include <filesystem>
#include <vector>

namespace plmap {

/// Writes the file set described above into `directory` and returns the paths written, the
/// collection last. Throws plmap::Error naming the file if a file cannot be written.
template <int d>
std::vector<std::filesystem::path> export_vtu(const PlMap<d>& map,
                                              const std::filesystem::path& directory);

/// Writes only the regions (the regions.vtu of export_vtu) to the file `path`, atomically.
/// Throws plmap::Error naming `path` if it cannot be written.
template <int d>
void write_regions_vtu(const std::filesystem::path& path, const PlMap<d>& map);

}  // namespace plmap
