// Per-element parametrization smoothing (paper 3.3.2); see smooth.hpp for the method.

#include <plmap/construct/smooth.hpp>

#include "convex_combination_system.hpp"
#include "free_node_fans.hpp"
#include "preimage_graph.hpp"
#include "quad_smoothing.hpp"
#include "region_condition.hpp"
#include "s2_stars.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/element_transfer.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/predicates.hpp>
#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>
#include <plmap/strategies/smoothing/uniform_weights.hpp>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>

namespace plmap {

namespace {

/// What one element's solve decided: new positions for its nodes [begin, end), or why not.
struct ElementOutcome {
  std::vector<LocalPoint<2>> positions;  ///< indexed by node - node_begin[T]; empty if skipped
  const char* skipped = nullptr;
  bool shortened = false;  ///< the κ guard kept only part of the solve's move
  /// With positions: per region of T (region - region_begin[T]), its corners' images in its S2
  /// element's local coordinates, as region_corner_target_local gives them on the input map.
  std::vector<std::array<LocalPoint<2>, 3>> region_images;
  /// With positions: per region of T, κ at the new positions, as the guard computed it. It is
  /// MapConditions::update's value on the new map when `kappa_exact` (no corner's image came from
  /// a region's affine map, which the new map re-fits), so the update need not evaluate T again.
  std::vector<double> region_kappa;
  bool kappa_exact = false;
};

class ElementSmoother {
 public:
  /// `worst_now`, if given, is worst_condition_per_element(map) (saves recomputing it per element).
  ElementSmoother(const PlMap<2>& map, const MapData<2>& m, const AnySmoothingWeights& weights, SmoothReport& report,
                  const std::vector<double>* worst_now)
      : map_(map), m_(m), weights_(weights), report_(report), worst_now_(worst_now),
        local_rings_(map.elements_with_stored_graph() == 0) {}

