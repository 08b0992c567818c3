// The .plmap map file: exact round trips, the header peek, and a typed error for every kind of
// damaged file.

#include "test_map_file_fixtures.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace plmap {
namespace {

using ::testing::HasSubstr;
using namespace test_maps;

template <int d>
std::string to_text(const PlMap<d>& map) {
  std::ostringstream out;
  write_map(out, map);
  return out.str();
}

template <int d>
void expect_same_map(const PlMap<d>& a, const PlMap<d>& b) {
  EXPECT_TRUE(a.data() == b.data());
  EXPECT_EQ(a.domain().vertices(), b.domain().vertices());
  EXPECT_EQ(a.domain().elements(), b.domain().elements());
  EXPECT_EQ(a.target().vertices(), b.target().vertices());
  EXPECT_EQ(a.target().elements(), b.target().elements());
}

/// save -> load -> save: the loaded map equals the original and the second file is identical.
template <int d>
void check_file_round_trip(const PlMap<d>& map, const std::string& name) {
  const auto dir = scratch_directory(name);
  const auto first = dir / "first.plmap";
  const auto second = dir / "second.plmap";
  save_map(first, map);
  const PlMap<d> loaded = load_map<d>(first);
  expect_same_map(map, loaded);
  save_map(second, loaded);
  EXPECT_EQ(read_bytes(first), read_bytes(second));
  EXPECT_EQ(map_file_dimension(first), d);

  const AnyPlMap any = load_map(first);
  ASSERT_TRUE(std::holds_alternative<PlMap<d>>(any));
  expect_same_map(map, std::get<PlMap<d>>(any));
}

TEST(MapFile, HandMadeTriangleRoundTripsExactly) {
  check_file_round_trip(hand_made_triangle(), "hand_triangle");
}

TEST(MapFile, HandMadeSegmentRoundTripsExactly) {
  check_file_round_trip(hand_made_segment(), "hand_segment");
}

TEST(MapFile, BuilderMapWithIntersectionsRoundTripsExactly) {
  const PlMap<2> map = builder_square_flip();
  ASSERT_GT(map.region_count(), 2);
  check_file_round_trip(map, "builder_square");
}

TEST(MapFile, BuilderPolylineRoundTripsExactly) {
  const PlMap<1> map = builder_polyline();
  ASSERT_GT(map.region_count(), 1);
  check_file_round_trip(map, "builder_polyline");
}

TEST(MapFile, AwkwardDoublesSurviveBitForBit) {
  // Values whose decimal forms are long or special: they must come back as the same bits.
  const PlMap<2> base = hand_made_triangle();
  MapData<2> m = base.data();
  m.region_map[0] << 0.1 + 0.2, -0.0, 1.0 / 3.0,  //
      std::numeric_limits<double>::denorm_min(), 1e308, -std::numeric_limits<double>::min();
  m.node_image_local[1] << 1.0 - std::numeric_limits<double>::epsilon() / 2, 1e-300;
  const PlMap<2> map(base.domain_ptr(), base.target_ptr(), m);
  const std::string text = to_text(map);
  const PlMap<2> loaded = std::get<PlMap<2>>(parse_map(text, "awkward"));
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(std::signbit(loaded.data().region_map[0](i, j)),
                std::signbit(m.region_map[0](i, j)));
    }
  }
  EXPECT_TRUE(loaded.data() == m);
  EXPECT_EQ(to_text(loaded), text);
}

TEST(MapFile, HeaderNamesFormatVersionAndDimension) {
  const std::string text = to_text(hand_made_triangle());
  EXPECT_EQ(text.rfind("plmap-map 1\ndimension 2\norientation 1\n", 0), 0u);
  EXPECT_THAT(text, ::testing::EndsWith("\nend\n"));
}

TEST(MapFile, SavingANonFiniteMapFailsAndKeepsTheOldFile) {
  const auto dir = scratch_directory("non_finite");
  const auto path = dir / "map.plmap";
  const PlMap<2> good = hand_made_triangle();
  save_map(path, good);
  const std::string before = read_bytes(path);

  MapData<2> m = good.data();
  m.region_map[0](0, 2) = std::numeric_limits<double>::quiet_NaN();
  const PlMap<2> bad(good.domain_ptr(), good.target_ptr(), m);
  EXPECT_THROW(save_map(path, bad), InvalidMapError);
  EXPECT_EQ(read_bytes(path), before);
  // No temporary file is left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(MapFile, LoadingTheWrongDimensionIsAParseError) {
  const auto dir = scratch_directory("wrong_dimension");
  save_map(dir / "map.plmap", hand_made_triangle());
  EXPECT_THROW(load_map<1>(dir / "map.plmap"), ParseError);
}

TEST(MapFile, MissingFileIsAParseErrorNamingIt) {
  const auto path = scratch_directory("missing") / "nothing-here.plmap";
  try {
    load_map(path);
    FAIL() << "expected a ParseError";
  } catch (const ParseError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nothing-here.plmap"));
  }
  EXPECT_THROW(map_file_dimension(path), ParseError);
}

// ---- damaged files ----------------------------------------------------------------------------

/// Replaces the first occurrence of `from` in `text` by `to` (the test fails if it is absent).
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "pattern not in file: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

