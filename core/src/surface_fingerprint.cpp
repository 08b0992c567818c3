#include "plmap/core/surface_fingerprint.hpp"

#include "fnv1a.hpp"

#include <fmt/format.h>

namespace plmap {

template <int d>
std::uint64_t surface_fingerprint(const Surface<d>& surface) {
  detail::Fnv1a64 h;
  const std::uint64_t counts[2] = {surface.vertices().size(), surface.elements().size()};
  h.bytes(counts, sizeof counts);
  static_assert(sizeof(WorldPoint<d>) == (d + 1) * sizeof(double));
  static_assert(sizeof(ElementCorners<d>) == (d + 1) * sizeof(Index));
  h.bytes(surface.vertices().data(), surface.vertices().size() * sizeof(WorldPoint<d>));
  h.bytes(surface.elements().data(), surface.elements().size() * sizeof(ElementCorners<d>));
  return h.value();
}

std::string fingerprint_hex(std::uint64_t fingerprint) { return fmt::format("{:016x}", fingerprint); }

template std::uint64_t surface_fingerprint<1>(const Surface<1>&);
template std::uint64_t surface_fingerprint<2>(const Surface<2>&);

}  // namespace plmap
