// Fuzz-style robustness test of every surface reader: valid files are truncated at every length
// and mutated with seeded random byte edits; each read must either raise a plmap error that
// names the file or return a valid surface. Runs under AddressSanitizer in CI, so any
// out-of-bounds access, giant allocation or crash shows up here.
#include "test_surface_io_samples.hpp"

#include <plmap/core/errors.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

using namespace plmap;
using namespace plmap::surface_io_test;

namespace {

struct Seed {
  std::string name;
  SurfaceFormat format;
  int dimension;
  std::string bytes;
};

std::vector<Seed> seeds() {
  std::vector<Seed> out;
  const std::vector<std::tuple<std::string, SurfaceFormat, SurfaceWriteOptions>> triangle_writers = {
      {"w.off", SurfaceFormat::off, {}},
      {"w.obj", SurfaceFormat::obj, {}},
      {"ascii.stl", SurfaceFormat::stl, {Encoding::ascii, GmshVersion::v4_1}},
      {"binary.stl", SurfaceFormat::stl, {Encoding::binary, GmshVersion::v4_1}},
      {"ascii.ply", SurfaceFormat::ply, {Encoding::ascii, GmshVersion::v4_1}},
      {"little.ply", SurfaceFormat::ply, {Encoding::binary, GmshVersion::v4_1}},
      {"big.ply", SurfaceFormat::ply, {Encoding::binary_big_endian, GmshVersion::v4_1}},
      {"v2.msh", SurfaceFormat::gmsh, {Encoding::ascii, GmshVersion::v2_2}},
      {"v2b.msh", SurfaceFormat::gmsh, {Encoding::binary, GmshVersion::v2_2}},
      {"v4.msh", SurfaceFormat::gmsh, {Encoding::ascii, GmshVersion::v4_1}},
      {"v4b.msh", SurfaceFormat::gmsh, {Encoding::binary, GmshVersion::v4_1}},
  };
  for (const auto& [name, format, options] : triangle_writers)
    out.push_back({name, format, 2, format_surface(tetrahedron(), format, options)});
  const std::vector<std::tuple<std::string, SurfaceWriteOptions>> curve_writers = {
      {"w.curve", {}},
      {"cv2.msh", {Encoding::ascii, GmshVersion::v2_2}},
      {"cv2b.msh", {Encoding::binary, GmshVersion::v2_2}},
      {"cv4.msh", {Encoding::ascii, GmshVersion::v4_1}},
      {"cv4b.msh", {Encoding::binary, GmshVersion::v4_1}},
  };
  for (const auto& [name, options] : curve_writers)
    out.push_back({name, format_from_extension(name).value(), 1, format_surface(polyline(), *format_from_extension(name), options)});
  out.push_back({"hand.off", SurfaceFormat::off, 2, off_quad_with_comments});
  out.push_back({"hand.obj", SurfaceFormat::obj, 2, obj_mixed_corners});
  out.push_back({"hand.stl", SurfaceFormat::stl, 2, stl_ascii_square});
  out.push_back({"hand.ply", SurfaceFormat::ply, 2, ply_ascii_with_extras});
  out.push_back({"hand2.msh", SurfaceFormat::gmsh, 2, gmsh_v2_mixed});
  out.push_back({"hand41.msh", SurfaceFormat::gmsh, 2, gmsh_v41_blocks});
  out.push_back({"hand2c.msh", SurfaceFormat::gmsh, 1, gmsh_v2_mixed});
  out.push_back({"hand41c.msh", SurfaceFormat::gmsh, 1, gmsh_v41_blocks});
  out.push_back({"hand.curve", SurfaceFormat::curve, 1, curve_text_triangle});
  return out;
}

enum class Outcome { surface, plmap_error };

template <int d>
Outcome read_once(const Seed& seed, const std::string& bytes) {
  try {
    const Surface<d> s = parse_surface<d>(bytes, seed.format, seed.name);
    // What the reader returns must be a surface Surface accepted: finite vertices and
    // elements with in-range corners.
    EXPECT_GT(s.element_count(), 0);
    for (const auto& p : s.vertices()) EXPECT_TRUE(p.allFinite());
    for (const auto& e : s.elements())
      for (Index v : e) EXPECT_TRUE(v >= 0 && v < s.vertex_count());
    return Outcome::surface;
  } catch (const ParseError& e) {
    EXPECT_EQ(e.file(), seed.name);
    return Outcome::plmap_error;
  } catch (const InvalidSurfaceError& e) {
    EXPECT_TRUE(std::string_view(e.what()).starts_with(seed.name)) << e.what();
    return Outcome::plmap_error;
  }
  // Anything else (std::bad_alloc, std::length_error, ...) escapes and fails the test.
}

Outcome read_any(const Seed& seed, const std::string& bytes) {
  return seed.dimension == 1 ? read_once<1>(seed, bytes) : read_once<2>(seed, bytes);
}

/// One random edit: overwrite, insert or delete bytes, biased towards characters that matter
/// to the parsers (digits, signs, separators, huge numbers).
void mutate(std::string& bytes, std::mt19937& rng) {
  static const std::vector<std::string> interesting = {
      "0", "1", "9", "-", "-1", " ", "\n", "#", "/", ".", "e", "nan", "inf", "99999999999",
      "4294967295", "2147483648", "\xff", std::string(1, '\0'), "$", "$EndNodes", "end_header"};
  const auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n)(rng); };
  const std::size_t at = bytes.empty() ? 0 : pick(bytes.size() - 1);
  switch (pick(5)) {
    case 0:
      if (!bytes.empty()) bytes[at] = static_cast<char>(pick(255));
      break;
    case 1:
      if (!bytes.empty()) bytes[at] = static_cast<char>(bytes[at] ^ (1 << pick(7)));
      break;
    case 2: bytes.insert(at, interesting[pick(interesting.size() - 1)]); break;
    case 3:
      if (!bytes.empty()) bytes.erase(at, 1 + pick(std::min<std::size_t>(8, bytes.size() - at - 1)));
      break;
    case 4: {
      const std::string& s = interesting[pick(interesting.size() - 1)];
      if (at + s.size() <= bytes.size()) bytes.replace(at, s.size(), s);
      break;
    }
    default: {  // duplicate a short range (repeated records, repeated headers)
      const std::size_t len = std::min<std::size_t>(pick(16), bytes.size() - at);
      bytes.insert(at, bytes.substr(at, len));
      break;
    }
  }
}

