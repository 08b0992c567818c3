#pragma once
/// \file
/// The acceptance rules of a normal projection: which hits of a ray along the direction field
/// count (docs/projection.md). `plmap::project` records the rules it was run with in the map it
/// returns (PlMap::provenance), and the ray check reads them back, so that a map is checked
/// under the rules it was made with unless the caller says otherwise. The rules live here,
/// below construct/ and verify/, because both sides must agree on how they are written.

#include <plmap/core/map_provenance.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace plmap {

/// Which S2 points may be the image of an S1 point, judged by the S2 vertex normal n2 at the
/// image against the projection direction nu at the preimage (paper section 3.2 compares n2 with
/// w = q - p; w = mu nu, and comparing nu itself keeps the test meaningful for mu = 0 (S1 = S2)
/// and for negative mu (penetrating contact)). ProjectionOptions::normal_check (as
/// TargetNormalCheck) and RayCheckOptions::normal_check (as RayNormalCheck) take it.
enum class NormalCheck {
  none,     ///< accept any orientation (default)
  facing,   ///< <nu, n2> < 0: the paper's check, for contact pairs whose normals face each other
  aligned,  ///< <nu, n2> > 0: both surfaces oriented the same way (offset or remeshed copies)
};

/// "none", "facing", "aligned": the names of the command line and of the recorded rules.
std::string_view to_string(NormalCheck check);
/// The check of that name, or nullopt.
std::optional<NormalCheck> normal_check_from_name(std::string_view name);

struct ProjectionRules {
  /// Largest |mu| of an accepted hit (infinity: no limit).
  double max_distance = std::numeric_limits<double>::infinity();
  /// max_distance is a multiple of the diagonal of S1's bounding box, not a length.
  bool max_distance_is_relative = false;
  /// Hits behind S1 (mu < 0) count too.
  bool allow_negative_distance = false;
  NormalCheck normal_check = NormalCheck::none;
  /// The fingerprint of the direction field given to the projection (directions_fingerprint),
  /// or nullopt for the default field, S1's averaged vertex normals.
  std::optional<std::uint64_t> directions_fingerprint;

  friend bool operator==(const ProjectionRules&, const ProjectionRules&) = default;
};

/// The provenance key that says which command made the map; record_projection_rules sets it to
/// "project".
inline constexpr std::string_view provenance_made_by = "made_by";

/// Writes the rules into `provenance` (keys "made_by" and "projection.*"; other keys stay).
void record_projection_rules(const ProjectionRules& rules, MapProvenance& provenance);

/// The rules recorded by record_projection_rules, or nullopt if `provenance` holds none (a map
/// not made by projection, or written before the rules were recorded). Throws InvalidMapError
/// naming the entry if one of the recorded values cannot be read.
std::optional<ProjectionRules> recorded_projection_rules(const MapProvenance& provenance);

/// FNV-1a (64 bit) over the IEEE-754 bytes of the direction values as the projection takes
/// them (`per_direction` = d+1 numbers per S1 vertex, vertex-major; ProjectionOptions::
/// directions), preceded by their count, each direction first scaled exactly by the power of two
/// that brings its largest |component| into [1, 2): directions are directions whatever their
/// length, and rows that differ by such a factor give the same fingerprint (other factors, whose
/// scaling rounds, do not).
std::uint64_t directions_fingerprint(std::span<const double> values, int per_direction);

/// "projection.directions" as recorded: "averaged-normals" or "given:" + 16 hex digits.
std::string directions_description(const ProjectionRules& rules);

}  // namespace plmap
