#pragma once
// The tools compared by bench_projection_peers: plmap and, when their Debian packages are
// installed, PSurface 2.0 (ContactMapping) and dune-grid-glue 2.9 (ContactMerge). Each tool
// converts the input into its own form first (not measured), then calls `clock.start()`, runs its
// projection, calls `clock.stop()` once its overlaps exist, and only then adds up their measure.

#include "inputs.hpp"
#include "measurement.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace plmap::peers {

struct ToolOutcome {
  bool ok = false;
  std::string error;     ///< why the tool did not produce overlaps (exception text)
  double covered = 0.0;  ///< sum of the overlap measures on S1
  long pieces = 0;       ///< regions (plmap), intersection primitives or simplices (peers)
  nlohmann::json details = nlohmann::json::object();
};

/// `renumbering`: ProjectionOptions::renumbering ("auto", "always", "target" or "never").
template <int d>
ToolOutcome run_plmap(const SurfacePair<d>& input, unsigned threads, const std::string& renumbering,
                      Measurement& clock);

#ifdef PLMAP_PEERS_HAVE_PSURFACE
template <int d>
ToolOutcome run_psurface(const SurfacePair<d>& input, Measurement& clock);
#endif

#ifdef PLMAP_PEERS_HAVE_CONTACTMERGE
template <int d>
ToolOutcome run_contactmerge(const SurfacePair<d>& input, Measurement& clock);
#endif

}  // namespace plmap::peers
