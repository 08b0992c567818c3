// Projection directions given per S1 vertex in a text file (directions_file.hpp).

#include "directions_file.hpp"

#include "cli_common.hpp"

#include <plmap/core/errors.hpp>

#include <fmt/format.h>

#include <cmath>
#include <exception>
#include <fstream>
#include <sstream>

namespace plmap::cli {

std::vector<double> read_directions(const std::string& file, int d, Index vertices) {
  require_readable_file(file);
  std::ifstream in(file);
  std::vector<double> out;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::vector<double> row;
    for (std::string w; words >> w;) {
      std::size_t used = 0;
      double x = 0.0;
      try {
        x = std::stod(w, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != w.size() || !std::isfinite(x))
        throw ParseError(file, fmt::format("line {}", line_no), fmt::format("'{}' is not a finite number", w));
      row.push_back(x);
    }
    if (row.empty()) continue;
    if (static_cast<int>(row.size()) != d + 1)
      throw ParseError(file, fmt::format("line {}", line_no),
                       fmt::format("a direction needs {} numbers, found {}", d + 1, row.size()));
    out.insert(out.end(), row.begin(), row.end());
  }
  if (out.size() != static_cast<std::size_t>(vertices) * (d + 1))
    throw ParseError(file, "", fmt::format("{} directions given, but S1 has {} vertices",
                                           out.size() / (d + 1), vertices));
  return out;
}

}  // namespace plmap::cli
