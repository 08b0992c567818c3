#pragma once
// Normal projection, edge walks: the S1 elements and edges a ring search around a stop has met
// (fold_reentry.hpp, rim_reentry.hpp). Each ring gathers the elements around the last one, a
// dozen or more copies of each; a set that answers "seen?" in constant time makes a ring linear
// in its candidates, where sorting them and merging sorted sets took 8 % of the femur pair's
// projection. A hash set of the search's own, not a mark per S1 element: that would cost a
// cleared array of S1's size per block of walks.

#include <plmap/core/types.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace plmap::projection {

/// A set of non-negative indices, open addressing with linear probing; a search meets hundreds.
class SeenIndices {
 public:
  /// Adds i; false if it was there already.
  bool insert(Index i) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    for (std::size_t at = slot_of(i);; at = (at + 1) & (slots_.size() - 1)) {
      if (slots_[at] == i) return false;
      if (slots_[at] == empty) {
        slots_[at] = i;
        ++size_;
        return true;
      }
    }
  }

 private:
  static constexpr Index empty = invalid_index;
  std::size_t slot_of(Index i) const {  // Fibonacci hashing: neighbouring indices spread out
    return static_cast<std::size_t>((static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  void grow() {
    std::vector<Index> old = std::move(slots_);
    slots_.assign(old.empty() ? 512 : 2 * old.size(), empty);
    shift_ = 64;
    for (std::size_t n = slots_.size(); n > 1; n >>= 1) --shift_;
    size_ = 0;
    for (const Index i : old)
      if (i != empty) insert(i);
  }

  std::vector<Index> slots_;
  std::size_t size_ = 0;
  int shift_ = 64;
};

/// `fresh` := the values of `candidates` not in `seen`, each once, in the order they come;
/// `seen` takes them in.
inline void take_unseen_into(std::span<const Index> candidates, SeenIndices& seen, std::vector<Index>& fresh) {
  fresh.clear();
  for (const Index i : candidates)
    if (seen.insert(i)) fresh.push_back(i);
}

}  // namespace plmap::projection
