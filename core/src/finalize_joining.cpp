// finalize(), phase 4: joining (finalize_joining.hpp).

#include "finalize_joining.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <functional>
#include <type_traits>

namespace plmap::detail {

namespace {

/// offsets[k]: where part k starts in the joined arrays, by what an array counts
using Offsets = std::vector<std::size_t>;

template <class Count>
Offsets offsets_of(const std::vector<MapData<2>>& parts, Count count) {
  Offsets at(parts.size() + 1, 0);
  for (std::size_t k = 0; k < parts.size(); ++k) at[k + 1] = at[k] + count(parts[k]);
  return at;
}

/// Resizes v to n, its new pages backed in one call where its room is reserved already (the
/// first part's is: size_part): one system call instead of a page fault per page.
template <class Vector>
void grow_backed(Vector& v, std::size_t n) {
  if (n > v.size() && n <= v.capacity()) back_pages(v.data() + v.size(), (n - v.size()) * sizeof(v[0]));
  v.resize(n);
}

/// Joins the parts into one map, an array at a time. The first part's arrays become the joined
/// ones: size_part gave them room for the whole map, and its values need no shift (it starts at
/// node, region and entry 0), so only the later parts are copied, appended after it (with two
/// blocks, half of the map instead of all of it: the copy and the first touch of the joined
/// memory were the join's cost). The arrays are joined side by side, one thread per array, the
/// largest first: sizing an array value-initialises its new tail on the thread that sizes it, and
/// that first touch costs as much as the copy, so both are spread over the threads, and no large
/// array is left to start last.
class PartJoiner {
 public:
  PartJoiner(std::vector<MapData<2>>& parts, MapData<2>& m) : parts_(parts), m_(m) {}

  /// Joins array `field` of the parts at `at` (each part's values passed through shift(k,
  /// value)), then releases the parts' copies.
  template <class Field, class Shift>
  void join(Field MapData<2>::*field, const Offsets& at, Shift shift) {
    const std::size_t appended = (at[parts_.size()] - at[1]) * sizeof(typename Field::value_type);
    jobs_.push_back({appended, [this, field, &at, shift] {
                       auto& out = m_.*field;
                       out = std::move(parts_[0].*field);
                       grow_backed(out, at[parts_.size()]);
                       for (std::size_t k = 1; k < parts_.size(); ++k) {
                         auto& in = parts_[k].*field;
                         for (std::size_t i = 0; i < in.size(); ++i) out[at[k] + i] = shift(k, in[i]);
                         Field().swap(in);
                       }
                     }});
  }

  /// The same for a CSR begin array: a leading 0, then each part's ends shifted by the values of
  /// the parts before.
  void join_begins(std::vector<Index> MapData<2>::*field, const Offsets& at, const Offsets& values) {
    const std::size_t appended = (at[parts_.size()] - at[1]) * sizeof(Index);
    jobs_.push_back({appended, [this, field, &at, &values] {
                       auto& out = m_.*field;
                       out = std::move(parts_[0].*field);  // [0, at[1]]: the first part's, unshifted
                       grow_backed(out, at[parts_.size()] + 1);
                       for (std::size_t k = 1; k < parts_.size(); ++k) {
                         auto& in = parts_[k].*field;
                         for (std::size_t i = 0; i + 1 < in.size(); ++i) out[at[k] + i + 1] = in[i + 1] + static_cast<Index>(values[k]);
                         std::vector<Index>().swap(in);
                       }
                     }});
  }

  /// Runs the joins given, each array on one of up to `threads` threads, the most bytes first.
  void run(unsigned threads) {
    std::stable_sort(jobs_.begin(), jobs_.end(), [](const Job& a, const Job& b) { return a.bytes > b.bytes; });
    parallel_for_pieces(jobs_.size(), jobs_.size(), threads, [&](std::size_t k, std::size_t, std::size_t) { jobs_[k].join(); });
    jobs_.clear();
  }

