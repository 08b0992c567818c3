// The cost of loading a map file and, separately, of the structural validation that loading
// runs (map_validation.hpp), for docs/robustness.md.
//
//   bench_map_load MAP.plmap [--repeat N]
//
// Prints, for the fastest of N repetitions, the seconds of the whole load (parsing, surfaces,
// PlMap constructor and validation) and of validate_map_structure alone, and their ratio.

#include <plmap/core/io/map_file.hpp>
#include <plmap/core/map_validation.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <limits>
#include <string>
#include <variant>

int main(int argc, char** argv) {
  if (argc < 2) {
    fmt::print(stderr, "usage: bench_map_load MAP.plmap [--repeat N]\n");
    return 64;
  }
  const std::string path = argv[1];
  int repeat = 3;
  if (argc == 4 && std::string(argv[2]) == "--repeat") repeat = std::max(1, std::atoi(argv[3]));
  using clock = std::chrono::steady_clock;
  double load = std::numeric_limits<double>::infinity();
  double validate = std::numeric_limits<double>::infinity();
  long long regions = 0, nodes = 0;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = clock::now();
    const plmap::AnyPlMap map = plmap::load_map(path);
    const auto t1 = clock::now();
    std::visit([](const auto& m) { plmap::validate_map_structure(m); }, map);
    const auto t2 = clock::now();
    load = std::min(load, std::chrono::duration<double>(t1 - t0).count());
    validate = std::min(validate, std::chrono::duration<double>(t2 - t1).count());
    std::visit([&](const auto& m) { regions = m.region_count(), nodes = m.node_count(); }, map);
  }
  fmt::print("{}: {} nodes, {} regions\n", path, nodes, regions);
  fmt::print("load (incl. validation): {:.3f} s, validation alone: {:.4f} s ({:.1f} % of the load)\n",
             load, validate, 100.0 * validate / load);
  return 0;
}
