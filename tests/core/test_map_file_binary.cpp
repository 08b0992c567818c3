// The binary map format (.plmapb, io/map_file_binary.hpp): bit-exact round trips of generated
// maps (d = 1 and 2), text -> binary -> text byte for byte, and every kind of damage refused with
// a ParseError naming the file: truncation at many offsets, bit flips in the header, the table
// and the arrays, a wrong version, and a map loaded against other surfaces.

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/map_file_binary.hpp>
#include <plmap/core/surface_fingerprint.hpp>
#include <plmap/verify/generators/rc_generators.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace plmap {
namespace {

template <int d>
std::string binary_bytes(const PlMap<d>& map) {
  std::ostringstream out;
  write_binary_map(out, map);
  return std::move(out).str();
}

template <int d>
std::string text_bytes(const PlMap<d>& map) {
  std::ostringstream out;
  write_map(out, map);
  return std::move(out).str();
}

template <int d>
void check_round_trips(const PlMap<d>& map) {
  const std::string bytes = binary_bytes(map);
  const AnyPlMap loaded = parse_map(bytes, "generated.plmapb");
  const auto& back = std::get<PlMap<d>>(loaded);
  RC_ASSERT(back.data() == map.data());
  RC_ASSERT(back.domain().vertices() == map.domain().vertices());
  RC_ASSERT(back.domain().elements() == map.domain().elements());
  RC_ASSERT(back.target().vertices() == map.target().vertices());
  RC_ASSERT(back.target().elements() == map.target().elements());
  // text -> binary -> text: the same file, byte for byte; and the writer is deterministic.
  RC_ASSERT(text_bytes(back) == text_bytes(map));
  RC_ASSERT(binary_bytes(back) == bytes);
}

RC_GTEST_PROP(MapFileBinary, RefinementsOfTriangleSurfacesRoundTrip, ()) {
  check_round_trips<2>(*(*rc::gen::scale(0.5, generators::refinement_maps<2>())).map);
}
RC_GTEST_PROP(MapFileBinary, OverlaysOfPlanarTriangulationsRoundTrip, ()) {
  check_round_trips<2>(*(*rc::gen::scale(0.5, generators::overlay_maps<2>())).map);
}
RC_GTEST_PROP(MapFileBinary, CurveRefinementsRoundTrip, ()) {
  check_round_trips<1>(*(*generators::refinement_maps<1>()).map);
}
RC_GTEST_PROP(MapFileBinary, CurveOverlaysRoundTrip, ()) {
  check_round_trips<1>(*(*generators::overlay_maps<1>()).map);
}

// A map with no nodes and no regions (D empty) has empty arrays, whose data() is null: found by
// the map_binary fuzzer as undefined behaviour (UBSan: member call on a null pointer) when the
// flat views of the region arrays were taken through their first element.
TEST(MapFileBinary, MapWithoutRegionsRoundTrips) {
  const auto surface = std::make_shared<const Surface<2>>(
      std::vector<WorldPoint<2>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}},
      std::vector<ElementCorners<2>>{{0, 1, 2}, {1, 3, 2}});
  MapData<2> m;
  m.node_begin = {0, 0, 0};
  m.neighbor_begin = {0};
  m.edge_node_begin.assign(7, 0);
  m.region_begin = {0, 0, 0};
  m.start_region = {invalid_index, invalid_index};
  const PlMap<2> empty(surface, surface, m);
  const AnyPlMap back = parse_map(binary_bytes(empty), "empty.plmapb");
  EXPECT_EQ(std::get<PlMap<2>>(back).data(), m);
  EXPECT_EQ(std::get<PlMap<2>>(back).region_count(), 0);
}

/// One fixed map with a few hundred regions, for the damage tests.
const PlMap<2>& sample_map() {
  static const std::shared_ptr<const PlMap<2>> map = [] {
    const auto cases = rc::gen::scale(0.5, generators::overlay_maps<2>());
    for (int seed = 0;; ++seed) {
      auto c = cases(rc::Random(static_cast<std::uint64_t>(seed)), 40).value();
      if (c.map->region_count() >= 100) return c.map;
    }
  }();
  return *map;
}

/// Parsing must end in a ParseError (or the constructors' typed errors) naming the file.
void expect_refused(const std::string& bytes, const std::string& why) {
  try {
    parse_map(bytes, "damaged.plmapb");
    ADD_FAILURE() << "accepted a damaged file: " << why;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("damaged.plmapb"), std::string::npos) << why << ": " << e.what();
  }
}

TEST(MapFileBinary, TruncationAtAnyOffsetIsRefused) {
  const std::string bytes = binary_bytes(sample_map());
  // Every offset of the header and the table, then a few hundred spread over the arrays.
  const std::size_t step = std::max<std::size_t>(1, bytes.size() / 300);
  for (std::size_t size = 0; size < bytes.size(); size += size < 4096 ? 1 : step) {
    expect_refused(bytes.substr(0, size), "truncated to " + std::to_string(size));
  }
}