 private:
  struct Job {
    std::size_t bytes;  // what the join appends to the first part's array
    std::function<void()> join;
  };
  std::vector<MapData<2>>& parts_;
  MapData<2>& m_;
  std::vector<Job> jobs_;
};

}  // namespace

void join_parts(std::vector<MapData<2>>& parts, Index elements, unsigned threads, MapData<2>& m) {
  if (parts.size() == 1) {  // one block: already numbered globally, and no second copy of the map
    if (parts[0].start_region.size() != static_cast<std::size_t>(elements))
      throw BuilderError("internal: the assembled block does not cover every element");
    const int orientation = m.orientation;
    m = std::move(parts[0]);
    m.orientation = orientation;
    return;
  }
  const Offsets node0 = offsets_of(parts, [](const MapData<2>& p) { return p.node_type.size(); });
  const Offsets region0 = offsets_of(parts, [](const MapData<2>& p) { return p.region_target.size(); });
  const Offsets entry0 = offsets_of(parts, [](const MapData<2>& p) { return p.neighbor.size(); });
  // neighbour ends too, by the nodes of those elements (after each part's leading 0)
  const Offsets graph_node0 = offsets_of(parts, [](const MapData<2>& p) { return p.neighbor_begin.size() - 1; });
  const Offsets edge0 = offsets_of(parts, [](const MapData<2>& p) { return p.edge_node.size(); });
  // region neighbours are kept only for the elements with neighbour entries (finalize_assembly.hpp):
  // placed by their own counts, shifted by the region counts
  const Offsets graph_region0 = offsets_of(parts, [](const MapData<2>& p) { return p.region_neighbors.size(); });
  const Offsets element0 = offsets_of(parts, [](const MapData<2>& p) { return p.start_region.size(); });
  if (element0.back() != static_cast<std::size_t>(elements))
    throw BuilderError("internal: the assembled blocks do not cover every element");
  Offsets edge_begin0 = element0;  // edge_node_begin has three entries per element
  for (auto& e : edge_begin0) e *= 3;

  const auto same = [](std::size_t, const auto& value) { return value; };
  const auto node_index = [&](std::size_t k, Index n) { return n + static_cast<Index>(node0[k]); };
  const auto region_index = [&](std::size_t k, Index r) {
    return r == invalid_index ? invalid_index : r + static_cast<Index>(region0[k]);
  };
  PartJoiner joiner(parts, m);
  joiner.join(&MapData<2>::node_position, node0, same);
  joiner.join(&MapData<2>::node_type, node0, same);
  joiner.join(&MapData<2>::node_location, node0, same);
  joiner.join(&MapData<2>::node_image_element, node0, same);
  joiner.join(&MapData<2>::node_image_local, node0, same);
  joiner.join(&MapData<2>::node_target, node0, same);
  joiner.join_begins(&MapData<2>::neighbor_begin, graph_node0, entry0);
  joiner.join(&MapData<2>::neighbor, entry0, node_index);
  joiner.join(&MapData<2>::neighbor_edge_kind, entry0, same);
  joiner.join_begins(&MapData<2>::edge_node_begin, edge_begin0, edge0);
  joiner.join(&MapData<2>::edge_node, edge0, node_index);
  joiner.join(&MapData<2>::region_corners, region0, [&](std::size_t k, std::array<Index, 3> c) {
    for (Index& n : c) n = node_index(k, n);
    return c;
  });
  joiner.join(&MapData<2>::region_neighbors, graph_region0, [&](std::size_t k, std::array<Index, 3> c) {
    for (Index& r : c) r = region_index(k, r);
    return c;
  });
  joiner.join(&MapData<2>::region_target, region0, same);
  // by its own sizes: with deferred region maps (finalize_region_maps.hpp) the parts have none
  const Offsets region_map0 = offsets_of(parts, [](const MapData<2>& p) { return p.region_map.size(); });
  joiner.join(&MapData<2>::region_map, region_map0, same);
  joiner.join_begins(&MapData<2>::node_begin, element0, node0);
  joiner.join_begins(&MapData<2>::region_begin, element0, region0);
  joiner.join(&MapData<2>::start_region, element0, region_index);
  joiner.run(threads);
}

}  // namespace plmap::detail
