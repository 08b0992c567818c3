#include "plmap/core/io/map_file.hpp"

#include "plmap/core/errors.hpp"
#include "plmap/core/io/atomic_file.hpp"
#include "plmap/core/io/map_file_binary.hpp"
#include "plmap/core/surface_fingerprint.hpp"
#include "plmap/core/io/surface_format.hpp"
#include "plmap/core/map_validation.hpp"

#include "whole_file.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <memory>
#include <limits>
#include <ostream>
#include <string>
#include <system_error>

namespace plmap {
namespace {

// ================================================================================================
// Writing
// ================================================================================================

constexpr std::string_view edge_kind_name(GraphEdgeKind kind) {
  return kind == GraphEdgeKind::target_edge ? "target_edge" : "closure";
}

/// Accumulates the file in memory and hands it to the stream in large pieces; formatting with
/// fmt is several times faster than operator<< for doubles and gives the shortest round-trip
/// representation.
class MapFileWriter {
 public:
  /// `records` is the number of end_line() calls the whole file makes, for progress.
  MapFileWriter(std::ostream& out, const ProgressCallback& progress, std::uint64_t records)
      : out_(out), progress_(progress), records_(records) {}
  MapFileWriter(const MapFileWriter&) = delete;
  MapFileWriter& operator=(const MapFileWriter&) = delete;

  void section(std::string_view name, std::size_t count) {
    fmt::format_to(std::back_inserter(buffer_), "{} {}\n", name, count);
  }
  void integer(long long value) { fmt::format_to(std::back_inserter(buffer_), "{}", value); }
  void text(std::string_view s) { buffer_.append(s.data(), s.data() + s.size()); }
  /// `array` and `index` name the value in the error raised when it is not finite.
  void real(double value, std::string_view array, std::size_t index) {
    if (!std::isfinite(value)) {
      throw InvalidMapError(fmt::format(
          "cannot save map: {}[{}] is not finite ({}); the map file stores finite numbers only",
          array, index, value));
    }
    fmt::format_to(std::back_inserter(buffer_), "{}", value);
  }
  void space() { buffer_.push_back(' '); }
  void end_line() {
    buffer_.push_back('\n');
    ++records_done_;
    if (buffer_.size() > (1u << 20)) flush();
  }
  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
    report_progress(progress_, "writing map", records_done_, records_);
  }

