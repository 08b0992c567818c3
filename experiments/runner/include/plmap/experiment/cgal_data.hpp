#pragma once
/// \file
/// Meshes of CGAL's example data set, as shipped by Debian's libcgal-demo package: a tarball
/// (/usr/share/doc/libcgal-demo/data.tar.gz) holding data/meshes/<name>.off. A mesh is extracted
/// on demand with tar into a cache directory.

#include <filesystem>
#include <string>
#include <vector>

namespace plmap::experiment {

/// The data tarball: $PLMAP_CGAL_DATA if set (a data.tar.gz or a directory holding
/// meshes/<name>.off), else libcgal-demo's. Empty if none exists.
std::filesystem::path cgal_data_location();

/// The path of mesh `name` (e.g. "femur"), extracted into `cache_directory` if it comes from the
/// tarball. Throws plmap::Error saying what is missing: the package (with the apt-get line) or
/// the mesh (with a few names that exist).
std::filesystem::path resolve_cgal_mesh(const std::string& name,
                                        const std::filesystem::path& cache_directory);

/// The names of the meshes in the data set (sorted); empty if the data set is missing.
std::vector<std::string> cgal_mesh_names();

}  // namespace plmap::experiment
