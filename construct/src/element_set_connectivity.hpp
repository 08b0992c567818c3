#pragma once
// Whether a set of S1 elements is connected across their edges (d = 1: across their vertices):
// the sheet selection asks it of every S2 element's preimage (image_overlaps.cpp), so it is
// asked hundreds of thousands of times, mostly of sets of two to six elements.

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/surface.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace plmap::projection {

/// The S1 elements adjacent to element t (across its edges; d = 1 across its vertices).
template <int d>
void for_each_neighbour(const Surface<d>& s, Index t, auto&& f) {
  if constexpr (d == 2) {
    for (int k = 0; k < 3; ++k)
      for (const auto& incidence : s.edge_elements(s.element_edge(t, k)))
        if (incidence.element != t) f(incidence.element);
  } else {
    for (Index v : s.element(t))
      for (Index u : s.vertex_elements(v))
        if (u != t) f(u);
  }
}

/// Answers "are these elements of S1 one connected set?" for many sets in turn, one object per
/// thread. A set of up to 64 elements is searched in place: membership by binary search in the
/// sorted list, the reached ones as bits of a mask. A larger one takes two arrays over all of
/// S1, made on the first such set (two S1-sized arrays per search were 8 MB each on the 1M
/// circles, made on every run for sets that are almost never large), stamped per set so that
/// they need no clearing.
template <int d>
class ElementSetConnectivity {
 public:
  explicit ElementSetConnectivity(const Surface<d>& s1) : s1_(s1) {}

  /// Whether `list` (increasing, each element once, not empty) is connected.
  bool connected(std::span<const Index> list) {
    return list.size() <= 64 ? connected_in_place(list) : connected_by_stamps(list);
  }

 private:
  bool connected_in_place(std::span<const Index> list) const {
    std::array<int, 64> stack;
    int top = 0, count = 0;
    std::uint64_t reached = 1;
    stack[top++] = 0;
    while (top > 0) {
      const Index t = list[static_cast<std::size_t>(stack[--top])];
      ++count;
      for_each_neighbour(s1_, t, [&](Index u) {
        const auto at = std::lower_bound(list.begin(), list.end(), u);
        if (at == list.end() || *at != u) return;
        const auto j = static_cast<int>(at - list.begin());
        if ((reached >> j) & 1u) return;
        reached |= std::uint64_t{1} << j;
        stack[top++] = j;  // each element is pushed once: at most 64 on the stack
      });
    }
    return count == static_cast<int>(list.size());
  }

  bool connected_by_stamps(std::span<const Index> list) {
    if (member_.empty()) {
      assign_on_huge_pages(member_, static_cast<std::size_t>(s1_.element_count()), std::uint32_t{0});
      assign_on_huge_pages(reached_, static_cast<std::size_t>(s1_.element_count()), std::uint32_t{0});
    }
    const std::uint32_t stamp = ++stamp_;  // 2^32 large sets per object before a stamp repeats
    for (const Index t : list) member_[t] = stamp;
    std::size_t count = 0;
    stack_.assign(1, list.front());
    reached_[list.front()] = stamp;
    while (!stack_.empty()) {
      const Index t = stack_.back();
      stack_.pop_back();
      ++count;
      for_each_neighbour(s1_, t, [&](Index u) {
        if (member_[u] == stamp && reached_[u] != stamp) {
          reached_[u] = stamp;
          stack_.push_back(u);
        }
      });
    }
    return count == list.size();
  }

  const Surface<d>& s1_;
  std::vector<std::uint32_t> member_, reached_;  // per S1 element: the stamp of the last set it was in / reached in
  std::vector<Index> stack_;
  std::uint32_t stamp_ = 0;
};

}  // namespace plmap::projection