  ElementOutcome solve(Index t, bool count_nodes) {
    const Index nb = m_.node_begin[t], ne = m_.node_begin[t + 1];
    const Index rb = m_.region_begin[t], re = m_.region_begin[t + 1];
    const auto local = [nb](Index n) { return static_cast<std::size_t>(n - nb); };
    // unknown index of each node of T, -1 for fixed nodes
    unknown_.assign(static_cast<std::size_t>(ne - nb), -1);
    int unknowns = 0;
    for (Index n = nb; n < ne; ++n)
      if (m_.node_type[n] == NodeType::interior) unknown_[local(n)] = unknowns++;
    ElementOutcome out;
    if (unknowns == 0) return out;
    if (count_nodes) report_.free_nodes += unknowns;

    // A free node's neighbours must close a fan of regions around it (deg regions contain it),
    // else the regions are not a triangulation of a disc around it and Tutte does not apply.
    incidence_.assign(static_cast<std::size_t>(ne - nb), 0);
    for (Index r = rb; r < re; ++r)
      for (Index c : m_.region_corners[r]) ++incidence_[local(c)];

    if (local_rings_) {
      free_.resize(unknown_.size());
      for (std::size_t v = 0; v < unknown_.size(); ++v) free_[v] = unknown_[v] >= 0;
      fans_.collect(m_, t, free_);
    }
    system_.reset(unknowns);
    for (Index n = nb; n < ne; ++n) {
      const int i = unknown_[local(n)];
      if (i < 0) continue;
      const std::span<const Index> ring_nodes = local_rings_ ? fans_.ring(n) : map_.neighbors(n);
      if (incidence_[local(n)] != static_cast<int>(ring_nodes.size()) || ring_nodes.size() < 3) {
        out.skipped = "open star";
        return out;
      }
      ring_.clear();
      for (Index q : ring_nodes) ring_.push_back(map_.node_target_world(q));
      auto w = weights_(map_.node_target_world(n), ring_);
      if (!w) {
        w = UniformWeights{}.weights(map_.node_target_world(n), ring_);
        if (count_nodes) ++report_.uniform_fallback_nodes;
      }
      system_.add(i, i, 1.0);
      for (std::size_t j = 0; j < ring_nodes.size(); ++j) {
        const Index q = ring_nodes[j];
        const int col = unknown_[local(q)];
        if (col >= 0)
          system_.add(i, col, -(*w)[j]);
        else
          system_.add_rhs(i, (*w)[j] * m_.node_position[q]);
      }
    }
    if (!system_.solve()) {
      out.skipped = "solver";
      return out;
    }
    // The solve's positions, then, if they would raise the element's worst κ (below), the
    // positions part of the way there: 1/2, 1/4, ... of the move.
    std::vector<LocalPoint<2>> solved(m_.node_position.begin() + nb, m_.node_position.begin() + ne);
    for (Index n = nb; n < ne; ++n)
      if (unknown_[local(n)] >= 0) solved[local(n)] = system_.solution(unknown_[local(n)]);
    // The images of t's region corners do not move: their positions and frames are computed once
    // for all the trials below, and the positions again serve to re-fit the region maps.
    images_.clear();
    target_frames_.clear();
    bool any_fitted = false;
    for (Index r = rb; r < re; ++r) {
      std::array<LocalPoint<2>, 3> image;
      std::array<Eigen::Vector3d, 3> world;
      for (int k = 0; k < 3; ++k) {
        bool fitted = false;
        image[k] = smoothing::region_corner_target_local(map_, r, k, &fitted);
        any_fitted = any_fitted || fitted;
        world[k] = map_.target().world_position(m_.region_target[r], image[k]);
      }
      images_.push_back(image);
      target_frames_.push_back(smoothing::frame_coordinates(world));
    }
    const double worst_before = worst_now_ != nullptr
                                    ? (*worst_now_)[static_cast<std::size_t>(t)]
                                    : worst_condition(t, {m_.node_position.begin() + nb, m_.node_position.begin() + ne});
    const double allowed = std::max(worst_before, smoothing::free_condition);
    std::vector<LocalPoint<2>> candidate(solved.size());
    bool embeds = false;
    for (int halvings = 0; halvings <= max_halvings; ++halvings) {
      const double step = std::ldexp(1.0, -halvings);
      for (std::size_t i = 0; i < solved.size(); ++i)
        candidate[i] = m_.node_position[nb + static_cast<Index>(i)] + step * (solved[i] - m_.node_position[nb + static_cast<Index>(i)]);
      if (!embeds_in_element(t, candidate)) continue;
      embeds = true;
      if (worst_condition(t, candidate) <= allowed) {
        out.positions = candidate;
        out.shortened = halvings > 0;
        out.region_images = images_;
        out.region_kappa = kappa_;
        out.kappa_exact = !any_fitted;
        return out;
      }
    }
    // Tutte/Floater guarantee the full step embeds; a refusal by the orientation test means the
    // solve was inaccurate, one by the κ guard that no part of the move keeps κ in bounds.
    out.skipped = embeds ? "would raise the worst condition number" : "fold-over";
    return out;
  }

 private:
  /// Halvings of a move the κ guard tries before it leaves the element as it was.
  static constexpr int max_halvings = 6;

  /// Every free node strictly inside the reference triangle (else it would leave its element)
  /// and every region of t positively oriented (exact predicate): no fold-over.
  bool embeds_in_element(Index t, const std::vector<LocalPoint<2>>& positions) const {
    const Index nb = m_.node_begin[t];
    for (std::size_t i = 0; i < positions.size(); ++i) {
      if (m_.node_type[nb + static_cast<Index>(i)] != NodeType::interior) continue;
      const LocalPoint<2>& p = positions[i];
      if (!(p.x() > 0.0 && p.y() > 0.0 && p.x() + p.y() < 1.0)) return false;
    }
    for (Index r = m_.region_begin[t]; r < m_.region_begin[t + 1]; ++r) {
      const auto& c = m_.region_corners[r];
      if (orient2d(positions[c[0] - nb], positions[c[1] - nb], positions[c[2] - nb]) <= 0) return false;
    }
    return true;
  }

