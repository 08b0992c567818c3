// The binary map reader and writer on several threads (MapReadOptions::threads,
// MapWriteOptions::threads): the checksums in pieces, the two surfaces and the map's arrays side
// by side, the structural validation in pieces of elements. The map loaded, the file written and
// the error a damaged file gives must not depend on the thread count, and an error raised on a
// worker thread must reach the caller naming the file.

#include "io/binary_container.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/map_file_binary.hpp>
#include <plmap/core/map_validation.hpp>
#include <plmap/verify/generators/random_maps.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace plmap {
namespace {

template <int d>
std::string binary_bytes(const PlMap<d>& map, unsigned threads) {
  std::ostringstream out;
  MapWriteOptions options;
  options.threads = threads;
  write_binary_map(out, map, options);
  return std::move(out).str();
}

AnyPlMap parse_with(const std::string& bytes, unsigned threads, bool verify_checksums = true) {
  MapReadOptions options;
  options.threads = threads;
  options.verify_checksums = verify_checksums;
  return parse_map(bytes, "threads.plmapb", options);
}

/// The identity map of a jittered 80 x 80 grid: 12,800 elements, so that the validation has
/// several pieces of elements and the surfaces take long enough to overlap.
const PlMap<2>& grid_map() {
  static const std::shared_ptr<const PlMap<2>> map = [] {
    generators::Rng rng(7);
    generators::GridOptions grid;
    grid.cells = 80;
    grid.jitter = 0.1;
    auto surface = std::make_shared<const Surface<2>>(generators::grid_triangulation(grid, rng));
    return generators::identity_map<2>(surface).map;
  }();
  return *map;
}

template <int d>
void check_thread_counts_agree(const PlMap<d>& map) {
  const std::string bytes = binary_bytes(map, 1);
  for (const unsigned threads : {2u, 3u, 0u}) {
    RC_ASSERT(binary_bytes(map, threads) == bytes);
    const AnyPlMap loaded = parse_with(bytes, threads);
    RC_ASSERT(std::get<PlMap<d>>(loaded).data() == map.data());
  }
  RC_ASSERT(std::get<PlMap<d>>(parse_with(bytes, 1)).data() == map.data());
}

RC_GTEST_PROP(MapFileBinaryThreads, OverlaysLoadAndWriteTheSameOnEveryThreadCount, ()) {
  check_thread_counts_agree<2>(*(*rc::gen::scale(0.5, generators::overlay_maps<2>())).map);
}
RC_GTEST_PROP(MapFileBinaryThreads, CurveRefinementsLoadAndWriteTheSameOnEveryThreadCount, ()) {
  check_thread_counts_agree<1>(*(*generators::refinement_maps<1>()).map);
}

TEST(MapFileBinaryThreads, ALargeMapLoadsAndWritesTheSameOnEveryThreadCount) {
  const std::string bytes = binary_bytes(grid_map(), 1);
  for (const unsigned threads : {2u, 4u, 0u}) {
    EXPECT_EQ(binary_bytes(grid_map(), threads), bytes) << threads << " threads";
    EXPECT_EQ(std::get<PlMap<2>>(parse_with(bytes, threads)).data(), grid_map().data()) << threads << " threads";
  }
}

/// The parsing error's message, or "" if the bytes were accepted.
std::string error_of(const std::string& bytes, unsigned threads, bool verify_checksums) {
  try {
    parse_with(bytes, threads, verify_checksums);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(MapFileBinaryThreads, ADamagedFileGivesTheSameErrorOnEveryThreadCount) {
  // Damage in the surfaces, the map's arrays and behind the checksums (the decoders and the
  // validation, which run on worker threads): the caller gets the error, naming the file, and
  // the same one whatever the thread count.
  const std::string bytes = binary_bytes(grid_map(), 1);
  int refused = 0;
  for (const bool verify : {true, false}) {
    for (std::size_t at = 4096; at < bytes.size(); at += bytes.size() / 97) {
      std::string damaged = bytes;
      damaged[at] = static_cast<char>(damaged[at] ^ 0x41);
      const std::string sequential = error_of(damaged, 1, verify);
      if (!sequential.empty()) {
        ++refused;
        EXPECT_NE(sequential.find("threads.plmapb"), std::string::npos) << sequential;
      }
      for (const unsigned threads : {2u, 4u}) {
        EXPECT_EQ(error_of(damaged, threads, verify), sequential) << "flip at " << at << ", " << threads << " threads";
      }
    }
  }
  EXPECT_GT(refused, 100);
}

TEST(MapFileBinaryThreads, TwoDamagedArraysReportTheFirstInFileOrder) {
  // Every checksum is verified at once on several threads; the array named must be the first
  // damaged one in the file, as a reader going through the file would find.
  std::string bytes = binary_bytes(grid_map(), 1);
  bytes[bytes.size() - 200] ^= 0x10;  // the last arrays
  const binary::Container c(bytes, "x");
  const auto in_domain_vertices =
      static_cast<std::size_t>(c.array("domain_vertices").data - reinterpret_cast<const unsigned char*>(bytes.data()));
  bytes[in_domain_vertices + 5] ^= 0x10;
  for (const unsigned threads : {1u, 2u, 4u}) {
    const std::string error = error_of(bytes, threads, true);
    EXPECT_NE(error.find("array 'domain_vertices'"), std::string::npos) << error;
    EXPECT_NE(error.find("checksum mismatch"), std::string::npos) << error;
  }
}

TEST(MapFileBinaryThreads, ParallelChecksumsEqualZlibs) {
  std::mt19937_64 rng(3);
  std::vector<unsigned char> data((std::size_t{9} << 20) + 12345);
  for (auto& byte : data) byte = static_cast<unsigned char>(rng());
  const std::uint32_t expected = binary::crc32_of(data.data(), data.size());
  for (const unsigned threads : {1u, 2u, 4u}) {
    EXPECT_EQ(binary::crc32_parallel(data.data(), data.size(), threads), expected);
  }
  // Several ranges of which some span many pieces, one is empty.
  const std::vector<std::pair<const void*, std::size_t>> ranges = {
      {data.data(), 100}, {data.data() + 100, 0}, {data.data() + 100, data.size() - 200}, {data.data(), data.size()}};
  const std::vector<std::uint32_t> each = binary::crc32_of_each(ranges, 2);
  ASSERT_EQ(each.size(), ranges.size());
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    EXPECT_EQ(each[i], binary::crc32_of(ranges[i].first, ranges[i].second)) << "range " << i;
  }
}

TEST(MapFileBinaryThreads, ValidationNamesTheLowestDefectiveElementOnEveryThreadCount) {
  // Defects in two elements that fall in different pieces of the parallel validation (4096
  // elements each); the later piece may finish first, the error must still name the earlier.
  MapData<2> data = grid_map().data();
  const Index early = 5000, late = 11000;
  for (const Index t : {late, early}) {
    data.node_position[data.node_begin[t]].x() = std::numeric_limits<double>::quiet_NaN();
  }
  const PlMap<2> damaged(grid_map().domain_ptr(), grid_map().target_ptr(), data);
  for (const unsigned threads : {1u, 2u, 4u, 0u}) {
    try {
      validate_map_structure(damaged, threads);
      ADD_FAILURE() << "a NaN node position was accepted";
    } catch (const InvalidMapError& e) {
      EXPECT_NE(std::string(e.what()).find("at S1 element 5000:"), std::string::npos) << threads << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace plmap