 private:
  std::ostream& out_;
  ProgressCallback progress_;
  std::uint64_t records_ = 0, records_done_ = 0;
  fmt::memory_buffer buffer_;
};

template <int d>
void write_surface(MapFileWriter& w, const Surface<d>& surface, std::string_view prefix) {
  const std::string vertices = fmt::format("{}_vertices", prefix);
  w.section(vertices, surface.vertices().size());
  for (std::size_t v = 0; v < surface.vertices().size(); ++v) {
    for (int i = 0; i <= d; ++i) {
      if (i > 0) w.space();
      w.real(surface.vertices()[v](i), vertices, v);
    }
    w.end_line();
  }
  w.section(fmt::format("{}_elements", prefix), surface.elements().size());
  for (const auto& corners : surface.elements()) {
    for (int i = 0; i <= d; ++i) {
      if (i > 0) w.space();
      w.integer(corners[i]);
    }
    w.end_line();
  }
}

void write_index_array(MapFileWriter& w, std::string_view name, const std::vector<Index>& values) {
  w.section(name, values.size());
  for (Index x : values) {
    w.integer(x);
    w.end_line();
  }
}

template <int d>
void write_map_data(MapFileWriter& w, const MapData<d>& m) {
  write_index_array(w, "node_begin", m.node_begin);

  // The per-node arrays are written as one record per node; their common length is the node
  // count (PlMap's constructor guarantees it).
  const std::size_t node_count = m.node_type.size();
  w.section("nodes", node_count);
  for (std::size_t n = 0; n < node_count; ++n) {
    w.text(to_string(m.node_type[n]));
    w.space();
    w.integer(m.node_location[n]);
    for (int i = 0; i < d; ++i) {
      w.space();
      w.real(m.node_position[n](i), "node_position", n);
    }
    w.space();
    w.integer(m.node_image_element[n]);
    for (int i = 0; i < d; ++i) {
      w.space();
      w.real(m.node_image_local[n](i), "node_image", n);
    }
    w.space();
    w.integer(m.node_target[n]);
    w.end_line();
  }

  write_index_array(w, "neighbor_begin", m.neighbor_begin);
  w.section("neighbors", m.neighbor.size());
  for (std::size_t i = 0; i < m.neighbor.size(); ++i) {
    w.integer(m.neighbor[i]);
    w.space();
    w.text(edge_kind_name(m.neighbor_edge_kind[i]));
    w.end_line();
  }

  write_index_array(w, "edge_node_begin", m.edge_node_begin);
  write_index_array(w, "edge_nodes", m.edge_node);

  write_index_array(w, "region_begin", m.region_begin);
  const std::size_t region_count = m.region_target.size();
  w.section("regions", region_count);
  for (std::size_t r = 0; r < region_count; ++r) {
    for (int i = 0; i <= d; ++i) {
      if (i > 0) w.space();
      w.integer(m.region_corners[r][i]);
    }
    for (int i = 0; i <= d; ++i) {
      w.space();
      w.integer(m.region_neighbors[r][i]);
    }
    w.space();
    w.integer(m.region_target[r]);
    // [A | b] row by row.
    for (int row = 0; row < d; ++row) {
      for (int col = 0; col <= d; ++col) {
        w.space();
        w.real(m.region_map[r](row, col), "region_map", r);
      }
    }
    w.end_line();
  }
  write_index_array(w, "start_region", m.start_region);
}

// ================================================================================================
// Reading
// ================================================================================================

/// Upper bound on the tokens of one record: a d = 2 region has 3 + 3 + 1 + 6 = 13.
constexpr std::size_t max_fields = 16;

struct Fields {
  std::array<std::string_view, max_fields> token;
  std::size_t count = 0;
};

/// A cursor over the lines of the file that knows where it is, so that every error can name the
/// file, the line and the section being read.
class MapFileReader {
 public:
  MapFileReader(std::string_view content, std::string file, const ProgressCallback& progress = {})
      : content_(content), file_(std::move(file)), progress_(progress) {}

  /// Reports the bytes parsed so far, and all of them at the end of the file.
  void report_done() const { report_progress(progress_, "reading map", position_, content_.size()); }

  [[noreturn]] void fail(const std::string& what) const {
    const std::string location =
        section_.empty() ? fmt::format("line {}", line_number_)
                         : fmt::format("line {} (section {})", line_number_, section_);
    throw ParseError(file_, location, what);
  }

  void enter_section(std::string_view name) { section_ = name; }

  /// Splits the next line into fields separated by spaces or tabs; expects exactly `expected`.
  Fields next_record(std::size_t expected) {
    const std::string_view line = next_line();
    Fields f;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i == line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
      if (f.count == max_fields || f.count == expected) {
        fail(fmt::format("expected {} field{}, found more", expected, expected == 1 ? "" : "s"));
      }
      f.token[f.count++] = line.substr(start, i - start);
    }
    if (f.count != expected) {
      fail(fmt::format("expected {} field{}, found {}", expected, expected == 1 ? "" : "s",
                       f.count));
    }
    return f;
  }

  /// Reads a line `<name> <count>` and checks the count against the bytes that remain: each
  /// record takes at least two bytes (one character and the newline), so a count larger than
  /// that is a corrupt file, and nothing is allocated for it.
  std::size_t section_header(std::string_view name) {
    section_ = name;
    const Fields f = next_record(2);
    if (f.token[0] != name) {
      fail(fmt::format("expected section '{}', found '{}'", name, f.token[0]));
    }
    const long long count = integer(f.token[1], 0, std::numeric_limits<Index>::max(), "count");
    const std::size_t remaining = content_.size() - position_;
    if (static_cast<unsigned long long>(count) > remaining / 2) {
      fail(fmt::format("count {} is larger than the rest of the file can hold", count));
    }
    return static_cast<std::size_t>(count);
  }

