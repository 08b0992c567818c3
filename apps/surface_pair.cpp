#include "surface_pair.hpp"

#include <plmap/core/parallel_ranges.hpp>

#include <algorithm>
#include <exception>
#include <optional>

namespace plmap::cli {

std::pair<AnySurface, AnySurface> read_surface_pair(const std::filesystem::path& s1,
                                                    const std::filesystem::path& s2, int forced_dimension,
                                                    unsigned threads) {
  std::optional<AnySurface> a, b;
  std::exception_ptr b_failure;
  // Piece 0 is S1: if both fail, S1's error is the one rethrown (parallel_ranges.hpp).
  parallel_for_pieces_of_size(2, 1, std::min(2u, resolve_thread_count(threads)), [&](std::size_t piece, std::size_t, std::size_t) {
    if (piece == 0) {
      a = read_any_surface(s1, forced_dimension);
      return;
    }
    try {
      b = read_any_surface(s2, forced_dimension);
    } catch (...) {
      b_failure = std::current_exception();
    }
  });
  if (forced_dimension == 0 && (!b || b->index() != a->index())) {
    // The sequential rule: S2 in S1's dimension. Its result (or error) is what a one-by-one
    // reading gives; the guess above only saved time when it agreed.
    b = read_any_surface(s2, static_cast<int>(a->index()) + 1);
  } else if (!b) {
    std::rethrow_exception(b_failure);
  }
  return {std::move(*a), std::move(*b)};
}

}  // namespace plmap::cli
