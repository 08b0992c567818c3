#pragma once
/// \file
/// Run-time choice of a point-location strategy by name (config files, the command line).
///
///   with_point_locator<2>("brown-faigle", [&](auto& locator) {
///     evaluate_batch(map, points, out, locator);
///   });
///
/// The callable is instantiated once per locator type, so the hot loop inside it runs with the
/// concrete type: the name is looked up once, never per query.

#include <plmap/strategies/point_location/bisection.hpp>
#include <plmap/strategies/point_location/brown_faigle_walk.hpp>
#include <plmap/strategies/point_location/brute_force.hpp>
#include <plmap/strategies/point_location/bucket_walk.hpp>
#include <plmap/strategies/point_location/cell_grid.hpp>
#include <plmap/strategies/point_location/straight_walk.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <type_traits>
#include <utility>

namespace plmap {

/// Settings the registry passes to the locators it creates.
struct PointLocatorOptions {
  /// Seed of randomized locators (brown-faigle). Copies made by evaluate_batch share it.
  std::uint64_t seed = point_location::BrownFaigleWalk::default_seed;
};

namespace detail {
inline constexpr std::array<std::string_view, 2> point_locator_names_1 = {"bisection",
                                                                           "brute-force"};
inline constexpr std::array<std::string_view, 5> point_locator_names_2 = {
    "brown-faigle", "cell-grid", "bucket-walk", "straight-walk", "brute-force"};

/// Throws plmap::Error naming `name` and listing the valid names for dimension d.
[[noreturn]] void throw_unknown_point_locator(std::string_view name, int d);
}  // namespace detail

/// The names with_point_locator<d> accepts; the first one is the default.
template <int d>
  requires SurfaceDimension<d>
constexpr std::span<const std::string_view> point_locator_names() {
  if constexpr (d == 1)
    return detail::point_locator_names_1;
  else
    return detail::point_locator_names_2;
}

/// The locator used when none is named: bisection (d = 1), brown-faigle (d = 2).
template <int d>
  requires SurfaceDimension<d>
constexpr std::string_view default_point_locator_name() {
  return point_locator_names<d>().front();
}

/// Calls f(locator) with a locator of the concrete type registered under `name` and returns
/// what f returns (f must return the same type for every locator). Unknown names throw
/// plmap::Error listing the valid ones.
template <int d, class F>
  requires SurfaceDimension<d>
decltype(auto) with_point_locator(std::string_view name, F&& f,
                                  const PointLocatorOptions& options = {}) {
  using namespace point_location;
  if (name == "brute-force") {
    BruteForce<d> locator;
    return std::invoke(std::forward<F>(f), locator);
  }
  if constexpr (d == 1) {
    if (name == "bisection") {
      Bisection locator;
      return std::invoke(std::forward<F>(f), locator);
    }
  } else {
    if (name == "brown-faigle") {
      BrownFaigleWalk locator(options.seed);
      return std::invoke(std::forward<F>(f), locator);
    }
    if (name == "bucket-walk") {
      BucketWalk locator(options.seed);
      return std::invoke(std::forward<F>(f), locator);
    }
    if (name == "cell-grid") {
      CellGridLocator locator;
      return std::invoke(std::forward<F>(f), locator);
    }
    if (name == "straight-walk") {
      StraightWalk locator;
      return std::invoke(std::forward<F>(f), locator);
    }
  }
  plmap::detail::throw_unknown_point_locator(name, d);
}

}  // namespace plmap
