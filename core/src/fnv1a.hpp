#pragma once
// FNV-1a (64 bit), the hash of the fingerprints that map files record (surface_fingerprint.hpp,
// projection_rules.hpp). Private to core.

#include <bit>
#include <cstddef>
#include <cstdint>

namespace plmap::detail {

static_assert(std::endian::native == std::endian::little,
              "the fingerprints hash the in-memory bytes, which must be little-endian");

/// FNV-1a over 8-byte words would not be FNV-1a; the byte-wise loop is the documented hash and
/// runs at about 1 GB/s, i.e. milliseconds for the surfaces plmap handles.
class Fnv1a64 {
 public:
  void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::uint64_t h = hash_;
    for (std::size_t i = 0; i < size; ++i) {
      h ^= p[i];
      h *= 0x100000001b3ULL;
    }
    hash_ = h;
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

}  // namespace plmap::detail
