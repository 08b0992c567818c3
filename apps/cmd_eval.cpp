// `plmap eval MAP --random N`: evaluates the map (or its inverse, --inverse) at random points of
// S1 (S2) and reports the throughput and the fraction of points that lie in the domain D of the
// map (in its image Xi(D)). `plmap eval MAP --points FILE` evaluates at the user's points
// (eval_points.cpp).

#include "cli_common.hpp"
#include "progress_bar.hpp"
#include "eval_points.hpp"

#include <plmap/core/evaluation.hpp>
#include <plmap/core/inverse_evaluation.hpp>
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
  bool inverse = false;
  ProgressMode progress = ProgressMode::automatic;
  EvalPointsOptions at_points;  // used when --points is given
};

/// Points uniformly distributed over a surface by measure: the element by its length/area
/// (inverse CDF on the running sum), the point uniformly on it. Drawn batch by batch from one
/// random stream, so the points do not depend on the batch size.
template <int d>
class RandomPoints {
 public:
  RandomPoints(const Surface<d>& s, std::uint64_t seed) : s_(s), rng_(seed), cumulative_(static_cast<std::size_t>(s.element_count())) {
    for (Index t = 0; t < s.element_count(); ++t) cumulative_[static_cast<std::size_t>(t)] = total_ += s.element_measure(t);
  }

  /// The next n points into `points` (resized to n).
  void next(std::size_t n, std::vector<SurfacePoint<d>>& points) {
    points.resize(n);
    for (auto& p : points) {
      const double u = generators::uniform_unit(rng_) * total_;
      const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), u);
      p.element = static_cast<Index>(std::min<std::ptrdiff_t>(it - cumulative_.begin(), s_.element_count() - 1));
      if constexpr (d == 1) {
        p.local(0) = generators::uniform_unit(rng_);
      } else {
        double a = generators::uniform_unit(rng_), b = generators::uniform_unit(rng_);
        if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;  // fold the square onto the triangle
        p.local = LocalPoint<2>(a, b);
      }
    }
  }

 private:
  const Surface<d>& s_;
  generators::Rng rng_;
  std::vector<double> cumulative_;
  double total_ = 0.0;
};

/// Points are drawn and evaluated in batches of this many: a point and its result take about 110
/// bytes, so `-n 1e9` held all of them at once needed ~110 GB and ended in "out of memory".
constexpr std::size_t eval_batch_points = std::size_t{1} << 20;

template <int d>
Json evaluate_random(const PlMap<d>& map, const EvalOptions& o) {
  const std::string locator_name =
      o.locator.empty() ? std::string(default_point_locator_name<d>()) : o.locator;
  RandomPoints<d> sample(o.inverse ? map.target() : map.domain(), o.seed);
  std::vector<SurfacePoint<d>> points;
  std::size_t found = 0;
  double seconds = 0.0;  // the fastest repetition of each batch, added up
  // Every batch: its points drawn (not timed), evaluated o.repeat times (timed), its hits counted.
  auto in_batches = [&](auto&& evaluate, auto&& count) {
    for (std::size_t done = 0; done < o.points; done += points.size()) {
      sample.next(std::min(eval_batch_points, o.points - done), points);
      double best = std::numeric_limits<double>::infinity();
      for (int r = 0; r < o.repeat; ++r) {
        const auto start = std::chrono::steady_clock::now();
        evaluate();
        const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
        best = std::min(best, elapsed.count());
      }
      seconds += best;
      found += count();
    }
  };
  double index_seconds = 0.0;
  if (o.inverse) {
    // The index is set-up, like a locator's tables: timed apart.
    const auto start = std::chrono::steady_clock::now();
    const InverseIndex<d> index(map);
    index_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<InverseEvaluation<d>> out;
    in_batches(
        [&] {
          out.resize(points.size());
          inverse_evaluate_batch<d>(index, points, out, o.threads);
        },
        [&] { return static_cast<std::size_t>(std::count_if(out.begin(), out.end(), [](const auto& e) { return e.in_image; })); });
  } else {
    std::vector<Evaluation<d>> out;
    PointLocatorOptions locator_options;
    locator_options.seed = o.seed;
    with_point_locator<d>(
        locator_name,
        [&](auto& locator) {
          prepare_point_locator<d>(locator, map);  // tables are set-up, not evaluation time
          in_batches(
              [&] {
                out.resize(points.size());
                evaluate_batch<d>(map, points, out, locator, o.threads);
              },
              [&] { return static_cast<std::size_t>(std::count_if(out.begin(), out.end(), [](const auto& e) { return e.in_domain; })); });
        },
        locator_options);
  }
  Json j;
  j["file"] = o.file;
  j["dimension"] = d;
  j["direction"] = o.inverse ? "inverse" : "forward";
  if (o.inverse)
    j["index_seconds"] = index_seconds;
  else
    j["locator"] = locator_name;
  j["threads"] = resolved_threads(o.threads);
  j["seed"] = o.seed;
  j["points"] = o.points;
  j["found"] = found;
  j["fraction_found"] = o.points == 0 ? 0.0 : static_cast<double>(found) / static_cast<double>(o.points);
  j["repeat"] = o.repeat;
  j["seconds"] = seconds;
  j["evaluations_per_second"] = seconds > 0 ? static_cast<double>(o.points) / seconds : 0.0;
  return j;
}

