#pragma once
/// \file
/// Parametrization smoothing (paper 3.3.2), per S1 element: on every element T, the nodes
/// strictly inside T (type `interior`: S2 vertex preimages) are re-placed by a convex-combination
/// parametrization of T's regions, with every node on ∂T fixed. Each free node becomes
/// Σ_j w_j · neighbour_j, with weights (a strategy, smoothing_weights_registry.hpp) computed from
/// the node's star on S2, so that the map gets closer to an isometry. T is convex and the weights
/// positive, so Tutte's/Floater's theorem gives an embedding; the result is still checked with
/// the exact orientation predicate, and an element whose solve would fold keeps its old nodes.
/// Every step is also guarded by κ_Ξ of the regions it changes, so that after a sweep
/// κ max ≤ max(κ max before, 3) (docs/algorithms/smoothing.md, "Guarantee").
///
/// The element pass changes node positions and region maps only. Then (SmoothOptions::
/// quadrilaterals) every S1 edge with two triangles is smoothed over their quadrilateral
/// (construct/src/quad_smoothing.hpp): the S2 vertex preimages of both triangles are re-placed
/// together and may cross the shared edge, whose crossings with S2 edges are recomputed; the map
/// is rebuilt through MapBuilder after the pass. Quadrilaterals need a map in which every S2
/// vertex and edge has a complete preimage and no S1 vertex is a ghost (a parametrization such
/// as a simplification-built map); for other maps only the element pass runs
/// (SmoothReport::quadrilaterals_not_applicable says why). d = 2 only.
///
///   SmoothOptions options;                 // floater weights, one sweep
///   SmoothResult r = smooth(map, options); // r.map: the smoothed PlMap<2>

#include <plmap/core/pl_map.hpp>
#include <plmap/core/progress.hpp>

#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>

namespace plmap {

/// The distribution of κ_Ξ over a map's regions (DESIGN.md §4.7). construct/ does not compute it
/// (κ lives in verify/, on which construct/ does not depend): SmoothOptions::measure_kappa does.
struct KappaSummary {
  double max = 1.0;
  double mean = 1.0;
  std::vector<double> quantile_levels;  ///< e.g. 0.5, 0.9, 0.99
  std::vector<double> quantiles;        ///< κ at those levels
  /// Histogram of log10 κ: bin i counts regions with log10 κ in [i w, (i + 1) w).
  double histogram_bin_width = 0.25;
  std::vector<std::size_t> histogram;
  Index degenerate_regions = 0;  ///< zero measure on either side (κ infinite), not counted above
};

struct SmoothOptions {
  /// Passes over all elements and edges (default 1). The element pass alone is a fixed point
  /// after one sweep; the quadrilaterals couple neighbouring elements, so more sweeps keep
  /// improving the map (paper: fewer than ten are enough).
  int sweeps = 1;
  /// Run the element pass in each sweep (default true); false leaves only the quadrilaterals.
  bool elements = true;
  /// After the element pass of each sweep, smooth over the quadrilateral of every interior S1
  /// edge (default true).
  bool quadrilaterals = true;
  /// Smoothing weights: "floater" (default, the paper's shape-preserving weights), "mean-value",
  /// "uniform".
  std::string weights = "floater";
  /// If given, κ_Ξ is measured before the first sweep and after each one, into the report
  /// (e.g. from verify's compute_quality, as `plmap smooth` does).
  std::function<KappaSummary(const PlMap<2>&)> measure_kappa;
  /// Used instead of measure_kappa when that is not given: the smoothing hands over the κ_Ξ of
  /// every region (region order; infinite for a degenerate region) of the input and of the map
  /// after each sweep, which its guards compute anyway, the same values as verify's
  /// region_conditioning (e.g. `plmap smooth` passes them to verify's kappa_statistics), so that
  /// the report costs no second evaluation of the map.
  std::function<KappaSummary(std::span<const double> region_kappas)> summarize_kappa;
  /// Called after each sweep with its number (1-based) and the map so far; e.g. the CLI computes
  /// κ with verify/ there, which construct/ does not depend on. Optional.
  std::function<void(int sweep, const PlMap<2>&)> after_sweep;
  /// Phase "smoothing sweeps", counting sweeps: at the start and end of each. Optional; a
  /// callback that throws cancels.
  ProgressCallback progress = {};
};

struct SmoothSweepReport {
  Index elements_smoothed = 0;  ///< elements with free nodes whose new positions were kept
  Index nodes_moved = 0;        ///< free nodes whose position changed
  /// Largest node displacement, in the element's local coordinates (the reference triangle).
  double max_displacement = 0.0;
  /// Elements whose solve would have raised their worst κ_Ξ above max(old, 3), so that only a
  /// part of the move (1/2, 1/4, ... 1/64) was kept (elements refused outright are counted in
  /// SmoothReport::skipped_by_reason["would raise the worst condition number"]).
  Index elements_shortened = 0;
  /// κ_Ξ after this sweep (when SmoothOptions::measure_kappa or summarize_kappa is given).
  std::optional<KappaSummary> kappa;

