#include <plmap/core/errors.hpp>
#include <plmap/core/io/numeric_table.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>

namespace plmap {

static_assert(std::endian::native == std::endian::little, "the .npy and raw readers assume a little-endian machine");

std::string NumericTable::row_location(std::size_t row) const {
  if (row < source_line.size()) return "line " + std::to_string(source_line[row]);
  return "row " + std::to_string(row);
}

namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ',' || std::isspace(static_cast<unsigned char>(line[i])))) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ',' && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

NumericTable read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw ParseError(path.string(), "", "cannot open the file");
  NumericTable t;
  std::string line;
  std::size_t line_number = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++line_number;
    const auto tokens = split_tokens(line);
    if (tokens.empty() || tokens.front().front() == '#') continue;
    double value = 0.0;
    if (first && !parse_double(tokens.front(), value)) {
      for (auto tok : tokens) t.column_names.emplace_back(tok);
      t.columns = tokens.size();
      first = false;
      continue;
    }
    if (first) t.columns = tokens.size();
    first = false;
    const std::string where = "line " + std::to_string(line_number);
    if (tokens.size() != t.columns)
      throw ParseError(path.string(), where,
                       fmt::format("expected {} values, found {}", t.columns, tokens.size()));
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      if (!parse_double(tokens[k], value))
        throw ParseError(path.string(), where, fmt::format("value {} ('{}') is not a number", k + 1, tokens[k]));
      if (!std::isfinite(value))
        throw ParseError(path.string(), where, fmt::format("value {} ('{}') is not finite", k + 1, tokens[k]));
      t.values.push_back(value);
    }
    t.source_line.push_back(line_number);
    ++t.rows;
  }
  if (in.bad()) throw ParseError(path.string(), "", "read error");
  return t;
}

/// The value of `key` in a .npy header dictionary (Python literal), as text.
std::string npy_header_field(const std::string& header, const std::string& key, const std::string& file) {
  const std::size_t k = header.find("'" + key + "'");
  if (k == std::string::npos) throw ParseError(file, "header", "the .npy header has no '" + key + "'");
  std::size_t i = header.find(':', k);
  if (i == std::string::npos) throw ParseError(file, "header", "malformed .npy header");
  ++i;
  while (i < header.size() && header[i] == ' ') ++i;
  std::size_t j = i;
  if (header[i] == '(') {
    j = header.find(')', i);
    if (j == std::string::npos) throw ParseError(file, "header", "malformed shape in the .npy header");
    return header.substr(i, j - i + 1);
  }
  if (header[i] == '\'') {
    j = header.find('\'', i + 1);
    if (j == std::string::npos) throw ParseError(file, "header", "malformed .npy header");
    return header.substr(i + 1, j - i - 1);
  }
  while (j < header.size() && header[j] != ',' && header[j] != '}') ++j;
  return header.substr(i, j - i);
}

