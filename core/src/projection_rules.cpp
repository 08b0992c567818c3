// The acceptance rules of a projection, as a map's provenance records them (projection_rules.hpp).

#include "fnv1a.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/projection_rules.hpp>
#include <plmap/core/surface_fingerprint.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace plmap {
namespace {

// The keys, as docs/map-format.md lists them.
constexpr std::string_view made_by_project = "project";
constexpr std::string_view key_max_distance = "projection.max_distance";
constexpr std::string_view key_relative = "projection.max_distance_is_relative";
constexpr std::string_view key_allow_negative = "projection.allow_negative_distance";
constexpr std::string_view key_normal_check = "projection.normal_check";
constexpr std::string_view key_directions = "projection.directions";
constexpr std::string_view averaged_normals = "averaged-normals";
constexpr std::string_view given_prefix = "given:";

std::string_view boolean_text(bool b) { return b ? "true" : "false"; }

[[noreturn]] void unreadable(std::string_view key, std::string_view value, std::string_view expected) {
  throw InvalidMapError(fmt::format("provenance entry '{}' has the value '{}', expected {}", key, value, expected));
}

const std::string& entry(const MapProvenance& p, std::string_view key) {
  const auto it = p.find(key);
  if (it == p.end()) throw InvalidMapError(fmt::format("provenance of a projection map lacks the entry '{}'", key));
  return it->second;
}

bool boolean_entry(const MapProvenance& p, std::string_view key) {
  const std::string& value = entry(p, key);
  if (value == "true") return true;
  if (value == "false") return false;
  unreadable(key, value, "true or false");
}

}  // namespace

std::string_view to_string(NormalCheck check) {
  switch (check) {
    case NormalCheck::none: return "none";
    case NormalCheck::facing: return "facing";
    case NormalCheck::aligned: return "aligned";
  }
  return "none";
}

std::optional<NormalCheck> normal_check_from_name(std::string_view name) {
  for (const NormalCheck check : {NormalCheck::none, NormalCheck::facing, NormalCheck::aligned})
    if (to_string(check) == name) return check;
  return std::nullopt;
}

void record_projection_rules(const ProjectionRules& rules, MapProvenance& provenance) {
  provenance[std::string(provenance_made_by)] = made_by_project;
  // the shortest text that reads back as the same double ("inf" without a limit)
  provenance[std::string(key_max_distance)] = fmt::format("{}", rules.max_distance);
  provenance[std::string(key_relative)] = boolean_text(rules.max_distance_is_relative);
  provenance[std::string(key_allow_negative)] = boolean_text(rules.allow_negative_distance);
  provenance[std::string(key_normal_check)] = to_string(rules.normal_check);
  provenance[std::string(key_directions)] = directions_description(rules);
}

std::optional<ProjectionRules> recorded_projection_rules(const MapProvenance& provenance) {
  const auto made_by = provenance.find(provenance_made_by);
  if (made_by == provenance.end() || made_by->second != made_by_project) return std::nullopt;
  ProjectionRules rules;
  {
    const std::string& value = entry(provenance, key_max_distance);
    const char* end = value.data() + value.size();
    const auto [ptr, ec] = std::from_chars(value.data(), end, rules.max_distance);
    if (ec != std::errc() || ptr != end || !(rules.max_distance >= 0.0))
      unreadable(key_max_distance, value, "a number >= 0 or inf");
  }
  rules.max_distance_is_relative = boolean_entry(provenance, key_relative);
  rules.allow_negative_distance = boolean_entry(provenance, key_allow_negative);
  {
    const std::string& value = entry(provenance, key_normal_check);
    const std::optional<NormalCheck> check = normal_check_from_name(value);
    if (!check) unreadable(key_normal_check, value, "none, facing or aligned");
    rules.normal_check = *check;
  }
  const std::string& directions = entry(provenance, key_directions);
  if (directions != averaged_normals) {
    const std::string_view hex = std::string_view(directions).substr(std::min(directions.size(), given_prefix.size()));
    std::uint64_t fingerprint = 0;
    const auto [ptr, ec] = std::from_chars(hex.data(), hex.data() + hex.size(), fingerprint, 16);
    if (!directions.starts_with(given_prefix) || hex.size() != 16 || ec != std::errc() ||
        ptr != hex.data() + hex.size())
      unreadable(key_directions, directions, "averaged-normals or given: and 16 hex digits");
    rules.directions_fingerprint = fingerprint;
  }
  return rules;
}

std::uint64_t directions_fingerprint(std::span<const double> values, int per_direction) {
  if (per_direction < 1) throw Error(fmt::format("directions_fingerprint: {} values per direction", per_direction));
  detail::Fnv1a64 h;
  const std::uint64_t count = values.size();
  h.bytes(&count, sizeof count);
  const auto k = static_cast<std::size_t>(per_direction);
  for (std::size_t begin = 0; begin < values.size(); begin += k) {
    const std::span<const double> row = values.subspan(begin, std::min(k, values.size() - begin));
    double largest = 0.0;
    for (const double x : row) largest = std::max(largest, std::abs(x));
    // frexp gives largest = m 2^e with m in [0.5, 1); 2^(1 - e) brings it into [1, 2), exactly
    // (ldexp by an integer power of two does not round unless the result leaves the normal
    // range, which a row's smaller components may: they then round the same way for any row
    // that differs by a power of two from this one)
    int exponent = 0;
    if (std::isfinite(largest) && largest > 0.0) std::frexp(largest, &exponent);
    for (const double x : row) {
      const double scaled = std::ldexp(x, 1 - exponent);
      h.bytes(&scaled, sizeof scaled);
    }
  }
  return h.value();
}

std::string directions_description(const ProjectionRules& rules) {
  if (!rules.directions_fingerprint) return std::string(averaged_normals);
  return fmt::format("{}{}", given_prefix, fingerprint_hex(*rules.directions_fingerprint));
}

}  // namespace plmap