  long long integer(std::string_view token, long long min, long long max, std::string_view what) {
    long long value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error != std::errc() || end != token.data() + token.size()) {
      fail(fmt::format("{}: '{}' is not an integer", what, token));
    }
    if (value < min || value > max) {
      fail(fmt::format("{}: {} is outside [{}, {}]", what, value, min, max));
    }
    return value;
  }

  Index index(std::string_view token, std::string_view what) {
    return static_cast<Index>(integer(token, std::numeric_limits<Index>::min(),
                                      std::numeric_limits<Index>::max(), what));
  }

  double real(std::string_view token, std::string_view what) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value,
                                              std::chars_format::general);
    if (error != std::errc() || end != token.data() + token.size()) {
      fail(fmt::format("{}: '{}' is not a number", what, token));
    }
    if (!std::isfinite(value)) fail(fmt::format("{}: '{}' is not finite", what, token));
    return value;
  }

  void expect_end() {
    section_ = "end";
    const Fields f = next_record(1);
    if (f.token[0] != "end") fail(fmt::format("expected 'end', found '{}'", f.token[0]));
    while (position_ < content_.size()) {
      const std::string_view line = next_line();
      if (line.find_first_not_of(" \t") != std::string_view::npos) {
        fail("unexpected content after 'end'");
      }
    }
  }

  const std::string& file() const { return file_; }
  std::string_view content() const { return content_; }

 private:
  std::string_view next_line() {
    if (position_ >= content_.size()) {
      ++line_number_;
      fail("unexpected end of file");
    }
    const std::size_t newline = content_.find('\n', position_);
    const std::size_t end = newline == std::string_view::npos ? content_.size() : newline;
    std::string_view line = content_.substr(position_, end - position_);
    position_ = newline == std::string_view::npos ? content_.size() : newline + 1;
    ++line_number_;
    if ((line_number_ & 0xffff) == 0) report_done();
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // files edited on Windows
    return line;
  }

  std::string_view content_;
  std::string file_;
  ProgressCallback progress_;  // a copy: the reader may be built from a temporary
  std::size_t position_ = 0;
  long long line_number_ = 0;
  std::string_view section_;
};

struct Header {
  int dimension = 0;
  int orientation = 0;
  MapProvenance provenance;  // version 2 only
};

/// A surface file given where a map is expected is common enough to deserve its own message
/// (the field-count error it would otherwise get says nothing useful). The content decides; the
/// extension only when the content is not recognised (binary STL has no magic word).
void reject_surface_file(std::string_view content, const std::string& file) {
  if (content.starts_with(map_file_magic)) return;
  std::optional<SurfaceFormat> format = format_from_content(content.substr(0, 4096));
  const bool by_extension = !format;
  if (!format) format = format_from_extension(file);
  if (format) {
    throw ParseError(file, "",
                     fmt::format("this is a surface file ({}{}), not a map (.plmap); build a map "
                                 "from surfaces first",
                                 format_name(*format), by_extension ? " by its extension" : ""));
  }
}

Header read_header(MapFileReader& r) {
  reject_surface_file(r.content(), r.file());
  r.enter_section("header");
  Fields f = r.next_record(2);
  if (f.token[0] != map_file_magic) {
    r.fail(fmt::format("not a plmap map file (the first line must be '{} {}')", map_file_magic,
                       map_file_version));
  }
  const long long version = r.integer(f.token[1], 0, std::numeric_limits<int>::max(), "version");
  if (version != map_file_version && version != map_file_version_with_provenance) {
    r.fail(fmt::format("unsupported map file version {} (this build reads versions {} and {})", version,
                       map_file_version, map_file_version_with_provenance));
  }
  Header h;
  f = r.next_record(2);
  if (f.token[0] != "dimension") r.fail(fmt::format("expected 'dimension', found '{}'", f.token[0]));
  h.dimension = static_cast<int>(r.integer(f.token[1], 1, 2, "dimension"));
  f = r.next_record(2);
  if (f.token[0] != "orientation") {
    r.fail(fmt::format("expected 'orientation', found '{}'", f.token[0]));
  }
  h.orientation = static_cast<int>(r.integer(f.token[1], -1, 1, "orientation"));
  if (h.orientation == 0) r.fail("orientation must be 1 or -1");
  if (version == map_file_version_with_provenance) {
    const std::size_t entries = r.section_header("provenance");
    for (std::size_t i = 0; i < entries; ++i) {
      f = r.next_record(2);
      if (!is_provenance_token(f.token[0]) || !is_provenance_token(f.token[1]))
        r.fail("a provenance entry must be two tokens of printable ASCII");
      if (!h.provenance.emplace(std::string(f.token[0]), std::string(f.token[1])).second)
        r.fail(fmt::format("provenance entry '{}' appears twice", f.token[0]));
    }
  }
  return h;
}