  /// The largest κ_Ξ of t's regions with t's nodes at `positions` (their images unchanged, their
  /// frames in target_frames_), each region's in kappa_: exactly what the quality report measures
  /// on these regions.
  double worst_condition(Index t, const std::vector<LocalPoint<2>>& positions) {
    const Index nb = m_.node_begin[t];
    world_.resize(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) world_[i] = map_.domain().world_position(t, positions[i]);
    double worst = 1.0;
    kappa_.clear();
    for (Index r = m_.region_begin[t]; r < m_.region_begin[t + 1]; ++r) {
      const auto& c = m_.region_corners[r];
      const std::array<Eigen::Vector3d, 3> from = {world_[c[0] - nb], world_[c[1] - nb], world_[c[2] - nb]};
      const double kappa = smoothing::frames_condition(smoothing::frame_coordinates(from),
                                                       target_frames_[static_cast<std::size_t>(r - m_.region_begin[t])]);
      kappa_.push_back(kappa);
      worst = std::max(worst, kappa);
    }
    return worst;
  }

  const PlMap<2>& map_;
  const MapData<2>& m_;
  const AnySmoothingWeights& weights_;
  SmoothReport& report_;
  std::vector<int> unknown_, incidence_;
  const std::vector<double>* worst_now_;
  /// No element of the map stores its graph: the free nodes' rings come from their regions
  /// (free_node_fans.hpp), the map's graph is not derived.
  bool local_rings_;
  smoothing::FreeNodeFans fans_;
  std::vector<char> free_;
  smoothing::ConvexCombinationSystem system_;
  std::vector<Eigen::Vector3d> ring_, world_;
  /// per region of the element being solved: its corners' images (local to its S2 element), the
  /// frame of the image triangle (region_condition.hpp), κ at the last positions tried
  std::vector<std::array<LocalPoint<2>, 3>> images_;
  std::vector<Eigen::Matrix2d> target_frames_;
  std::vector<double> kappa_;
};

/// Writes the kept positions of element t into `out` and recomputes its regions' maps from them,
/// the images (on each region's S2 element, `images` per region) unchanged.
/// Returns whether a node moved.
bool apply_outcome(const PlMap<2>& map, Index t, const std::vector<LocalPoint<2>>& positions,
                   const std::vector<std::array<LocalPoint<2>, 3>>& images, MapData<2>& out, SmoothSweepReport& sweep) {
  const MapData<2>& old = map.stored();
  const Index nb = old.node_begin[t];
  bool moved_any = false;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Index n = nb + static_cast<Index>(i);
    if (old.node_type[n] != NodeType::interior) continue;  // fixed: bit for bit
    const double shift = (positions[i] - old.node_position[n]).norm();
    if (shift > 0.0) ++sweep.nodes_moved, moved_any = true;
    sweep.max_displacement = std::max(sweep.max_displacement, shift);
    out.node_position[n] = positions[i];
  }
  ++sweep.elements_smoothed;
  if (!moved_any) return false;
  for (Index r = old.region_begin[t]; r < old.region_begin[t + 1]; ++r) {
    const auto& c = old.region_corners[r];
    std::array<LocalPoint<2>, 3> from;
    for (int k = 0; k < 3; ++k) from[k] = out.node_position[c[k]];
    // the images on the region's S2 element, exactly where they are vertices or on edges
    out.region_map[r] = affine_through<2>(from, images[static_cast<std::size_t>(r - old.region_begin[t])]);
  }
  return true;
}

/// The stored arrays of `map` without the graph arrays derived into them: the element pass
/// moves interior nodes and re-fits region maps only, so the graph, and which elements must
/// store theirs (map.stored_graph()), stay those of `map`, and the new map is built in stored
/// form without deriving every element's graph to compare it (which the full-array
/// constructor does).
MapData<2> stored_arrays(const PlMap<2>& map) {
  MapData<2> out = map.stored();
  out.neighbor_begin = {};
  out.neighbor = {};
  out.neighbor_edge_kind = {};
  out.edge_node_begin = {};
  out.edge_node = {};
  out.region_neighbors = {};
  return out;
}

/// Total area of the region images on S2: smoothing re-places preimages, so it must not change.
/// Reads only stored arrays (the graph of a rebuilt map is never derived for it). Each node's
/// image is evaluated once per element, not once per region corner (about six), in a buffer
/// reused from call to call: the same values in the same order of summation.
double image_area(const PlMap<2>& map) {
  const MapData<2>& m = map.stored();
  thread_local std::vector<Eigen::Vector3d> world;
  double total = 0.0;
  for (Index t = 0; t < map.domain().element_count(); ++t) {
    const Index nb = m.node_begin[t];
    world.resize(static_cast<std::size_t>(m.node_begin[t + 1] - nb));
    for (Index n = nb; n < m.node_begin[t + 1]; ++n) world[static_cast<std::size_t>(n - nb)] = map.node_target_world(n);
    for (Index r = m.region_begin[t]; r < m.region_begin[t + 1]; ++r) {
      const auto& c = m.region_corners[r];
      const auto at = [&](int k) -> const Eigen::Vector3d& { return world[static_cast<std::size_t>(c[k] - nb)]; };
      total += 0.5 * (at(1) - at(0)).cross(at(2) - at(0)).norm();
    }
  }
  return total;
}

/// Per S1 element, the largest of its own and its edge neighbours' values: a quadrilateral step
/// moves regions only between the two triangles of its edge.
std::vector<double> neighbourhood_max(const Surface<2>& s1, const std::vector<double>& value) {
  std::vector<double> out = value;
  for (Index e = 0; e < s1.edge_count(); ++e) {
    double worst = 1.0;
    for (const auto& inc : s1.edge_elements(e)) worst = std::max(worst, value[static_cast<std::size_t>(inc.element)]);
    for (const auto& inc : s1.edge_elements(e)) {
      auto& o = out[static_cast<std::size_t>(inc.element)];
      o = std::max(o, worst);
    }
  }
  return out;
}

/// The quadrilateral pass of one sweep (`worst_before`: worst_condition_per_element(current)): every S1 edge with two triangles, in index order, each
/// step seeing the previous ones; then the map is rebuilt from the edited graph. Each step's own
/// κ guard sees the spoke triangles, not the regions MapBuilder makes of the edited graph (it
/// triangulates faces that include fixed points on the quadrilateral's boundary); so the rebuilt
/// map is measured, the edges of every element whose worst region got worse than
/// max(the worst before in it and its neighbours, free_condition) are frozen, and the pass is
/// redone without them, a few times at most; then the pass is refused.
/// A redone pass gives the result of a pass from scratch without the frozen edges, but solves
/// only the steps near the newly frozen edges and replays the others from the previous attempt's
/// records (run_quadrilateral_pass in quad_smoothing.hpp).
/// `conditions` are those of `current` and, if the pass is kept, become those of the new map.
void smooth_quadrilaterals(PlMap<2>& current, smoothing::MapConditions& conditions, double worst_at_sweep_start,
                           smoothing::S2Stars& stars, SmoothReport& report, SmoothSweepReport& sweep) {
  constexpr int max_attempts = 8;
  const std::vector<double>& worst_before = conditions.element;
  const Surface<2>& s1 = current.domain();
  const std::vector<double> allowed = neighbourhood_max(s1, worst_before);
  // the sweep's guarantee is against the map before its element pass, which only lowers κ
  const double global_allowed =
      std::max(worst_at_sweep_start, *std::max_element(worst_before.begin(), worst_before.end()));
  const double area = image_area(current);
  std::vector<char> frozen(static_cast<std::size_t>(s1.edge_count()), 0);
  std::string why;
  const std::optional<smoothing::PreimageGraph> start = smoothing::PreimageGraph::from_map(current, &why);
  if (!start) {
    report.quadrilaterals_not_applicable = why;
    return;
  }
  std::optional<smoothing::EdgesInElement> start_index;
  std::vector<smoothing::QuadStepRecord> previous, records;
  std::vector<char> newly_frozen(static_cast<std::size_t>(s1.edge_count()), 0);
  smoothing::MapConditions rebuilt_conditions;  // of the rebuilt map of the last run
  const std::vector<double>& worst = rebuilt_conditions.element;
  std::optional<PlMap<2>> last_rebuilt;
  std::vector<char> reuse;  // per S1 element: copied from last_rebuilt in a repeated run's rebuild
  for (int attempt = 0; attempt < max_attempts; ++attempt) {
    smoothing::PreimageGraph graph = *start;
    smoothing::QuadSmoother smoother(graph, s1, stars, start_index ? &*start_index : nullptr);
    if (!start_index) start_index = smoother.edges_in_element();
    const smoothing::QuadPassTally pass = smoothing::run_quadrilateral_pass(
        smoother, s1, frozen, attempt == 0 ? nullptr : &previous, &newly_frozen, records);
    std::optional<PlMap<2>> rebuilt;
    // the same graph as the last run (its newly frozen edges had all refused): the same map
    const bool reused = attempt > 0 && std::ranges::none_of(pass.changed, [](char c) { return c != 0; });
    if (reused) {
      rebuilt = std::move(last_rebuilt);
      last_rebuilt.reset();
    } else try {
      FinalizeReport built;
      // A repeated run's graph differs from the last run's only on pass.changed: the other
      // elements are copied from the last rebuilt map instead of closed again (the same arrays).
      const bool repeated = attempt > 0 && last_rebuilt.has_value();
      if (repeated) {
        reuse.resize(pass.changed.size());
        for (std::size_t t = 0; t < reuse.size(); ++t) reuse[t] = pass.changed[t] ? 0 : 1;
      }
      PlMap<2> map = repeated ? graph.to_map_reusing(current.domain_ptr(), current.target_ptr(), *last_rebuilt, reuse, &built)
                              : graph.to_map(current.domain_ptr(), current.target_ptr(), &built);
      // The same coverage of S2, up to rounding: guards against a map the graph form cannot hold
      // (e.g. an S2 edge whose preimage leaves D between two vertex preimages).
      if (built.reversed_faces == 0 && built.dropped_edges.empty() && map.region_count() > 0 &&
          std::abs(image_area(map) - area) <= 1e-9 * area)
        rebuilt = std::move(map);
    } catch (const Error&) {
      // the step checks missed an inconsistency: keep the element pass's map
    }
    if (!rebuilt) {
      sweep.quadrilateral_pass_rejected = true;
      return;
    }
    // MapBuilder closes each element from its own part of the graph, so where that part is the
    // previous run's (pass.changed), so are the regions and their κ
    if (attempt == 0)
      rebuilt_conditions = smoothing::MapConditions::of(*rebuilt);
    else if (!reused)
      rebuilt_conditions = rebuilt_conditions.moved_to(*last_rebuilt, *rebuilt, pass.changed);
    bool raised = false, beyond_repair = false;
    std::fill(newly_frozen.begin(), newly_frozen.end(), 0);
    for (Index t = 0; t < s1.element_count(); ++t) {
      const std::size_t i = static_cast<std::size_t>(t);
      if (!(worst[i] > std::max(allowed[i], smoothing::free_condition))) continue;
      bool all_frozen = true;
      for (int k = 0; k < 3; ++k) {
        const std::size_t edge = static_cast<std::size_t>(s1.element_edge(t, k));
        all_frozen = all_frozen && frozen[edge];
        if (!frozen[edge]) newly_frozen[edge] = 1;
        frozen[edge] = 1;
      }
      raised = raised || !all_frozen;
      // No step touched t: MapBuilder triangulated its faces differently from the element pass's
      // regions. Freezing more cannot help; tolerated up to the map's worst κ before the sweep.
      if (all_frozen && worst[i] > std::max(global_allowed, smoothing::free_condition)) beyond_repair = true;
    }
    if (beyond_repair) break;
    if (raised) {
      std::swap(previous, records);
      last_rebuilt = std::move(rebuilt);
      continue;
    }
    sweep.quadrilaterals_smoothed = pass.smoothed;
    sweep.quad_nodes_moved = pass.nodes_moved;
    sweep.nodes_crossed = pass.nodes_crossed;
    sweep.quad_max_displacement = pass.max_displacement;
    sweep.quad_uniform_fallbacks = smoother.uniform_fallbacks();
    sweep.quadrilaterals_skipped_by_reason = pass.skipped_by_reason;
    sweep.quadrilateral_attempts = attempt + 1;
    current = std::move(*rebuilt);
    conditions = std::move(rebuilt_conditions);
    return;
  }
  sweep.quadrilateral_pass_refused_by_kappa = true;
}

}  // namespace

