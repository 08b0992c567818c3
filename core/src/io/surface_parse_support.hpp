#pragma once
// Internal to the surface readers: a cursor over the file's bytes that reads text lines,
// whitespace-separated tokens and binary scalars, and raises ParseError with the file name and
// the line (text) or byte offset (binary) of the offending place. Locations are computed only
// when an error is raised, so reading stays a single pass with no bookkeeping.

#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_reader.hpp>
#include <plmap/core/types.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace plmap::surface_io_detail {

/// What a reader produces before Surface validates it. `element_offset[t]` is the byte offset of
/// the line or record that defined element t, for error messages.
template <int d>
struct RawMesh {
  std::vector<WorldPoint<d>> vertices;
  std::vector<ElementCorners<d>> elements;
  std::vector<std::size_t> element_offset;
  /// The polygons of more than three corners, each as (first element, element count) of the
  /// fan add_polygon made of it (polygon_triangulation.hpp cuts those that fold again).
  std::vector<std::pair<std::size_t, std::size_t>> polygons;
};

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
inline bool is_space(char c) { return is_blank(c) || c == '\n'; }

/// Whitespace-separated tokens of one line.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : rest_(line) {}
  /// Next token, or an empty view when the line is exhausted.
  std::string_view next() {
    std::size_t i = 0;
    while (i < rest_.size() && is_space(rest_[i])) ++i;
    std::size_t j = i;
    while (j < rest_.size() && !is_space(rest_[j])) ++j;
    std::string_view token = rest_.substr(i, j - i);
    rest_ = rest_.substr(j);
    // Keep an empty token pointing at the end of the line so errors still locate the line.
    if (token.empty()) return rest_.substr(rest_.size());
    return token;
  }
  bool empty() const {
    return std::all_of(rest_.begin(), rest_.end(), [](char c) { return is_space(c); });
  }
  std::size_t count() const {
    Tokens copy = *this;
    std::size_t n = 0;
    while (!copy.next().empty()) ++n;
    return n;
  }

 private:
  std::string_view rest_;
};