NumericTable read_npy(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ParseError(file, "", "cannot open the file");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0)
    throw ParseError(file, "offset 0", "not a .npy file (no \\x93NUMPY magic)");
  const int major = static_cast<unsigned char>(bytes[6]);
  std::size_t header_length = 0, header_start = 0;
  if (major == 1) {
    header_length = static_cast<unsigned char>(bytes[8]) | static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8;
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) throw ParseError(file, "offset 8", "truncated .npy header");
    std::uint32_t len = 0;
    std::memcpy(&len, bytes.data() + 8, 4);
    header_length = len;
    header_start = 12;
  } else {
    throw ParseError(file, "offset 6", "unsupported .npy format version " + std::to_string(major));
  }
  if (bytes.size() < header_start + header_length) throw ParseError(file, "offset 8", "truncated .npy header");
  const std::string header = bytes.substr(header_start, header_length);
  const std::string descr = npy_header_field(header, "descr", file);
  const std::string order = npy_header_field(header, "fortran_order", file);
  const std::string shape_text = npy_header_field(header, "shape", file);
  std::size_t item = 0;
  char kind = 0;
  if (descr == "<f8" || descr == "<i8" || descr == "<f4" || descr == "<i4") {
    kind = descr[1];
    item = static_cast<std::size_t>(descr[2] - '0');
  } else {
    throw ParseError(file, "header", "unsupported .npy dtype '" + descr + "' (use float64, float32, int64 or int32, little-endian)");
  }
  std::vector<std::size_t> shape;
  for (auto tok : split_tokens(std::string_view(shape_text).substr(1, shape_text.size() - 2))) {
    std::size_t v = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc() || end != tok.data() + tok.size())
      throw ParseError(file, "header", "malformed shape " + shape_text + " in the .npy header");
    shape.push_back(v);
  }
  if (shape.size() != 2)
    throw ParseError(file, "header", "expected a 2-D array (one row per point), found shape " + shape_text);
  NumericTable t;
  t.rows = shape[0];
  t.columns = shape[1];
  const std::size_t data_start = header_start + header_length;
  if (t.columns != 0 && t.rows > bytes.size() / item / t.columns)  // also guards the product below
    throw ParseError(file, "offset " + std::to_string(data_start),
                     fmt::format("truncated .npy data: shape {} does not fit in {} bytes", shape_text, bytes.size()));
  const std::size_t need = t.rows * t.columns * item;
  if (bytes.size() - data_start != need)
    throw ParseError(file, "offset " + std::to_string(data_start),
                     fmt::format("expected {} bytes of data for shape {}, found {}", need, shape_text, bytes.size() - data_start));
  const bool fortran = order == "True";
  t.values.resize(t.rows * t.columns);
  for (std::size_t r = 0; r < t.rows; ++r)
    for (std::size_t c = 0; c < t.columns; ++c) {
      const std::size_t k = fortran ? c * t.rows + r : r * t.columns + c;
      const char* p = bytes.data() + data_start + k * item;
      double v = 0.0;
      if (kind == 'f' && item == 8) std::memcpy(&v, p, 8);
      else if (kind == 'f') { float f; std::memcpy(&f, p, 4); v = f; }
      else if (item == 8) { std::int64_t i; std::memcpy(&i, p, 8); v = static_cast<double>(i); }
      else { std::int32_t i; std::memcpy(&i, p, 4); v = i; }
      if (!std::isfinite(v)) throw ParseError(file, fmt::format("row {}", r), fmt::format("value {} is not finite", c + 1));
      t.values[r * t.columns + c] = v;
    }
  return t;
}

}  // namespace

NumericTable read_numeric_table(const std::filesystem::path& path) {
  return lower_extension(path) == ".npy" ? read_npy(path) : read_text(path);
}

void write_table_csv(std::ostream& out, const NumericTable& table) {
  fmt::memory_buffer buffer;
  for (std::size_t c = 0; c < table.column_names.size(); ++c)
    fmt::format_to(std::back_inserter(buffer), "{}{}", c == 0 ? "" : ",", table.column_names[c]);
  if (!table.column_names.empty()) buffer.push_back('\n');
  for (std::size_t r = 0; r < table.rows; ++r) {
    for (std::size_t c = 0; c < table.columns; ++c)
      fmt::format_to(std::back_inserter(buffer), "{}{}", c == 0 ? "" : ",", table(r, c));
    buffer.push_back('\n');
    if (buffer.size() > (1u << 20)) {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    }
  }
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

void write_table_npy(std::ostream& out, const NumericTable& table) {
  std::string header = fmt::format("{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, {}), }}", table.rows, table.columns);
  // magic (6) + version (2) + length (2) + header, padded with blanks to a multiple of 64, '\n'-terminated
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header.push_back('\n');
  const auto length = static_cast<std::uint16_t>(header.size());
  out.write("\x93NUMPY\x01\x00", 8);
  const char len_bytes[2] = {static_cast<char>(length & 0xff), static_cast<char>(length >> 8)};
  out.write(len_bytes, 2);
  out << header;
  write_table_raw(out, table);
}

void write_table_raw(std::ostream& out, const NumericTable& table) {
  out.write(reinterpret_cast<const char*>(table.values.data()), static_cast<std::streamsize>(table.values.size() * sizeof(double)));
}

}  // namespace plmap
