// Map provenance: its entries' syntax (map_provenance.hpp).

#include <plmap/core/errors.hpp>
#include <plmap/core/map_provenance.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace plmap {

bool is_provenance_token(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '!' && c <= '~'; });
}

void validate_provenance(const MapProvenance& provenance) {
  for (const auto& [key, value] : provenance) {
    if (!is_provenance_token(key))
      throw InvalidMapError(fmt::format("provenance key '{}' is not a single token of printable ASCII", key));
    if (!is_provenance_token(value))
      throw InvalidMapError(
          fmt::format("provenance entry '{}' has the value '{}', not a single token of printable ASCII", key, value));
  }
}

}  // namespace plmap
