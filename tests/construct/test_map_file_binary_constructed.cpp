// The binary map format on maps that the construction algorithms make (projection d = 1 and 2,
// simplification, smoothing): bit-exact round trips, text -> binary -> text byte for byte, and
// the region maps recomputed on load (stored only where recomputing is not exact), which is what
// keeps the file at a fifth of the text file.

#include "projection_fixtures.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/construct/simplify.hpp>
#include <plmap/construct/smooth.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/map_file_binary.hpp>
#include <plmap/verify/generators/closed_surfaces.hpp>

#include <gtest/gtest.h>

#include <sstream>

namespace plmap {
namespace {

using test::circle;
using test::grid;

template <int d>
void expect_exact_and_compact(const PlMap<d>& map, double largest_size_ratio) {
  std::ostringstream binary, text;
  write_binary_map(binary, map);
  write_map(text, map);
  const AnyPlMap loaded = parse_map(binary.str(), "constructed.plmapb");
  const auto& back = std::get<PlMap<d>>(loaded);
  EXPECT_EQ(back.data(), map.data());
  std::ostringstream text_again, binary_again;
  write_map(text_again, back);
  write_binary_map(binary_again, back);
  EXPECT_EQ(text_again.str(), text.str());
  EXPECT_EQ(binary_again.str(), binary.str());
  // The table of contents says the region maps are recomputed, not stored.
  EXPECT_NE(binary.str().find("\"region_map\":{\"crc32\""), std::string::npos);
  EXPECT_LT(static_cast<double>(binary.str().size()), largest_size_ratio * static_cast<double>(text.str().size()))
      << binary.str().size() << " vs " << text.str().size();
}

TEST(MapFileBinaryConstructed, ProjectionOfTriangleSurfaces) {
  const auto s1 = grid(30, 30, 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.2);
  const auto s2 = grid(23, 41, -0.05, 1.05, -0.05, 1.05, 0.1, true, 0.3);
  const auto r = project<2>(s1, s2, {.normal_check = TargetNormalCheck::facing});
  ASSERT_GT(r.map.region_count(), 1000);
  expect_exact_and_compact(r.map, 0.25);
}

TEST(MapFileBinaryConstructed, ProjectionOfCurves) {
  const auto r = project<1>(circle(400, 1.0), circle(333, 1.01, 0.1));
  ASSERT_GT(r.map.region_count(), 700);
  // d = 1 text records are short (two coordinates fewer per node, no edge arrays): ~0.4.
  expect_exact_and_compact(r.map, 0.45);
}

TEST(MapFileBinaryConstructed, SimplificationAndSmoothing) {
  generators::Rng rng(3);
  auto fine = std::make_shared<const Surface<2>>(generators::icosphere({3, 0.0}, rng));
  SimplifyOptions options;
  options.target_elements = 80;
  const PlMap<2> simplified = simplify(fine, options).map;
  expect_exact_and_compact(simplified, 0.35);
  const PlMap<2> smoothed = smooth(simplified, {}).map;
  expect_exact_and_compact(smoothed, 0.35);
}

}  // namespace
}  // namespace plmap