TEST(MapFileBinary, TruncationNamesTheCause) {
  const std::string bytes = binary_bytes(sample_map());
  try {
    parse_map(bytes.substr(0, bytes.size() - 100), "cut.plmapb");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

TEST(MapFileBinary, BitFlipsAnywhereAreRefused) {
  const std::string bytes = binary_bytes(sample_map());
  const std::size_t step = std::max<std::size_t>(1, bytes.size() / 2000);
  int flips = 0;
  for (std::size_t at = 0; at < bytes.size(); at += at < 2048 ? 1 : step) {
    // Flipping a padding byte changes nothing the map is made of; the checksums cover the
    // header, the table and every array byte.
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ (1 << (at % 8)));
    try {
      const AnyPlMap loaded = parse_map(damaged, "damaged.plmapb");
      // Accepted: only harmless if it is the same map (a flip in the zero padding).
      EXPECT_TRUE(std::get<PlMap<2>>(loaded).data() == sample_map().data()) << "flip at byte " << at;
    } catch (const ParseError& e) {
      ++flips;
      EXPECT_NE(std::string(e.what()).find("damaged.plmapb"), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(flips, 1000);
}

TEST(MapFileBinary, WrongVersionIsRefused) {
  std::string bytes = binary_bytes(sample_map());
  bytes[8] = 3;  // the version's low byte
  try {
    parse_map(bytes, "future.plmapb");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("unsupported binary map version 3 (this build reads versions 1 to 2)"),
              std::string::npos)
        << e.what();
  }
}

TEST(MapFileBinary, DamageBehindTheChecksumsIsStillRefused) {
  // With the checksums off (the fuzzer's mode) a flipped index must still be caught by the
  // decoders and the structural validation, never crash or give another map silently.
  const std::string bytes = binary_bytes(sample_map());
  MapReadOptions unchecked;
  unchecked.verify_checksums = false;
  int refused = 0, same = 0;
  for (std::size_t at = 4096; at < bytes.size(); at += 7) {
    std::string damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x40);
    try {
      const AnyPlMap loaded = parse_map(damaged, "damaged.plmapb", unchecked);
      same += std::get<PlMap<2>>(loaded).data() == sample_map().data();
    } catch (const Error&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(same, 0);  // padding flips
}

class MapFileBinaryOnDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("plmap_binary_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(MapFileBinaryOnDisk, ExtensionChoosesTheFormatAndLoadingReadsBoth) {
  const PlMap<2>& map = sample_map();
  const auto binary = dir_ / "m.plmapb", text = dir_ / "m.plmap", upper = dir_ / "M.PLMAPB";
  save_map(binary, map);
  save_map(text, map);
  save_map(upper, map);
  std::ifstream in(binary, std::ios::binary);
  std::string head(8, '\0');
  in.read(head.data(), 8);
  EXPECT_TRUE(looks_like_binary_map(head));
  EXPECT_EQ(std::filesystem::file_size(binary), std::filesystem::file_size(upper));
  EXPECT_LT(std::filesystem::file_size(binary), std::filesystem::file_size(text));
  EXPECT_EQ(load_map<2>(binary).data(), map.data());
  EXPECT_EQ(std::get<PlMap<2>>(load_map(binary)).data(), map.data());
  EXPECT_EQ(load_map<2>(text).data(), map.data());
  EXPECT_EQ(map_file_dimension(binary), 2);
  EXPECT_THROW(load_map<1>(binary), ParseError);
}

TEST_F(MapFileBinaryOnDisk, ProgressIsReportedWhileWritingAndReading) {
  const auto path = dir_ / "m.plmapb";
  std::uint64_t last_written = 0, last_read = 0, total = 0;
  MapWriteOptions write;
  write.progress = [&](const Progress& p) {
    EXPECT_EQ(p.phase, "writing map");
    EXPECT_GE(p.done, last_written);
    last_written = p.done;
    total = p.total;
  };
  save_map(path, sample_map(), write);
  EXPECT_EQ(last_written, std::filesystem::file_size(path));
  EXPECT_EQ(total, last_written);
  MapReadOptions read;
  read.progress = [&](const Progress& p) { last_read = std::max<std::uint64_t>(last_read, p.done); };
  load_map<2>(path, read);
  EXPECT_GT(last_read, total / 2);
}

TEST_F(MapFileBinaryOnDisk, AMapForOtherSurfacesIsRefused) {
  const PlMap<2>& map = sample_map();
  for (const char* name : {"m.plmapb", "m.plmap"}) {
    const auto path = dir_ / name;
    save_map(path, map);
    const PlMap<2> same = load_map<2>(path, map.domain_ptr(), map.target_ptr());
    EXPECT_EQ(same.data(), map.data());
    EXPECT_EQ(same.domain_ptr(), map.domain_ptr());  // the caller's surfaces

    std::vector<WorldPoint<2>> moved = map.target().vertices();
    moved[0](2) += 1e-9;
    const auto other = std::make_shared<const Surface<2>>(std::move(moved), map.target().elements());
    try {
      load_map<2>(path, map.domain_ptr(), other);
      ADD_FAILURE() << name;
    } catch (const ParseError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path.string()), std::string::npos) << what;
      EXPECT_NE(what.find("another target (S2) surface"), std::string::npos) << what;
    }
    // Swapped surfaces: the domain is the one refused first.
    EXPECT_THROW(load_map<2>(path, map.target_ptr(), map.domain_ptr()), ParseError);
  }
}

TEST(SurfaceFingerprint, ChangesWithEveryCoordinateAndIndex) {
  const Surface<2>& s = sample_map().domain();
  const std::uint64_t f = surface_fingerprint(s);
  EXPECT_EQ(fingerprint_hex(f).size(), 16u);
  std::vector<WorldPoint<2>> v = s.vertices();
  v.back()(0) = std::nextafter(v.back()(0), 1e300);
  EXPECT_NE(surface_fingerprint(Surface<2>(v, s.elements())), f);
  std::vector<ElementCorners<2>> e = s.elements();
  std::swap(e[0], e[1]);
  EXPECT_NE(surface_fingerprint(Surface<2>(s.vertices(), e)), f);
  EXPECT_EQ(surface_fingerprint(Surface<2>(s.vertices(), s.elements())), f);
}

}  // namespace
}  // namespace plmap
