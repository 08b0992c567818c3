// libFuzzer target for what the commands do with a map file: the input is parsed as a .plmap
// file and, if it loads, every command runs on it (exercise_map.hpp). A map the loader accepts
// must be safe for all of them: they may throw a plmap::Error, nothing else.

#include "exercise_map.hpp"

#include <plmap/core/io/map_file.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <variant>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    std::visit([](const auto& map) { plmap::fuzz::exercise_map(map); },
               plmap::parse_map(bytes, "fuzz-input"));
  } catch (const plmap::Error&) {
    // refused with a message
  }
  return 0;
}
