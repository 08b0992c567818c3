// The cost of loading a map file and, separately, of the structural validation that loading
// runs (map_validation.hpp), for docs/robustness.md; with --formats also the size and the write
// and load times of the same map in the text (.plmap) and binary (.plmapb) formats, for
// docs/benchmarks.md ("Binary map files").
//
//   bench_map_load MAP [--repeat N] [--formats DIR] [--binary-only 1]
//
// Prints, for the fastest of N repetitions, the seconds of the whole load (parsing, surfaces,
// PlMap constructor and validation) and of validate_map_structure alone, and their ratio. With
// --formats, writes DIR/bench.plmap and DIR/bench.plmapb (removed afterwards) and prints one
// JSON line per format: bytes, write and load seconds (fastest of N); --binary-only 1 skips the
// text format (minutes on the large maps) when only the binary one is being measured.

#include <plmap/core/io/map_file.hpp>
#include <plmap/core/map_validation.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <variant>

namespace {

using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point start) {
  return std::chrono::duration<double>(clock_type::now() - start).count();
}

void compare_formats(const plmap::AnyPlMap& map, const std::filesystem::path& dir, int repeat, bool binary_only) {
  for (const char* extension : {".plmap", ".plmapb"}) {
    if (binary_only && std::string(extension) == ".plmap") continue;
    const std::filesystem::path path = dir / (std::string("bench") + extension);
    double write = std::numeric_limits<double>::infinity();
    double load = std::numeric_limits<double>::infinity();
    bool same = true;
    for (int r = 0; r < repeat; ++r) {
      auto t0 = clock_type::now();
      std::visit([&](const auto& m) { plmap::save_map(path, m); }, map);
      write = std::min(write, seconds_since(t0));
      t0 = clock_type::now();
      const plmap::AnyPlMap back = plmap::load_map(path);
      load = std::min(load, seconds_since(t0));
      std::visit(
          [&](const auto& m) {
            using Map = std::decay_t<decltype(m)>;
            same &= std::get_if<Map>(&back) != nullptr && std::get<Map>(back).data() == m.data();
          },
          map);
    }
    fmt::print("{{\"format\": \"{}\", \"bytes\": {}, \"write_seconds\": {:.3f}, \"load_seconds\": {:.3f}, "
               "\"exact\": {}}}\n",
               extension, std::filesystem::file_size(path), write, load, same);
    std::filesystem::remove(path);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    fmt::print(stderr, "usage: bench_map_load MAP [--repeat N] [--formats DIR] [--binary-only 1]\n");
    return 64;
  }
  const std::string path = argv[1];
  int repeat = 3;
  std::string formats_dir;
  bool binary_only = false;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--repeat") {
      repeat = std::max(1, std::atoi(argv[i + 1]));
    } else if (flag == "--formats") {
      formats_dir = argv[i + 1];
    } else if (flag == "--binary-only") {
      binary_only = std::atoi(argv[i + 1]) != 0;
    } else {
      fmt::print(stderr, "bench_map_load: unknown option '{}'\n", flag);
      return 64;
    }
  }
  double load = std::numeric_limits<double>::infinity();
  double validate = std::numeric_limits<double>::infinity();
  long long regions = 0, nodes = 0;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = clock_type::now();
    const plmap::AnyPlMap map = plmap::load_map(path);
    const auto t1 = clock_type::now();
    std::visit([](const auto& m) { plmap::validate_map_structure(m); }, map);
    load = std::min(load, std::chrono::duration<double>(t1 - t0).count());
    validate = std::min(validate, seconds_since(t1));
    std::visit([&](const auto& m) { regions = m.region_count(), nodes = m.node_count(); }, map);
    if (r + 1 == repeat) {
      fmt::print("{}: {} nodes, {} regions\n", path, nodes, regions);
      fmt::print("load (incl. validation): {:.3f} s, validation alone: {:.4f} s ({:.1f} % of the load)\n",
                 load, validate, 100.0 * validate / load);
      if (!formats_dir.empty()) compare_formats(map, formats_dir, repeat, binary_only);
    }
  }
  return 0;
}
