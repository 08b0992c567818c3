// Running the pipeline of every run and writing the outputs (runner.hpp).

#include "inputs.hpp"
#include "peer_benchmark.hpp"
#include <plmap/verify/generators/subdivision_maps.hpp>

#include <plmap/core/evaluation.hpp>
#include <plmap/core/io/atomic_file.hpp>
#include <plmap/experiment/config_error.hpp>
#include <plmap/experiment/runner.hpp>
#include <plmap/experiment/schema.hpp>
#include <plmap/experiment/summary.hpp>
#include <plmap/experiment/sweep.hpp>
#include <plmap/strategies/point_locator_registry.hpp>
#include <plmap/verify/check.hpp>
#include <plmap/verify/generators/random_maps.hpp>
#ifdef PLMAP_EXPERIMENT_HAS_CONSTRUCT
#include <plmap/construct/project.hpp>
#include <plmap/construct/refine_through_map.hpp>
#include <plmap/construct/simplify.hpp>
#include <plmap/construct/smooth.hpp>
#include <plmap/verify/quality.hpp>
#endif
#include "peers/measurement.hpp"
#include "resolve.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <thread>

namespace plmap::experiment {

namespace {

using Json = nlohmann::ordered_json;
using generators::Rng;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// JSON of a double; non-finite values (an infinite condition number) become null.
Json number(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

/// What one repetition of a run measured.
struct Measurements {
  Json metrics = Json::object();
  std::map<std::string, double> timings;
};

/// One run of the pipeline on a surface of dimension d.
template <int d>
class Pipeline {
 public:
  Pipeline(const ExperimentConfig& config, const RunSpec& run, detail::InputCache& inputs)
      : config_(config), run_(run), inputs_(inputs) {}

  Measurements operator()() {
    Measurements m;
    s1_ = inputs_.surface<d>(run_.input_index, run_.input_parameters);
    m.metrics["input.dimension"] = d;
    m.metrics["input.vertices"] = s1_->vertex_count();
    m.metrics["input.elements"] = s1_->element_count();
    map_.reset();
    for (std::size_t s = 0; s < config_.pipeline.size(); ++s) {
      const StepConfig& step = config_.pipeline[s];
      try {
        run_step(step, run_.step_parameters[s], m, step.name + ".");
      } catch (const Error& e) {
        throw Error(fmt::format("run {} (input \"{}\"), {} ({}): {}", run_.index, config_.inputs[run_.input_index].name,
                                step.key, step.name, e.what()));
      }
    }
    return m;
  }

 private:
  void run_step(const StepConfig& step, const ParameterSet& p, Measurements& m, const std::string& prefix) {
    if (step.kind == "build") return build(p, m, prefix);
    if (step.kind == "project") return project(p, m, prefix);
    if (step.kind == "evaluate") return evaluate(p, m, prefix);
    if (step.kind == "check") return check(p, m, prefix);
    if (step.kind == "peer_project") return peer_project(p, m, prefix);
    if (step.kind == "peer_simplify") return peer_simplify(p, m, prefix);
    if constexpr (d == 2) {
#ifdef PLMAP_EXPERIMENT_HAS_CONSTRUCT
      if (step.kind == "simplify") return simplify_step(p, m, prefix);
      if (step.kind == "smooth") return smooth_step(p, m, prefix);
      if (step.kind == "refine") return refine_step(p, m, prefix);
#endif
    }
    throw Error("unknown step " + step.kind);
  }

  void build(const ParameterSet& p, Measurements& m, const std::string& prefix) {
    const std::string& kind = p.text("map");
    const auto start = std::chrono::steady_clock::now();
    if (kind == "identity") {
      map_ = generators::identity_map<d>(s1_).map;
    } else if (kind == "subdivision") {
      map_ = generators::subdivision_map(s1_, int(p.integer("k")), p.real("jitter"), std::uint64_t(p.integer("seed"))).map;
    } else if (kind == "refinement") {
      Rng rng(std::uint64_t(p.integer("seed")));
      const generators::RefinementOptions options{.max_points_per_edge = int(p.integer("max_points_per_edge")),
                                                  .max_points_per_element = int(p.integer("max_points_per_element"))};
      map_ = generators::refinement_map<d>(s1_, generators::random_refinement<d>(*s1_, options, rng)).map;
    } else if (kind == "overlay") {
      Rng rng(std::uint64_t(p.integer("seed")));
      if constexpr (d == 2) {
        const bool hole = run_.input_parameters.has("hole") && run_.input_parameters.boolean("hole");
        auto s2 = std::make_shared<const Surface<2>>(generators::grid_triangulation(
            {.cells = int(p.integer("overlay_cells")), .jitter = p.real("overlay_jitter"), .with_hole = hole}, rng));
        map_ = generators::plane_overlay_map(s1_, s2).map;
      } else {
        map_ = generators::polyline_overlay_map(generators::random_subdivisions(s1_, int(p.integer("overlay_cells")), rng)).map;
      }
    }
    m.timings[prefix + "seconds"] = seconds_since(start);
    record_map(m, prefix);
    m.metrics[prefix + "memory_bytes"] = map_->memory_bytes();
  }

  void record_map(Measurements& m, const std::string& prefix) {
    m.metrics[prefix + "nodes"] = map_->node_count();
    m.metrics[prefix + "regions"] = map_->region_count();
    m.metrics[prefix + "regions_per_element"] = double(map_->region_count()) / map_->domain().element_count();
    m.metrics[prefix + "target_vertices"] = map_->target().vertex_count();
    m.metrics[prefix + "target_elements"] = map_->target().element_count();
  }

  void project([[maybe_unused]] const ParameterSet& p, [[maybe_unused]] Measurements& m,
               [[maybe_unused]] const std::string& prefix) {
#ifdef PLMAP_EXPERIMENT_HAS_CONSTRUCT
    const std::string& target = p.text("target");
    int index = 0;
    while (config_.inputs[index].name != target) ++index;
    auto s2 = inputs_.surface<d>(index, config_.inputs[index].parameters);
    ProjectionOptions options;
    options.solver = p.text("solver");
    const double limit = p.real("max_distance");
    if (limit > 0) {
      options.max_distance = limit;
      options.max_distance_is_relative = p.boolean("relative_distance");
    }
    options.allow_negative_distance = p.boolean("allow_negative_distance");
    options.normal_check = *normal_check_from_name(p.text("normal_check"));  // the schema checked it
    options.threads = unsigned(p.integer("threads"));
    options.renumbering = *spatial_renumbering_from_name(p.text("renumbering"));  // the schema checked it
    const auto start = std::chrono::steady_clock::now();
    auto result = plmap::project<d>(s1_, s2, options);
    m.timings[prefix + "seconds"] = seconds_since(start);
    map_ = std::make_shared<const PlMap<d>>(std::move(result.map));
    m.metrics[prefix + "nodes"] = map_->node_count();
    m.metrics[prefix + "regions"] = map_->region_count();
    m.metrics[prefix + "target_elements"] = s2->element_count();
    const auto& r = result.report;
    m.metrics[prefix + "vertex_preimages"] = r.vertex_preimages;
    m.metrics[prefix + "edges_inserted"] = r.edges_inserted;
    m.metrics[prefix + "edges_partly_inserted"] = r.edges_partly_inserted;
    m.metrics[prefix + "edges_not_inserted"] = r.edges_not_inserted.size();
    m.metrics[prefix + "renumbered_domain"] = r.renumbered_domain;
    m.metrics[prefix + "renumbered_target"] = r.renumbered_target;
    m.metrics[prefix + "covered_fraction"] =
        result.measures.domain > 0 ? result.measures.covered_domain / result.measures.domain : 0.0;
    m.metrics[prefix + "solver_calls"] = r.solver_calls;
    m.metrics[prefix + "solver_failures"] = r.solver_failures;
#else
    throw Error("this build has no plmap::construct");
#endif
  }

  /// Query points uniform in the reference element of uniformly chosen elements (portable: drawn
  /// through the generators' own uniform functions).
  std::vector<SurfacePoint<d>> queries(std::size_t n, std::uint64_t seed) const {
    Rng rng(seed);
    const Surface<d>& s = map_->domain();
    std::vector<SurfacePoint<d>> q(n);
    for (auto& point : q) {
      point.element = Index(generators::uniform_index(rng, int(s.element_count())));
      if constexpr (d == 1) {
        point.local = LocalPoint<1>(generators::uniform_unit(rng));
      } else {
        double x = generators::uniform_unit(rng), y = generators::uniform_unit(rng);
        if (x + y > 1) x = 1 - x, y = 1 - y;
        point.local = LocalPoint<2>(x, y);
      }
    }
    return q;
  }

  void evaluate(const ParameterSet& p, Measurements& m, const std::string& prefix) {
    const auto points = queries(std::size_t(p.integer("queries")), std::uint64_t(p.integer("seed")));
    std::vector<Evaluation<d>> out(points.size());
    const unsigned threads = unsigned(p.integer("threads"));
    double seconds = 0;
    with_point_locator<d>(
        p.text("locator"),
        [&](auto& locator) {
          prepare_point_locator<d>(locator, *map_);  // tables are set-up, not evaluation time
          const auto start = std::chrono::steady_clock::now();
          evaluate_batch<d>(*map_, points, out, locator, threads);
          seconds = seconds_since(start);
        },
        PointLocatorOptions{.seed = std::uint64_t(p.integer("seed"))});
    std::int64_t in_domain = 0;
    double checksum = 0;
    for (const auto& e : out)
      if (e.in_domain) ++in_domain, checksum += e.world.sum();
    m.metrics[prefix + "in_domain"] = in_domain;
    m.metrics[prefix + "checksum"] = checksum;
    m.timings[prefix + "seconds"] = seconds;
    m.timings[prefix + "ns_per_eval"] = 1e9 * seconds / double(points.size());
    m.timings[prefix + "evals_per_second"] = seconds > 0 ? double(points.size()) / seconds : 0.0;
  }

  void check(const ParameterSet& p, Measurements& m, const std::string& prefix) {
    VerifyOptions options;
    options.expect_parametrization = p.boolean("parametrization");
    if (p.real("max_condition") > 0) options.max_condition = p.real("max_condition");
    const auto start = std::chrono::steady_clock::now();
    const VerificationReport report = verify<d>(*map_, options);
    m.timings[prefix + "seconds"] = seconds_since(start);
    m.metrics[prefix + "ok"] = report.ok();
    m.metrics[prefix + "violations"] = report.violation_count();
    m.metrics[prefix + "kappa_max"] = report.quality ? number(report.quality->kappa_max) : Json(nullptr);
    m.metrics[prefix + "kappa_mean"] = report.quality ? number(report.quality->kappa_mean) : Json(nullptr);
  }

  /// One tool's projection of the input's contact pair, run by experiments/peers' benchmark in a
  /// child process (the benchmark generates the same pair from the same parameters), so that plmap
  /// and the peers are measured the same way: wall time and peak memory of the projection alone.
  void peer_project(const ParameterSet& p, Measurements& m, const std::string& prefix) {
    const InputConfig& input = config_.inputs[run_.input_index];
    const ParameterSet& in = run_.input_parameters;
    const std::string& tool = p.text("tool");
    std::vector<std::string> argv = {peer_benchmark_program(), "--tool", tool, "--seed",
                                     std::to_string(in.integer("seed")), "--threads",
                                     std::to_string(tool == "plmap" ? p.integer("threads") : 1), "--order",
                                     p.text("order")};
    detail::require_peer_benchmark("peer_project", argv[0], "benchmark", "bench_projection_peers", "PLMAP_PEER_BENCH");
    if (input.kind == "contact-circles") {
      argv.insert(argv.end(), {"--case", "circle", "--size", std::to_string(in.integer("segments"))});
    } else {
      const std::string& which = in.text("case");
      argv.insert(argv.end(), {"--case", which, "--size", std::to_string(in.integer("size"))});
      if (which.starts_with("femur")) argv.insert(argv.end(), {"--femur", inputs_.cgal_mesh(in.text("mesh")).string()});
    }
    const auto limit = p.integer("psurface_max_elements");
    if (tool == "psurface" && limit > 0 && std::int64_t(s1_->element_count()) > limit) {
      m.metrics[prefix + "ok"] = false;
      m.metrics[prefix + "error"] = fmt::format("skipped: S1 has {} elements, more than psurface_max_elements = {}",
                                                s1_->element_count(), limit);
      return;
    }
    const auto outcome = detail::run_peer_benchmark("peer_project", argv, p.real("timeout_seconds"), false);
    m.metrics[prefix + "ok"] = outcome.ok;
    m.metrics[prefix + "error"] = outcome.error;
    if (outcome.line.is_null()) return;
    auto real = [&](const char* key) { return detail::number_or_null(outcome.line, key); };
    m.metrics[prefix + "target_elements"] = real("s2_cells");
    if (outcome.line.contains("label") && outcome.line["label"].is_string()) m.metrics[prefix + "label"] = outcome.line["label"];
    if (!outcome.ok) return;
    m.metrics[prefix + "pieces"] = real("pieces");
    m.metrics[prefix + "covered_error"] = real("covered_relative_error");
    m.metrics[prefix + "covered_target_error"] = real("covered_target_relative_error");
    if (const Json t = real("seconds"); t.is_number()) m.timings[prefix + "seconds"] = t.get<double>();
    if (const Json mib = real("peak_increase_mib"); mib.is_number()) m.timings[prefix + "peak_mib"] = mib.get<double>();
  }

#ifdef PLMAP_EXPERIMENT_HAS_CONSTRUCT
  /// The modified Hausdorff distance of the current map over S2's bounding-box diagonal: the
  /// largest node-to-image distance (convex on each region, so the maximum is at a node).
  double relative_hausdorff() const {
    double h = 0.0;
    for (Index n = 0; n < map_->node_count(); ++n)
      h = std::max(h, (map_->node_domain_world(n) - map_->node_target_world(n)).norm());
    const auto& v = map_->target().vertices();
    WorldPoint<d> lo = v.front(), hi = v.front();
    for (const auto& x : v) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
    return h / (hi - lo).norm();
  }

  void record_kappa(Measurements& m, const std::string& prefix, const std::string& suffix) {
    const QualityReport q = compute_quality(*map_);
    m.metrics[prefix + "kappa_max" + suffix] = number(q.kappa_max);
    m.metrics[prefix + "kappa_mean" + suffix] = number(q.kappa_mean);
    double p99 = q.kappa_max;
    for (std::size_t i = 0; i < q.quantile_levels.size(); ++i)
      if (q.quantile_levels[i] == 0.99) p99 = q.quantiles[i];
    m.metrics[prefix + "kappa_p99" + suffix] = number(p99);
  }

  /// The step's wall time, and its peak resident memory above what the process held before it
  /// (MiB) when known.
  static void record_measurement(Measurements& m, const std::string& prefix, const peers::Measurement& clock) {
    m.timings[prefix + "seconds"] = clock.seconds();
    if (const auto mib = clock.exact_peak_increase_mib()) m.timings[prefix + "peak_mib"] = *mib;
  }

  static void record_aspect(Measurements& m, const std::string& name, const AspectRatioSummary& a) {
    m.metrics[name + "_mean"] = a.mean;
    m.metrics[name + "_p90"] = a.p90;
    m.metrics[name + "_max"] = a.max;
  }

  /// plmap::simplify on the input: S1 becomes the coarse surface, the map Ξ: S1 → input.
  void simplify_step(const ParameterSet& p, Measurements& m, const std::string& prefix) {
    SimplifyOptions options;
    options.target_elements = Index(p.integer("target_elements"));
    const double diagonal = [&] {
      const auto& v = s1_->vertices();
      WorldPoint<d> lo = v.front(), hi = v.front();
      for (const auto& x : v) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      return (hi - lo).norm();
    }();
    if (p.real("max_error") > 0) options.max_error = p.real("max_error") * diagonal;
    for (const auto& spec : detail::split_oracles(p.text("oracles"))) options.oracles.add_spec(spec);
    options.feature_angle_degrees = p.real("feature_angle");
    options.flattening = p.text("flattening");
    options.hole_triangulation = p.text("hole_triangulation");
    options.ranking = p.text("ranking");
    options.cut = p.text("cut");
    peers::Measurement clock;
    clock.start();
    SimplifyResult result = plmap::simplify(s1_, options);
    clock.stop();
    record_measurement(m, prefix, clock);
    map_ = std::make_shared<const PlMap<d>>(std::move(result.map));
    m.metrics[prefix + "elements"] = map_->domain().element_count();
    m.metrics[prefix + "vertices"] = map_->domain().vertex_count();
    m.metrics[prefix + "nodes"] = map_->node_count();
    m.metrics[prefix + "regions"] = map_->region_count();
    m.metrics[prefix + "hausdorff"] = relative_hausdorff();
    record_kappa(m, prefix, "");
    record_aspect(m, prefix + "coarse_aspect", aspect_ratio_summary(map_->domain()));
    m.metrics[prefix + "target_reached"] = result.report.target_reached;
  }

  void smooth_step(const ParameterSet& p, Measurements& m, const std::string& prefix) {
    record_kappa(m, prefix, "_before");
    SmoothOptions options;
    options.sweeps = int(p.integer("sweeps"));
    options.weights = p.text("weights");
    options.quadrilaterals = p.boolean("quadrilaterals");
    peers::Measurement clock;
    clock.start();
    SmoothResult result = plmap::smooth(*map_, options);
    clock.stop();
    record_measurement(m, prefix, clock);
    map_ = std::make_shared<const PlMap<d>>(std::move(result.map));
    record_kappa(m, prefix, "");
    m.metrics[prefix + "hausdorff"] = relative_hausdorff();
    m.metrics[prefix + "nodes_moved"] = result.report.sweeps.empty() ? 0 : result.report.sweeps.back().nodes_moved;
    Index quadrilaterals = 0;
    for (const auto& sweep : result.report.sweeps) quadrilaterals += sweep.quadrilaterals_smoothed;
    m.metrics[prefix + "quadrilaterals_smoothed"] = quadrilaterals;
  }

  void refine_step(const ParameterSet& p, Measurements& m, const std::string& prefix) {
    peers::Measurement clock;
    clock.start();
    const RefineResult result = refine_through_map(*map_, {.levels = int(p.integer("levels"))});
    clock.stop();
    record_measurement(m, prefix, clock);
    m.metrics[prefix + "elements"] = result.report.elements;
    m.metrics[prefix + "distance_max"] = result.report.distance_max_relative;
    m.metrics[prefix + "distance_mean"] = result.report.distance_mean;
    record_aspect(m, prefix + "coarse_aspect", result.report.coarse_quality);
    record_aspect(m, prefix + "refined_aspect", result.report.refined_quality);
  }
#endif

  /// One tool's simplification of the input mesh (plmap, PSurface or CGAL's floor), run by
  /// experiments/peers' bench_simplification_peers in a child process per repetition, so that
  /// the tools are measured the same way (wall time and peak memory of the child's measured part,
  /// every result measured with plmap's code).
  void peer_simplify(const ParameterSet& p, Measurements& m, const std::string& prefix) {
    const InputConfig& input = config_.inputs[run_.input_index];
    const ParameterSet& in = run_.input_parameters;
    const std::string program = simplification_benchmark_program();
    detail::require_peer_benchmark("peer_simplify", program, "simplification benchmark", "bench_simplification_peers",
                                   "PLMAP_SIMPLIFICATION_BENCH");
    std::filesystem::path mesh;
    if (input.kind == "cgal") {
      mesh = inputs_.cgal_mesh(in.text("mesh"));
    } else {
      mesh = in.text("path");
      if (mesh.is_relative()) mesh = config_.base_directory / mesh;
    }
    std::vector<std::string> argv = {program, "--tool", p.text("tool"), "--mesh", mesh.string(), "--target",
                                     std::to_string(p.integer("target_elements")), "--feature-angle",
                                     fmt::format("{}", p.real("feature_angle")), "--sweeps",
                                     std::to_string(p.integer("sweeps")), "--weights", p.text("weights"),
                                     "--refine-levels", std::to_string(p.integer("refine_levels")),
                                     "--psurface-aspect-ratio", fmt::format("{}", p.real("psurface_aspect_ratio")),
                                     "--psurface-hausdorff", fmt::format("{}", p.real("psurface_hausdorff"))};
    for (const auto& spec : detail::split_oracles(p.text("oracles"))) argv.insert(argv.end(), {"--oracle", spec});
    argv.insert(argv.end(), {"--ranking", p.text("ranking"), "--cut", p.text("cut")});
    if (!p.boolean("quadrilaterals")) argv.push_back("--no-quadrilaterals");
    const auto outcome = detail::run_peer_benchmark("peer_simplify", argv, p.real("timeout_seconds"), true);
    m.metrics[prefix + "ok"] = outcome.ok;
    m.metrics[prefix + "error"] = outcome.error;
    if (!outcome.ok) return;
    const Json& line = outcome.line;
    const auto field = [&](const char* group, const char* key) {
      return detail::number_or_null(group ? (line.contains(group) ? line[group] : Json()) : line, key);
    };
    m.metrics[prefix + "elements"] = field(nullptr, "elements");
    m.metrics[prefix + "hausdorff_before_smoothing"] = field(nullptr, "hausdorff_before_smoothing");
    m.metrics[prefix + "hausdorff"] = field(nullptr, "hausdorff");
    m.metrics[prefix + "quadrilaterals_smoothed"] = field(nullptr, "quadrilaterals_smoothed");  // plmap only
    for (const char* q : {"max", "mean", "p99"}) {
      m.metrics[prefix + "kappa_" + q + "_before"] = field("kappa_before", q);
      m.metrics[prefix + "kappa_" + q] = field("kappa_after", q);
    }
    for (const char* q : {"mean", "p90", "max"}) {
      m.metrics[prefix + "coarse_aspect_" + q] = field("coarse_aspect", q);
      m.metrics[prefix + "refined_aspect_" + q] = field("refined_aspect", q);
    }
    for (const char* t :
         {"seconds", "seconds_simplify", "seconds_smooth", "cpu_seconds", "cpu_seconds_simplify", "cpu_seconds_smooth"})
      if (const Json v = field(nullptr, t); v.is_number()) m.timings[prefix + t] = v.get<double>();
    if (const Json mib = field(nullptr, "peak_increase_mib"); mib.is_number())
      m.timings[prefix + "peak_mib"] = mib.get<double>();
  }

  const ExperimentConfig& config_;
  const RunSpec& run_;
  detail::InputCache& inputs_;
  std::shared_ptr<const Surface<d>> s1_;
  std::shared_ptr<const PlMap<d>> map_;
};

int run_dimension(const ExperimentConfig& config, const RunSpec& run) {
  const InputConfig& input = config.inputs[run.input_index];
  if (input.kind != "file") return input.dimension;
  const auto dim = run.input_parameters.integer("dimension");
  if (dim != 0) return int(dim);
  return std::filesystem::path(run.input_parameters.text("path")).extension() == ".curve" ? 1 : 2;
}

/// The swept values of a run, for progress messages: "evaluate.locator=brute-force, ...".
std::string describe(const ExperimentConfig& config, const RunSpec& run) {
  std::string text = fmt::format("input {}", config.inputs[run.input_index].name);
  std::set<std::string> shown;  // axes of several inputs share a column ("inputs.a.size", "inputs.b.size")
  for (const auto& group : config.sweeps)
    for (const auto& axis : group.axes) {
      const std::string column = axis.target == SweepAxis::Target::input
                                     ? "input." + axis.parameter
                                     : config.pipeline[axis.index].name + "." + axis.parameter;
      if (run.columns.contains(column) && shown.insert(column).second)
        text += fmt::format(", {}={}", column, run.columns[column].dump());
    }
  return text;
}

}  // namespace

std::vector<RunResult> run_all(const ExperimentConfig& config, const std::filesystem::path& cache_dir,
                               const RunOptions& options) {
  const auto runs = expand_runs(config);
  const int repetitions = options.repetitions_override > 0 ? options.repetitions_override : config.repetitions;
  const auto available = available_metrics(config);
  std::set<std::string> selected(config.metrics.begin(), config.metrics.end());
  auto wanted = [&](const std::string& name) { return selected.empty() || selected.count(name) > 0; };

  detail::InputCache inputs(config, cache_dir);
  std::vector<RunResult> rows;
  for (const RunSpec& run : runs) {
    if (options.progress)
      report_progress(options.progress, "runs", static_cast<std::uint64_t>(run.index), runs.size(),
                      fmt::format("run {}/{}: {}", run.index + 1, runs.size(), describe(config, run)));
    RunResult row;
    row.run = run.index;
    row.config = run.columns;
    std::map<std::string, std::vector<double>> samples;
    Json first;
    for (int rep = 0; rep < repetitions; ++rep) {
      Measurements m = run_dimension(config, run) == 1 ? Pipeline<1>(config, run, inputs)()
                                                        : Pipeline<2>(config, run, inputs)();
      for (const auto& [name, t] : m.timings) samples[name].push_back(t);
      if (rep == 0) {
        first = m.metrics;
      } else if (m.metrics != first) {
        for (const auto& [name, value] : m.metrics.items())
          if (first[name] != value)
            row.notes.push_back(fmt::format("{} differs between repetitions ({} then {})", name, first[name].dump(),
                                            value.dump()));
        first = m.metrics;  // report each difference once per repetition
      }
    }
    // Metrics in pipeline order, restricted to the selection.
    for (const auto& [name, timing] : available) {
      if (!wanted(name)) continue;
      if (timing) {
        if (!samples.count(name)) continue;
        const TimingSummary t = summarize(samples[name]);
        row.timings[name] = {{"median", t.median}, {"min", t.min}, {"max", t.max}, {"samples", t.samples}};
      } else if (first.contains(name)) {
        row.metrics[name] = first[name];
      }
    }
    if (row.metrics.is_null()) row.metrics = Json::object();
    if (row.timings.is_null()) row.timings = Json::object();
    rows.push_back(std::move(row));
  }
  report_progress(options.progress, "runs", runs.size(), runs.size());
  return rows;
}

ExperimentOutcome run_experiment(const ExperimentConfig& config, const std::filesystem::path& output_dir,
                                 const RunOptions& options) {
  ExperimentOutcome outcome;
  outcome.output_directory = output_dir;
  outcome.provenance = collect_provenance();
  std::filesystem::create_directories(output_dir);
  write_file_atomically(output_dir / "config.toml", [&](std::ostream& out) { out << config.text; }, true);
  write_file_atomically(
      output_dir / "provenance.json", [&](std::ostream& out) { out << to_json(outcome.provenance).dump(2) << '\n'; },
      false);
  {
    Json runs = Json::array();
    for (const auto& run : expand_runs(config)) runs.push_back(run.columns);
    write_file_atomically(output_dir / "runs.json", [&](std::ostream& out) { out << runs.dump(2) << '\n'; }, false);
  }
  outcome.rows = run_all(config, output_dir / "inputs", options);
  write_jsonl(output_dir / "results.jsonl", outcome.rows, outcome.provenance);
  write_csv(output_dir / "results.csv", outcome.rows, outcome.provenance);
  if (options.make_plots && !config.plots.empty()) {
    report_progress(options.progress, "plots", 0, 1);
    outcome.plots = write_plots(config, outcome.rows, output_dir, options.plots);
    report_progress(options.progress, "plots", 1, 1);
  }
  const std::string summary = summary_markdown(config, outcome.rows, outcome.provenance, outcome.plots);
  write_file_atomically(output_dir / "summary.md", [&](std::ostream& out) { out << summary; }, false);
  return outcome;
}

}  // namespace plmap::experiment
