// Uniform refinement (random_maps.hpp): every element cut into 2^levels (d = 1) or 4^levels
// (d = 2) similar pieces, each new vertex located on the original surface.

#include <plmap/core/errors.hpp>
#include <plmap/verify/generators/random_maps.hpp>

#include <map>
#include <tuple>

namespace plmap::generators {

namespace {

/// Where a grid point of an element lies on the original surface, as a key shared by all the
/// elements that see the point: (kind, index, position on the edge in units of 1/n).
using PointKey = std::tuple<int, Index, Index>;

}  // namespace

template <int d>
Refinement<d> uniform_refinement(const Surface<d>& s, int levels, Index max_elements) {
  using Location = DomainLocation<d>;
  if (levels < 0 || levels > 20) throw Error("refinement levels must be between 0 and 20");
  const Index n = Index{1} << levels;  // pieces per edge
  const double pieces_per_element = d == 1 ? double(n) : double(n) * double(n);
  if (double(s.element_count()) * pieces_per_element > double(max_elements))
    throw Error("refining " + std::to_string(s.element_count()) + " elements " +
                std::to_string(levels) + " times would give more than " +
                std::to_string(max_elements) + " elements");

  std::vector<WorldPoint<d>> vertices;
  std::vector<Location> locations;
  std::vector<ElementCorners<d>> elements;
  std::map<PointKey, Index> shared;  // vertices on S1 vertices and edges, entered once
  auto add_point = [&](const PointKey& key, const Location& where, Index t) {
    if (std::get<0>(key) != static_cast<int>(Location::Kind::element)) {
      const auto [it, inserted] = shared.try_emplace(key, static_cast<Index>(vertices.size()));
      if (!inserted) return it->second;
    }
    vertices.push_back(s.world_position(t, where.point.local));
    locations.push_back(where);
    return static_cast<Index>(vertices.size() - 1);
  };
  const auto vertex_kind = static_cast<int>(Location::Kind::vertex);
  const auto edge_kind = static_cast<int>(Location::Kind::edge);
  const auto element_kind = static_cast<int>(Location::Kind::element);

  for (Index t = 0; t < s.element_count(); ++t) {
    if constexpr (d == 1) {
      std::vector<Index> ids(static_cast<std::size_t>(n) + 1);
      for (Index i = 0; i <= n; ++i) {
        Location where;
        where.point.element = t;
        where.point.local(0) = double(i) / double(n);
        PointKey key;
        if (i == 0 || i == n) {
          where.kind = Location::Kind::vertex;
          where.index = s.element(t)[i == 0 ? 0 : 1];
          key = {vertex_kind, where.index, 0};
        } else {
          where.kind = Location::Kind::element;
          where.index = t;
          key = {element_kind, t, i};
        }
        ids[static_cast<std::size_t>(i)] = add_point(key, where, t);
      }
      for (Index i = 0; i < n; ++i)
        elements.push_back({ids[static_cast<std::size_t>(i)], ids[static_cast<std::size_t>(i) + 1]});
    } else {
      // Grid point (i, j) has local coordinates (i/n, j/n), i + j <= n.
      auto id_of = [&](Index i, Index j) {
        Location where;
        where.point.element = t;
        where.point.local = LocalPoint<2>(double(i) / double(n), double(j) / double(n));
        int corner = -1;
        if (i == 0 && j == 0) corner = 0;
        if (i == n && j == 0) corner = 1;
        if (i == 0 && j == n) corner = 2;
        if (corner >= 0) {
          where.kind = Location::Kind::vertex;
          where.index = s.element(t)[corner];
          return add_point({vertex_kind, where.index, 0}, where, t);
        }
        // Local edge k runs from corner k to corner k+1; `steps` counts from corner k.
        int k = -1;
        Index steps = 0;
        if (j == 0) k = 0, steps = i;
        else if (i + j == n) k = 1, steps = j;
        else if (i == 0) k = 2, steps = n - j;
        if (k >= 0) {
          where.kind = Location::Kind::edge;
          where.index = s.element_edge(t, k);
          const Index from_smaller = s.local_edge_is_forward(t, k) ? steps : n - steps;
          where.edge_parameter = double(from_smaller) / double(n);
          return add_point({edge_kind, where.index, from_smaller}, where, t);
        }
        where.kind = Location::Kind::element;
        where.index = t;
        return add_point({element_kind, t, 0}, where, t);
      };
      std::vector<Index> ids;
      ids.reserve(static_cast<std::size_t>((n + 1) * (n + 2) / 2));
      auto at = [&](Index i, Index j) {  // row-major over j, then i
        return ids[static_cast<std::size_t>(j * (n + 1) - j * (j - 1) / 2 + i)];
      };
      for (Index j = 0; j <= n; ++j)
        for (Index i = 0; i + j <= n; ++i) ids.push_back(id_of(i, j));
      for (Index j = 0; j < n; ++j)
        for (Index i = 0; i + j < n; ++i) {
          elements.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
          if (i + j + 1 < n) elements.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
  }
  return Refinement<d>{Surface<d>(std::move(vertices), std::move(elements)),
                                   std::move(locations)};
}

template Refinement<1> uniform_refinement<1>(const Surface<1>&, int, Index);
template Refinement<2> uniform_refinement<2>(const Surface<2>&, int, Index);

}  // namespace plmap::generators
