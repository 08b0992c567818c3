// DESIGN.md §4.5: Xi agrees on shared S1 edges (d = 1: shared vertices) evaluated from either
// side. Samples on each shared edge are located among the regions of every incident element
// that have a side on that edge, and the world images are compared.

#include "check_context.hpp"

#include <optional>

namespace plmap::detail {

namespace {

/// Evaluates Xi at p among the given regions, trying them cyclically from `*hint` on: the
/// callers pass regions sorted along the edge and samples in increasing order, so the search
/// usually succeeds at the first or second try and the check stays linear.
template <int d>
std::optional<WorldPoint<d>> evaluate_among(const MapContext<d>& ctx, std::span<const Index> regions,
                                            const LocalPoint<d>& p, std::size_t* hint,
                                            Index* region_found) {
  const auto& m = ctx.data;
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const std::size_t at = (*hint + k) % regions.size();
    const Index r = regions[at];
    std::array<LocalPoint<d>, d + 1> c;
    for (int i = 0; i <= d; ++i) c[i] = m.node_position[m.region_corners[r][i]];
    const Barycentric<d> b = barycentric_in<d>(c, p);
    if (b.minCoeff() >= -ctx.options.local_tolerance) {
      *hint = at;
      *region_found = r;
      return ctx.s2.world_position(m.region_target[r], apply<d>(m.region_map[r], p));
    }
  }
  return std::nullopt;
}

}  // namespace

template <int d>
void run_continuity(const MapContext<d>& ctx, ViolationSink& sink) {
  const auto& m = ctx.data;
  const double world_tol = ctx.world_tolerance_s2;
  const double snap = ctx.options.snap_tolerance;

  struct Sample {
    std::optional<WorldPoint<d>> reference;
    Index reference_element = invalid_index;
    double reference_rounding = 0.0;  ///< of the region map that gave `reference`, in space
  };
  std::vector<Sample> samples;
  std::vector<Index> candidates;

  auto compare = [&](Sample& sample, const std::optional<WorldPoint<d>>& value, Index t, Index r,
                     const char* what, Index which, double s) {
    if (!value) return;
    // Each side's region map rounds as its stretch says (region_map_rounding).
    const double rounding = r == invalid_index ? 0.0 : rounding_in_space(region_map_rounding<d>(m.region_map[r]), ctx.s2);
    if (!sample.reference) {
      sample.reference = value;
      sample.reference_element = t;
      sample.reference_rounding = rounding;
      return;
    }
    const double dist = (*value - *sample.reference).norm();
    const double tolerance = world_tol + sample.reference_rounding + rounding;
    if (!(dist <= tolerance))
      sink.add("shared_boundary_mismatch", {t, invalid_index, r}, [&] {
        return fmt::format("Xi on S1 {} {} at parameter {:.6g}: element {} gives {}, element {} "
                           "gives {} ({:.3g} apart, tolerance {:.3g})",
                           what, which, s, sample.reference_element, fmt_point<d + 1>(*sample.reference), t,
                           fmt_point<d + 1>(*value), dist, tolerance);
      });
  };

  if constexpr (d == 2) {
    const auto& map = ctx.map;
    std::vector<double> parameters, points;
    std::vector<std::pair<double, Index>> keyed;
    const int per_piece = std::max(1, ctx.options.continuity_samples_per_piece);
    for (Index e = 0; e < ctx.s1.edge_count(); ++e) {
      const auto inc = ctx.s1.edge_elements(e);
      if (inc.size() < 2) continue;
      parameters.assign({0.0, 1.0});
      for (Index n : map.edge_nodes(inc[0].element, inc[0].local_edge))
        parameters.push_back(std::clamp(
            global_edge_parameter(ctx.s1, inc[0].element, inc[0].local_edge, m.node_position[n]),
            0.0, 1.0));
      std::sort(parameters.begin(), parameters.end());
      points.clear();
      for (std::size_t i = 1; i < parameters.size(); ++i) {
        const double a = parameters[i - 1], b = parameters[i];
        if (!(b > a)) continue;
        for (int j = 1; j <= per_piece; ++j) points.push_back(a + (b - a) * j / (per_piece + 1));
      }
      samples.assign(points.size(), Sample{});
      for (const EdgeIncidence& ei : inc) {
        const Index t = ei.element;
        const int opposite = (ei.local_edge + 2) % 3;
        keyed.clear();
        for (Index r = ctx.regions_begin(t); r < ctx.regions_end(t); ++r) {
          int on_edge = 0;
          double along = 0.0;
          for (Index c : m.region_corners[r])
            if (std::abs(barycentric_from_local<2>(m.node_position[c])(opposite)) <= snap) {
              ++on_edge;
              along += global_edge_parameter(ctx.s1, t, ei.local_edge, m.node_position[c]);
            }
          if (on_edge >= 2) keyed.push_back({along / on_edge, r});
        }
        std::sort(keyed.begin(), keyed.end());
        candidates.clear();
        for (const auto& [key, r] : keyed) candidates.push_back(r);
        std::size_t hint = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
          Index r = invalid_index;
          const auto value = evaluate_among<2>(
              ctx, candidates, point_on_global_edge(ctx.s1, t, ei.local_edge, points[i]), &hint, &r);
          compare(samples[i], value, t, r, "edge", e, points[i]);
        }
      }
    }
  } else {
    for (Index v = 0; v < ctx.s1.vertex_count(); ++v) {
      const auto elements = ctx.s1.vertex_elements(v);
      if (elements.size() < 2) continue;
      Sample sample;
      for (Index t : elements) {
        candidates.clear();
        for (Index r = ctx.regions_begin(t); r < ctx.regions_end(t); ++r) candidates.push_back(r);
        LocalPoint<1> p;
        p(0) = ctx.s1.local_corner(t, v) == 0 ? 0.0 : 1.0;
        Index r = invalid_index;
        std::size_t hint = 0;
        compare(sample, evaluate_among<1>(ctx, candidates, p, &hint, &r), t, r, "vertex", v, 0.0);
      }
    }
  }
}

template void run_continuity(const MapContext<1>&, ViolationSink&);
template void run_continuity(const MapContext<2>&, ViolationSink&);

}  // namespace plmap::detail
