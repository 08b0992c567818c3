// libFuzzer target for the map loader (d = 1 and d = 2, chosen by the file's header). Bad input
// must end in a plmap::Error; a map that loads must save and load back to the same arrays (the
// exactness docs/map-format.md promises). Anything else is a bug.

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string_view>
#include <variant>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::optional<plmap::AnyPlMap> loaded;
  try {
    loaded.emplace(plmap::parse_map(bytes, "fuzz-input"));
  } catch (const plmap::Error&) {
    return 0;  // refused with a message
  }
  std::visit(
      [](const auto& map) {
        std::ostringstream saved;
        plmap::write_map(saved, map);
        const plmap::AnyPlMap again = plmap::parse_map(saved.str(), "fuzz-input (saved again)");
        using Map = std::decay_t<decltype(map)>;
        const auto* same = std::get_if<Map>(&again);
        if (same == nullptr || !(same->data() == map.data())) std::abort();
      },
      *loaded);
  return 0;
}
