#pragma once
/// \file
/// Tables of numbers, one row per point, as users hand them to `plmap eval` and get them back:
/// - text (CSV or whitespace-separated): one row per line, values separated by commas and/or
///   blanks, blank lines and lines starting with `#` skipped, an optional first line of column
///   names (any line whose first token is not a number);
/// - NumPy `.npy` (format versions 1–3): a 2-D array of little-endian float64, float32, int64 or
///   int32, C or Fortran order, as `numpy.save` writes it;
/// - raw binary (written only): the values as little-endian float64, row after row, no header.
/// Every value read must be finite; errors name the file and the line (text) or byte offset.

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace plmap {

struct NumericTable {
  std::size_t rows = 0;
  std::size_t columns = 0;
  std::vector<double> values;             ///< row-major, rows * columns
  std::vector<std::string> column_names;  ///< from a text file's header line, else empty
  std::vector<std::size_t> source_line;   ///< text files: the line of each row (1-based), else empty

  double operator()(std::size_t row, std::size_t column) const { return values[row * columns + column]; }
  /// "line 12" for text files, "row 12" (0-based, as in numpy) otherwise: for error messages.
  std::string row_location(std::size_t row) const;
};

/// Reads a `.npy` file (by extension, case-insensitive) or a text table. Throws ParseError naming
/// the file and line/offset: ragged rows, non-numbers, non-finite values, an unsupported or
/// truncated `.npy`.
NumericTable read_numeric_table(const std::filesystem::path& path);

/// Writers (to a stream; callers use write_file_atomically). `write_table_csv` writes the column
/// names as the header line and every double in its shortest exact form.
void write_table_csv(std::ostream& out, const NumericTable& table);
void write_table_npy(std::ostream& out, const NumericTable& table);  ///< float64, format 1.0
void write_table_raw(std::ostream& out, const NumericTable& table);  ///< float64 little-endian

}  // namespace plmap
