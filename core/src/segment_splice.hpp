#pragma once
// Moving the per-element segments of a finished map's array in place, when some elements change
// how many entries they hold (region_clipping.cpp: the nodes and regions of the elements a cut
// changes; regions.cpp: the image measures' per-region terms after such a change).

#include <plmap/core/huge_page_allocator.hpp>
#include <plmap/core/types.hpp>

#include <cstddef>
#include <vector>

namespace plmap::detail {

/// Rewrites the per-element segments of an array in place: element t's segment moves from
/// [old_begin[t], old_begin[t + 1]) to start at new_begin[t]. An unchanged element's values are
/// moved through adjust(t, value); a changed element's first kept(t) values are moved so too, and
/// its segment is then written by fill(t, first) (where the kept ones are already in place).
/// Segments that move left are moved first, in increasing order, then those that move right, in
/// decreasing order: a segment's destination then never holds values not yet moved (the new
/// segments are in the same order as the old ones, and a changed element's old values are not
/// needed).
template <class T, class Adjust, class Fill, class Kept = Index (*)(Index)>
void splice_segments(std::vector<T>& v, const std::vector<Index>& old_begin, const std::vector<Index>& new_begin,
                     const std::vector<char>& changed, Adjust&& adjust, Fill&& fill,
                     Kept&& kept = [](Index) { return Index{0}; }) {
  const auto nt = static_cast<Index>(old_begin.size()) - 1;
  const auto new_size = static_cast<std::size_t>(new_begin[static_cast<std::size_t>(nt)]);
  if (new_size > v.capacity()) v.reserve(new_size);  // exactly: resize alone would double the room
  if (new_size > v.size()) {
    // The few entries added go to the array's room (BuilderOptions::spare_room), which may be
    // marked for huge pages: there a first write would make 2 MiB resident for a few KiB.
    advise_small_pages(v.data() + v.size(), (new_size - v.size()) * sizeof(T));
    v.resize(new_size);
  }
  const auto length_of = [&](Index t) {
    return changed[static_cast<std::size_t>(t)] ? kept(t) : old_begin[t + 1] - old_begin[t];
  };
  const auto move_segment = [&](Index t) {
    const Index from = old_begin[t], to = new_begin[t], length = length_of(t);
    if (to <= from)
      for (Index i = 0; i < length; ++i) v[static_cast<std::size_t>(to + i)] = adjust(t, v[static_cast<std::size_t>(from + i)]);
    else
      for (Index i = length; i-- > 0;) v[static_cast<std::size_t>(to + i)] = adjust(t, v[static_cast<std::size_t>(from + i)]);
  };
  for (Index t = 0; t < nt; ++t)
    if (new_begin[t] <= old_begin[t]) move_segment(t);
  for (Index t = nt; t-- > 0;)
    if (new_begin[t] > old_begin[t]) move_segment(t);
  for (Index t = 0; t < nt; ++t)
    if (changed[static_cast<std::size_t>(t)]) fill(t, v.data() + new_begin[t]);
  v.resize(new_size);
}

}  // namespace plmap::detail
