#pragma once
/// \file
/// The binary map file (`.plmapb`): the same content as the text `.plmap` file (both surfaces and
/// the compact map, MapData) in a versioned, checksummed layout of little-endian arrays that
/// loads with a few large reads and that numpy reads with np.frombuffer. The full specification
/// is docs/map-format.md ("The binary format").
///
/// Layout: a 32-byte header (magic, version, the table of contents' length and CRC-32, the file
/// length), a JSON table of contents naming every array's dtype, shape, encoding, offset and
/// CRC-32, then the arrays, each at a 64-byte aligned offset.
///
/// Exact: load(save(m)).data() == m.data(), and text -> binary -> text reproduces the text file
/// byte for byte. Safe: every length, offset, checksum and decoded index is checked before use;
/// any damage is a ParseError naming the file (and the array), never a crash; a map that decodes
/// then passes the same PlMap constructor checks and validate_map_structure as a text map.
///
/// The generic entry points of map_file.hpp (save_map, load_map, map_file_dimension) choose this
/// format by the file's extension (writing) or its first bytes (reading); the functions here are
/// for callers that hold the bytes in memory.

#include <plmap/core/io/map_file.hpp>
#include <plmap/core/progress.hpp>

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>

namespace plmap {

/// The first 8 bytes of every binary map file. The non-ASCII first byte and the line ending keep
/// it from being mistaken for text and reveal a file mangled by a text-mode transfer.
inline constexpr std::string_view binary_map_magic{"\x89PLMAPB\n", 8};
/// The binary format version this build writes. Version 2 stores a triangle map's graph arrays
/// only for the elements that store them (PlMap::stored_graph); version 1 stored them all.
inline constexpr std::uint32_t binary_map_version = 2;
/// The oldest version this build reads (version 1 files are converted on load: each element's
/// graph is compared with its derivation once, as for a text file).
inline constexpr std::uint32_t oldest_binary_map_version = 1;
/// The extension that selects the binary format when writing (compared case-insensitively).
inline constexpr std::string_view binary_map_extension = ".plmapb";

/// True if `path` ends in binary_map_extension (case-insensitive).
bool has_binary_map_extension(const std::filesystem::path& path);

/// True if `head` (the first bytes of a file) starts with binary_map_magic.
bool looks_like_binary_map(std::string_view head);

/// Writes the binary map file to `out`. Throws InvalidMapError if the map holds a non-finite
/// number (as the text writer does, so that both formats hold the same maps).
template <int d>
void write_binary_map(std::ostream& out, const PlMap<d>& map, const MapWriteOptions& options = {});

/// Parses a binary map file held in memory; `source_name` names it in error messages.
AnyPlMap parse_binary_map(std::string_view content, const std::string& source_name,
                          const MapReadOptions& options = {});

/// The dimension declared in a binary map file's table of contents (reads the header and the
/// table only). Throws ParseError if the file is not a readable binary map file.
int binary_map_file_dimension(const std::filesystem::path& path);

}  // namespace plmap