template <class ErrorType>
std::string parse_error_message(const std::string& text) {
  try {
    parse_map(text, "damaged.plmap");
  } catch (const ErrorType& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "file was accepted";
  return {};
}

class DamagedMapFile : public ::testing::Test {
 protected:
  std::string text = to_text(hand_made_triangle());
};

TEST_F(DamagedMapFile, WrongMagic) {
  const auto what = parse_error_message<ParseError>(replace_once(text, "plmap-map", "plmap-mop"));
  EXPECT_THAT(what, HasSubstr("damaged.plmap:line 1"));
  EXPECT_THAT(what, HasSubstr("not a plmap map file"));
}

TEST_F(DamagedMapFile, FutureVersion) {
  const auto what = parse_error_message<ParseError>(replace_once(text, "plmap-map 1", "plmap-map 3"));
  EXPECT_THAT(what, HasSubstr("unsupported map file version 3 (this build reads versions 1 and 2)"));
}

TEST_F(DamagedMapFile, UnsupportedDimension) {
  const auto what = parse_error_message<ParseError>(replace_once(text, "dimension 2", "dimension 3"));
  EXPECT_THAT(what, HasSubstr("line 2"));
}

TEST_F(DamagedMapFile, ZeroOrientation) {
  parse_error_message<ParseError>(replace_once(text, "orientation 1", "orientation 0"));
}

TEST_F(DamagedMapFile, CountLargerThanTheFile) {
  const auto what =
      parse_error_message<ParseError>(replace_once(text, "nodes 3", "nodes 2000000000"));
  EXPECT_THAT(what, HasSubstr("section nodes"));
  EXPECT_THAT(what, HasSubstr("larger than the rest of the file"));
}

TEST_F(DamagedMapFile, NegativeCount) {
  parse_error_message<ParseError>(replace_once(text, "regions 1", "regions -1"));
}

TEST_F(DamagedMapFile, Truncated) {
  const auto what = parse_error_message<ParseError>(text.substr(0, text.size() / 2));
  EXPECT_THAT(what, HasSubstr("damaged.plmap:line"));
}

TEST_F(DamagedMapFile, MissingEnd) {
  const auto what = parse_error_message<ParseError>(text.substr(0, text.size() - 4));
  EXPECT_THAT(what, HasSubstr("unexpected end of file"));
}

TEST_F(DamagedMapFile, ContentAfterEnd) {
  const auto what = parse_error_message<ParseError>(text + "0\n");
  EXPECT_THAT(what, HasSubstr("after 'end'"));
}

TEST_F(DamagedMapFile, NotANumber) {
  // Line 6 holds the second domain vertex; the message names line and section.
  const auto what = parse_error_message<ParseError>(replace_once(text, "\n1 0 0\n", "\n1 zero 0\n"));
  EXPECT_THAT(what, HasSubstr("line 6 (section domain_vertices)"));
  EXPECT_THAT(what, HasSubstr("'zero'"));
}

TEST_F(DamagedMapFile, NonFiniteCoordinate) {
  const auto what = parse_error_message<ParseError>(replace_once(text, "\n1 0 0\n", "\n1 nan 0\n"));
  EXPECT_THAT(what, HasSubstr("not finite"));
}

TEST_F(DamagedMapFile, IndexBeyondInt32) {
  parse_error_message<ParseError>(replace_once(text, "start_region 1\n0\n", "start_region 1\n4294967296\n"));
}

TEST_F(DamagedMapFile, WrongFieldCount) {
  const auto what = parse_error_message<ParseError>(replace_once(text, "\n1 0 0\n", "\n1 0\n"));
  EXPECT_THAT(what, HasSubstr("expected 3 fields, found 2"));
}

TEST_F(DamagedMapFile, UnknownNodeType) {
  const auto what = parse_error_message<ParseError>(replace_once(text, "corner 1", "cornet 1"));
  EXPECT_THAT(what, HasSubstr("unknown node type 'cornet'"));
}

TEST_F(DamagedMapFile, UnknownEdgeKind) {
  parse_error_message<ParseError>(replace_once(text, "target_edge", "target_edges"));
}

TEST_F(DamagedMapFile, SectionsOutOfOrder) {
  const auto what = parse_error_message<ParseError>(replace_once(text, "node_begin", "nodes_begin"));
  EXPECT_THAT(what, HasSubstr("expected section 'node_begin'"));
}

TEST_F(DamagedMapFile, SurfaceIndexOutOfRangeIsAnInvalidSurface) {
  const auto what = parse_error_message<InvalidSurfaceError>(
      replace_once(text, "domain_elements 1\n0 1 2\n", "domain_elements 1\n0 1 7\n"));
  EXPECT_THAT(what, HasSubstr("damaged.plmap"));
  EXPECT_THAT(what, HasSubstr("domain surface"));
}

TEST_F(DamagedMapFile, RegionTargetOutOfRangeIsAnInvalidMap) {
  // The region record is "0 1 2 -1 -1 -1 <target> ..."; point it at a missing S2 element.
  const auto what = parse_error_message<InvalidMapError>(
      replace_once(text, "0 1 2 -1 -1 -1 0 ", "0 1 2 -1 -1 -1 5 "));
  EXPECT_THAT(what, HasSubstr("damaged.plmap"));
}

TEST_F(DamagedMapFile, InconsistentArraySizesAreAnInvalidMap) {
  parse_error_message<InvalidMapError>(replace_once(text, "start_region 1\n0\n", "start_region 0\n"));
}

TEST(MapFile, WindowsLineEndingsAreAccepted) {
  const PlMap<2> map = hand_made_triangle();
  std::string text = to_text(map);
  std::string crlf;
  for (char c : text) {
    if (c == '\n') crlf.push_back('\r');
    crlf.push_back(c);
  }
  EXPECT_TRUE(std::get<PlMap<2>>(parse_map(crlf, "crlf")).data() == map.data());
}

}  // namespace
}  // namespace plmap
