// libFuzzer target for the binary map loader (.plmapb, d = 1 and 2). The checksums would refuse
// almost every mutation before the decoders see it, so each input is parsed twice: with the
// checksums off (the decoders, the local-index and count decoding, the surfaces and the
// structural validation must be safe on their own) and on. Bad input must end in a plmap::Error;
// a map that loads must save and load back to the same arrays. Anything else is a bug.

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/map_file_binary.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string_view>
#include <variant>

namespace {

void round_trip(const plmap::AnyPlMap& loaded) {
  std::visit(
      [](const auto& map) {
        std::ostringstream saved;
        plmap::write_binary_map(saved, map);
        const plmap::AnyPlMap again = plmap::parse_binary_map(saved.str(), "fuzz-input (saved again)");
        using Map = std::decay_t<decltype(map)>;
        const auto* same = std::get_if<Map>(&again);
        if (same == nullptr || !(same->data() == map.data())) std::abort();
      },
      loaded);
}

void parse(std::string_view bytes, bool verify_checksums) {
  plmap::MapReadOptions options;
  options.verify_checksums = verify_checksums;
  std::optional<plmap::AnyPlMap> loaded;
  try {
    loaded.emplace(plmap::parse_binary_map(bytes, "fuzz-input", options));
  } catch (const plmap::Error&) {
    return;  // refused with a message
  }
  round_trip(*loaded);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  parse(bytes, false);
  parse(bytes, true);
  return 0;
}
