// Evaluation throughput of the point locators (docs/benchmarks.md, "Evaluation throughput").
//
// For maps whose elements carry about 10, 100 and 1000 regions, and for a femur-like map
// (PSurface's femur case: about 500 coarse triangles and 8,900 graph nodes), measures
// evaluations per second of Xi for every registered locator, on one thread and on all threads,
// and the "floor": the cost of the same query stream when the region is already known (one
// stored affine map plus the world position on S2). Prints a markdown table, fits the growth
// exponent of (locator - floor) time with the number of regions per element, reports the memory
// of the compact form per node and per region (PSurface 2.0 itself is measured in the same run
// by experiments/psurface_eval). Locators with per-map tables (cell-grid, bucket-walk) are prepared before
// the timed loop; their build time and bytes per region are reported apart from the map's.
// Optionally writes everything as JSON.
//
// Usage: bench_point_location [--queries N] [--femur path/to/femur.off] [--json out.json]
//                             [--quick] [--cells-per-region X] [--only LOCATOR] [--femur-only]
//                             [--map FILE.plmap]...
//   --cells-per-region  grid density of cell-grid (default: CellGridOptions's)
//   --only              measure only this locator (and the floor)
//   --femur-only        skip the growth series (no growth exponents then)
//   --map FILE.plmap    also measure a map from a file (d = 2 and covering S1, e.g. one made by
//                       `plmap simplify`); repeatable

#include "evaluation_cases/evaluation_cases.hpp"

#include <plmap/verify/generators/subdivision_maps.hpp>

#include <plmap/core/evaluation.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/parallel_ranges.hpp>
#include <plmap/strategies/point_locator_registry.hpp>


#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using namespace plmap;
using Json = nlohmann::json;

/// PSurface 2.0's evaluation throughput on its femur map, as quoted in issue 2 (other machine).
constexpr double psurface_femur_evals_per_cpu_s = 2.3e6;

// ---- clocks ------------------------------------------------------------------------------------

double seconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Timing {
  double wall = 0;  ///< seconds per query, wall clock
  double cpu = 0;   ///< seconds per query, CPU time of the process (all threads)
};

/// Runs work(count) (which processes the first `count` queries) until the measurement is long
/// enough to trust, and returns the best of three repetitions per query. CPU time makes the
/// single-thread figures robust against other processes on a shared machine.
template <class Work>
Timing measure(Work&& work, std::size_t available, double target_seconds) {
  std::size_t count = std::min<std::size_t>(available, 4096);
  const double t0 = seconds(CLOCK_PROCESS_CPUTIME_ID);
  work(count);
  const double probe = std::max(1e-9, (seconds(CLOCK_PROCESS_CPUTIME_ID) - t0) / double(count));
  count = std::clamp<std::size_t>(std::size_t(target_seconds / probe), 4096, available);
  Timing best{1e30, 1e30};
  for (int rep = 0; rep < 3; ++rep) {
    const double w0 = seconds(CLOCK_MONOTONIC), c0 = seconds(CLOCK_PROCESS_CPUTIME_ID);
    work(count);
    const double w1 = seconds(CLOCK_MONOTONIC), c1 = seconds(CLOCK_PROCESS_CPUTIME_ID);
    best.wall = std::min(best.wall, (w1 - w0) / double(count));
    best.cpu = std::min(best.cpu, (c1 - c0) / double(count));
  }
  return best;
}

// ---- maps --------------------------------------------------------------------------------------

struct Case {
  std::string name;
  std::shared_ptr<const PlMap<2>> map;
};

// ---- one case ----------------------------------------------------------------------------------

