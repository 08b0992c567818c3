#pragma once
// Internal: loading the surfaces of [[inputs]] (files, CGAL meshes, generators), cached per
// experiment so that a sweep over pipeline parameters loads each input once.

#include <plmap/core/surface.hpp>
#include <plmap/experiment/config.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace plmap::experiment::detail {

class InputCache {
 public:
  InputCache(const ExperimentConfig& config, std::filesystem::path cgal_cache)
      : config_(config), cgal_cache_(std::move(cgal_cache)) {}

  /// The surface of input `index` with resolved parameters `parameters`.
  template <int d>
  std::shared_ptr<const Surface<d>> surface(int index, const ParameterSet& parameters);
  /// A mesh of the CGAL data set by name, extracted into the cache if needed.
  std::filesystem::path cgal_mesh(const std::string& name);

 private:
  const ExperimentConfig& config_;
  std::filesystem::path cgal_cache_;
  std::map<std::string, std::shared_ptr<const Surface<1>>> curves_;
  std::map<std::string, std::shared_ptr<const Surface<2>>> surfaces_;
};

}  // namespace plmap::experiment::detail
