#include "process.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/experiment/cgal_data.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <mutex>
#include <sstream>

namespace plmap::experiment {

namespace {
constexpr const char* mesh_folder = "data/meshes/";
}

std::filesystem::path cgal_data_location() {
  std::error_code ec;
  if (const char* env = std::getenv("PLMAP_CGAL_DATA"); env && *env) {
    const std::filesystem::path p = env;
    return std::filesystem::exists(p, ec) ? p : std::filesystem::path{};
  }
  for (const char* candidate : {"/usr/share/doc/libcgal-demo/data.tar.gz", "/usr/share/doc/libcgal-dev/data.tar.gz"})
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
  return {};
}

std::vector<std::string> cgal_mesh_names() {
  const auto location = cgal_data_location();
  if (location.empty()) return {};
  // Listing the tarball takes a few tenths of a second: once per location and process.
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::vector<std::string>> cache;
  std::lock_guard lock(mutex);
  if (auto it = cache.find(location); it != cache.end()) return it->second;
  std::vector<std::string> names;
  std::error_code ec;
  if (std::filesystem::is_directory(location, ec)) {
    for (const auto& entry : std::filesystem::directory_iterator(location / "meshes", ec))
      if (entry.path().extension() == ".off") names.push_back(entry.path().stem().string());
  } else {
    const auto listing = detail::run_process({"tar", "-tzf", location.string()});
    std::istringstream lines(listing.output);
    for (std::string line; std::getline(lines, line);)
      if (line.starts_with(mesh_folder) && line.ends_with(".off") && line.find('/', std::string(mesh_folder).size()) == std::string::npos)
        names.push_back(line.substr(std::string(mesh_folder).size(), line.size() - std::string(mesh_folder).size() - 4));
  }
  std::sort(names.begin(), names.end());
  cache[location] = names;
  return names;
}

std::filesystem::path resolve_cgal_mesh(const std::string& name, const std::filesystem::path& cache_directory) {
  const auto location = cgal_data_location();
  if (location.empty())
    throw Error(fmt::format("CGAL mesh \"{}\": the CGAL data set is missing; install Debian's libcgal-demo "
                            "(apt-get install libcgal-demo) or set PLMAP_CGAL_DATA",
                            name));
  std::error_code ec;
  if (std::filesystem::is_directory(location, ec)) {
    const auto path = location / "meshes" / (name + ".off");
    if (!std::filesystem::is_regular_file(path, ec))
      throw Error(fmt::format("CGAL mesh \"{}\": no file {}", name, path.string()));
    return path;
  }
  const std::string member = mesh_folder + name + ".off";
  const auto target = cache_directory / member;
  if (std::filesystem::is_regular_file(target, ec)) return target;
  std::filesystem::create_directories(cache_directory);
  const auto result =
      detail::run_process({"tar", "-xzf", location.string(), "-C", cache_directory.string(), member});
  if (result.exit_code != 0 || !std::filesystem::is_regular_file(target, ec))
    throw Error(fmt::format("CGAL mesh \"{}\": cannot extract {} from {}: {}", name, member, location.string(),
                            result.errors));
  return target;
}

}  // namespace plmap::experiment
