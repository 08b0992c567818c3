#include <plmap/core/errors.hpp>
#include <plmap/strategies/point_locator_registry.hpp>

#include <string>

namespace plmap::detail {

void throw_unknown_point_locator(std::string_view name, int d) {
  const auto names = d == 1 ? point_locator_names<1>() : point_locator_names<2>();
  std::string valid;
  for (const auto n : names) {
    if (!valid.empty()) valid += ", ";
    valid += n;
  }
  throw Error("unknown point locator '" + std::string(name) + "' for " +
              (d == 1 ? "curves (d = 1)" : "triangle surfaces (d = 2)") + "; valid names: " + valid);
}

}  // namespace plmap::detail
