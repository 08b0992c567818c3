#include <plmap/core/io/surface_reader.hpp>

#include "polygon_triangulation.hpp"
#include "surface_parse_support.hpp"
#include "whole_file.hpp"

#include <optional>

namespace plmap {

namespace {

using namespace surface_io_detail;

/// Reads a decimal number at `at` in `text`, advancing `at` past it.
std::optional<std::size_t> number_at(std::string_view text, std::size_t& at) {
  std::size_t value = 0;
  const char* first = text.data() + at;
  const auto result = std::from_chars(first, text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr == first) return std::nullopt;
  at = static_cast<std::size_t>(result.ptr - text.data());
  return value;
}

/// Surface's message in the file's terms. Surface numbers elements in its own list, which after
/// polygons are split is no number the file shows; the reader knows where each element came
/// from. "element 12 is degenerate ..." becomes "file:line 40: this element is degenerate ...",
/// "elements 3 and 5 have ..." becomes "file:line 8: the elements at line 8 and line 10 have
/// ...". Messages that name no element keep their text after the file name.
std::string located_surface_message(const std::string& file, const Cursor& cursor,
                                    const std::vector<std::size_t>& offsets, std::string_view message) {
  const auto located = [&](std::size_t t) { return t < offsets.size(); };
  const auto is_polygon_piece = [&](std::size_t t) {
    return (t > 0 && offsets[t - 1] == offsets[t]) || (t + 1 < offsets.size() && offsets[t + 1] == offsets[t]);
  };
  if (message.starts_with("elements ")) {
    std::size_t at = 9;
    const auto a = number_at(message, at);
    if (a && located(*a) && message.substr(at).starts_with(" and ")) {
      at += 5;
      const auto b = number_at(message, at);
      if (b && located(*b)) {
        const std::string first = cursor.location(offsets[*a]);
        const std::string second = cursor.location(offsets[*b]);
        const std::string which = first == second ? fmt::format("two pieces of the polygon at {}", first)
                                                  : fmt::format("the elements at {} and {}", first, second);
        return fmt::format("{}:{}: {}{}", file, first, which, message.substr(at));
      }
    }
  } else if (message.starts_with("element ")) {
    std::size_t at = 8;
    const auto t = number_at(message, at);
    if (t && located(*t))
      return fmt::format("{}:{}: {}{}", file, cursor.location(offsets[*t]),
                         is_polygon_piece(*t) ? "a triangle of the polygon here" : "this element",
                         message.substr(at));
  }
  return fmt::format("{}: {}", file, message);
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
  if constexpr (d == 2)
    if (options.polygons == PolygonPolicy::triangulate) triangulate_polygons_in_their_planes(raw);
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
    throw InvalidSurfaceError(located_surface_message(file_name, cursor, offsets, e.what()));
  }
}

template <int d>
  requires SurfaceDimension<d>
Surface<d> read_surface(const std::filesystem::path& path, const SurfaceReadOptions& options) {
  const std::string name = path.string();
  const io_detail::FileBytes file = io_detail::read_whole_file(path);
  const std::string_view bytes = file.view();
  auto format = format_from_extension(path);
  if (!format) format = format_from_content(bytes.substr(0, 4096));
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
