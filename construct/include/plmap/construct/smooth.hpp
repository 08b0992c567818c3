#pragma once
/// \file
/// Parametrization smoothing (paper 3.3.2), per S1 element: on every element T, the nodes
/// strictly inside T (type `interior`: S2 vertex preimages) are re-placed by a convex-combination
/// parametrization of T's regions, with every node on ∂T fixed. Each free node becomes
/// Σ_j w_j · neighbour_j, with weights (a strategy, smoothing_weights_registry.hpp) computed from
/// the node's star on S2, so that the map gets closer to an isometry. T is convex and the weights
/// positive, so Tutte's/Floater's theorem gives an embedding; the result is still checked with
/// the exact orientation predicate, and an element whose solve would fold keeps its old nodes.
///
/// Node images do not change; node positions and region maps do, everything else is kept.
/// d = 2 only. Smoothing over the quadrilaterals of two elements (the paper's enlarged domains)
/// is not done yet: with fixed element boundaries the per-element solve is a fixed point, so a
/// second sweep reproduces the first.
///
///   SmoothOptions options;                 // floater weights, one sweep
///   SmoothResult r = smooth(map, options); // r.map: the smoothed PlMap<2>

#include <plmap/core/pl_map.hpp>
#include <plmap/core/progress.hpp>

#include <functional>
#include <map>
#include <string>

namespace plmap {

struct SmoothOptions {
  /// Passes over all elements (default 1; see the file comment: more sweeps change nothing until
  /// quadrilateral smoothing exists).
  int sweeps = 1;
  /// Smoothing weights: "floater" (default, the paper's shape-preserving weights), "mean-value",
  /// "uniform".
  std::string weights = "floater";
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
};

struct SmoothReport {
  std::vector<SmoothSweepReport> sweeps;
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
  double seconds = 0.0;
};

struct SmoothResult {
  PlMap<2> map;
  SmoothReport report;
};

/// Throws plmap::Error for an unknown weights name or sweeps < 1 (before any work).
SmoothResult smooth(const PlMap<2>& map, const SmoothOptions& options = {});

}  // namespace plmap
