#pragma once
/// \file
/// The plmap map file (`.plmap`): both surfaces and the compact map (MapData) in one versioned,
/// line-oriented text file. The full specification is docs/map-format.md.
///
/// Doubles are written in the shortest decimal form that reads back to the same IEEE value, so
/// a file is exact: load(save(m)).data() == m.data(), and save -> load -> save reproduces the
/// file byte for byte.
///
/// Loading never trusts the file: every count is bounded by the bytes left in the file before
/// anything is allocated, every syntax error is a ParseError naming the file, line and section,
/// and the surfaces and the map then pass the constructors' checks and validate_map_structure
/// (InvalidSurfaceError, InvalidMapError, with the file name prepended): a map that loads is safe
/// for every query, listing, drawing and check. The invariants of DESIGN.md §4 beyond that
/// (orientation, tiling, continuity, ...) are for verify/ to check. A surface file given as a
/// map is a ParseError that says so.

#include <plmap/core/pl_map.hpp>
#include <plmap/core/progress.hpp>

#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>
#include <variant>

namespace plmap {

/// The first token of every map file.
inline constexpr std::string_view map_file_magic = "plmap-map";
/// The format version of a map without provenance (PlMap::provenance), as every version of plmap
/// reads it.
inline constexpr int map_file_version = 1;
/// The version of a map with provenance: version 1 with a section `provenance` after the
/// orientation. This build reads both and writes the lower one that holds the map.
inline constexpr int map_file_version_with_provenance = 2;

/// A map of either dimension, as returned by the dimension-agnostic loader.
using AnyPlMap = std::variant<PlMap<1>, PlMap<2>>;

/// Options of writing a map file (either format).
struct MapWriteOptions {
  /// Called now and then with the bytes written so far (phase "writing map").
  ProgressCallback progress;
  /// Binary files: threads that compute the checksums and derive the stored arrays (0: all
  /// cores). The file is the same, byte for byte, for every thread count.
  unsigned threads = 0;
};

/// Options of reading a map file (either format).
struct MapReadOptions {
  /// Called now and then with the bytes read and decoded so far (phase "reading map").
  ProgressCallback progress;
  /// Binary files: check every array's CRC-32 and the surfaces' fingerprints. Only the fuzzer
  /// turns this off, so that its mutations reach the decoders behind the checksums (which must
  /// be safe on their own).
  bool verify_checksums = true;
  /// Binary files: threads that check, decode and validate the arrays, and build the two
  /// surfaces side by side (0: all cores). The map, and the error a damaged file gives, are the
  /// same for every thread count.
  unsigned threads = 0;
};

/// Writes the map file to `out`. Throws InvalidMapError if the map holds a non-finite number
/// (such a file could not be read back exactly).
/// `progress` (optional) is called with phase "writing map", counting records (lines), about
/// every megabyte of text and once at the end; if it throws, nothing more is written.
template <int d>
void write_map(std::ostream& out, const PlMap<d>& map, const ProgressCallback& progress = {});

/// Writes the map file atomically: `path` is replaced only once the new file is complete. The
/// extension chooses the format: `.plmapb` binary (io/map_file_binary.hpp), anything else text.
/// A progress callback that throws cancels the write, and `path` is left as it was.
template <int d>
void save_map(const std::filesystem::path& path, const PlMap<d>& map,
              const MapWriteOptions& options = {});
/// The same with only a progress callback.
template <int d>
void save_map(const std::filesystem::path& path, const PlMap<d>& map, const ProgressCallback& progress);

/// Parses a map file held in memory, text or binary (the first bytes decide). `source_name` is
/// used in error messages (the file name). The text reader reports phase "reading map", counting
/// bytes parsed, every 64k lines and once at the end.
AnyPlMap parse_map(std::string_view content, const std::string& source_name);
AnyPlMap parse_map(std::string_view content, const std::string& source_name, const MapReadOptions& options);

/// Loads a map file of either dimension and either format (the file's first bytes decide).
AnyPlMap load_map(const std::filesystem::path& path, const MapReadOptions& options = {});
/// The same with only a progress callback.
AnyPlMap load_map(const std::filesystem::path& path, const ProgressCallback& progress);

/// Loads a map file that must have dimension d; a file of the other dimension is a ParseError.
template <int d>
PlMap<d> load_map(const std::filesystem::path& path, const MapReadOptions& options = {});
/// The same with only a progress callback.
template <int d>
PlMap<d> load_map(const std::filesystem::path& path, const ProgressCallback& progress);

/// Loads a map file that must have been built for the surfaces `domain` (S1) and `target` (S2):
/// a map whose stored surfaces differ from them (by surface_fingerprint) is refused with a
/// ParseError that names the file and the surface. The returned map holds the given surfaces.
template <int d>
PlMap<d> load_map(const std::filesystem::path& path, std::shared_ptr<const Surface<d>> domain,
                  std::shared_ptr<const Surface<d>> target, const MapReadOptions& options = {});

/// Reads only the header and returns the dimension (1 or 2) declared there, for either format.
/// Throws ParseError if the file is not a plmap map file of a supported version.
int map_file_dimension(const std::filesystem::path& path);

}  // namespace plmap