TEST(SurfaceIoFuzz, EverySeedReadsBackUnchanged) {
  for (const Seed& seed : seeds()) {
    SCOPED_TRACE(seed.name);
    EXPECT_EQ(read_any(seed, seed.bytes), Outcome::surface);
  }
}

TEST(SurfaceIoFuzz, TruncatedFilesRaiseErrorsOrReadAsSurfaces) {
  for (const Seed& seed : seeds()) {
    SCOPED_TRACE(seed.name);
    int errors = 0;
    // Every length for small files; for larger ones a stride keeps the test to seconds.
    const std::size_t stride = std::max<std::size_t>(1, seed.bytes.size() / 400);
    for (std::size_t length = 0; length < seed.bytes.size(); length += stride)
      errors += read_any(seed, seed.bytes.substr(0, length)) == Outcome::plmap_error;
    EXPECT_GT(errors, 0);  // the empty file, at least, is an error
  }
}

/// A longer exploration: PLMAP_SURFACE_FUZZ_MUTANTS=100000 PLMAP_SURFACE_FUZZ_SEED=7.
long environment_number(const char* name, long fallback) {
  const char* value = std::getenv(name);
  return value ? std::strtol(value, nullptr, 10) : fallback;
}

TEST(SurfaceIoFuzz, RandomlyMutatedFilesRaiseErrorsOrReadAsSurfaces) {
  std::mt19937 rng(static_cast<std::mt19937::result_type>(
      environment_number("PLMAP_SURFACE_FUZZ_SEED", 20261122)));
  const long mutants_per_seed = environment_number("PLMAP_SURFACE_FUZZ_MUTANTS", 400);
  for (const Seed& seed : seeds()) {
    SCOPED_TRACE(seed.name);
    int errors = 0, surfaces = 0;
    for (long i = 0; i < mutants_per_seed; ++i) {
      std::string bytes = seed.bytes;
      const int edits = 1 + static_cast<int>(rng() % 3);
      for (int k = 0; k < edits; ++k) mutate(bytes, rng);
      (read_any(seed, bytes) == Outcome::surface ? surfaces : errors)++;
    }
    // Both outcomes occur: the mutations neither always break nor never break the file.
    EXPECT_GT(errors, 0);
    EXPECT_GT(surfaces, 0);
  }
}

}  // namespace
