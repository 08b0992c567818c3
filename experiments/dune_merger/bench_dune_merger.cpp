// ContactMerge (dune-grid-glue 2.9) against plmap::dune::PlmapMerge through the same Dune
// interface (Merger::build, then the intersection list), in the same process, on the contact pairs
// of the peer benchmark (experiments/peers/inputs.hpp): covered measure on both sides and time.
//
//   bench_dune_merger --case femur --femur femur.off [--repeat 3] [--threads N]
//   bench_dune_merger --case sphere --size 5 | --case plane --size 20000 | --case circle --size 10000
//
// Prints one JSON object per merger (time = median wall seconds of build() over the repetitions).

#include "peers/dune_contact.hpp"
#include "peers/inputs.hpp"

#include <plmap/core/parallel_ranges.hpp>
#include <plmap/dune/plmap_merge.hh>

#include <dune/grid-glue/merging/contactmerge.hh>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

template <int d>
struct DuneInput {
  plmap::peers::DuneSimplices<d> s1, s2;
};

struct Outcome {
  std::string merger;
  double seconds = 0.0;
  double covered1 = 0.0, covered2 = 0.0;
  std::size_t intersections = 0;
  std::string error;
};

template <int d>
Outcome run(const std::string& name, Dune::GridGlue::Merger<double, d, d, d + 1>& merger, const DuneInput<d>& in,
            const plmap::peers::SurfacePair<d>& pair, int repeat) {
  Outcome out;
  out.merger = name;
  std::vector<double> times;
  for (int r = 0; r < repeat; ++r) {
    merger.clear();
    std::ostringstream quiet;  // StandardMerge reports on std::cout
    auto* old = std::cout.rdbuf(quiet.rdbuf());
    const auto start = std::chrono::steady_clock::now();
    try {
      merger.build(in.s1.coords, in.s1.cells, in.s1.types, in.s2.coords, in.s2.cells, in.s2.types);
    } catch (const std::exception& e) {
      out.error = e.what();
    } catch (...) {
      out.error = "unknown exception";
    }
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    std::cout.rdbuf(old);
    if (!out.error.empty()) return out;
  }
  std::sort(times.begin(), times.end());
  out.seconds = times[times.size() / 2];
  out.intersections = merger.intersectionList()->size();
  const auto covered = plmap::peers::overlap_measures(merger, pair);
  out.covered1 = covered.s1;
  out.covered2 = covered.s2;
  return out;
}

template <int d>
void compare(const plmap::peers::SurfacePair<d>& pair, int repeat, unsigned threads) {
  const DuneInput<d> in{plmap::peers::to_dune_simplices(pair.s1), plmap::peers::to_dune_simplices(pair.s2)};
  std::vector<Outcome> outcomes;
  {
    Dune::GridGlue::ContactMerge<d + 1, double> contact;
    outcomes.push_back(run<d>("ContactMerge", contact, in, pair, repeat));
  }
  // ContactMerge's normal field (the default, so that both project along the same rays) on one
  // thread and on `threads`, and plmap's own measure-weighted normals.
  struct Variant {
    unsigned threads;
    plmap::dune::NormalAveraging averaging;
    const char* label;
  };
  for (const Variant& v : {Variant{1u, plmap::dune::NormalAveraging::unit_element_normals, "unit normals"},
                           Variant{threads, plmap::dune::NormalAveraging::unit_element_normals, "unit normals"},
                           Variant{threads, plmap::dune::NormalAveraging::measure_weighted, "weighted normals"}}) {
    plmap::dune::PlmapMergeOptions<d + 1> options;
    options.projection.threads = v.threads;
    options.averaging = v.averaging;
    plmap::dune::PlmapMerge<d + 1> plmap_merger(options);
    outcomes.push_back(run<d>(fmt::format("PlmapMerge {}, threads={}", v.label, v.threads), plmap_merger, in, pair, repeat));
  }
  const double s1 = pair.s1.measure(), s2 = pair.s2.measure();
  for (const auto& o : outcomes)
    fmt::print(
        "{{\"case\": \"{}\", \"s1_elements\": {}, \"s2_elements\": {}, \"merger\": \"{}\", \"seconds\": {:.4f}, "
        "\"intersections\": {}, \"covered_s1\": {:.6f}, \"covered_s2\": {:.6f}, \"exact_s1\": {:.6f}, "
        "\"time_vs_contactmerge\": {:.3f}, \"error\": \"{}\"}}\n",
        pair.label, pair.s1.cells.size(), pair.s2.cells.size(), o.merger, o.seconds, o.intersections,
        o.covered1 / s1, o.covered2 / s2, pair.exact_overlap / s1,
        outcomes.front().seconds > 0 ? o.seconds / outcomes.front().seconds : 0.0, o.error);
}

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr,
               "bench_dune_merger: %s\nusage: bench_dune_merger --case femur|femur-offset|sphere|plane|circle "
               "[--femur FILE.off] [--size N] [--repeat R] [--threads T] [--seed S]\n",
               why.c_str());
  std::exit(64);
}

}  // namespace

int main(int argc, char** argv) {
  std::string which, femur;
  long size = 0;
  int repeat = 3;
  unsigned threads = 0;
  std::uint64_t seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) usage("missing value after " + a);
    const std::string v = argv[++i];
    if (a == "--case") which = v;
    else if (a == "--femur") femur = v;
    else if (a == "--size") size = std::stol(v);
    else if (a == "--repeat") repeat = std::max(1, std::stoi(v));
    else if (a == "--threads") threads = static_cast<unsigned>(std::stoul(v));
    else if (a == "--seed") seed = std::stoull(v);
    else usage("unknown option " + a);
  }
  threads = plmap::resolve_thread_count(threads);  // 0: the CPUs this process may run on
  try {
    if (which == "femur" || which == "femur-offset") {
      if (femur.empty()) usage("--case femur needs --femur FILE.off");
      compare<2>(plmap::peers::femur_pair(femur, which == "femur", seed), repeat, threads);
    } else if (which == "sphere") {
      compare<2>(plmap::peers::concentric_spheres(size ? static_cast<int>(size) : 4, seed), repeat, threads);
    } else if (which == "plane") {
      compare<2>(plmap::peers::facing_planes(size ? size : 20000, seed), repeat, threads);
    } else if (which == "circle") {
      compare<1>(plmap::peers::concentric_circles(size ? size : 10000, seed), repeat, threads);
    } else {
      usage("unknown or missing --case '" + which + "'");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_dune_merger: %s\n", e.what());
    return 2;
  }
}
