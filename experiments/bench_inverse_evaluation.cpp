// Forward against inverse evaluation (docs/benchmarks.md, "Inverse evaluation").
//
// Builds a map by normal projection of S1 onto S2 (or loads one), then measures, single-threaded
// and in process CPU time, the cost per query of
// - forward evaluation Xi(x): evaluate_batch with the default locator (brown-faigle, d = 2;
//   bisection, d = 1) and with cell-grid, at random points of S1 (uniform per element);
// - inverse evaluation Xi^{-1}(y): inverse_evaluate_batch at random points of S2 (uniform per
//   element) and at the images Xi(x) of the forward queries (all in Xi(D));
// - building the InverseIndex (once, wall time) and its memory.
// Every timing is the best of three runs over the whole query set.
//
// Usage: bench_inverse_evaluation --s1 A.off --s2 B.off [--queries N] [--json out.json]
//        bench_inverse_evaluation --map M.plmap [--queries N] [--json out.json]

#include "peers/measurement.hpp"

#include <plmap/construct/project.hpp>
#include <plmap/core/evaluation.hpp>
#include <plmap/core/inverse_evaluation.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/io/surface_reader.hpp>
#include <plmap/strategies/point_locator_registry.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <ctime>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace plmap;
using Json = nlohmann::ordered_json;

/// Best of three runs of work(), in CPU nanoseconds per query.
template <class Work>
double ns_per_query(std::size_t queries, Work&& work) {
  double best = 1e300;
  for (int rep = 0; rep < 3; ++rep) {
    const double t0 = peers::process_cpu_seconds();
    work();
    best = std::min(best, peers::process_cpu_seconds() - t0);
  }
  return 1e9 * best / double(queries);
}

template <int d>
std::vector<SurfacePoint<d>> random_points(const Surface<d>& s, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<Index> element(0, s.element_count() - 1);
  std::vector<SurfacePoint<d>> q(n);
  for (auto& p : q) {
    p.element = element(rng);
    if constexpr (d == 1) {
      p.local(0) = u(rng);
    } else {
      double x = u(rng), y = u(rng);
      if (x + y > 1) x = 1 - x, y = 1 - y;
      p.local = LocalPoint<2>(x, y);
    }
  }
  return q;
}

template <int d>
Json run(const PlMap<d>& map, std::size_t n) {
  Json j;
  j["s1_elements"] = map.domain().element_count();
  j["s2_elements"] = map.target().element_count();
  j["regions"] = map.region_count();
  j["regions_per_s1_element"] = double(map.region_count()) / map.domain().element_count();
  j["regions_per_s2_element"] = double(map.region_count()) / map.target().element_count();
  j["queries"] = n;

  const auto xs = random_points(map.domain(), n, 1);
  const auto ys = random_points(map.target(), n, 2);
  std::vector<Evaluation<d>> forward(n);
  std::vector<InverseEvaluation<d>> inverse(n);

  std::vector<std::string> locators{std::string(default_point_locator_name<d>())};
  if constexpr (d == 2) locators.push_back("cell-grid");
  for (const auto& name : locators)
    with_point_locator<d>(name, [&](auto& locator) {
      prepare_point_locator<d>(locator, map);
      j["forward_ns_" + name] = ns_per_query(n, [&] { evaluate_batch<d>(map, xs, forward, locator, 1); });
    });
  std::size_t found = 0;
  for (const auto& e : forward) found += e.in_domain;
  j["forward_fraction_in_domain"] = double(found) / double(n);

  const double t0 = peers::now_seconds();
  const InverseIndex<d> index(map);
  j["inverse_index_build_seconds"] = peers::now_seconds() - t0;
  j["inverse_index_bytes"] = index.memory_bytes();
  j["map_bytes"] = map.memory_bytes();

  j["inverse_ns_random_s2"] = ns_per_query(n, [&] { inverse_evaluate_batch<d>(index, ys, inverse, 1); });
  found = 0;
  for (const auto& e : inverse) found += e.in_image;
  j["inverse_fraction_in_image_random_s2"] = double(found) / double(n);

  std::vector<SurfacePoint<d>> images;
  for (const auto& e : forward)
    if (e.in_domain) images.push_back(e.image);
  std::vector<InverseEvaluation<d>> back(images.size());
  j["inverse_ns_images"] = ns_per_query(images.size(), [&] { inverse_evaluate_batch<d>(index, images, back, 1); });
  found = 0;
  for (const auto& e : back) found += e.in_image;
  j["inverse_fraction_found_images"] = images.empty() ? 0.0 : double(found) / double(images.size());
  j["inverse_over_forward"] = j["inverse_ns_random_s2"].get<double>() / j["forward_ns_" + locators.front()].get<double>();
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  std::string s1_path, s2_path, map_path, json_path;
  std::size_t queries = 1u << 20;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw plmap::Error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--s1") s1_path = next();
    else if (a == "--s2") s2_path = next();
    else if (a == "--map") map_path = next();
    else if (a == "--json") json_path = next();
    else if (a == "--queries") queries = std::stoul(next());
    else {
      fmt::print(stderr, "usage: bench_inverse_evaluation (--s1 A --s2 B | --map M) [--queries N] [--json F]\n");
      return 64;
    }
  }
  try {
    Json result;
    if (!map_path.empty()) {
      result["map"] = map_path;
      result.update(std::visit([&](const auto& m) { return run(m, queries); }, plmap::load_map(map_path)));
    } else if (!s1_path.empty() && !s2_path.empty()) {
      auto s1 = std::make_shared<const plmap::Surface<2>>(plmap::read_surface<2>(s1_path));
      auto s2 = std::make_shared<const plmap::Surface<2>>(plmap::read_surface<2>(s2_path));
      const double t0 = peers::now_seconds();
      const auto projected = plmap::project<2>(s1, s2);
      result["s1"] = s1_path;
      result["s2"] = s2_path;
      result["projection_seconds"] = peers::now_seconds() - t0;
      result.update(run(projected.map, queries));
    } else {
      fmt::print(stderr, "usage: bench_inverse_evaluation (--s1 A --s2 B | --map M) [--queries N] [--json F]\n");
      return 64;
    }
    const std::string text = result.dump(2);
    fmt::print("{}\n", text);
    if (!json_path.empty()) std::ofstream(json_path) << text << "\n";
  } catch (const std::exception& e) {
    fmt::print(stderr, "bench_inverse_evaluation: {}\n", e.what());
    return 2;
  }
  return 0;
}