int run_eval(const EvalOptions& o) {
  if (!o.at_points.points_file.empty()) {
    EvalPointsOptions p = o.at_points;
    p.map_file = o.file;
    p.locator = o.locator;
    p.inverse = o.inverse;
    p.threads = o.threads;
    p.json = o.json;
    p.progress = o.progress;
    return run_eval_points(p);
  }
  require_readable_file(o.file);
  const Json j =
      std::visit([&](const auto& map) { return evaluate_random(map, o); }, load_map_showing_progress(o.file, o.progress));
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
      "of the map; or, with --points, at the points of a file and write the images. --inverse "
      "evaluates the inverse map at points of S2.");
  cmd->add_option("MAP", o->file, "Map file (.plmap)")->required();
  // The points and their results take about 100 bytes each: more than 10^9 cannot be meant.
  auto* random = cmd->add_option("--random,-n", o->points, "Number of random query points (at most 10^9)")
      ->check(CLI::Range(std::size_t{0}, std::size_t{1'000'000'000}))
      ->capture_default_str();
  auto* points_option = cmd->add_option("--points", o->at_points.points_file,
                  "Evaluate at the points in this file instead: a text table (CSV or blanks; rows "
                  "'element,u,v' / 'element,u' or world points 'x,y,z' / 'x,y') or a 2-D .npy array")
      ->excludes(random);
  cmd->add_option("--points-kind", o->at_points.points_kind,
                  "What the --points rows are: local (element and local coordinates) or world (points "
                  "in space, taken to the nearest point of the surface). Default: from the header "
                  "line ('element,...' or 'x,...'), else local")
      ->check(CLI::IsMember({"local", "world"}))
      ->needs(points_option);
  cmd->add_option("-o,--output", o->at_points.output,
                  "With --points: write the results here, format by extension (.csv, .json, .npy, "
                  ".bin = raw float64); default: CSV on stdout")
      ->check(CLI::Validator(
          [](std::string& path) {
            return is_known_points_output(path) ? std::string()
                                                : "unknown output format '" + path + "' (use .csv, .json, .npy or .bin)";
          },
          "FILE"))
      ->needs(points_option);
  cmd->add_flag("--inverse", o->inverse,
                "Evaluate the inverse map S2 -> S1: the points (random or --points) lie on S2");
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
  cmd->add_option("--repeat", o->repeat,
                  "Time this many runs of each batch of 2^20 points and report the fastest of each, added up")
      ->check(positive_number)
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  add_progress_options(*cmd, o->progress);
  cmd->callback([o, &action] { action = [o] { return run_eval(*o); }; });
}

}  // namespace plmap::cli