template <int d>
std::shared_ptr<const Surface<d>> read_surface(MapFileReader& r, std::string_view prefix) {
  const std::string vertices_name = fmt::format("{}_vertices", prefix);
  const std::size_t vertex_count = r.section_header(vertices_name);
  std::vector<WorldPoint<d>> vertices(vertex_count);
  for (auto& x : vertices) {
    const Fields f = r.next_record(d + 1);
    for (int i = 0; i <= d; ++i) x(i) = r.real(f.token[i], "coordinate");
  }
  const std::string elements_name = fmt::format("{}_elements", prefix);
  const std::size_t element_count = r.section_header(elements_name);
  std::vector<ElementCorners<d>> elements(element_count);
  for (auto& corners : elements) {
    const Fields f = r.next_record(d + 1);
    for (int i = 0; i <= d; ++i) corners[i] = r.index(f.token[i], "vertex index");
  }
  try {
    return std::make_shared<const Surface<d>>(std::move(vertices), std::move(elements));
  } catch (const InvalidSurfaceError& e) {
    throw InvalidSurfaceError(fmt::format("{}: {} surface: {}", r.file(), prefix, e.what()));
  }
}

std::vector<Index> read_index_array(MapFileReader& r, std::string_view name) {
  const std::size_t count = r.section_header(name);
  std::vector<Index> values(count);
  for (Index& x : values) x = r.index(r.next_record(1).token[0], name);
  return values;
}

template <int d>
PlMap<d> read_map_body(MapFileReader& r, int orientation, MapProvenance provenance) {
  auto domain = read_surface<d>(r, "domain");
  auto target = read_surface<d>(r, "target");

  MapData<d> m;
  m.orientation = orientation;
  m.node_begin = read_index_array(r, "node_begin");

  const std::size_t node_count = r.section_header("nodes");
  m.node_type.resize(node_count);
  m.node_location.resize(node_count);
  m.node_position.resize(node_count);
  m.node_image_element.resize(node_count);
  m.node_image_local.resize(node_count);
  m.node_target.resize(node_count);
  for (std::size_t n = 0; n < node_count; ++n) {
    const Fields f = r.next_record(2 * d + 4);
    std::size_t k = 0;
    const auto type = node_type_from_string(f.token[k]);
    if (!type) r.fail(fmt::format("unknown node type '{}'", f.token[k]));
    m.node_type[n] = *type;
    ++k;
    m.node_location[n] = static_cast<std::int8_t>(r.integer(
        f.token[k++], std::numeric_limits<std::int8_t>::min(),
        std::numeric_limits<std::int8_t>::max(), "node location"));
    for (int i = 0; i < d; ++i) m.node_position[n](i) = r.real(f.token[k++], "node position");
    m.node_image_element[n] = r.index(f.token[k++], "image element");
    for (int i = 0; i < d; ++i) m.node_image_local[n](i) = r.real(f.token[k++], "image local");
    m.node_target[n] = r.index(f.token[k++], "node target");
  }

  m.neighbor_begin = read_index_array(r, "neighbor_begin");
  const std::size_t neighbor_count = r.section_header("neighbors");
  m.neighbor.resize(neighbor_count);
  m.neighbor_edge_kind.resize(neighbor_count);
  for (std::size_t i = 0; i < neighbor_count; ++i) {
    const Fields f = r.next_record(2);
    m.neighbor[i] = r.index(f.token[0], "neighbor");
    if (f.token[1] == "target_edge") {
      m.neighbor_edge_kind[i] = GraphEdgeKind::target_edge;
    } else if (f.token[1] == "closure") {
      m.neighbor_edge_kind[i] = GraphEdgeKind::closure;
    } else {
      r.fail(fmt::format("unknown edge kind '{}' (expected target_edge or closure)", f.token[1]));
    }
  }

  m.edge_node_begin = read_index_array(r, "edge_node_begin");
  m.edge_node = read_index_array(r, "edge_nodes");

  m.region_begin = read_index_array(r, "region_begin");
  const std::size_t region_count = r.section_header("regions");
  m.region_corners.resize(region_count);
  m.region_neighbors.resize(region_count);
  m.region_target.resize(region_count);
  m.region_map.resize(region_count);
  for (std::size_t q = 0; q < region_count; ++q) {
    const Fields f = r.next_record(2 * (d + 1) + 1 + d * (d + 1));
    std::size_t k = 0;
    for (int i = 0; i <= d; ++i) m.region_corners[q][i] = r.index(f.token[k++], "region corner");
    for (int i = 0; i <= d; ++i) {
      m.region_neighbors[q][i] = r.index(f.token[k++], "region neighbor");
    }
    m.region_target[q] = r.index(f.token[k++], "region target");
    for (int row = 0; row < d; ++row) {
      for (int col = 0; col <= d; ++col) {
        m.region_map[q](row, col) = r.real(f.token[k++], "region map");
      }
    }
  }
  m.start_region = read_index_array(r, "start_region");
  r.expect_end();
  r.report_done();

  // A file is untrusted input: beyond the constructor's index ranges, everything the queries
  // rely on is validated, so that a map that loads is safe for every command.
  try {
    PlMap<d> map(std::move(domain), std::move(target), std::move(m));
    validate_map_structure(map);
    map.set_provenance(std::move(provenance));
    return map;
  } catch (const InvalidMapError& e) {
    throw InvalidMapError(fmt::format("{}: {}", r.file(), e.what()));
  }
}

