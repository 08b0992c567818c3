#include "cli_common.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/surface_format.hpp>
#include <plmap/core/io/surface_reader.hpp>

#include <fstream>
#include <iostream>
#include <system_error>

namespace plmap::cli {

void require_readable_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw Error(path.string() + ": no such file");
  if (std::filesystem::is_directory(status))
    throw Error(path.string() + ": is a directory, expected a file");
}

bool looks_like_map_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const std::size_t first = head.find_first_not_of(" \t\r\n");
  return first != std::string::npos && head.compare(first, map_file_magic.size(), map_file_magic) == 0;
}

namespace {

/// The format the reader will use, as far as the dimension is concerned.
std::optional<SurfaceFormat> guess_format(const std::filesystem::path& path) {
  if (auto f = format_from_extension(path)) return f;
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return format_from_content(head);
}

}  // namespace

AnySurface read_any_surface(const std::filesystem::path& path, int forced_dimension) {
  require_readable_file(path);
  if (forced_dimension == 1) return read_surface<1>(path);
  if (forced_dimension == 2) return read_surface<2>(path);
  if (looks_like_map_file(path))
    throw Error(path.string() + ": is a plmap map file, expected a surface");
  const auto format = guess_format(path);
  if (format && !format_supports_dimension(*format, 2)) return read_surface<1>(path);
  if (format && format_supports_dimension(*format, 1)) {
    // Gmsh files can hold either; a file without triangles is read as a curve.
    try {
      return read_surface<2>(path);
    } catch (const ParseError& e) {
      if (std::string_view(e.what()).find("no triangle elements") == std::string_view::npos) throw;
      return read_surface<1>(path);
    }
  }
  return read_surface<2>(path);  // also reports an unknown format with the reader's message
}

void print_json(const Json& value) { std::cout << value.dump(2) << '\n'; }

namespace {

std::string scalar_text(const Json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_null()) return "-";
  return v.dump();
}

bool is_flat_array(const Json& v) {
  if (!v.is_array()) return false;
  for (const auto& e : v)
    if (e.is_structured()) return false;
  return true;
}

void print_text_at(const Json& value, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  for (const auto& [key, v] : value.items()) {
    if (is_flat_array(v)) {
      std::cout << pad << key << ": [";
      bool first = true;
      for (const auto& e : v) {
        std::cout << (first ? "" : ", ") << scalar_text(e);
        first = false;
      }
      std::cout << "]\n";
    } else if (v.is_structured()) {
      std::cout << pad << key << ":\n";
      print_text_at(v, indent + 2);
    } else {
      std::cout << pad << key << ": " << scalar_text(v) << '\n';
    }
  }
}

}  // namespace

void print_text(const Json& value) {
  if (value.is_structured())
    print_text_at(value, 0);
  else
    std::cout << scalar_text(value) << '\n';
}

CLI::Option* add_dimension_option(CLI::App& command, int& dimension) {
  return command
      .add_option("--dim", dimension,
                  "Surface dimension: 1 (curves in the plane) or 2 (triangle surfaces); by default "
                  "derived from the file format")
      ->check(CLI::IsMember({1, 2}));
}

}  // namespace plmap::cli
