// verify() and the single checks: the index check gates everything that dereferences indices.

#include <plmap/verify/check.hpp>

#include "check_context.hpp"

namespace plmap {

namespace {

using detail::MapContext;
using detail::ViolationSink;

constexpr const char* skipped_because = "skipped: indices out of range (see structure/index_range)";

/// Runs the index check (and, when asked, the rest of "structure") into a CheckResult.
template <int d>
CheckResult structure_result(const MapContext<d>& ctx, bool full, bool& indices_ok) {
  CheckResult result;
  result.name = check_names::structure;
  ViolationSink sink(result, ctx.options.max_reported_per_rule);
  indices_ok = detail::check_indices(ctx, sink);
  if (indices_ok && full) detail::run_structure(ctx, sink);
  return result;
}

template <int d, class Run>
CheckResult gated_result(const MapContext<d>& ctx, std::string_view name, bool indices_ok, Run run) {
  CheckResult result;
  result.name = name;
  if (!indices_ok) {
    result.skipped = true;
    result.skipped_reason = skipped_because;
    return result;
  }
  ViolationSink sink(result, ctx.options.max_reported_per_rule);
  run(ctx, sink);
  return result;
}

template <int d>
CheckResult quality_result(const PlMap<d>& map, const VerifyOptions& options, bool indices_ok,
                           std::optional<QualityReport>& quality) {
  CheckResult result;
  result.name = check_names::quality;
  if (!indices_ok) {
    result.skipped = true;
    result.skipped_reason = skipped_because;
    return result;
  }
  ViolationSink sink(result, options.max_reported_per_rule);
  if (std::isfinite(options.max_condition)) {
    for (Index r = 0; r < map.region_count(); ++r) {
      const RegionConditioning c = region_conditioning(map, r);
      if (!(c.kappa <= options.max_condition))
        sink.add("condition", {map.node_element(map.data().region_corners[r][0]), invalid_index, r,
                               map.data().region_target[r]},
                 [&] {
                   return fmt::format("region {} has condition number {:.6g} > {:g}", r, c.kappa,
                                      options.max_condition);
                 });
    }
  }
  quality = compute_quality(map);
  return result;
}

/// A single check run alone: the index check first, its violations reported under "structure"
/// only if it fails (then the check itself is skipped).
template <int d, class Run>
VerificationReport single_check(const PlMap<d>& map, const VerifyOptions& options,
                                std::string_view name, Run run) {
  const MapContext<d> ctx(map, options);
  bool indices_ok = true;
  CheckResult structure = structure_result(ctx, false, indices_ok);
  VerificationReport report;
  if (!indices_ok) report.checks.push_back(std::move(structure));
  report.checks.push_back(gated_result(ctx, name, indices_ok, run));
  return report;
}

}  // namespace

template <int d>
VerificationReport verify(const PlMap<d>& map, const VerifyOptions& options) {
  const MapContext<d> ctx(map, options);
  VerificationReport report;
  bool indices_ok = true;
  report.checks.push_back(structure_result(ctx, true, indices_ok));
  report.checks.push_back(gated_result(ctx, check_names::plane_graph, indices_ok,
                                       detail::run_plane_graph<d>));
  report.checks.push_back(gated_result(ctx, check_names::minimal_embedding, indices_ok,
                                       detail::run_minimal_embedding<d>));
  report.checks.push_back(gated_result(ctx, check_names::map, indices_ok, detail::run_map<d>));
  report.checks.push_back(gated_result(ctx, check_names::continuity, indices_ok,
                                       detail::run_continuity<d>));
  report.checks.push_back(gated_result(ctx, check_names::coverage, indices_ok,
                                       detail::run_coverage<d>));
  if (options.compute_quality || std::isfinite(options.max_condition)) {
    std::optional<QualityReport> quality;
    report.checks.push_back(quality_result(map, options, indices_ok, quality));
    report.quality = std::move(quality);
  }
  return report;
}

template <int d>
VerificationReport check_structure(const PlMap<d>& map, const VerifyOptions& options) {
  const MapContext<d> ctx(map, options);
  bool indices_ok = true;
  VerificationReport report;
  report.checks.push_back(structure_result(ctx, true, indices_ok));
  return report;
}

template <int d>
VerificationReport check_plane_graph(const PlMap<d>& map, const VerifyOptions& options) {
  return single_check(map, options, check_names::plane_graph, detail::run_plane_graph<d>);
}
template <int d>
VerificationReport check_minimal_embedding(const PlMap<d>& map, const VerifyOptions& options) {
  return single_check(map, options, check_names::minimal_embedding, detail::run_minimal_embedding<d>);
}
template <int d>
VerificationReport check_map(const PlMap<d>& map, const VerifyOptions& options) {
  return single_check(map, options, check_names::map, detail::run_map<d>);
}
template <int d>
VerificationReport check_continuity(const PlMap<d>& map, const VerifyOptions& options) {
  return single_check(map, options, check_names::continuity, detail::run_continuity<d>);
}
template <int d>
VerificationReport check_coverage(const PlMap<d>& map, const VerifyOptions& options) {
  return single_check(map, options, check_names::coverage, detail::run_coverage<d>);
}
template <int d>
VerificationReport check_quality(const PlMap<d>& map, const VerifyOptions& options) {
  const MapContext<d> ctx(map, options);
  bool indices_ok = true;
  CheckResult structure = structure_result(ctx, false, indices_ok);
  VerificationReport report;
  if (!indices_ok) report.checks.push_back(std::move(structure));
  std::optional<QualityReport> quality;
  report.checks.push_back(quality_result(map, options, indices_ok, quality));
  report.quality = std::move(quality);
  return report;
}

#define PLMAP_INSTANTIATE_CHECKS(D)                                                             \
  template VerificationReport verify(const PlMap<D>&, const VerifyOptions&);                    \
  template VerificationReport check_structure(const PlMap<D>&, const VerifyOptions&);           \
  template VerificationReport check_plane_graph(const PlMap<D>&, const VerifyOptions&);         \
  template VerificationReport check_minimal_embedding(const PlMap<D>&, const VerifyOptions&);   \
  template VerificationReport check_map(const PlMap<D>&, const VerifyOptions&);                 \
  template VerificationReport check_continuity(const PlMap<D>&, const VerifyOptions&);          \
  template VerificationReport check_coverage(const PlMap<D>&, const VerifyOptions&);            \
  template VerificationReport check_quality(const PlMap<D>&, const VerifyOptions&);

PLMAP_INSTANTIATE_CHECKS(1)
PLMAP_INSTANTIATE_CHECKS(2)

#undef PLMAP_INSTANTIATE_CHECKS

}  // namespace plmap
