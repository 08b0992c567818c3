// libFuzzer target for corrupt maps whose syntax is valid: the input is a list of edits of the
// arrays of a valid map (set or shift one entry of node_begin, region_corners, region_neighbors,
// ...), the kind of damage flipped digits in a .plmap file do. The edited map is written as a
// file and loaded; if it loads, every command runs on it (exercise_map.hpp). Mutating text
// rarely gets past the parser; editing the arrays reaches the loader's validation and what
// lies behind it directly.
//
// Input: byte 0 picks the base map; then records of 5 bytes: array, index (2 bytes), value
// (2 bytes, signed); the top bit of the array byte chooses "add" instead of "set".

#include "exercise_map.hpp"

#include <plmap/core/io/map_file.hpp>
#include <plmap/verify/generators/random_maps.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <sstream>
#include <string_view>
#include <variant>
#include <vector>

namespace {

using namespace plmap;

/// The base maps: an overlay of two grids (intersection, touching and ghost nodes), a random
/// refinement of a grid, and a random refinement of a polyline.
const std::vector<AnyPlMap>& base_maps() {
  static const std::vector<AnyPlMap> maps = [] {
    std::vector<AnyPlMap> out;
    generators::Rng rng(12);
    auto grid = [&](int cells) {
      return std::make_shared<const Surface<2>>(
          generators::grid_triangulation(generators::GridOptions{cells, 0.0, false}, rng));
    };
    out.emplace_back(*generators::plane_overlay_map(grid(2), grid(3)).map);
    const auto s1 = grid(2);
    out.emplace_back(*generators::refinement_map<2>(
                          s1, generators::random_refinement<2>(*s1, {}, rng)).map);
    const auto curve =
        std::make_shared<const Surface<1>>(generators::random_open_polyline(4, rng));
    out.emplace_back(*generators::refinement_map<1>(
                          curve, generators::random_refinement<1>(*curve, {}, rng)).map);
    return out;
  }();
  return maps;
}

/// Applies one edit to one entry of one array (entries picked modulo the array's size).
template <int d>
void edit(MapData<d>& m, unsigned array, unsigned index, int value, bool add) {
  auto change = [&](auto& entry) {
    using T = std::remove_reference_t<decltype(entry)>;
    entry = static_cast<T>(add ? static_cast<int>(entry) + value : value);
  };
  auto in = [&](auto& v) {
    if (!v.empty()) change(v[index % v.size()]);
  };
  auto in_arrays = [&](auto& v) {  // arrays of d + 1 indices, flattened
    if (!v.empty()) change(v[(index / (d + 1)) % v.size()][index % (d + 1)]);
  };
  switch (array % 14) {
    case 0: in(m.node_begin); break;
    case 1: in(m.region_begin); break;
    case 2: in_arrays(m.region_corners); break;
    case 3: in_arrays(m.region_neighbors); break;
    case 4: in(m.region_target); break;
    case 5: in(m.start_region); break;
    case 6: in(m.neighbor_begin); break;
    case 7: in(m.neighbor); break;
    case 8: in(m.edge_node_begin); break;
    case 9: in(m.edge_node); break;
    case 10: in(m.node_target); break;
    case 11: in(m.node_location); break;
    case 12:
      if (!m.node_image_element.empty()) change(m.node_image_element[index % m.node_image_element.size()]);
      break;
    case 13:  // move a node: positions in 1/256 of the element
      if (!m.node_position.empty()) {
        auto& x = m.node_position[index % m.node_position.size()];
        x(0) = add ? x(0) + value / 256.0 : value / 256.0;
      }
      break;
  }
}

template <int d>
void run(const PlMap<d>& base, std::span<const std::uint8_t> edits) {
  MapData<d> m = base.data();
  for (std::size_t k = 0; k + 5 <= edits.size(); k += 5) {
    const unsigned index = edits[k + 1] | unsigned(edits[k + 2]) << 8;
    const int value = static_cast<std::int16_t>(edits[k + 3] | edits[k + 4] << 8);
    edit<d>(m, edits[k] & 0x7f, index, value, (edits[k] & 0x80) != 0);
  }
  std::string text;
  try {
    const PlMap<d> edited(base.domain_ptr(), base.target_ptr(), std::move(m));
    std::ostringstream file;
    write_map(file, edited);
    text = file.str();
  } catch (const InvalidMapError&) {
    return;  // the constructor refuses it: no file to load
  }
  try {
    fuzz::exercise_map(std::get<PlMap<d>>(parse_map(text, "edited.plmap")));
  } catch (const Error&) {
    // refused with a message
  }
}

}  // namespace

// The base maps are built before fuzzing starts, so that their construction (seconds in an
// unoptimized build) does not count against the first input's time limit.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  (void)base_maps();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto& maps = base_maps();
  const std::span<const std::uint8_t> edits(data + 1, size - 1);
  std::visit([&](const auto& base) { run(base, edits); }, maps[data[0] % maps.size()]);
  return 0;
}