SmoothResult smooth(const PlMap<2>& map, const SmoothOptions& options) {
  if (options.sweeps < 1) throw Error(fmt::format("smoothing needs at least one sweep (got {})", options.sweeps));
  const AnySmoothingWeights weights = make_smoothing_weights(options.weights);
  const auto start = std::chrono::steady_clock::now();

  SmoothReport report;
  report.weights = options.weights;
  // A copy keeps the stored form: the graph is derived once, where the element pass reads it
  // (handing over map.data() made the constructor derive every element's graph to compare it).
  PlMap<2> current(map);
  if (options.measure_kappa) report.kappa_before = options.measure_kappa(current);
  // κ of every region of `current`, kept up to date through the sweeps
  smoothing::MapConditions conditions = smoothing::MapConditions::of(current);
  if (!options.measure_kappa && options.summarize_kappa) report.kappa_before = options.summarize_kappa(conditions.region);
  const Index elements = map.domain().element_count();
  // S2's stars as the quadrilateral steps read them: S2 and the weights are those of every sweep
  smoothing::S2Stars stars(map.target(), weights);
  for (int s = 1; s <= options.sweeps; ++s) {
    report_progress(options.progress, "smoothing sweeps", static_cast<std::uint64_t>(s - 1), static_cast<std::uint64_t>(options.sweeps));
    SmoothSweepReport sweep;
    // per element, its worst κ: the element pass's guard, then (updated where it moved nodes)
    // the quadrilateral pass's
    const double worst_at_sweep_start = std::ranges::max(conditions.element);
    std::vector<Index> moved;
    // per moved element whose guard's κ are the new map's: where they start in moved_kappa, else -1
    std::vector<std::ptrdiff_t> kappa_at;
    std::vector<double> moved_kappa;
    MapData<2> next = stored_arrays(current);
    ElementSmoother smoother(current, current.stored(), weights, report, &conditions.element);
    report.skipped_elements.clear();
    for (Index t = 0; t < (options.elements ? elements : 0); ++t) {
      ElementOutcome outcome = smoother.solve(t, s == 1);
      if (outcome.skipped != nullptr) {
        ++report.skipped_by_reason[outcome.skipped];
        report.skipped_elements.push_back(t);
        continue;
      }
      if (outcome.shortened) ++sweep.elements_shortened;
      if (!outcome.positions.empty() && apply_outcome(current, t, outcome.positions, outcome.region_images, next, sweep)) {
        moved.push_back(t);
        kappa_at.push_back(outcome.kappa_exact ? static_cast<std::ptrdiff_t>(moved_kappa.size()) : -1);
        if (outcome.kappa_exact) moved_kappa.insert(moved_kappa.end(), outcome.region_kappa.begin(), outcome.region_kappa.end());
      }
    }
    current = PlMap<2>(map.domain_ptr(), map.target_ptr(), std::move(next), StoredGraph(current.stored_graph()));
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const Index t = moved[i];
      if (kappa_at[i] < 0) {
        conditions.update(current, t);
        continue;
      }
      // the guard's values for the kept positions: the same function of the same numbers
      const auto& begin = current.stored().region_begin;
      double worst = 1.0;  // in region order, as MapConditions::update takes the maximum
      for (Index r = begin[t]; r < begin[t + 1]; ++r) {
        const double kappa = moved_kappa[static_cast<std::size_t>(kappa_at[i] + (r - begin[t]))];
        conditions.region[static_cast<std::size_t>(r)] = kappa;
        worst = std::max(worst, kappa);
      }
      conditions.element[static_cast<std::size_t>(t)] = worst;
    }
    std::vector<double>().swap(moved_kappa);  // not held through the quadrilateral pass (the memory peak)
    if (options.quadrilaterals) smooth_quadrilaterals(current, conditions, worst_at_sweep_start, stars, report, sweep);
    if (options.measure_kappa)
      sweep.kappa = options.measure_kappa(current);
    else if (options.summarize_kappa)
      sweep.kappa = options.summarize_kappa(conditions.region);
    report.sweeps.push_back(sweep);
    if (options.after_sweep) options.after_sweep(s, current);
    report_progress(options.progress, "smoothing sweeps", static_cast<std::uint64_t>(s), static_cast<std::uint64_t>(options.sweeps));
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {std::move(current), std::move(report)};
}

}  // namespace plmap
