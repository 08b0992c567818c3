#pragma once
/// \file
/// The container of the binary map format (docs/map-format.md, "The binary format"): a fixed
/// header, a JSON table of contents, and 64-byte aligned little-endian arrays, each with a CRC-32.
/// It knows nothing of maps: map_file_binary.cpp decides which arrays a map consists of.
///
/// Private to core: the public interface is io/map_file_binary.hpp.

#include <plmap/core/progress.hpp>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace plmap::binary {

/// Bytes of the fixed header: magic (8), version (u32), CRC-32 of the table (u32), table length
/// (u64), file length (u64).
inline constexpr std::size_t header_bytes = 32;
/// Every array starts at a multiple of this offset (cache lines; enough for any SIMD load).
inline constexpr std::size_t array_alignment = 64;

/// CRC-32 (zlib's, the one of gzip and PNG) of a byte range.
std::uint32_t crc32_of(const void* data, std::size_t size);

/// The same CRC-32 as crc32_of, computed in pieces of a few megabytes on up to `threads` threads
/// (0: all cores) and combined with zlib's crc32_combine: the checksums of a large map file are
/// a tenth of its loading time on one thread.
std::uint32_t crc32_parallel(const void* data, std::size_t size, unsigned threads);

/// The CRC-32 of each of `ranges` (pointer, bytes), all computed together in pieces on up to
/// `threads` threads, so that many small arrays and a few large ones keep every thread busy.
std::vector<std::uint32_t> crc32_of_each(const std::vector<std::pair<const void*, std::size_t>>& ranges,
                                         unsigned threads);

/// numpy's name of an element type ("<f8", "<i4", "|u1", ...) and its size; 0 if unknown.
std::size_t dtype_size(std::string_view dtype);

/// One array to write. `data` points to `bytes` bytes that stay alive until the write ends
/// (the caller's vectors, or `owned` for arrays re-encoded for the file).
struct OutArray {
  std::string name;
  std::string dtype;
  std::vector<std::uint64_t> shape;
  std::string encoding;  ///< "raw", "counts" or "local" (docs/map-format.md)
  std::string base;      ///< for "local": the begin array the values are relative to
  const void* data = nullptr;
  std::size_t bytes = 0;
  std::vector<unsigned char> owned;
};

/// Writes header, table of contents (`toc` plus the "arrays" list built here) and arrays; the
/// arrays' checksums are computed on up to `threads` threads (0: all cores).
void write_container(std::ostream& out, nlohmann::json toc, const std::vector<OutArray>& arrays,
                     const ProgressCallback& progress, unsigned threads = 0);

/// An array of a file being read: its description from the table and its bytes in the file.
struct InArray {
  std::string name;
  std::string dtype;
  std::size_t item_bytes = 0;
  std::vector<std::uint64_t> shape;
  std::uint64_t items = 0;  ///< product of shape
  std::string encoding;
  std::string base;
  const unsigned char* data = nullptr;
  std::size_t bytes = 0;
  std::uint32_t crc32 = 0;
};

/// A parsed header and table of contents over the file's bytes. Every throw is a ParseError
/// naming `file`.
class Container {
 public:
  /// Checks the header, the table's checksum (unless `verify_table_checksum` is false: the
  /// fuzzer's mode) and syntax, and each array's dtype, shape, offset, alignment and extent
  /// (within the file, after the table, not overlapping the next one).
  Container(std::string_view content, std::string file, bool verify_table_checksum = true);

  const nlohmann::json& toc() const { return toc_; }
  const std::string& file() const { return file_; }
  /// The format version in the header (one this build reads).
  std::uint32_t version() const { return version_; }
  std::size_t file_bytes() const { return content_.size(); }

  /// The array named `name`; a ParseError if the file has none.
  const InArray& array(const std::string& name) const;
  bool has(const std::string& name) const { return arrays_.count(name) != 0; }
  /// Checks the array's CRC-32 against the table (ParseError on mismatch).
  void verify_checksum(const InArray& a) const;
  /// Checks every array's CRC-32 at once, on up to `threads` threads (0: all cores). A damaged
  /// file is reported as verify_checksum reports it, naming the first damaged array in file
  /// order, whatever the thread count.
  void verify_all_checksums(unsigned threads) const;

  [[noreturn]] void fail(const std::string& what) const;
  [[noreturn]] void fail(const InArray& a, const std::string& what) const;

  /// Reads the header and the table only, from the first bytes of a file (at least
  /// header_bytes); returns the table's length so that the caller can read that much more.
  static std::uint64_t table_bytes_from_header(std::string_view head, const std::string& file);
  /// Parses the table alone (for peeking at the dimension): `head` holds header and table.
  static nlohmann::json table_only(std::string_view head, const std::string& file);

 private:
  std::string_view content_;
  std::string file_;
  std::uint32_t version_ = 0;
  nlohmann::json toc_;
  std::map<std::string, InArray> arrays_;
};

}  // namespace plmap::binary
