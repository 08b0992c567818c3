// Damaged map files never crash the loader: every truncation and a few thousand seeded byte
// mutations of real map files end in a typed plmap::Error or in a map that is fully usable
// (it saves, reloads to the same data, and exports its regions).

#include "test_map_file_fixtures.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/regions_csv.hpp>

#include <gtest/gtest.h>

#include <random>
#include <sstream>

namespace plmap {
namespace {

using namespace test_maps;

enum class Outcome { rejected, loaded };

/// Parses `text`; a loaded map must survive a save/reload cycle and a regions export.
Outcome parse_and_use(const std::string& text) {
  const AnyPlMap map = parse_map(text, "fuzz.plmap");  // a typed rejection propagates
  std::visit(
      [&](const auto& m) {
        std::ostringstream saved;
        write_map(saved, m);
        const AnyPlMap again = parse_map(saved.str(), "fuzz-resaved.plmap");
        using Map = std::decay_t<decltype(m)>;
        EXPECT_TRUE(std::get<Map>(again).data() == m.data());
        std::ostringstream csv;
        write_regions_csv(csv, m);
        EXPECT_FALSE(csv.str().empty());
      },
      map);
  return Outcome::loaded;
}

Outcome classify(const std::string& text) {
  try {
    return parse_and_use(text);
  } catch (const Error&) {
    return Outcome::rejected;
  }
  // Any other exception escapes and fails the test.
}

template <int d>
std::string text_of(const PlMap<d>& map) {
  std::ostringstream out;
  write_map(out, map);
  return out.str();
}

TEST(MapFileFuzz, EveryTruncationIsRejected) {
  for (const std::string& text : {text_of(builder_square_flip()), text_of(builder_polyline())}) {
    // Every proper prefix lacks the final "end" line or part of it, so none may load. A prefix
    // that only drops the last newline still ends in "end" and is accepted.
    for (std::size_t length = 0; length + 1 < text.size(); ++length) {
      EXPECT_EQ(classify(text.substr(0, length)), Outcome::rejected) << "prefix length " << length;
    }
    EXPECT_EQ(classify(text), Outcome::loaded);
  }
}

TEST(MapFileFuzz, SeededMutationsGiveATypedErrorOrAUsableMap) {
  // Characters that keep a mutated file close to parseable, so that mutations reach deep into
  // the loader instead of failing at the first token.
  const std::string alphabet = "0123456789-.e+ \n\t-1xnai";
  std::mt19937 random(20261122);
  int loaded = 0;
  int rejected = 0;
  for (const std::string& original :
       {text_of(builder_square_flip()), text_of(builder_polyline()), text_of(hand_made_triangle())}) {
    for (int trial = 0; trial < 1500; ++trial) {
      std::string text = original;
      const int edits = 1 + static_cast<int>(random() % 3);
      for (int e = 0; e < edits && !text.empty(); ++e) {
        const std::size_t at = random() % text.size();
        switch (random() % 4) {
          case 0: text[at] = alphabet[random() % alphabet.size()]; break;
          case 1: text.erase(at, 1); break;
          case 2: text.insert(at, 1, alphabet[random() % alphabet.size()]); break;
          default: text[at] = static_cast<char>(random() % 256); break;
        }
      }
      (classify(text) == Outcome::loaded ? loaded : rejected) += 1;
    }
  }
  // Both outcomes occur: the mutations are neither all harmless nor all fatal.
  EXPECT_GT(loaded, 0);
  EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace plmap
