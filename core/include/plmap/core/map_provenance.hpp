#pragma once
/// \file
/// How a map was made: a few key/value entries that travel with the map through both file
/// formats (docs/map-format.md), so that a later command can act on them without being told
/// again. normal projection records its acceptance rules here (projection_rules.hpp), which the
/// ray check (plmap::verify::check_against_rays) then applies by itself.

#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace plmap {

/// Keys and values are single tokens: non-empty, printable ASCII without blanks ('!' .. '~'),
/// so that the text map format stores an entry as one line "key value". Sorted by key.
using MapProvenance = std::map<std::string, std::string, std::less<>>;

/// Whether s is a valid key or value: non-empty, every character in '!' .. '~'.
bool is_provenance_token(std::string_view s);

/// Throws InvalidMapError naming the first entry whose key or value is not a provenance token.
void validate_provenance(const MapProvenance& provenance);

}  // namespace plmap
