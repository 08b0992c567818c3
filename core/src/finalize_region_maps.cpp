// finalize(), phase 5: the regions' affine maps (finalize_region_maps.hpp).

#include "finalize_region_maps.hpp"
#include "local_simplex_measure.hpp"
#include "map_arrays.hpp"
#include "weights_by_vertex_identity.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_first_touch.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>

namespace plmap::detail {

namespace {

/// The omitted weight of node n (finalize_region_maps.hpp): kept, or 1 minus the stored two.
double omitted_weight(std::span<const KeptOmittedWeight> kept, const LocalPoint<2>& local, Index n) {
  const auto it = std::lower_bound(kept.begin(), kept.end(), n,
                                   [](const KeptOmittedWeight& k, Index node) { return k.node < node; });
  return it != kept.end() && it->node == n ? it->weight : 1.0 - local.sum();
}

/// Node n's image in the local coordinates of S2 element t, which contains it: the value
/// support_local gives from the node's support (its weights are node_image_local's two values
/// and the omitted one), as the binary map file derives it but for the kept omitted weights.
LocalPoint<2> image_on(const Surface<2>& s2, const MapData<2>& m, std::span<const KeptOmittedWeight> kept, Index n,
                       Index t) {
  const auto i = static_cast<std::size_t>(n);
  const Index e = m.node_image_element[i];
  const LocalPoint<2>& local = m.node_image_local[i];
  if (e == t) return local;
  return weights_by_vertex_identity<2>(s2.element(e), s2.element(t), local,
                                       [&] { return omitted_weight(kept, local, n); });
}

}  // namespace

double omitted_image_weight(const Support<2>& s) {
  for (int i = 0; i < s.count; ++i)
    if (s.corner(i) == 0) return s.weight[i];
  return 0.0;
}

std::optional<double> omitted_weight_to_keep(const Support<2>& s, const LocalPoint<2>& stored) {
  const double omitted = omitted_image_weight(s), derived = 1.0 - stored.sum();
  if (std::bit_cast<std::uint64_t>(omitted) == std::bit_cast<std::uint64_t>(derived)) return std::nullopt;
  return omitted;
}

namespace {

/// The region maps, and with `terms` each region's image term: written to terms->per_region when
/// that is sized (several threads), else added to terms->per_target in region order (one thread).
struct ImageTerms {
  std::vector<double> per_region;
  std::vector<double>* per_target = nullptr;
};

void write_maps(const Surface<2>& s2, std::span<const KeptOmittedWeight> kept, MapData<2>& m, unsigned threads,
                double spare_room, ImageTerms* terms) {
  if (!m.region_map.empty()) throw BuilderError("internal: region maps written twice");
  const std::size_t regions = m.region_target.size();
  m.region_map.reserve(with_spare_room(regions, spare_room));
  advise_huge_pages(m.region_map.data(), regions * sizeof(m.region_map[0]));  // before the first write
  m.region_map.resize(regions);
  // The array is first-touched here, in a tight loop of stores, one page fault per 85 regions
  // (the assembly used to spread them over the closing pass): backing its pages ahead in one call
  // took the 200k plane pair's finalize from a median 2.37 s back to 2.31 s (seven alternating
  // runs, docs/benchmarks.md), and doing so on all threads keeps it from being a serial phase of
  // its own (parallel_first_touch.hpp).
  populate_in_parallel(m.region_map.data(), regions * sizeof(m.region_map[0]), threads);
  // (chunks of 4096 regions: they only balance the threads, each region's map and term being its
  // own; with 16384 the 41k regions of the bones pair were three chunks for two threads)
  parallel_for_chunks(regions, 4096, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      const auto& corners = m.region_corners[r];
      const Index t = m.region_target[r];
      std::array<LocalPoint<2>, 3> from, to;
      for (int i = 0; i < 3; ++i) {
        from[i] = m.node_position[static_cast<std::size_t>(corners[i])];
        to[i] = image_on(s2, m, kept, corners[i], t);
      }
      m.region_map[r] = affine_through<2>(from, to);
      if (terms == nullptr) continue;
      if (terms->per_region.empty())
        (*terms->per_target)[static_cast<std::size_t>(t)] += local_simplex_measure<2>(to);
      else
        terms->per_region[r] = local_simplex_measure<2>(to);
    }
  });
}

}  // namespace

void write_region_maps(const Surface<2>& s2, std::span<const KeptOmittedWeight> kept, MapData<2>& m, unsigned threads,
                       double spare_room) {
  write_maps(s2, kept, m, threads, spare_room, nullptr);
}

ImageMeasures write_region_maps_and_measure(const Surface<2>& s1, const Surface<2>& s2,
                                            std::span<const KeptOmittedWeight> kept, MapData<2>& m, unsigned threads,
                                            double spare_room) {
  ImageMeasures out;
  assign_on_huge_pages(out.per_target, static_cast<std::size_t>(s2.element_count()), 0.0, threads);
  ImageTerms terms;
  terms.per_target = &out.per_target;
  const bool one_thread = resolve_thread_count(threads) <= 1;
  if (!one_thread) assign_on_huge_pages(terms.per_region, m.region_target.size(), 0.0, threads);
  write_maps(s2, kept, m, threads, spare_room, &terms);
  if (!one_thread) {
    for (std::size_t r = 0; r < m.region_target.size(); ++r)
      out.per_target[static_cast<std::size_t>(m.region_target[r])] += terms.per_region[r];
    std::vector<double>().swap(terms.per_region);
  }
  // as image_measures sums them: per S1 element with regions, in element order
  for (Index t = 0; t < s1.element_count(); ++t)
    if (m.region_begin[t] != m.region_begin[t + 1]) out.covered.domain += element_regions_measure(m, s1, t);
  out.covered.target = covered_target_measure(out.per_target, s2);
  return out;
}

}  // namespace plmap::detail
