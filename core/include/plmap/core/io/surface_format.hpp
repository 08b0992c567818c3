#pragma once
/// \file
/// The surface file formats plmap reads and writes, and how a file's format is recognised.
/// See docs/surface-formats.md for what each reader accepts.

#include <filesystem>
#include <optional>
#include <string_view>

namespace plmap {

enum class SurfaceFormat {
  off,    ///< Object File Format (.off), triangle surfaces
  obj,    ///< Wavefront OBJ (.obj), triangle surfaces
  stl,    ///< STL, ASCII or binary (.stl), triangle surfaces
  ply,    ///< Stanford PLY, ASCII or binary either endianness (.ply), triangle surfaces
  gmsh,   ///< Gmsh MSH 2.2 or 4.1, ASCII or binary (.msh), triangle surfaces and curves
  curve,  ///< plmap's own curve text format (.curve), curves in the plane
};

/// Short human name ("OFF", "Gmsh MSH", ...), for messages.
std::string_view format_name(SurfaceFormat format);

/// True if the format can hold a surface of dimension d (1: curves, 2: triangle surfaces).
bool format_supports_dimension(SurfaceFormat format, int d);

/// The format named by the file's extension (case-insensitive), if any.
std::optional<SurfaceFormat> format_from_extension(const std::filesystem::path& path);

/// The format recognised from the first bytes of a file (magic words such as "ply",
/// "$MeshFormat", "OFF", "solid", "plmap-curve"), if any. Used when the extension is unknown.
std::optional<SurfaceFormat> format_from_content(std::string_view leading_bytes);

/// How a writer encodes numbers. `format_default` is binary for STL and PLY (little endian),
/// ASCII for the others.
enum class Encoding { format_default, ascii, binary, binary_big_endian };

/// Which Gmsh MSH version a writer produces.
enum class GmshVersion { v2_2, v4_1 };

}  // namespace plmap
