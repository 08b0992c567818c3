#pragma once
/// \file
/// A fingerprint of a surface: a 64-bit hash of its vertex coordinates and elements, so that a map
/// file can record which surfaces it was built for and a loader can refuse a map given with other
/// surfaces (load_map(path, s1, s2) in io/map_file.hpp).
///
/// The hash is FNV-1a (64 bit) over the little-endian bytes of: the vertex count and element
/// count (as 64-bit integers), every vertex coordinate (IEEE-754 doubles, vertex by vertex) and
/// every element's corner indices (32-bit integers). Two surfaces with the same fingerprint are
/// equal up to hash collisions (one in 2^64 for unrelated surfaces); any change of a coordinate
/// bit, an index or the order changes it. It is written as 16 lower-case hex digits.

#include <plmap/core/surface.hpp>

#include <cstdint>
#include <string>

namespace plmap {

template <int d>
std::uint64_t surface_fingerprint(const Surface<d>& surface);

/// 16 lower-case hex digits, as stored in map files.
std::string fingerprint_hex(std::uint64_t fingerprint);

}  // namespace plmap
