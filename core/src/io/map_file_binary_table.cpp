#include "map_file_binary_table.hpp"

#include "plmap/core/errors.hpp"
#include "plmap/core/surface_fingerprint.hpp"

#include <fmt/format.h>

namespace plmap::binary {

template <int d>
nlohmann::json map_table_header(const PlMap<d>& map) {
  nlohmann::json toc = {{"format", "plmap-map"},
                        {"dimension", d},
                        {"orientation", map.stored().orientation},
                        {"domain_fingerprint", fingerprint_hex(surface_fingerprint(map.domain()))},
                        {"target_fingerprint", fingerprint_hex(surface_fingerprint(map.target()))}};
  // Written only when there is one, so that a map without provenance gives the same bytes as
  // before the key existed.
  if (!map.provenance().empty()) toc["provenance"] = map.provenance();
  return toc;
}

MapTableHeader read_map_table_header(const nlohmann::json& toc, const std::string& file) {
  auto integer = [&](const char* key, int lo, int hi) {
    const auto it = toc.find(key);
    if (it == toc.end() || !it->is_number_integer() || *it < lo || *it > hi) {
      throw ParseError(file, "table of contents", fmt::format("'{}' is missing or not in [{}, {}]", key, lo, hi));
    }
    return it->get<int>();
  };
  const auto format = toc.find("format");
  if (format == toc.end() || *format != "plmap-map") {
    throw ParseError(file, "table of contents", "'format' is not \"plmap-map\"");
  }
  MapTableHeader h;
  h.dimension = integer("dimension", 1, 2);
  h.orientation = integer("orientation", -1, 1);
  if (h.orientation == 0) throw ParseError(file, "table of contents", "'orientation' must be 1 or -1");
  if (const auto p = toc.find("provenance"); p != toc.end()) {
    if (!p->is_object()) throw ParseError(file, "table of contents", "'provenance' is not an object");
    for (const auto& [key, value] : p->items()) {
      if (!value.is_string() || !is_provenance_token(key) || !is_provenance_token(value.get_ref<const std::string&>()))
        throw ParseError(file, "table of contents",
                         "a 'provenance' entry is not a pair of tokens of printable ASCII");
      h.provenance.emplace(key, value.get<std::string>());
    }
  }
  return h;
}

template nlohmann::json map_table_header<1>(const PlMap<1>&);
template nlohmann::json map_table_header<2>(const PlMap<2>&);

}  // namespace plmap::binary