  // ---- the quadrilateral pass ----
  Index quadrilaterals_smoothed = 0;  ///< quadrilateral steps kept
  Index quad_nodes_moved = 0;         ///< vertex preimages moved by them (counted per step)
  Index nodes_crossed = 0;            ///< of these, those that changed S1 element
  /// Largest move in one step, relative to the length of the quadrilateral's shared edge.
  double quad_max_displacement = 0.0;
  /// Steps' unknowns whose weights model refused their star and got uniform weights instead.
  Index quad_uniform_fallbacks = 0;
  /// Steps refused (the quadrilateral left as it was), by reason: "non-convex quadrilateral",
  /// "fold-over", "node leaves the quadrilateral", "crossing next to a vertex", ...
  std::map<std::string, Index> quadrilaterals_skipped_by_reason;
  /// Times the pass ran: after each run the rebuilt map is measured, and where an element's worst
  /// κ_Ξ rose above max(the worst before in it and its edge neighbours, 3) the element's edges
  /// are frozen (counted in quadrilaterals_skipped_by_reason as "would raise the worst condition
  /// number of the rebuilt map") and the pass runs again; at most 8 times.
  int quadrilateral_attempts = 0;
  /// True if the rebuilt map was refused (MapBuilder found a crossing or a reversed face, which
  /// the step's checks should have prevented): the sweep then keeps the element pass only.
  bool quadrilateral_pass_rejected = false;
  /// True if the last run still raised κ (or an element no step touched rose above the map's
  /// worst κ before the sweep): the sweep then keeps the element pass only.
  bool quadrilateral_pass_refused_by_kappa = false;
};

struct SmoothReport {
  std::vector<SmoothSweepReport> sweeps;
  /// κ_Ξ of the input (when SmoothOptions::measure_kappa or summarize_kappa is given).
  std::optional<KappaSummary> kappa_before;
  Index free_nodes = 0;  ///< interior nodes (the unknowns), counted once
  /// Nodes whose weights model refused their star (degenerate: a zero spoke or angle); they were
  /// given uniform weights, which never fail.
  Index uniform_fallback_nodes = 0;
  /// Elements whose nodes were left where they were, by reason ("fold-over": the solve would
  /// have turned a region over; "open star": a free node's regions do not close around it;
  /// "solver": the sparse solve failed), summed over the sweeps.
  std::map<std::string, Index> skipped_by_reason;
  std::vector<Index> skipped_elements;  ///< of the last sweep
  std::string weights;
  /// Why the quadrilateral pass did not run (the map is not a parametrization in the needed
  /// sense), or empty.
  std::string quadrilaterals_not_applicable;
  double seconds = 0.0;
};

struct SmoothResult {
  PlMap<2> map;
  SmoothReport report;
};

/// Throws plmap::Error for an unknown weights name or sweeps < 1 (before any work).
SmoothResult smooth(const PlMap<2>& map, const SmoothOptions& options = {});

}  // namespace plmap
