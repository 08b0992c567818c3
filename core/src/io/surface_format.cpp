#include <plmap/core/io/surface_format.hpp>

#include <algorithm>
#include <cctype>
#include <string>

namespace plmap {

std::string_view format_name(SurfaceFormat format) {
  switch (format) {
    case SurfaceFormat::off: return "OFF";
    case SurfaceFormat::obj: return "OBJ";
    case SurfaceFormat::stl: return "STL";
    case SurfaceFormat::ply: return "PLY";
    case SurfaceFormat::gmsh: return "Gmsh MSH";
    case SurfaceFormat::curve: return "plmap curve";
  }
  return "unknown";
}

bool format_supports_dimension(SurfaceFormat format, int d) {
  switch (format) {
    case SurfaceFormat::gmsh: return d == 1 || d == 2;
    case SurfaceFormat::curve: return d == 1;
    default: return d == 2;
  }
}

std::optional<SurfaceFormat> format_from_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".off") return SurfaceFormat::off;
  if (ext == ".obj") return SurfaceFormat::obj;
  if (ext == ".stl") return SurfaceFormat::stl;
  if (ext == ".ply") return SurfaceFormat::ply;
  if (ext == ".msh") return SurfaceFormat::gmsh;
  if (ext == ".curve") return SurfaceFormat::curve;
  return std::nullopt;
}

std::optional<SurfaceFormat> format_from_content(std::string_view bytes) {
  // Skip leading blank lines and comments so "# exported by ...\nOFF" is recognised too.
  std::size_t i = 0;
  while (i < bytes.size()) {
    while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
    if (i < bytes.size() && bytes[i] == '#') {
      while (i < bytes.size() && bytes[i] != '\n') ++i;
      continue;
    }
    break;
  }
  const std::string_view head = bytes.substr(i);
  auto word_is = [&](std::string_view w) {
    return head.starts_with(w) &&
           (head.size() == w.size() || std::isspace(static_cast<unsigned char>(head[w.size()])));
  };
  if (bytes.starts_with("ply") && word_is("ply")) return SurfaceFormat::ply;
  if (head.starts_with("$MeshFormat")) return SurfaceFormat::gmsh;
  if (word_is("plmap-curve")) return SurfaceFormat::curve;
  for (std::string_view off : {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCOFF", "STNOFF", "STCNOFF"})
    if (word_is(off)) return SurfaceFormat::off;
  if (word_is("solid")) return SurfaceFormat::stl;
  if (word_is("v") || word_is("vn") || word_is("vt") || word_is("o") || word_is("g") ||
      word_is("mtllib"))
    return SurfaceFormat::obj;
  return std::nullopt;
}

}  // namespace plmap
