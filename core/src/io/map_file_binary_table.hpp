#pragma once
/// \file
/// The map-level keys of a binary map file's table of contents (docs/map-format.md, "The binary
/// format"): format, dimension, orientation, the two surface fingerprints and the optional
/// provenance. The arrays' own entries are the container's business (binary_container.hpp).
///
/// Private to core: map_file_binary.cpp writes and reads the whole file through it.

#include <plmap/core/map_provenance.hpp>
#include <plmap/core/pl_map.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace plmap::binary {

/// The map-level keys as read back from a table of contents.
struct MapTableHeader {
  int dimension = 0;
  int orientation = 0;
  MapProvenance provenance;  // the optional key "provenance": an object of string values
};

/// The table of contents of `map`'s file before its arrays are added.
template <int d>
nlohmann::json map_table_header(const PlMap<d>& map);

/// The map-level keys of a table of contents, checked; throws ParseError naming `file` when one
/// is missing, out of range or malformed.
MapTableHeader read_map_table_header(const nlohmann::json& toc, const std::string& file);

}  // namespace plmap::binary
