#pragma once
// TriangleLists: one list of indices per S1 triangle slot of EditableMap (its vertex preimages,
// or the S2 edges with a segment in it), all in one pool.
//
// Why a pool. A triangle's lists are written once, when the triangle is made (the identity start
// or apply()), and only read until the triangle dies; a simplification makes and kills
// hundreds of thousands of triangles. As a vector per slot that was two allocations per new
// triangle and a pointer to follow before every read; here a list is a range of one array, and
// a dead triangle's range is garbage that the pool drops (compacting, lists in slot order) once
// it outweighs the live entries.

#include <plmap/core/types.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace plmap {

class TriangleLists {
 public:
  /// Slots for `count` more triangles, with empty lists.
  void add_slots(std::size_t count) {
    begin_.resize(begin_.size() + count, 0);
    size_.resize(size_.size() + count, 0);
  }
  std::size_t slot_count() const { return begin_.size(); }

  /// The list of slot t.
  std::span<const Index> operator[](Index t) const {
    const auto k = static_cast<std::size_t>(t);
    return {pool_.data() + begin_[k], size_[k]};
  }

  /// Gives each slot of `sizes` (slot, size) its range at the end of the pool, empty so far, to
  /// be filled with append(); a slot given a range again leaves its old range as garbage.
  template <class SlotSizes>
  void open(const SlotSizes& sizes) {
    std::size_t total = 0;
    for (const auto& [t, size] : sizes) total += size;
    if (garbage_ > 0 && garbage_ + total > live_) compact();
    for (const auto& [t, size] : sizes) {
      const auto k = static_cast<std::size_t>(t);
      garbage_ += size_[k];
      live_ -= size_[k];
      begin_[k] = static_cast<std::uint32_t>(pool_.size());
      size_[k] = 0;
      pool_.resize(pool_.size() + size);
      live_ += size;
    }
  }
  /// Appends x to slot t's list, within the range open() gave it.
  void append(Index t, Index x) {
    const auto k = static_cast<std::size_t>(t);
    pool_[begin_[k] + size_[k]++] = x;
  }
  /// Empties slot t's list (its range becomes garbage).
  void clear(Index t) {
    const auto k = static_cast<std::size_t>(t);
    garbage_ += size_[k];
    live_ -= size_[k];
    size_[k] = 0;
  }

 private:
  /// Drops the garbage: the live lists move to a new pool in slot order. Only open() calls it,
  /// before it gives new ranges, when every earlier range is filled.
  void compact() {
    std::vector<Index> pool;
    pool.reserve(live_ + live_ / 2);
    for (std::size_t k = 0; k < begin_.size(); ++k) {
      const std::uint32_t from = begin_[k];
      begin_[k] = static_cast<std::uint32_t>(pool.size());
      pool.insert(pool.end(), pool_.begin() + from, pool_.begin() + from + size_[k]);
    }
    pool_ = std::move(pool);
    garbage_ = 0;
    live_ = pool_.size();
  }

  std::vector<Index> pool_;
  std::vector<std::uint32_t> begin_;  ///< per slot, where its list starts in pool_
  std::vector<std::uint32_t> size_;   ///< per slot, its list's length
  std::size_t live_ = 0;              ///< pool entries in live lists (or in open ranges)
  std::size_t garbage_ = 0;           ///< pool entries of emptied or replaced lists
};

}  // namespace plmap