Json run_case(const Case& c, std::size_t query_count, unsigned all_threads, double target_seconds,
             const point_location::CellGridOptions& cell_grid_options, const std::string& only) {
  const PlMap<2>& map = *c.map;
  const auto& s1 = map.domain();
  const auto queries = bench::random_queries(s1, query_count, 12345);
  std::vector<Evaluation<2>> out(queries.size());

  // The true regions, for the floor (and a check that every locator finds every query).
  std::vector<Index> region(queries.size());
  {
    std::vector<Evaluation<2>> ref(queries.size());
    evaluate_batch<2>(map, queries, ref, point_location::StraightWalk{}, all_threads);
    for (std::size_t i = 0; i < queries.size(); ++i) {
      if (!ref[i].in_domain) throw Error("benchmark query outside D; the maps cover S1");
      region[i] = ref[i].region;
    }
  }

  auto floor_work = [&](unsigned threads) {
    return [&, threads](std::size_t count) {
      auto chunk = [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) out[i] = evaluate_in_region(map, region[i], queries[i].local);
      };
      if (threads <= 1) return chunk(0, count);
      std::vector<std::jthread> pool;
      const std::size_t step = (count + threads - 1) / threads;
      for (unsigned k = 0; k < threads; ++k)
        pool.emplace_back(chunk, std::min(count, k * step), std::min(count, (k + 1) * step));
    };
  };

  const double regions_per_element = double(map.region_count()) / s1.element_count();
  const double nodes_per_element = double(map.node_count()) / s1.element_count();
  Json result = {{"case", c.name},
                 {"elements", s1.element_count()},
                 {"target_elements", map.target().element_count()},
                 {"nodes", map.node_count()},
                 {"regions", map.region_count()},
                 {"regions_per_element", regions_per_element},
                 {"nodes_per_element", nodes_per_element},
                 {"memory_bytes", map.memory_bytes()},
                 {"bytes_per_node", double(map.memory_bytes()) / map.node_count()},
                 {"bytes_per_region", double(map.memory_bytes()) / map.region_count()}};
  {
    // memory_bytes() counts capacity; the sizes show what the data needs, split into the
    // per-node arrays (the graph) and the per-region arrays (the query form).
    const auto& m = map.data();
    auto b = [](const auto& v) { return double(v.size() * sizeof(v[0])); };
    const double node_part = b(m.node_begin) + b(m.node_position) + b(m.node_type) +
                             b(m.node_location) + b(m.node_image_element) +
                             b(m.node_image_local) + b(m.node_target) +
                             b(m.neighbor_begin) + b(m.neighbor) + b(m.neighbor_edge_kind) +
                             b(m.edge_node_begin) + b(m.edge_node);
    const double region_part = b(m.region_begin) + b(m.region_corners) + b(m.region_neighbors) +
                               b(m.region_target) + b(m.region_map) + b(m.start_region);
    result["size_bytes_graph_per_node"] = node_part / map.node_count();
    result["size_bytes_regions_per_region"] = region_part / map.region_count();
    result["size_bytes_total_per_node"] = (node_part + region_part) / map.node_count();
  }

  const Timing floor1 = measure(floor_work(1), queries.size(), target_seconds);
  const Timing floor_all = measure(floor_work(all_threads), queries.size(), target_seconds);
  result["floor"] = {{"evals_per_cpu_s_1thread", 1 / floor1.cpu},
                     {"evals_per_s_all_threads", 1 / floor_all.wall},
                     {"evals_per_cpu_s_all_threads", 1 / floor_all.cpu}};

  for (const auto name : point_locator_names<2>()) {
    if (!only.empty() && name != only) continue;
    Timing one, all;
    double prepare_seconds = 0;
    std::size_t locator_bytes = 0;
    Json locator_extra = Json::object();
    with_point_locator<2>(name, [&](auto& locator) {
      // Locators with per-map tables build them once, outside the timed loop (evaluate_batch
      // copies the locator per call; the copies share a prepared table).
      // The registry builds cell-grid with default options; --cells-per-region overrides them.
      if constexpr (std::is_same_v<std::decay_t<decltype(locator)>, point_location::CellGridLocator>)
        locator = point_location::CellGridLocator(cell_grid_options);
      if constexpr (requires { locator.prepare(map); }) {
        const double t0 = seconds(CLOCK_MONOTONIC);
        locator.prepare(map);
        prepare_seconds = seconds(CLOCK_MONOTONIC) - t0;
      }
      if constexpr (requires { locator.memory_bytes(); }) locator_bytes = locator.memory_bytes();
      if constexpr (requires { locator.grid()->memory(); }) {
        const auto mem = locator.grid()->memory();
        locator_extra = {{"cells", mem.cells},
                         {"whole_cells", mem.whole_cells},
                         {"split_cells", mem.split_cells},
                         {"whole_area", mem.whole_area},
                         {"split_area", mem.split_area},
                         {"region_record_bytes", mem.region_record_bytes},
                         {"cell_bytes", mem.cell_bytes},
                         {"element_bytes", mem.element_bytes}};
      }
      auto work = [&](unsigned threads) {
        return [&, threads](std::size_t count) {
          evaluate_batch<2>(map, std::span(queries).first(count), std::span(out).first(count),
                            locator, threads);
        };
      };
      one = measure(work(1), queries.size(), target_seconds);
      all = measure(work(all_threads), queries.size(), target_seconds);
      // Correctness of what was timed: every query was found, in a region containing it.
      for (std::size_t i = 0; i < std::min<std::size_t>(queries.size(), 4096); ++i)
        if (!out[i].in_domain) throw Error(fmt::format("{} lost query {}", name, i));
    });
    result["locators"][std::string(name)] = {
        {"evals_per_cpu_s_1thread", 1 / one.cpu},
        {"evals_per_s_all_threads", 1 / all.wall},
        {"evals_per_cpu_s_all_threads", 1 / all.cpu},
        {"ratio_to_floor_1thread", one.cpu / floor1.cpu},
        {"ratio_to_psurface_femur_1thread", 1 / one.cpu / psurface_femur_evals_per_cpu_s},
        {"seconds_above_floor_1thread", one.cpu - floor1.cpu},
        {"prepare_seconds", prepare_seconds},
        {"locator_bytes", locator_bytes},
        {"locator_bytes_per_region", double(locator_bytes) / map.region_count()},
        {"tables", locator_extra}};
  }
  return result;
}

