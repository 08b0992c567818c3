// `plmap eval MAP --random N`: evaluates the map at random points of S1 and reports the
// throughput and the fraction of points that lie in the domain D of the map.

#include "cli_common.hpp"

#include <plmap/core/evaluation.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/strategies/point_locator_registry.hpp>
#include <plmap/verify/generators/random_surfaces.hpp>

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace plmap::cli {

namespace {

struct EvalOptions {
  std::string file;
  std::size_t points = 100000;
  std::uint64_t seed = 1;
  std::string locator;  // empty: the default of the map's dimension
  unsigned threads = 0;
  int repeat = 1;
  bool json = false;
};

/// N points uniformly distributed over S1 by measure: the element by its length/area (inverse
/// CDF on the running sum), the point uniformly on it.
template <int d>
std::vector<SurfacePoint<d>> random_points(const Surface<d>& s, std::size_t n,
                                           std::uint64_t seed) {
  generators::Rng rng(seed);
  std::vector<double> cumulative(static_cast<std::size_t>(s.element_count()));
  double total = 0.0;
  for (Index t = 0; t < s.element_count(); ++t)
    cumulative[static_cast<std::size_t>(t)] = total += s.element_measure(t);
  std::vector<SurfacePoint<d>> points(n);
  for (auto& p : points) {
    const double u = generators::uniform_unit(rng) * total;
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
    p.element = static_cast<Index>(std::min<std::ptrdiff_t>(it - cumulative.begin(),
                                                             s.element_count() - 1));
    if constexpr (d == 1) {
      p.local(0) = generators::uniform_unit(rng);
    } else {
      double a = generators::uniform_unit(rng), b = generators::uniform_unit(rng);
      if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;  // fold the square onto the triangle
      p.local = LocalPoint<2>(a, b);
    }
  }
  return points;
}

template <int d>
Json evaluate_random(const PlMap<d>& map, const EvalOptions& o) {
  const std::string locator_name =
      o.locator.empty() ? std::string(default_point_locator_name<d>()) : o.locator;
  const std::vector<SurfacePoint<d>> points = random_points(map.domain(), o.points, o.seed);
  std::vector<Evaluation<d>> out(points.size());
  PointLocatorOptions locator_options;
  locator_options.seed = o.seed;
  double best_seconds = std::numeric_limits<double>::infinity();
  with_point_locator<d>(
      locator_name,
      [&](auto& locator) {
        prepare_point_locator<d>(locator, map);  // tables are set-up, not evaluation time
        for (int r = 0; r < o.repeat; ++r) {
          const auto start = std::chrono::steady_clock::now();
          evaluate_batch<d>(map, points, out, locator, o.threads);
          const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
          best_seconds = std::min(best_seconds, elapsed.count());
        }
      },
      locator_options);
  const auto found = static_cast<std::size_t>(
      std::count_if(out.begin(), out.end(), [](const Evaluation<d>& e) { return e.in_domain; }));
  Json j;
  j["file"] = o.file;
  j["dimension"] = d;
  j["locator"] = locator_name;
  j["threads"] = resolved_threads(o.threads);
  j["seed"] = o.seed;
  j["points"] = points.size();
  j["found"] = found;
  j["fraction_found"] = points.empty() ? 0.0 : static_cast<double>(found) / points.size();
  j["repeat"] = o.repeat;
  j["seconds"] = best_seconds;  // the fastest repetition
  j["evaluations_per_second"] =
      best_seconds > 0 ? static_cast<double>(points.size()) / best_seconds : 0.0;
  return j;
}

int run_eval(const EvalOptions& o) {
  require_readable_file(o.file);
  const Json j =
      std::visit([&](const auto& map) { return evaluate_random(map, o); }, load_map(o.file));
  print_result(j, o.json);
  return exit_code::success;
}

}  // namespace

void register_eval(CLI::App& app, Action& action) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Evaluate a map at random points of S1 (uniform by length/area, reproducible from the "
      "seed) and report evaluations per second and the fraction of points found in the domain "
      "of the map.");
  cmd->add_option("MAP", o->file, "Map file (.plmap)")->required();
  // The points and their results take about 100 bytes each: more than 10^9 cannot be meant.
  cmd->add_option("--random,-n", o->points, "Number of random query points (at most 10^9)")
      ->check(CLI::Range(std::size_t{0}, std::size_t{1'000'000'000}))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the query points and of randomized locators")
      ->capture_default_str();
  // The list comes from the registry, so a newly registered strategy shows up here.
  auto names = [](auto list) {
    std::string text;
    for (std::size_t i = 0; i < list.size(); ++i)
      text += std::string(i == 0 ? "" : ", ") + std::string(list[i]) + (i == 0 ? " (default)" : "");
    return text;
  };
  cmd->add_option("--locator", o->locator,
                  "Point-location strategy: " + names(point_locator_names<2>()) +
                      " for triangle surfaces; " + names(point_locator_names<1>()) + " for curves");
  add_threads_option(*cmd, o->threads, "Threads");
  cmd->add_option("--repeat", o->repeat, "Time this many runs and report the fastest")
      ->check(positive_number)
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  cmd->callback([o, &action] { action = [o] { return run_eval(*o); }; });
}

}  // namespace plmap::cli
