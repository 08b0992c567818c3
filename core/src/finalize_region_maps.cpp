// finalize(), phase 5: the regions' affine maps (finalize_region_maps.hpp).

#include "finalize_region_maps.hpp"

#include <plmap/core/affine_through.hpp>
#include <plmap/core/errors.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <array>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace plmap::detail {

namespace {

/// Node n's image in the local coordinates of S2 element t (corners `to`), which contains it: the
/// value support_local gives from the node's support. The support's vertices are corners of the
/// image element e, and their weights are node_image_local's two values and the omitted one; a
/// corner of t that is no corner of e carries no weight (+0.0, as support_local leaves it).
LocalPoint<2> image_on(const Surface<2>& s2, const MapData<2>& m, const std::vector<double>& omitted, Index n, Index t,
                       const ElementCorners<2>& to) {
  const auto i = static_cast<std::size_t>(n);
  const Index e = m.node_image_element[i];
  const LocalPoint<2>& local = m.node_image_local[i];
  if (e == t) return local;
  const auto& from = s2.element(e);
  auto weight_of = [&](Index v) {
    return v == from[0] ? omitted[i] : v == from[1] ? local(0) : v == from[2] ? local(1) : 0.0;
  };
  return LocalPoint<2>(weight_of(to[1]), weight_of(to[2]));
}

}  // namespace

double omitted_image_weight(const Surface<2>& s2, const Support<2>& s) {
  const Index corner0 = s2.element(s.element)[0];
  for (int i = 0; i < s.count; ++i)
    if (s.vertex[i] == corner0) return s.weight[i];
  return 0.0;
}

void write_region_maps(const Surface<2>& s2, const std::vector<double>& omitted, MapData<2>& m, unsigned threads) {
  if (omitted.size() != m.node_position.size() || !m.region_map.empty())
    throw BuilderError("internal: region maps deferred without one omitted weight per node");
  const std::size_t regions = m.region_target.size();
  m.region_map.reserve(regions);
  advise_huge_pages(m.region_map.data(), regions * sizeof(m.region_map[0]));  // before the first write
  m.region_map.resize(regions);
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  // The array is first-touched here, in a tight loop of stores, one page fault per 85 regions
  // (the assembly used to spread them over the closing pass): prefaulting its pages in one call
  // took the 200k plane pair's finalize from a median 2.37 s back to 2.31 s (main: 2.21 s; seven
  // alternating runs, docs/benchmarks.md). Without the call (older kernels: EINVAL, ignored)
  // the pages fault in as they are written, to the same result.
  {
    const long page_size = sysconf(_SC_PAGESIZE);  // 4 KiB on x86-64, 16 or 64 KiB on some ARM systems
    const auto page = static_cast<std::uintptr_t>(page_size > 0 ? page_size : 4096);
    const auto first = (reinterpret_cast<std::uintptr_t>(m.region_map.data()) + page - 1) & ~(page - 1);
    const auto last = reinterpret_cast<std::uintptr_t>(m.region_map.data() + regions) & ~(page - 1);
    if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE);
  }
#endif
  parallel_for_chunks(regions, 16384, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      const auto& corners = m.region_corners[r];
      const Index t = m.region_target[r];
      const auto& target_corners = s2.element(t);
      std::array<LocalPoint<2>, 3> from, to;
      for (int i = 0; i < 3; ++i) {
        from[i] = m.node_position[static_cast<std::size_t>(corners[i])];
        to[i] = image_on(s2, m, omitted, corners[i], t, target_corners);
      }
      m.region_map[r] = affine_through<2>(from, to);
    }
  });
}

}  // namespace plmap::detail
