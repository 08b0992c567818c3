// rewrite_with_made_elements (region_clipping_rewrite.hpp): the clipped map's arrays.

#include "region_clipping_rewrite.hpp"

#include "element_graph.hpp"
#include "segment_splice.hpp"

#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <optional>

namespace plmap::detail {

/// The map with the made elements in place of the old ones: each array's per-element segments
/// move by what the changed elements before them gained or lost, and the changed elements'
/// segments are written from what was made (a copy of the arrays would double the map's memory
/// for a moment: on the femur pair of the projection peers that became the run's peak, 28 MiB
/// against 12); then the stored graph.
PlMap<2> rewrite_with_made_elements(PlMap<2>&& map, std::map<Index, MadeElement>& made, unsigned threads) {
  const Index nt = map.domain().element_count();
  std::shared_ptr<const Surface<2>> domain = map.domain_ptr(), target = map.target_ptr();
  const MapProvenance provenance = map.provenance();
  const StoredGraphOffsets old_offsets(map.stored(), map.stored_graph());
  // (named references, not a structured binding: the lambdas below capture n, which clang before
  // C++20's capture rule for bindings refuses)
  std::pair<MapData<2>, StoredGraph> released = std::move(map).release_stored_form();
  MapData<2>& n = released.first;
  const StoredGraph& old_stored = released.second;
  const std::vector<Index> old_node_begin = n.node_begin, old_region_begin = n.region_begin;
  std::vector<char> is_changed(static_cast<std::size_t>(nt), 0);
  for (const auto& [t, e] : made) is_changed[static_cast<std::size_t>(t)] = 1;
  for (Index t = 0, node_shift = 0, region_shift = 0; t < nt; ++t) {
    const auto it = made.find(t);
    if (it != made.end()) {
      node_shift += static_cast<Index>(it->second.position.size());  // the new nodes
      region_shift += static_cast<Index>(it->second.corners.size()) - (old_region_begin[t + 1] - old_region_begin[t]);
    }
    n.node_begin[t + 1] = old_node_begin[t + 1] + node_shift;
    n.region_begin[t + 1] = old_region_begin[t + 1] + region_shift;
  }
  const auto node_shift_of = [&](Index t) { return n.node_begin[t] - old_node_begin[t]; };
  const auto same = [](Index, const auto& value) { return value; };
  // a changed element keeps its old nodes first: they move with the array, the new ones follow
  const auto kept_nodes = [&](Index t) { return is_changed[static_cast<std::size_t>(t)] ? made.at(t).old_nodes : Index{0}; };
  const auto write_nodes = [&](auto& array, auto made_value) {
    splice_segments(
        array, old_node_begin, n.node_begin, is_changed, same,
        [&](Index t, auto* out) {
          const MadeElement& e = made.at(t);
          for (std::size_t v = 0; v < e.position.size(); ++v) out[static_cast<std::size_t>(e.old_nodes) + v] = made_value(e, v);
        },
        kept_nodes);
  };
  // Each array is spliced on its own, so the nine splices run side by side on `threads` threads
  // (each reads the made elements and the begin arrays, and writes only its own array). On one
  // thread they run one after the other, so that no two arrays grow at the same moment.
  parallel_for_pieces(9, 9, threads, [&](std::size_t k, std::size_t, std::size_t) {
    switch (k) {
      case 0: write_nodes(n.node_position, [](const MadeElement& e, std::size_t v) { return e.position[v]; }); break;
      case 1: write_nodes(n.node_type, [](const MadeElement& e, std::size_t v) { return e.type[v]; }); break;
      case 2: write_nodes(n.node_location, [](const MadeElement& e, std::size_t v) { return e.location[v]; }); break;
      case 3: write_nodes(n.node_image_element, [](const MadeElement& e, std::size_t v) { return e.image[v].element; }); break;
      case 4: write_nodes(n.node_image_local, [](const MadeElement& e, std::size_t v) { return e.image[v].local; }); break;
      case 5: write_nodes(n.node_target, [](const MadeElement& e, std::size_t v) { return e.target[v]; }); break;
      case 6:
        splice_segments(
            n.region_corners, old_region_begin, n.region_begin, is_changed,
            [&](Index t, std::array<Index, 3> c) {
              for (Index& x : c) x += node_shift_of(t);
              return c;
            },
            [&](Index t, std::array<Index, 3>* out) {
              const MadeElement& e = made.at(t);
              for (std::size_t r = 0; r < e.corners.size(); ++r)
                for (int i = 0; i < 3; ++i) out[r][i] = e.corners[r][i] + n.node_begin[t];
            });
        break;
      case 7:
        splice_segments(n.region_target, old_region_begin, n.region_begin, is_changed, same, [&](Index t, Index* out) {
          const MadeElement& e = made.at(t);
          std::copy(e.region_target.begin(), e.region_target.end(), out);
        });
        break;
      default:
        splice_segments(n.region_map, old_region_begin, n.region_begin, is_changed, same, [&](Index t, AffineMap<2>* out) {
          const MadeElement& e = made.at(t);
          std::copy(e.region_map.begin(), e.region_map.end(), out);
        });
    }
  });
  // what the arrays took is freed now, for the graphs to reuse (only the graphs' parts are read
  // below)
  for (auto& [t, e] : made) {
    std::vector<LocalPoint<2>>().swap(e.position);
    std::vector<NodeType>().swap(e.type);
    std::vector<std::int8_t>().swap(e.location);
    std::vector<SurfacePoint<2>>().swap(e.image);
    std::vector<Index>().swap(e.target);
    std::vector<std::array<Index, 3>>().swap(e.corners);
    std::vector<Index>().swap(e.region_target);
    std::vector<AffineMap<2>>().swap(e.region_map);
  }
  for (Index t = 0; t < nt; ++t) {
    Index& start = n.start_region[t];
    if (is_changed[static_cast<std::size_t>(t)])
      start = n.region_begin[t] < n.region_begin[t + 1] ? n.region_begin[t] : invalid_index;
    else if (start != invalid_index)
      start += n.region_begin[t] - old_region_begin[t];
  }

  // The stored graph, in element order: a changed element's new graph where its regions do not
  // give it back, and the graphs the other elements stored, their indices shifted. The
  // candidates are listed in element order, made in pieces on all threads (each with its own
  // derivation scratch) and the pieces' graphs joined in order: the same graph for every count.
  struct Candidate {
    Index element;
    const MadeElement* made;  // the changed element, or nullptr: old stored graph `stored`
    std::size_t stored;
  };
  std::vector<Candidate> candidates;
  candidates.reserve(made.size() + old_stored.element.size());
  auto changed = made.begin();
  for (std::size_t s = 0; changed != made.end() || s < old_stored.element.size();) {
    const Index tc = changed != made.end() ? changed->first : nt;
    const Index ts = s < old_stored.element.size() ? old_stored.element[s] : nt;
    if (tc <= ts) {
      candidates.push_back({tc, &changed->second, 0});
      ++changed;
      if (ts == tc) ++s;  // its old stored graph is replaced
    } else {
      candidates.push_back({ts, nullptr, s++});
    }
  }
  const std::size_t piece_count = 4 * resolve_thread_count(threads);
  const std::size_t piece_size = std::max<std::size_t>(1, (candidates.size() + piece_count - 1) / piece_count);
  std::vector<StoredGraph> pieces((candidates.size() + piece_size - 1) / piece_size);
  parallel_for_pieces_of_size(candidates.size(), piece_size, threads, [&](std::size_t k, std::size_t begin, std::size_t end) {
    GraphDerivationScratch scratch;
    for (std::size_t i = begin; i < end; ++i) {
      const Index t = candidates[i].element;
      if (candidates[i].made == nullptr) {
        ElementGraph g = stored_element_graph(old_stored, old_offsets, candidates[i].stored);
        const Index node_shift = n.node_begin[t] - old_node_begin[t], region_shift = n.region_begin[t] - old_region_begin[t];
        for (Index& q : g.neighbor) q += node_shift;
        for (Index& q : g.edge_node) q += node_shift;
        for (auto& a : g.region_neighbors)
          for (Index& x : a) x = x == invalid_index ? invalid_index : x + region_shift;
        append(g, pieces[k]);
        continue;
      }
      const MadeElement& e = *candidates[i].made;
      const Index node_base = n.node_begin[t], region_base = n.region_begin[t];
      ElementGraph g;
      g.element = t;
      g.neighbor_count = e.neighbor_count;
      for (const auto& [q, kind] : e.neighbors) {
        g.neighbor.push_back(q + node_base);
        g.kind.push_back(kind);
      }
      for (const auto& list : e.edge_nodes) {
        g.edge_node_count.push_back(static_cast<Index>(list.size()));
        for (Index v : list) g.edge_node.push_back(v + node_base);
      }
      for (std::array<Index, 3> a : e.across) {
        for (Index& x : a) x = x == invalid_index ? invalid_index : x + region_base;
        g.region_neighbors.push_back(a);
      }
      const std::optional<ElementGraph> derived = derived_element_graph(n, *target, t, scratch);
      if (!derived || *derived != g) append(g, pieces[k]);
    }
  });
  StoredGraph graph = join_in_order(pieces);
  // the changed elements' graphs were compared with their derivation; the others kept as they were
  graph.known_minimal = old_stored.known_minimal;
  PlMap<2> out(std::move(domain), std::move(target), std::move(n), std::move(graph));
  out.set_provenance(provenance);
  return out;
}

}  // namespace plmap::detail
