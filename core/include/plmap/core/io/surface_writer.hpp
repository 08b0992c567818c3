#pragma once
/// \file
/// Writing triangle surfaces (d = 2) and plane curves (d = 1) to files.
///
/// Files are written atomically (a temporary file in the same directory, renamed into place),
/// so an existing file is never left half-written. ASCII output prints every coordinate with
/// the shortest decimal form that reads back to the same double, so ASCII round trips are
/// exact. Binary STL stores single-precision floats: coordinates that are not floats are
/// rounded.

#include <plmap/core/io/surface_format.hpp>
#include <plmap/core/surface.hpp>

#include <filesystem>
#include <string>

namespace plmap {

struct SurfaceWriteOptions {
  Encoding encoding = Encoding::format_default;
  GmshVersion gmsh_version = GmshVersion::v4_1;
};

/// Writes `surface` to `path` in the format named by the extension. Throws plmap::Error naming
/// the file if the extension is unknown, the format cannot hold a surface of dimension d or the
/// requested encoding, or the file cannot be written.
template <int d>
  requires SurfaceDimension<d>
void write_surface(const std::filesystem::path& path, const Surface<d>& surface,
                   const SurfaceWriteOptions& options = {});

/// The bytes write_surface would write.
template <int d>
  requires SurfaceDimension<d>
std::string format_surface(const Surface<d>& surface, SurfaceFormat format,
                           const SurfaceWriteOptions& options = {});

extern template void write_surface<1>(const std::filesystem::path&, const Surface<1>&,
                                      const SurfaceWriteOptions&);
extern template void write_surface<2>(const std::filesystem::path&, const Surface<2>&,
                                      const SurfaceWriteOptions&);
extern template std::string format_surface<1>(const Surface<1>&, SurfaceFormat,
                                              const SurfaceWriteOptions&);
extern template std::string format_surface<2>(const Surface<2>&, SurfaceFormat,
                                              const SurfaceWriteOptions&);

}  // namespace plmap
