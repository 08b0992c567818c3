// Per-element parametrization smoothing (paper 3.3.2); see smooth.hpp for the method.

#include <plmap/construct/smooth.hpp>

#include "preimage_graph.hpp"
#include "quad_smoothing.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/element_transfer.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/predicates.hpp>
#include <plmap/strategies/smoothing/smoothing_weights_registry.hpp>
#include <plmap/strategies/smoothing/uniform_weights.hpp>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace plmap {

namespace {

/// What one element's solve decided: new positions for its nodes [begin, end), or why not.
struct ElementOutcome {
  std::vector<LocalPoint<2>> positions;  ///< indexed by node - node_begin[T]; empty if skipped
  const char* skipped = nullptr;
};

class ElementSmoother {
 public:
  ElementSmoother(const PlMap<2>& map, const MapData<2>& m, const AnySmoothingWeights& weights, SmoothReport& report)
      : map_(map), m_(m), weights_(weights), report_(report) {}

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

    triplets_.clear();
    Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(unknowns, 2);
    for (Index n = nb; n < ne; ++n) {
      const int i = unknown_[local(n)];
      if (i < 0) continue;
      const auto ring_nodes = map_.neighbors(n);
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
      triplets_.emplace_back(i, i, 1.0);
      for (std::size_t j = 0; j < ring_nodes.size(); ++j) {
        const Index q = ring_nodes[j];
        const int col = unknown_[local(q)];
        if (col >= 0)
          triplets_.emplace_back(i, col, -(*w)[j]);
        else
          rhs.row(i) += (*w)[j] * m_.node_position[q].transpose();
      }
    }
    // The matrix is an M-matrix (diagonally dominant, strictly in rows next to a fixed node) but
    // not symmetric for geometric weights: a sparse LU, not a Cholesky factorization.
    Eigen::SparseMatrix<double> a(unknowns, unknowns);
    a.setFromTriplets(triplets_.begin(), triplets_.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(a);
    if (lu.info() != Eigen::Success) {
      out.skipped = "solver";
      return out;
    }
    const Eigen::MatrixX2d x = lu.solve(rhs);
    if (lu.info() != Eigen::Success || !x.allFinite()) {
      out.skipped = "solver";
      return out;
    }
    out.positions.assign(m_.node_position.begin() + nb, m_.node_position.begin() + ne);
    for (Index n = nb; n < ne; ++n) {
      const int i = unknown_[local(n)];
      if (i < 0) continue;
      const LocalPoint<2> p = x.row(i).transpose();
      // strictly inside the reference triangle, or the node would leave its element
      if (!(p.x() > 0.0 && p.y() > 0.0 && p.x() + p.y() < 1.0)) {
        out.positions.clear();
        out.skipped = "fold-over";
        return out;
      }
      out.positions[local(n)] = p;
    }
    for (Index r = rb; r < re; ++r) {
      const auto& c = m_.region_corners[r];
      if (orient2d(out.positions[local(c[0])], out.positions[local(c[1])], out.positions[local(c[2])]) <= 0) {
        out.positions.clear();
        out.skipped = "fold-over";
        return out;
      }
    }
    return out;
  }