/// Parses a whole token as a double (a leading '+' is allowed). Non-finite results are
/// reported as parsed; the caller decides.
inline bool parse_double(std::string_view token, double& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto result = std::from_chars(token.data(), token.data() + token.size(), out);
  if (result.ec == std::errc::result_out_of_range) {
    out = std::numeric_limits<double>::infinity();  // reported as non-finite by the caller
    return result.ptr == token.data() + token.size();
  }
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

/// Parses a whole token as a signed 64-bit integer (a leading '+' is allowed).
inline bool parse_integer(std::string_view token, std::int64_t& out) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto result = std::from_chars(token.data(), token.data() + token.size(), out);
  return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

/// A read position in a file held in memory.
class Cursor {
 public:
  Cursor(std::string_view data, const std::string& file, bool text_locations)
      : data_(data), file_(file), binary_from_(text_locations ? std::string_view::npos : 0) {}

  std::string_view data() const { return data_; }
  const std::string& file() const { return file_; }
  std::size_t position() const { return pos_; }
  void set_position(std::size_t p) { pos_ = std::min(p, data_.size()); }
  std::size_t remaining() const { return data_.size() - pos_; }
  bool at_end() const { return pos_ >= data_.size(); }
  /// From the current position on, locations are byte offsets (for files with a text header
  /// and binary data); errors in the header still name its lines.
  void use_byte_locations() { binary_from_ = std::min(binary_from_, pos_); }

  /// "line N" (text) or "byte N" (binary) for a byte offset.
  std::string location(std::size_t offset) const {
    offset = std::min(offset, data_.size());
    if (offset >= binary_from_) return fmt::format("byte {}", offset);
    const auto newlines = std::count(data_.begin(), data_.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
    return fmt::format("line {}", newlines + 1);
  }
  /// Offset of a view that points into the data (e.g. a line or token).
  std::size_t offset_of(std::string_view inside) const {
    const auto off = inside.data() - data_.data();
    if (off < 0) return 0;
    return std::min(static_cast<std::size_t>(off), data_.size());
  }

  [[noreturn]] void fail_at(std::size_t offset, const std::string& what) const {
    throw ParseError(file_, location(offset), what);
  }
  [[noreturn]] void fail_at(std::string_view inside, const std::string& what) const {
    fail_at(offset_of(inside), what);
  }
  [[noreturn]] void fail(const std::string& what) const { fail_at(pos_, what); }

  // ---- text ----

  /// The next line without its line break; false at the end of the data.
  bool read_line(std::string_view& line) {
    if (at_end()) return false;
    const std::size_t end = data_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? data_.size() : end;
    line = data_.substr(pos_, stop - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end == std::string_view::npos ? data_.size() : end + 1;
    return true;
  }

  /// The next line that is not blank once the comment (from `comment` to the end of the line)
  /// is dropped; comment == '\0' means the format has no comments.
  bool read_content_line(std::string_view& line, char comment = '#') {
    while (read_line(line)) {
      if (comment != '\0') {
        const std::size_t c = line.find(comment);
        if (c != std::string_view::npos) line = line.substr(0, c);
      }
      if (!Tokens(line).empty()) return true;
    }
    return false;
  }

  /// The next whitespace-separated token, crossing line breaks; empty at the end of the data.
  std::string_view read_token() {
    while (pos_ < data_.size() && is_space(data_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
    return data_.substr(start, pos_ - start);
  }

  // ---- binary ----

  /// Throws unless n more bytes are available.
  void require(std::size_t n, std::string_view what) const {
    if (remaining() < n)
      fail(fmt::format("file is truncated: {} needs {} bytes, only {} remain", what, n,
                       remaining()));
  }

  /// Reads one arithmetic value stored with the given byte order.
  template <class T>
  T read_binary(bool big_endian, std::string_view what) {
    static_assert(std::is_arithmetic_v<T>);
    require(sizeof(T), what);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    if (big_endian != (std::endian::native == std::endian::big))
      std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  void skip(std::size_t n, std::string_view what) {
    require(n, what);
    pos_ += n;
  }

 private:
  std::string_view data_;
  const std::string& file_;
  std::size_t pos_ = 0;
  std::size_t binary_from_;  // offsets from here on are reported as bytes
};

/// Checks a count read from a header against the bytes left: each item needs at least
/// `min_bytes_each` bytes, so a larger count means a corrupted or truncated file. Also keeps
/// counts within plmap's 32-bit indices.
inline std::size_t checked_count(const Cursor& cursor, std::size_t at, std::int64_t count,
                                 std::size_t min_bytes_each, std::string_view what) {
  if (count < 0) cursor.fail_at(at, fmt::format("negative {} count {}", what, count));
  const auto n = static_cast<std::uint64_t>(count);
  if (n > static_cast<std::uint64_t>(std::numeric_limits<Index>::max()))
    cursor.fail_at(at, fmt::format("{} count {} exceeds plmap's 32-bit index range", what, n));
  if (min_bytes_each > 0 && n > cursor.remaining() / min_bytes_each)
    cursor.fail_at(at, fmt::format("{} count {} cannot fit in the {} bytes that remain "
                                   "(truncated or corrupted file)",
                                   what, n, cursor.remaining()));
  return static_cast<std::size_t>(n);
}

/// Reads a coordinate token, rejecting non-numbers and non-finite values.
inline double read_coordinate(const Cursor& cursor, std::string_view token, std::string_view what) {
  if (token.empty()) cursor.fail_at(token, fmt::format("expected {}, found the end of the line", what));
  double value;
  if (!parse_double(token, value))
    cursor.fail_at(token, fmt::format("expected {}, found '{}'", what, token.substr(0, 40)));
  if (!std::isfinite(value))
    cursor.fail_at(token, fmt::format("{} '{}' is not finite", what, token.substr(0, 40)));
  return value;
}

inline std::int64_t read_integer(const Cursor& cursor, std::string_view token, std::string_view what) {
  if (token.empty()) cursor.fail_at(token, fmt::format("expected {}, found the end of the line", what));
  std::int64_t value;
  if (!parse_integer(token, value))
    cursor.fail_at(token, fmt::format("expected {} (an integer), found '{}'", what, token.substr(0, 40)));
  return value;
}

inline void check_finite(const Cursor& cursor, std::size_t at, double value, std::string_view what) {
  if (!std::isfinite(value)) cursor.fail_at(at, fmt::format("{} is not finite ({})", what, value));
}

/// Adds a polygon face given by vertex indices already resolved to 0-based and in range
/// (checked by the caller, or later by check_indices); fan-triangulates or rejects polygons (a
/// fan that folds is cut again once all vertices are read: polygon_triangulation.hpp).
inline void add_polygon(const Cursor& cursor, std::size_t at, std::span<const Index> corners,
                        const SurfaceReadOptions& options, RawMesh<2>& mesh) {
  if (corners.size() < 3)
    cursor.fail_at(at, fmt::format("a face needs at least 3 vertices, this one has {}", corners.size()));
  if (corners.size() > 3 && options.polygons == PolygonPolicy::reject)
    cursor.fail_at(at, fmt::format("face with {} vertices; only triangles are accepted "
                                   "(PolygonPolicy::reject)",
                                   corners.size()));
  if (corners.size() > 3) mesh.polygons.emplace_back(mesh.elements.size(), corners.size() - 2);
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    mesh.elements.push_back({corners[0], corners[k], corners[k + 1]});
    mesh.element_offset.push_back(at);
  }
}

/// How a file numbers its vertices, so that messages quote the file's own numbers: OFF and PLY
/// count from 0, OBJ from 1; STL and Gmsh have no vertex numbers of their own (STL merges equal
/// corners, Gmsh names nodes by tag and checks those itself).
enum class VertexNumbering { zero_based, one_based, internal };

/// Checks every element's indices against the vertex count and rejects repeated corners,
/// naming the element's line or byte offset (not its position in the list, which after fan
/// triangulation is no number the file shows).
template <int d>
void check_elements(const Cursor& cursor, const RawMesh<d>& mesh, VertexNumbering numbering) {
  const auto nv = static_cast<std::int64_t>(mesh.vertices.size());
  const std::int64_t base = numbering == VertexNumbering::one_based ? 1 : 0;
  for (std::size_t t = 0; t < mesh.elements.size(); ++t) {
    const auto& e = mesh.elements[t];
    for (int k = 0; k <= d; ++k) {
      if (e[k] < 0 || e[k] >= nv)
        cursor.fail_at(mesh.element_offset[t],
                       fmt::format("element refers to vertex {}, but the file has {} vertices{}",
                                   e[k] + base, nv, base == 1 ? " (numbered from 1)" : ""));
      for (int j = 0; j < k; ++j)
        if (e[j] == e[k])
          cursor.fail_at(mesh.element_offset[t],
                         numbering == VertexNumbering::internal
                             ? std::string("element has two corners at the same point")
                             : fmt::format("element uses vertex {} twice", e[k] + base));
    }
  }
}

/// Narrows a 64-bit index from a file to plmap's Index, or marks it out of range (-1 is then
/// caught by check_elements).
inline Index narrow_index(std::int64_t i) {
  if (i < 0 || i > std::numeric_limits<Index>::max()) return -1;
  return static_cast<Index>(i);
}

// ---- the readers (one source file each) ----
RawMesh<2> parse_off(Cursor& cursor, const SurfaceReadOptions& options);
RawMesh<2> parse_obj(Cursor& cursor, const SurfaceReadOptions& options);
RawMesh<2> parse_stl(Cursor& cursor, const SurfaceReadOptions& options);
RawMesh<2> parse_ply(Cursor& cursor, const SurfaceReadOptions& options);
template <int d>
RawMesh<d> parse_gmsh(Cursor& cursor, const SurfaceReadOptions& options);
RawMesh<1> parse_curve_text(Cursor& cursor, const SurfaceReadOptions& options);

/// True if a file that starts like ASCII STL ("solid") is really binary STL: binary files may
/// start with "solid" too, but then their size matches the facet count in the header.
bool stl_is_binary(std::string_view data);

}  // namespace plmap::surface_io_detail
