// The structural validation of loaded maps (map_validation.hpp): a corrupt file whose indices are
// in range but point into another element, or whose region neighbours disagree, is refused on
// load with the element named, instead of loading and crashing a later walk (issue 12, defect 1).
// Also: a surface file given as a map is named as such (issue 12, defect 9).

#include "test_map_file_fixtures.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/map_validation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <sstream>

namespace plmap {
namespace {

using ::testing::HasSubstr;
using namespace test_maps;

/// The file of `base` with its arrays changed by `change`; the change keeps every index in
/// range, so PlMap's constructor accepts it and only the validation can refuse it.
template <int d>
std::string corrupted_file(const PlMap<d>& base, const std::function<void(MapData<d>&)>& change) {
  MapData<d> m = base.data();
  change(m);
  const PlMap<d> corrupt(base.domain_ptr(), base.target_ptr(), std::move(m));
  std::ostringstream out;
  write_map(out, corrupt);
  return out.str();
}

/// Loads the text and returns the InvalidMapError's message (fails the test if it loads).
std::string load_error(const std::string& text) {
  try {
    (void)parse_map(text, "corrupt.plmap");
  } catch (const InvalidMapError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the corrupt map loaded";
  return {};
}

// builder_square_flip(): S1 = two triangles, two regions each (0, 1 on element 0; 2, 3 on 1).
TEST(MapValidation, BuilderMapsPass) {
  EXPECT_NO_THROW(validate_map_structure(builder_square_flip()));
  EXPECT_NO_THROW(validate_map_structure(builder_polyline()));
  EXPECT_NO_THROW(validate_map_structure(hand_made_triangle()));
  EXPECT_NO_THROW(validate_map_structure(hand_made_segment()));
}

TEST(MapValidation, RegionNeighbourInAnotherElement) {
  const PlMap<2> base = builder_square_flip();
  ASSERT_EQ(base.regions_end(0) - base.regions_begin(0), 2);
  const std::string what = load_error(corrupted_file<2>(base, [](MapData<2>& m) {
    for (Index& q : m.region_neighbors[0])
      if (q == 1) q = 2;  // region 2 belongs to element 1
  }));
  EXPECT_THAT(what, HasSubstr("corrupt.plmap"));
  EXPECT_THAT(what, HasSubstr("S1 element 0"));
  EXPECT_THAT(what, HasSubstr("region 0 lists neighbour region 2"));
}

TEST(MapValidation, RegionBeginShiftedIntoAnotherElement) {
  // Element 0 claims regions 0..2: region 2's corners are nodes of element 1.
  const std::string what = load_error(corrupted_file<2>(
      builder_square_flip(), [](MapData<2>& m) { m.region_begin[1] = 3; m.start_region[1] = 3; }));
  EXPECT_THAT(what, HasSubstr("S1 element 0"));
  EXPECT_THAT(what, HasSubstr("belongs to another element"));
}

// Found by the map_edits fuzz target with the validation switched off (its input is checked in
// as tests/fuzz/corpus/map_edits/regression-overlay-region-begin-shifted): region_begin[k]
// lowered by one hands element k-1's last region to element k, and the walks of element k
// answered with a region of element k-1.
TEST(MapValidation, RegionBeginShiftedDown) {
  const PlMap<2> base = builder_square_flip();
  const std::string what = load_error(corrupted_file<2>(base, [](MapData<2>& m) {
    m.region_begin[1] -= 1;
    m.start_region[1] = m.region_begin[1] + 1;  // stays inside element 1's new range
  }));
  EXPECT_THAT(what, HasSubstr("S1 element"));
}

TEST(MapValidation, NodeBeginShiftedIntoAnotherElement) {
  const PlMap<2> base = builder_square_flip();
  const std::string what = load_error(corrupted_file<2>(
      base, [](MapData<2>& m) { m.node_begin[1] -= 1; }));
  EXPECT_THAT(what, HasSubstr("S1 element"));
}

TEST(MapValidation, AsymmetricRegionNeighbours) {
  const std::string what = load_error(corrupted_file<2>(builder_square_flip(), [](MapData<2>& m) {
    for (Index& q : m.region_neighbors[1])
      if (q == 0) q = invalid_index;  // 0 still lists 1
  }));
  EXPECT_THAT(what, HasSubstr("S1 element 0"));
  EXPECT_THAT(what, HasSubstr("does not list it back"));
}

TEST(MapValidation, RegionCornerOfAnotherElement) {
  const PlMap<2> base = builder_square_flip();
  const std::string what = load_error(corrupted_file<2>(
      base, [&](MapData<2>& m) { m.region_corners[3][0] = base.nodes_begin(0); }));
  EXPECT_THAT(what, HasSubstr("S1 element 1"));
  EXPECT_THAT(what, HasSubstr("region 3 has corner node"));
}

TEST(MapValidation, NodeNeighbourOfAnotherElement) {
  const PlMap<2> base = builder_square_flip();
  const std::string what = load_error(corrupted_file<2>(
      base, [&](MapData<2>& m) { m.neighbor[m.neighbor_begin[0]] = base.nodes_begin(1); }));
  EXPECT_THAT(what, HasSubstr("S1 element 0"));
  EXPECT_THAT(what, HasSubstr("node 0 lists neighbour"));
}

TEST(MapValidation, EdgeNodeOfAnotherElement) {
  const PlMap<2> base = builder_square_flip();
  const std::string what = load_error(corrupted_file<2>(
      base, [&](MapData<2>& m) { m.edge_node[0] = base.nodes_begin(1); }));
  EXPECT_THAT(what, HasSubstr("S1 element 0"));
  EXPECT_THAT(what, HasSubstr("local edge 0"));
}

TEST(MapValidation, NodeLocationThatIsNoCorner) {
  const std::string what = load_error(
      corrupted_file<2>(builder_square_flip(), [](MapData<2>& m) { m.node_location[0] = 7; }));
  EXPECT_THAT(what, HasSubstr("node 0 (corner) has location 7"));
}

TEST(MapValidation, NodeTargetThatDoesNotExist) {
  const std::string what = load_error(
      corrupted_file<2>(builder_square_flip(), [](MapData<2>& m) { m.node_target[0] = 40; }));
  EXPECT_THAT(what, HasSubstr("S2 vertex 40, which does not exist"));
}

TEST(MapValidation, CurveRegionNeighbourInAnotherElement) {
  const PlMap<1> base = builder_polyline();
  ASSERT_GE(base.region_count(), 3);
  const std::string what = load_error(corrupted_file<1>(base, [&](MapData<1>& m) {
    m.region_neighbors[0][0] = base.regions_begin(2);
  }));
  EXPECT_THAT(what, HasSubstr("S1 element 0"));
}

TEST(MapValidation, SurfaceFileGivenAsAMapIsNamed) {
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  try {
    (void)parse_map(off, "s.off");
    FAIL() << "an OFF file loaded as a map";
  } catch (const ParseError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.off"));
    EXPECT_THAT(e.what(), HasSubstr("this is a surface file (OFF), not a map"));
  }
  // Binary STL has no magic word: the extension tells.
  try {
    (void)parse_map(std::string(84, '\0'), "part.stl");
    FAIL() << "an STL file loaded as a map";
  } catch (const ParseError& e) {
    EXPECT_THAT(e.what(), HasSubstr("this is a surface file (STL by its extension), not a map"));
  }
}

}  // namespace
}  // namespace plmap
