// libFuzzer target for one surface reader: the input is parsed as a file of the format named by
// PLMAP_FUZZ_FORMAT (a SurfaceFormat enumerator), as a triangle surface and as a curve where the
// format holds them. Bad input must end in a plmap::Error (ParseError, InvalidSurfaceError): a
// crash, a sanitizer report, a hang or any other exception is a bug.

#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_reader.hpp>

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace {

constexpr plmap::SurfaceFormat format = plmap::SurfaceFormat::PLMAP_FUZZ_FORMAT;

template <int d>
void parse_as(std::string_view bytes) {
  if (!plmap::format_supports_dimension(format, d)) return;
  try {
    const plmap::Surface<d> surface = plmap::parse_surface<d>(bytes, format, "fuzz-input");
    // What every command asks of a surface it has read.
    (void)surface.measure();
    (void)surface.max_edge_length();
  } catch (const plmap::Error&) {
    // refused with a message: the expected outcome for bad input
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  parse_as<2>(bytes);
  parse_as<1>(bytes);
  return 0;
}
