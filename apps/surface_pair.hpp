#pragma once
/// \file
/// Reading the two input surfaces of a command (S1 and S2) side by side: on large inputs each
/// takes a few tenths of a second (parsing, checks, adjacency), and the two files are
/// independent.

#include "cli_common.hpp"

#include <filesystem>
#include <utility>

namespace plmap::cli {

/// Reads S1 and S2 on two threads (one if `threads` is 1: a command asked for one thread reads
/// its inputs on one as well) with the rule of reading them one after the other: S1 in
/// `forced_dimension` (0: derived from its format), S2 in the same forced dimension or, if none
/// is forced, in S1's. Errors are those of the sequential reading: S1's first. S2 is first read
/// with its own derived dimension (which is S1's in every sensible call); if that fails or gives
/// another dimension, it is read again in S1's, exactly as the sequential rule reads it.
std::pair<AnySurface, AnySurface> read_surface_pair(const std::filesystem::path& s1,
                                                    const std::filesystem::path& s2, int forced_dimension,
                                                    unsigned threads);

}  // namespace plmap::cli
