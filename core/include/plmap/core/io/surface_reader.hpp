#pragma once
/// \file
/// Reading triangle surfaces (d = 2) and plane curves (d = 1) from files.
///
/// Every reader raises ParseError (naming the file and the line, or the byte offset for binary
/// data) for input it cannot parse: malformed or truncated files, non-finite coordinates,
/// vertex indices out of range, elements that repeat a vertex. Counts announced in a header are
/// checked against the bytes that remain before anything is allocated, so a corrupted count
/// cannot cause a giant allocation. Surfaces that parse but violate Surface's rules (degenerate
/// or duplicate elements) raise InvalidSurfaceError whose message starts with the file name and
/// the element's line or byte offset. Non-manifold surfaces and surfaces with boundary load.

#include <plmap/core/io/surface_format.hpp>
#include <plmap/core/surface.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace plmap {

/// What to do with polygon faces (more than three corners) in OFF, OBJ and PLY files.
enum class PolygonPolicy {
  /// Triangles inside the polygon, seen along its Newell normal: the fan (0, k, k+1) from the
  /// first corner where that lies inside (every convex polygon), else ear clipping in the
  /// polygon's plane. A polygon with no ear there (not simple in its plane) keeps the fan.
  triangulate,
  fan_triangulate,  ///< always the fan (0, k, k+1); right for convex polygons, folds others
  reject,           ///< raise ParseError naming the face
};

struct SurfaceReadOptions {
  PolygonPolicy polygons = PolygonPolicy::triangulate;
};

/// Reads a surface of dimension d from `path`. The format comes from the extension, or from
/// the content when the extension is unknown.
template <int d>
  requires SurfaceDimension<d>
Surface<d> read_surface(const std::filesystem::path& path, const SurfaceReadOptions& options = {});

/// Parses a surface of dimension d from bytes already in memory; `file_name` is only used in
/// error messages.
template <int d>
  requires SurfaceDimension<d>
Surface<d> parse_surface(std::string_view bytes, SurfaceFormat format, const std::string& file_name,
                         const SurfaceReadOptions& options = {});

inline TriangleSurface read_triangle_surface(const std::filesystem::path& path,
                                             const SurfaceReadOptions& options = {}) {
  return read_surface<2>(path, options);
}

inline Curve read_curve(const std::filesystem::path& path, const SurfaceReadOptions& options = {}) {
  return read_surface<1>(path, options);
}

extern template Surface<1> read_surface<1>(const std::filesystem::path&,
                                           const SurfaceReadOptions&);
extern template Surface<2> read_surface<2>(const std::filesystem::path&,
                                           const SurfaceReadOptions&);
extern template Surface<1> parse_surface<1>(std::string_view, SurfaceFormat, const std::string&,
                                            const SurfaceReadOptions&);
extern template Surface<2> parse_surface<2>(std::string_view, SurfaceFormat, const std::string&,
                                            const SurfaceReadOptions&);

}  // namespace plmap
