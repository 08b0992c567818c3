// A map's provenance (map_provenance.hpp) and the projection rules recorded in it
// (projection_rules.hpp): both file formats keep it, the text format only says version 2 when
// there is some, bad entries are refused with a named error, and recorded rules read back equal.

#include "test_map_file_fixtures.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/map_file_binary.hpp>
#include <plmap/core/projection_rules.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace plmap {
namespace {

MapProvenance some_provenance() {
  ProjectionRules rules;
  rules.max_distance = 0.25;
  rules.allow_negative_distance = true;
  rules.normal_check = NormalCheck::facing;
  MapProvenance p;
  record_projection_rules(rules, p);
  p["note"] = "made-by-a-test";
  return p;
}

std::string text_of(const PlMap<2>& map) {
  std::ostringstream out;
  write_map(out, map);
  return std::move(out).str();
}

std::string binary_of(const PlMap<2>& map) {
  std::ostringstream out;
  write_binary_map(out, map);
  return std::move(out).str();
}

TEST(MapProvenance, TextFilesKeepItAndSayVersionTwoOnlyWhenThereIsSome) {
  PlMap<2> map = test_maps::builder_square_flip();
  const std::string plain = text_of(map);
  EXPECT_TRUE(plain.starts_with("plmap-map 1\n")) << plain.substr(0, 40);
  EXPECT_EQ(plain.find("provenance"), std::string::npos);

  map.set_provenance(some_provenance());
  const std::string text = text_of(map);
  EXPECT_TRUE(text.starts_with("plmap-map 2\ndimension 2\norientation ")) << text.substr(0, 60);
  EXPECT_NE(text.find("\nprovenance 7\nmade_by project\nnote made-by-a-test\n"), std::string::npos) << text;
  const PlMap<2> back = std::get<PlMap<2>>(parse_map(text, "p.plmap"));
  EXPECT_EQ(back.provenance(), map.provenance());
  EXPECT_EQ(back.data(), map.data());
  EXPECT_EQ(text_of(back), text);  // byte for byte
  // everything after the provenance is the version 1 file
  EXPECT_EQ(text.substr(text.find("domain_vertices")), plain.substr(plain.find("domain_vertices")));
}

TEST(MapProvenance, BinaryFilesKeepItAndCopiesToo) {
  PlMap<2> map = test_maps::builder_square_flip();
  map.set_provenance(some_provenance());
  const std::string bytes = binary_of(map);
  const PlMap<2> back = std::get<PlMap<2>>(parse_map(bytes, "p.plmapb"));
  EXPECT_EQ(back.provenance(), map.provenance());
  EXPECT_EQ(binary_of(back), bytes);
  EXPECT_EQ(text_of(back), text_of(map));
  const PlMap<2> copy = back;  // NOLINT(performance-unnecessary-copy-initialization): the copy is tested
  EXPECT_EQ(copy.provenance(), map.provenance());
  const PlMap<2> without = std::get<PlMap<2>>(parse_map(binary_of(test_maps::builder_square_flip()), "q.plmapb"));
  EXPECT_TRUE(without.provenance().empty());
}

TEST(MapProvenance, LoadingAgainstGivenSurfacesKeepsIt) {
  PlMap<2> map = test_maps::builder_square_flip();
  map.set_provenance(some_provenance());
  const auto dir = std::filesystem::temp_directory_path() /
                   ("plmap_provenance_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  for (const char* name : {"m.plmap", "m.plmapb"}) {
    save_map(dir / name, map);
    const PlMap<2> back = load_map<2>(dir / name, map.domain_ptr(), map.target_ptr());
    EXPECT_EQ(back.provenance(), map.provenance()) << name;
  }
  std::filesystem::remove_all(dir);
}

TEST(MapProvenance, EntriesMustBeTokensOfPrintableAscii) {
  PlMap<2> map = test_maps::hand_made_triangle();
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"key", "two words"}, {"", "v"}, {"k", ""}, {"tab\tkey", "v"}, {"k", "line\nbreak"}, {"k", "caf\xc3\xa9"}}) {
    EXPECT_THROW(map.set_provenance({{key, value}}), InvalidMapError) << key << " = " << value;
  }
  EXPECT_TRUE(map.provenance().empty());  // a refused provenance leaves the old one
  map.set_provenance({{"k", "!~"}});
  EXPECT_EQ(map.provenance().at("k"), "!~");
}