using io_detail::FileBytes;
using io_detail::read_whole_file;

template <int d>
PlMap<d> of_dimension(AnyPlMap&& any, const std::string& file) {
  if (auto* map = std::get_if<PlMap<d>>(&any)) return std::move(*map);
  throw ParseError(file, "", fmt::format("the map has dimension {}, expected {}", 3 - d, d));
}

/// The number of records (lines ended by end_line) write_map writes for `map`.
template <int d>
std::uint64_t record_count(const PlMap<d>& map) {
  const MapData<d>& m = map.data();
  std::uint64_t n = 0;
  for (const Surface<d>* s : {&map.domain(), &map.target()}) n += s->vertices().size() + s->elements().size();
  for (const std::vector<Index>* a : {&m.node_begin, &m.neighbor_begin, &m.edge_node_begin, &m.edge_node,
                                      &m.region_begin, &m.start_region})
    n += a->size();
  return n + m.node_type.size() + m.neighbor.size() + m.region_target.size();
}

}  // namespace

template <int d>
void write_map(std::ostream& out, const PlMap<d>& map, const ProgressCallback& progress) {
  MapFileWriter w(out, progress, record_count(map));
  // Version 1 where there is no provenance, so that older readers still read such maps.
  const MapProvenance& provenance = map.provenance();
  w.text(fmt::format("{} {}\ndimension {}\norientation {}\n", map_file_magic,
                     provenance.empty() ? map_file_version : map_file_version_with_provenance, d,
                     map.data().orientation));
  if (!provenance.empty()) {
    w.text(fmt::format("provenance {}\n", provenance.size()));
    for (const auto& [key, value] : provenance) w.text(fmt::format("{} {}\n", key, value));
  }
  write_surface(w, map.domain(), "domain");
  write_surface(w, map.target(), "target");
  write_map_data(w, map.data());
  w.text("end\n");
  w.flush();
}

template <int d>
void save_map(const std::filesystem::path& path, const PlMap<d>& map, const MapWriteOptions& options) {
  if (has_binary_map_extension(path)) {
    write_file_atomically(path, [&](std::ostream& out) { write_binary_map(out, map, options); }, true);
    return;
  }
  write_file_atomically(path, [&](std::ostream& out) { write_map(out, map, options.progress); }, true);
}

template <int d>
void save_map(const std::filesystem::path& path, const PlMap<d>& map, const ProgressCallback& progress) {
  save_map(path, map, MapWriteOptions{progress});
}

AnyPlMap parse_map(std::string_view content, const std::string& source_name) {
  return parse_map(content, source_name, MapReadOptions{});
}

AnyPlMap parse_map(std::string_view content, const std::string& source_name, const MapReadOptions& options) {
  if (looks_like_binary_map(content)) return parse_binary_map(content, source_name, options);
  MapFileReader r(content, source_name, options.progress);
  const Header h = read_header(r);
  if (h.dimension == 1) return read_map_body<1>(r, h.orientation, h.provenance);
  return read_map_body<2>(r, h.orientation, h.provenance);
}