/// Least-squares slope of log(y) against log(x).
double fit_exponent(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double lx = std::log(x[i]), ly = std::log(std::max(y[i], 1e-15));
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t query_count = 1 << 20;
  std::string femur_path, json_path;
  std::vector<std::string> map_paths;
  bool quick = false, femur_only = false;
  std::string only;
  point_location::CellGridOptions cell_grid_options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--queries" && i + 1 < argc) query_count = std::stoul(argv[++i]);
    else if (a == "--cells-per-region" && i + 1 < argc) cell_grid_options.cells_per_region = std::stod(argv[++i]);
    else if (a == "--only" && i + 1 < argc) only = argv[++i];
    else if (a == "--femur-only") femur_only = true;
    else if (a == "--femur" && i + 1 < argc) femur_path = argv[++i];
    else if (a == "--map" && i + 1 < argc) map_paths.emplace_back(argv[++i]);
    else if (a == "--json" && i + 1 < argc) json_path = argv[++i];
    else if (a == "--quick") quick = true;
    else {
      fmt::print(stderr, "usage: {} [--queries N] [--femur femur.off] [--json out.json] [--quick]\n"
                 "       [--cells-per-region X] [--only LOCATOR] [--femur-only] [--map FILE.plmap]...\n", argv[0]);
      return 2;
    }
  }
  const double target_seconds = quick ? 0.05 : 0.4;
  const unsigned all_threads = plmap::available_threads();  // the CPUs this process may run on

  try {
    // Growth series: k x k sub-triangles per element, S1 sized so that every map has about
    // 50,000 regions (similar cache footprint).
    std::vector<int> ks = quick ? std::vector<int>{3, 10} : std::vector<int>{3, 6, 10, 18, 32};
    std::vector<Case> cases;
    if (femur_only) ks.clear();
    for (int k : ks) {
      const int grid = std::max(3, int(std::lround(std::sqrt(50000.0 / (2.0 * k * k)))));
      cases.push_back({fmt::format("grid{}x{}, {}x{} refinement", grid, grid, k, k),
                       generators::subdivision_map(generators::bumpy_grid(grid), k, 0.2, 100 + k).map});
    }
    const std::size_t growth_cases = cases.size();
    if (!femur_path.empty()) {
      const auto femur = bench::coarse_femur(femur_path, 500);
      for (int k : {4, 5})
        cases.push_back({fmt::format("femur {} tris, {}x{} refinement", femur->element_count(), k, k),
                         generators::subdivision_map(femur, k, 0.2, 200 + k).map});
    }
    for (const auto& path : map_paths)
      cases.push_back({std::filesystem::path(path).filename().string(),
                       std::make_shared<const PlMap<2>>(load_map<2>(path))});

    if (cases.empty()) throw Error("--femur-only needs --femur path/to/femur.off or --map FILE.plmap");
    Json report;
    report["threads"] = all_threads;
    report["queries"] = query_count;
    for (const auto& c : cases) {
      fmt::print(stderr, "measuring {} ...\n", c.name);
      report["cases"].push_back(run_case(c, query_count, all_threads, target_seconds, cell_grid_options, only));
    }
    // Growth exponents of the time above the floor against regions per element.
    for (const auto name : point_locator_names<2>()) {
      if (growth_cases < 2 || (!only.empty() && name != only)) continue;
      std::vector<double> x, y;
      for (std::size_t i = 0; i < growth_cases; ++i) {
        const Json& r = report["cases"][i];
        x.push_back(r["regions_per_element"].get<double>());
        y.push_back(r["locators"][std::string(name)]["seconds_above_floor_1thread"].get<double>());
      }
      report["growth_exponent"][std::string(name)] = fit_exponent(x, y);
    }

    // ---- markdown ----
    fmt::print("| map | regions/elem | nodes | locator | Meval/CPU-s (1 thr) | Meval/s ({} thr) | "
               "ratio to floor | x PSurface 2.3 M/s | locator B/region |\n", all_threads);
    fmt::print("|---|---:|---:|---|---:|---:|---:|---:|---:|\n");
    for (const auto& r : report["cases"]) {
      const auto& f = r["floor"];
      fmt::print("| {} | {:.0f} | {} | floor (region known) | {:.2f} | {:.2f} | 1.00 | | |\n",
                 r["case"].get<std::string>(), r["regions_per_element"].get<double>(),
                 r["nodes"].get<long>(), f["evals_per_cpu_s_1thread"].get<double>() / 1e6,
                 f["evals_per_s_all_threads"].get<double>() / 1e6);
      for (const auto& [name, l] : r["locators"].items())
        fmt::print("| | | | {} | {:.2f} | {:.2f} | {:.2f} | {:.1f} | {:.1f} |\n", name,
                   l["evals_per_cpu_s_1thread"].get<double>() / 1e6,
                   l["evals_per_s_all_threads"].get<double>() / 1e6,
                   l["ratio_to_floor_1thread"].get<double>(),
                   l["ratio_to_psurface_femur_1thread"].get<double>(),
                   l["locator_bytes_per_region"].get<double>());
    }
    fmt::print("\ncell-grid tables: share of element area in whole cells (answered by the look-up "
               "alone) and in split cells (one orient2d), build time\n");
    for (const auto& r : report["cases"]) {
      if (!r["locators"].contains("cell-grid")) continue;
      const auto& l = r["locators"]["cell-grid"];
      fmt::print("- {}: whole {:.1f} %, split {:.1f} %, {} cells ({:.1f} per region), built in {:.1f} ms\n",
                 r["case"].get<std::string>(), 100 * l["tables"]["whole_area"].get<double>(),
                 100 * l["tables"]["split_area"].get<double>(),
                 l["tables"]["cells"].get<long>(),
                 l["tables"]["cells"].get<double>() / r["regions"].get<double>(),
                 1e3 * l["prepare_seconds"].get<double>());
    }
    fmt::print("\nGrowth exponent of (locator - floor) CPU time vs regions per element:");
    if (report.contains("growth_exponent"))
      for (const auto& [name, e] : report["growth_exponent"].items())
        fmt::print(" {} {:.2f};", name, e.get<double>());
    fmt::print("\n\n| map | memory_bytes() | per node | per region | by size: graph/node | "
               "regions/region | total/node |\n|---|---:|---:|---:|---:|---:|---:|\n");
    for (const auto& r : report["cases"])
      fmt::print("| {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} |\n",
                 r["case"].get<std::string>(), r["memory_bytes"].get<long>(),
                 r["bytes_per_node"].get<double>(), r["bytes_per_region"].get<double>(),
                 r["size_bytes_graph_per_node"].get<double>(),
                 r["size_bytes_regions_per_region"].get<double>(),
                 r["size_bytes_total_per_node"].get<double>());
    if (!json_path.empty()) std::ofstream(json_path) << report.dump(2) << "\n";
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_point_location: {}\n", e.what());
    return 1;
  }
  return 0;
}
