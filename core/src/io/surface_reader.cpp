#include <plmap/core/io/surface_reader.hpp>

#include "surface_parse_support.hpp"

#include <cerrno>
#include <fstream>
#include <sstream>
#include <system_error>

namespace plmap {

namespace {

using namespace surface_io_detail;

std::string read_whole_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int e = errno;
    throw ParseError(path.string(), "", "cannot open file: " +
                                            std::error_code(e, std::generic_category()).message());
  }
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw ParseError(path.string(), "", "read error");
  return std::move(content).str();
}

/// The element index that Surface's message is about ("element 12 ...", "elements 3 and 5
/// ..."), if it names one.
std::optional<std::size_t> element_named_in(std::string_view message) {
  std::size_t at = message.find("element");
  if (at == std::string_view::npos) return std::nullopt;
  at += 7;
  if (at < message.size() && message[at] == 's') ++at;
  if (at >= message.size() || message[at] != ' ') return std::nullopt;
  std::size_t value = 0;
  const char* first = message.data() + at + 1;
  const auto result = std::from_chars(first, message.data() + message.size(), value);
  if (result.ec != std::errc() || result.ptr == first) return std::nullopt;
  return value;
}

template <int d>
RawMesh<d> parse_raw(Cursor& cursor, SurfaceFormat format, const SurfaceReadOptions& options) {
  if constexpr (d == 2) {
    switch (format) {
      case SurfaceFormat::off: return parse_off(cursor, options);
      case SurfaceFormat::obj: return parse_obj(cursor, options);
      case SurfaceFormat::stl: return parse_stl(cursor, options);
      case SurfaceFormat::ply: return parse_ply(cursor, options);
      case SurfaceFormat::gmsh: return parse_gmsh<2>(cursor, options);
      default: break;
    }
  } else {
    switch (format) {
      case SurfaceFormat::gmsh: return parse_gmsh<1>(cursor, options);
      case SurfaceFormat::curve: return parse_curve_text(cursor, options);
      default: break;
    }
  }
  throw ParseError(cursor.file(), "",
                   fmt::format("the {} format holds {}, not {}", format_name(format),
                               d == 1 ? "triangle surfaces" : "curves",
                               d == 1 ? "curves" : "triangle surfaces"));
}

}  // namespace

template <int d>
  requires SurfaceDimension<d>
Surface<d> parse_surface(std::string_view bytes, SurfaceFormat format, const std::string& file_name,
                         const SurfaceReadOptions& options) {
  const bool text = format != SurfaceFormat::stl || !stl_is_binary(bytes);
  Cursor cursor(bytes, file_name, text);
  RawMesh<d> raw = parse_raw<d>(cursor, format, options);
  if (raw.elements.empty())
    throw ParseError(file_name, "",
                     format == SurfaceFormat::gmsh
                         ? fmt::format("the file has no {} elements (Gmsh type {})",
                                       d == 1 ? "line" : "triangle", d == 1 ? 1 : 2)
                         : fmt::format("the file has no {}", d == 1 ? "segments" : "triangles"));
  const std::vector<std::size_t> offsets = std::move(raw.element_offset);
  try {
    return Surface<d>(std::move(raw.vertices), std::move(raw.elements));
  } catch (const InvalidSurfaceError& e) {
    // Surface names the element; add where the file defines it.
    std::string prefix = file_name;
    if (const auto t = element_named_in(e.what()); t && *t < offsets.size())
      prefix += ":" + cursor.location(offsets[*t]);
    throw InvalidSurfaceError(prefix + ": " + e.what());
  }
}

template <int d>
  requires SurfaceDimension<d>
Surface<d> read_surface(const std::filesystem::path& path, const SurfaceReadOptions& options) {
  const std::string name = path.string();
  const std::string bytes = read_whole_file(path);
  auto format = format_from_extension(path);
  if (!format) format = format_from_content(std::string_view(bytes).substr(0, 4096));
  if (!format)
    throw ParseError(name, "",
                     "unknown surface format: use the extension .off, .obj, .stl, .ply, .msh or "
                     ".curve");
  return parse_surface<d>(bytes, *format, name, options);
}

template Surface<1> read_surface<1>(const std::filesystem::path&, const SurfaceReadOptions&);
template Surface<2> read_surface<2>(const std::filesystem::path&, const SurfaceReadOptions&);
template Surface<1> parse_surface<1>(std::string_view, SurfaceFormat, const std::string&,
                                     const SurfaceReadOptions&);
template Surface<2> parse_surface<2>(std::string_view, SurfaceFormat, const std::string&,
                                     const SurfaceReadOptions&);

}  // namespace plmap
