#pragma once
// Projection directions given per S1 vertex in a text file (`plmap project --directions`, and the
// same field for `plmap check --against-rays --directions`).

#include <plmap/core/types.hpp>

#include <string>
#include <vector>

namespace plmap::cli {

/// Reads one direction per line (d+1 numbers; '#' starts a comment), one per S1 vertex, as the
/// flat list ProjectionOptions::directions takes. Throws ParseError naming the file and line.
std::vector<double> read_directions(const std::string& file, int d, Index vertices);

}  // namespace plmap::cli