 private:
  const PlMap<2>& map_;
  const MapData<2>& m_;
  const AnySmoothingWeights& weights_;
  SmoothReport& report_;
  std::vector<int> unknown_, incidence_;
  std::vector<Eigen::Triplet<double>> triplets_;
  std::vector<Eigen::Vector3d> ring_;
};

/// Writes the kept positions of element t into `out` and recomputes its regions' maps from them,
/// the images (on each region's S2 element) unchanged.
void apply_outcome(const PlMap<2>& map, Index t, const std::vector<LocalPoint<2>>& positions, MapData<2>& out,
                   SmoothSweepReport& sweep) {
  const MapData<2>& old = map.data();
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
  if (!moved_any) return;
  for (Index r = old.region_begin[t]; r < old.region_begin[t + 1]; ++r) {
    const auto& c = old.region_corners[r];
    std::array<LocalPoint<2>, 3> from, to;
    for (int k = 0; k < 3; ++k) {
      from[k] = out.node_position[c[k]];
      // the image on the region's S2 element, exactly where it is a vertex or on an edge
      to[k] = transfer_to_element(map.target(), old.node_image[c[k]], old.region_target[r])
                  .value_or(apply<2>(old.region_map[r], old.node_position[c[k]]));
    }
    out.region_map[r] = affine_through<2>(from, to);
  }
}

/// Total area of the region images on S2: smoothing re-places preimages, so it must not change.
double image_area(const PlMap<2>& map) {
  const MapData<2>& m = map.data();
  double total = 0.0;
  for (Index r = 0; r < map.region_count(); ++r) {
    const auto& c = m.region_corners[r];
    const Eigen::Vector3d a = map.node_target_world(c[0]);
    total += 0.5 * (map.node_target_world(c[1]) - a).cross(map.node_target_world(c[2]) - a).norm();
  }
  return total;
}

/// The quadrilateral pass of one sweep: every S1 edge with two triangles, in index order, each
/// step seeing the previous ones; then the map is rebuilt from the edited graph.
void smooth_quadrilaterals(PlMap<2>& current, const AnySmoothingWeights& weights, SmoothReport& report,
                           SmoothSweepReport& sweep) {
  std::string why;
  std::optional<smoothing::PreimageGraph> graph = smoothing::PreimageGraph::from_map(current, &why);
  if (!graph) {
    report.quadrilaterals_not_applicable = why;
    return;
  }
  smoothing::QuadSmoother smoother(*graph, current.domain(), current.target(), weights);
  for (Index e = 0; e < current.domain().edge_count(); ++e) {
    if (!smoother.has_quadrilateral(e)) continue;
    const smoothing::QuadOutcome o = smoother.smooth(e);
    if (o.skipped != nullptr) {
      ++sweep.quadrilaterals_skipped_by_reason[o.skipped];
      continue;
    }
    ++sweep.quadrilaterals_smoothed;
    sweep.quad_nodes_moved += o.nodes_moved;
    sweep.nodes_crossed += o.nodes_crossed;
    sweep.quad_max_displacement = std::max(sweep.quad_max_displacement, o.max_displacement);
  }
  sweep.quad_uniform_fallbacks = smoother.uniform_fallbacks();
  try {
    FinalizeReport built;
    PlMap<2> rebuilt = graph->to_map(current.domain_ptr(), current.target_ptr(), &built);
    // The same coverage of S2, up to rounding: guards against a map the graph form cannot hold
    // (e.g. an S2 edge whose preimage leaves D between two vertex preimages).
    const double area = image_area(current);
    if (built.reversed_faces == 0 && built.dropped_edges.empty() && rebuilt.region_count() > 0 &&
        std::abs(image_area(rebuilt) - area) <= 1e-9 * area) {
      current = std::move(rebuilt);
      return;
    }
  } catch (const Error&) {
    // falls through: the step checks missed an inconsistency; keep the element pass's map
  }
  sweep.quadrilateral_pass_rejected = true;
}

}  // namespace

SmoothResult smooth(const PlMap<2>& map, const SmoothOptions& options) {
  if (options.sweeps < 1) throw Error(fmt::format("smoothing needs at least one sweep (got {})", options.sweeps));
  const AnySmoothingWeights weights = make_smoothing_weights(options.weights);
  const auto start = std::chrono::steady_clock::now();

  SmoothReport report;
  report.weights = options.weights;
  PlMap<2> current(map.domain_ptr(), map.target_ptr(), map.data());
  if (options.measure_kappa) report.kappa_before = options.measure_kappa(current);
  const Index elements = map.domain().element_count();
  for (int s = 1; s <= options.sweeps; ++s) {
    report_progress(options.progress, "smoothing sweeps", static_cast<std::uint64_t>(s - 1), static_cast<std::uint64_t>(options.sweeps));
    SmoothSweepReport sweep;
    MapData<2> next = current.data();
    ElementSmoother smoother(current, current.data(), weights, report);
    report.skipped_elements.clear();
    for (Index t = 0; t < (options.elements ? elements : 0); ++t) {
      ElementOutcome outcome = smoother.solve(t, s == 1);
      if (outcome.skipped != nullptr) {
        ++report.skipped_by_reason[outcome.skipped];
        report.skipped_elements.push_back(t);
        continue;
      }
      if (!outcome.positions.empty()) apply_outcome(current, t, outcome.positions, next, sweep);
    }
    current = PlMap<2>(map.domain_ptr(), map.target_ptr(), std::move(next));
    if (options.quadrilaterals) smooth_quadrilaterals(current, weights, report, sweep);
    if (options.measure_kappa) sweep.kappa = options.measure_kappa(current);
    report.sweeps.push_back(sweep);
    if (options.after_sweep) options.after_sweep(s, current);
    report_progress(options.progress, "smoothing sweeps", static_cast<std::uint64_t>(s), static_cast<std::uint64_t>(options.sweeps));
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {std::move(current), std::move(report)};
}

}  // namespace plmap