TEST(MapProvenance, BadTextSectionsAreRefusedWithTheLine) {
  PlMap<2> map = test_maps::hand_made_triangle();
  map.set_provenance({{"a", "1"}, {"b", "2"}});
  const std::string good = text_of(map);
  auto expect_refused = [](const std::string& text, const std::string& mention) {
    try {
      parse_map(text, "bad.plmap");
      ADD_FAILURE() << "accepted: " << text.substr(0, 120);
    } catch (const ParseError& e) {
      EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
    }
  };
  std::string twice = good;
  twice.replace(twice.find("\nb 2\n"), 5, "\na 2\n");
  expect_refused(twice, "provenance entry 'a' appears twice");
  std::string three = good;
  three.replace(three.find("\nb 2\n"), 5, "\nb 2 3\n");
  expect_refused(three, "line 6");
  std::string missing = good;
  missing.replace(missing.find("provenance 2\n"), 13, "");
  expect_refused(missing, "expected section 'provenance'");
  std::string future = good;
  future.replace(0, 11, "plmap-map 3");
  expect_refused(future, "reads versions 1 and 2");
}

TEST(ProjectionRules, RecordedRulesReadBackEqual) {
  for (const double limit : {std::numeric_limits<double>::infinity(), 0.0, 0.1, 1e-300, 3.0000000000000004}) {
    ProjectionRules rules;
    rules.max_distance = limit;
    rules.max_distance_is_relative = limit < 1.0;
    rules.allow_negative_distance = limit > 1.0;
    rules.normal_check = limit > 1.0 ? NormalCheck::aligned : NormalCheck::none;
    if (limit == 0.1) rules.directions_fingerprint = directions_fingerprint(std::vector<double>{0.0, 0.0, 1.0}, 3);
    MapProvenance p{{"other", "kept"}};
    record_projection_rules(rules, p);
    EXPECT_EQ(p.at("other"), "kept");
    const std::optional<ProjectionRules> back = recorded_projection_rules(p);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(*back, rules) << p.at("projection.max_distance");
  }
  EXPECT_FALSE(recorded_projection_rules({}).has_value());
  EXPECT_FALSE(recorded_projection_rules({{"made_by", "simplify"}}).has_value());
  for (const NormalCheck check : {NormalCheck::none, NormalCheck::facing, NormalCheck::aligned})
    EXPECT_EQ(normal_check_from_name(to_string(check)), check);
  EXPECT_FALSE(normal_check_from_name("sideways").has_value());
}

TEST(ProjectionRules, UnreadableRecordsNameTheEntry) {
  MapProvenance good;
  record_projection_rules(ProjectionRules{}, good);
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"projection.max_distance", "-1"},
           {"projection.max_distance", "1x"},
           {"projection.max_distance", "nan"},
           {"projection.allow_negative_distance", "yes"},
           {"projection.max_distance_is_relative", "1"},
           {"projection.normal_check", "sideways"},
           {"projection.directions", "given:123"},
           {"projection.directions", "given:0123456789abcdeg"},
           {"projection.directions", "normals"}}) {
    MapProvenance p = good;
    p[key] = value;
    try {
      recorded_projection_rules(p);
      ADD_FAILURE() << key << " = " << value << " was read";
    } catch (const InvalidMapError& e) {
      EXPECT_NE(std::string(e.what()).find("'" + key + "'"), std::string::npos) << e.what();
    }
  }
  MapProvenance lacking = good;
  lacking.erase("projection.normal_check");
  EXPECT_THROW(recorded_projection_rules(lacking), InvalidMapError);
}

TEST(ProjectionRules, DirectionFingerprintsTellFieldsApartButNotPowersOfTwo) {
  const std::vector<double> a{0.0, 0.5, 1.0, 0.25, 0.0, 1.0}, b{0.0, 0.5, 1.0, 0.25, 1e-300, 1.0}, c{0.0, 0.5, 1.0};
  EXPECT_EQ(directions_fingerprint(a, 3), directions_fingerprint(std::vector<double>(a), 3));
  EXPECT_NE(directions_fingerprint(a, 3), directions_fingerprint(b, 3));
  EXPECT_NE(directions_fingerprint(a, 3), directions_fingerprint(c, 3));
  EXPECT_NE(directions_fingerprint(a, 3), directions_fingerprint(a, 2));  // other rows
  // each row scaled by its own power of two (down to subnormal and up to near overflow): the
  // same field; scaled by 3, whose products round: another
  std::vector<double> scaled = a, tripled = a;
  for (int i = 0; i < 3; ++i) {
    scaled[i] = std::ldexp(a[i], 1000);
    scaled[3 + i] = std::ldexp(a[3 + i], -1060);
    tripled[3 + i] = 3.0 * a[3 + i];
  }
  EXPECT_EQ(directions_fingerprint(a, 3), directions_fingerprint(scaled, 3));
  EXPECT_NE(directions_fingerprint(a, 3), directions_fingerprint(tripled, 3));
  EXPECT_THROW(directions_fingerprint(a, 0), Error);
  ProjectionRules rules;
  rules.directions_fingerprint = 0x0123456789abcdefULL;
  EXPECT_EQ(directions_description(rules), "given:0123456789abcdef");
  EXPECT_EQ(directions_description(ProjectionRules{}), "averaged-normals");
}

}  // namespace
}  // namespace plmap