AnyPlMap load_map(const std::filesystem::path& path, const MapReadOptions& options) {
  const FileBytes bytes = read_whole_file(path);
  return parse_map(bytes.view(), path.string(), options);
}

AnyPlMap load_map(const std::filesystem::path& path, const ProgressCallback& progress) {
  return load_map(path, MapReadOptions{.progress = progress});
}

template <int d>
PlMap<d> load_map(const std::filesystem::path& path, const ProgressCallback& progress) {
  return load_map<d>(path, MapReadOptions{.progress = progress});
}

template <int d>
PlMap<d> load_map(const std::filesystem::path& path, const MapReadOptions& options) {
  const FileBytes bytes = read_whole_file(path);
  if (looks_like_binary_map(bytes.view())) {
    return of_dimension<d>(parse_binary_map(bytes.view(), path.string(), options), path.string());
  }
  MapFileReader r(bytes.view(), path.string(), options.progress);
  const Header h = read_header(r);
  if (h.dimension != d) {
    throw ParseError(path.string(), "line 2",
                     fmt::format("the map has dimension {}, expected {}", h.dimension, d));
  }
  return read_map_body<d>(r, h.orientation, h.provenance);
}

template <int d>
PlMap<d> load_map(const std::filesystem::path& path, std::shared_ptr<const Surface<d>> domain,
                  std::shared_ptr<const Surface<d>> target, const MapReadOptions& options) {
  PlMap<d> map = load_map<d>(path, options);
  auto refuse_if_other = [&](const Surface<d>& stored, const Surface<d>& given, const char* which) {
    const std::uint64_t a = surface_fingerprint(stored), b = surface_fingerprint(given);
    if (a != b) {
      throw ParseError(path.string(), "",
                       fmt::format("the map was built for another {} surface (fingerprint {}, the given "
                                   "surface has {}: {} vs {} vertices, {} vs {} elements)",
                                   which, fingerprint_hex(a), fingerprint_hex(b), stored.vertices().size(),
                                   given.vertices().size(), stored.elements().size(),
                                   given.elements().size()));
    }
  };
  refuse_if_other(map.domain(), *domain, "domain (S1)");
  refuse_if_other(map.target(), *target, "target (S2)");
  MapProvenance provenance = map.provenance();
  PlMap<d> result(std::move(domain), std::move(target), std::move(map).release_data());
  result.set_provenance(std::move(provenance));
  return result;
}

int map_file_dimension(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw ParseError(path.string(), "",
                     fmt::format("cannot open: {}",
                                 std::error_code(errno, std::generic_category()).message()));
  }
  // The header is three short lines; 256 bytes is plenty and keeps the peek cheap for big maps.
  std::string head(256, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (looks_like_binary_map(head)) return binary_map_file_dimension(path);
  MapFileReader r(head, path.string());
  return read_header(r).dimension;
}

template void write_map<1>(std::ostream&, const PlMap<1>&, const ProgressCallback&);
template void write_map<2>(std::ostream&, const PlMap<2>&, const ProgressCallback&);
template void save_map<1>(const std::filesystem::path&, const PlMap<1>&, const MapWriteOptions&);
template void save_map<2>(const std::filesystem::path&, const PlMap<2>&, const MapWriteOptions&);
template void save_map<1>(const std::filesystem::path&, const PlMap<1>&, const ProgressCallback&);
template void save_map<2>(const std::filesystem::path&, const PlMap<2>&, const ProgressCallback&);
template PlMap<1> load_map<1>(const std::filesystem::path&, const MapReadOptions&);
template PlMap<2> load_map<2>(const std::filesystem::path&, const MapReadOptions&);
template PlMap<1> load_map<1>(const std::filesystem::path&, const ProgressCallback&);
template PlMap<2> load_map<2>(const std::filesystem::path&, const ProgressCallback&);
template PlMap<1> load_map<1>(const std::filesystem::path&, std::shared_ptr<const Surface<1>>,
                              std::shared_ptr<const Surface<1>>, const MapReadOptions&);
template PlMap<2> load_map<2>(const std::filesystem::path&, std::shared_ptr<const Surface<2>>,
                              std::shared_ptr<const Surface<2>>, const MapReadOptions&);

}  // namespace plmap
