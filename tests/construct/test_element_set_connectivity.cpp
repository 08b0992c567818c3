// ElementSetConnectivity (construct/src/element_set_connectivity.hpp), which the sheet selection
// asks of every S2 element's preimage: its answer for random sets of elements of random grids and
// polylines, small ones (searched in place) and large ones (searched with stamp arrays, reused
// from set to set), is that of a union-find over the sets' shared edges (d = 1: vertices).

#include "element_set_connectivity.hpp"
#include "projection_fixtures.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

using namespace plmap;
using namespace plmap::test;

namespace {

/// The independent answer: elements joined where they share an edge (d = 2) or a vertex (d = 1).
template <int d>
bool connected_by_union_find(const Surface<d>& s, const std::vector<Index>& list) {
  std::vector<Index> parent(static_cast<std::size_t>(s.element_count()), invalid_index);
  for (const Index t : list) parent[t] = t;
  const auto root = [&](Index t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  const auto join = [&](Index a, Index b) {
    if (parent[a] != invalid_index && parent[b] != invalid_index) parent[root(a)] = root(b);
  };
  if constexpr (d == 2) {
    for (Index e = 0; e < s.edge_count(); ++e) {
      const auto incidence = s.edge_elements(e);
      for (std::size_t i = 1; i < incidence.size(); ++i) join(incidence[0].element, incidence[i].element);
    }
  } else {
    for (Index v = 0; v < s.vertex_count(); ++v) {
      const auto around = s.vertex_elements(v);
      for (std::size_t i = 1; i < around.size(); ++i) join(around[0], around[i]);
    }
  }
  const Index first = root(list.front());
  return std::all_of(list.begin(), list.end(), [&](Index t) { return root(t) == first; });
}

/// A random set of `size` elements: grown from a random element across shared edges (connected
/// until one element may be taken out again), or drawn anywhere.
template <int d>
std::vector<Index> random_set(const Surface<d>& s, int size) {
  const Index n = s.element_count();
  std::vector<Index> list;
  if (*rc::gen::arbitrary<bool>()) {
    std::vector<char> in(static_cast<std::size_t>(n), 0);
    list.push_back(*rc::gen::inRange<Index>(0, n));
    in[list[0]] = 1;
    for (int tries = 0; static_cast<int>(list.size()) < size && tries < 20 * size; ++tries) {
      const Index from = list[static_cast<std::size_t>(*rc::gen::inRange<int>(0, static_cast<int>(list.size())))];
      projection::for_each_neighbour(s, from, [&](Index u) {
        if (!in[u] && static_cast<int>(list.size()) < size && *rc::gen::inRange(0, 3) == 0) {
          in[u] = 1;
          list.push_back(u);
        }
      });
    }
    if (list.size() > 2 && *rc::gen::arbitrary<bool>())
      list.erase(list.begin() + *rc::gen::inRange<int>(0, static_cast<int>(list.size())));
  } else {
    for (int i = 0; i < size; ++i) list.push_back(*rc::gen::inRange<Index>(0, n));
  }
  std::sort(list.begin(), list.end());
  list.erase(std::unique(list.begin(), list.end()), list.end());
  return list;
}

/// A polyline of n segments along a circle, closed or open, and a second one beside it.
Surface<1> two_polylines(int n, bool closed) {
  std::vector<WorldPoint<1>> v;
  std::vector<ElementCorners<1>> e;
  for (int c = 0; c < 2; ++c) {
    const auto base = static_cast<Index>(v.size());
    const int points = closed ? n : n + 1;
    for (int i = 0; i < points; ++i) v.emplace_back(3.0 * c + std::cos(6.0 * i / n), std::sin(6.0 * i / n));
    for (int i = 0; i < n; ++i) e.push_back({base + i, base + (i + 1) % points});
  }
  return Surface<1>(std::move(v), std::move(e));
}

}  // namespace

RC_GTEST_PROP(ElementSetConnectivityProperties, TrianglesAnswerAsAUnionFindDoes, ()) {
  const auto s = grid(*rc::gen::inRange(2, 30), *rc::gen::inRange(2, 30), 0.0, 1.0, 0.0, 1.0, 0.0, false, 0.1);
  projection::ElementSetConnectivity<2> search(*s);
  for (int k = 0; k < 4; ++k) {  // one object for several sets, as in a piece of the sheet selection
    // as many sets searched in place (up to 64 elements) as with stamps
    const int size = *rc::gen::arbitrary<bool>() ? *rc::gen::inRange(1, 65) : *rc::gen::inRange(65, 200);
    const std::vector<Index> list = random_set(*s, std::min<int>(size, s->element_count()));
    const bool expected = connected_by_union_find(*s, list);
    RC_CLASSIFY(list.size() > 64, "searched with stamps");
    RC_CLASSIFY(expected, "connected");
    RC_ASSERT(search.connected(list) == expected);
  }
}

RC_GTEST_PROP(ElementSetConnectivityProperties, SegmentsAnswerAsAUnionFindDoes, ()) {
  const Surface<1> s = two_polylines(*rc::gen::inRange(3, 120), *rc::gen::arbitrary<bool>());
  projection::ElementSetConnectivity<1> search(s);
  for (int k = 0; k < 4; ++k) {
    const int size = *rc::gen::arbitrary<bool>() ? *rc::gen::inRange(1, 65) : *rc::gen::inRange(65, 241);
    const std::vector<Index> list = random_set(s, std::min<int>(size, s.element_count()));
    const bool expected = connected_by_union_find(s, list);
    RC_CLASSIFY(list.size() > 64, "searched with stamps");
    RC_CLASSIFY(expected, "connected");
    RC_ASSERT(search.connected(list) == expected);
  }
}

TEST(ElementSetConnectivity, TwoHalvesOfAGridJoinedByOneElement) {
  // a 10 x 10 grid (200 triangles): its left and right thirds are two sets; with the middle
  // column of elements between them they are one
  const auto s = grid(10, 10, 0.0, 1.0, 0.0, 1.0, 0.0);
  projection::ElementSetConnectivity<2> search(*s);
  std::vector<Index> thirds, all(static_cast<std::size_t>(s->element_count()));
  std::iota(all.begin(), all.end(), 0);
  for (Index t = 0; t < s->element_count(); ++t) {
    const auto& c = s->element(t);
    const double x = (s->vertex(c[0])(0) + s->vertex(c[1])(0) + s->vertex(c[2])(0)) / 3.0;
    if (x < 0.3 || x > 0.7) thirds.push_back(t);
  }
  ASSERT_GT(thirds.size(), 64u);  // searched with stamps
  EXPECT_FALSE(search.connected(thirds));
  EXPECT_TRUE(search.connected(all));
  EXPECT_FALSE(search.connected(thirds));  // the stamps of the set before do not carry over
  const std::vector<Index> two_apart = {0, 150};
  EXPECT_FALSE(search.connected(two_apart));  // searched in place
  const std::vector<Index> one = {7};
  EXPECT_TRUE(search.connected(one));
}
