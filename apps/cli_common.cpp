#include "cli_common.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file_binary.hpp>
#include <plmap/core/io/surface_format.hpp>
#include <plmap/core/io/surface_reader.hpp>
#include <plmap/core/parallel_ranges.hpp>

#include <fmt/format.h>

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cmath>
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

namespace {

/// Peeking at an input consumes what a pipe delivers, and the reader that follows would see the
/// rest only (it reported an unknown format), or, opening the pipe again, wait forever.
void refuse_pipe_or_device(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_fifo(status) || std::filesystem::is_socket(status) ||
      std::filesystem::is_character_file(status))
    throw Error(path.string() +
                ": is a pipe or a device; plmap reads this input more than once, so save it to a file first");
}

}  // namespace

bool looks_like_map_file(const std::filesystem::path& path) {
  refuse_pipe_or_device(path);
  // named as a map: read as one, so that a damaged map file gets the map reader's error (was
  // "unknown surface format" from `plmap info` on an empty or truncated .plmapb)
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension == ".plmap" || extension == ".plmapb") return true;
  std::ifstream in(path, std::ios::binary);
  std::string head(64, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (looks_like_binary_map(head)) return true;
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
  refuse_pipe_or_device(path);  // read_surface_pair may read S2 twice
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

const CLI::Validator non_negative_integer(
    [](std::string& text) -> std::string {
      const auto first = text.find_first_not_of(" \t");
      if (first != std::string::npos && text[first] == '-')
        return "must be a non-negative integer, not '" + text + "'";
      return {};
    },
    "");  // no description: the help keeps saying UINT or INT

const CLI::Validator finite_number(
    [](std::string& text) -> std::string {
      double value = 0.0;
      if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value))
        return "must be a finite number, not '" + text + "'";
      return {};
    },
    "");

void reject_bad_numbers(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    // The type name is followed by the validators' descriptions: "INT:POSITIVE".
    const std::string full_type = option->get_type_name();
    const std::string type = full_type.substr(0, full_type.find(':'));
    if (type == "INT" || type == "UINT")
      option->check(non_negative_integer);
    else if (type == "FLOAT")
      option->check(finite_number);
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) reject_bad_numbers(*sub);
}

NormalCheck normal_check_named(const std::string& name) {
  if (const auto check = normal_check_from_name(name)) return *check;
  throw Error(fmt::format("unknown normal check '{}' (valid: none, facing, aligned)", name));
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  std::error_code ea, eb;
  const auto ca = std::filesystem::weakly_canonical(a, ea);
  const auto cb = std::filesystem::weakly_canonical(b, eb);
  return !ea && !eb && ca == cb;
}

void hint_if_large_text_map(const std::filesystem::path& output) {
  if (has_binary_map_extension(output)) return;
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(output, error);
  if (error || size < large_text_map_bytes) return;
  std::filesystem::path binary = output;
  binary.replace_extension(binary_map_extension);
  std::cerr << "hint: " << output.string() << " is a " << size / 1'000'000 << " MB text map; as "
            << binary.string() << " (binary) it would take under a quarter of that and load several times "
            << "faster (plmap convert " << output.string() << " " << binary.string() << ")\n";
}

namespace {

/// What kind of file an extension names, for the message when it is used for another kind.
std::string kind_of_extension(const std::string& ext) {
  if (ext == ".plmap" || ext == binary_map_extension) return "a map file";
  if (format_from_extension("x" + ext)) return "a surface file";
  if (ext == ".csv") return "a table";
  if (ext == ".vtu" || ext == ".pvd") return "a VTK file";
  if (ext == ".svg" || ext == ".png") return "a picture";
  if (ext == ".toml") return "an experiment config";
  return {};
}

struct OutputRule {
  const char* what;                  // "a map", for the message
  std::vector<std::string> allowed;  // lower-case extensions with the dot
};

OutputRule output_rule(OutputKind kind) {
  switch (kind) {
    case OutputKind::map: return {"a map", {".plmap", std::string(binary_map_extension)}};
    case OutputKind::surface:
      return {"a surface", {".off", ".obj", ".stl", ".ply", ".msh", ".curve"}};
    case OutputKind::regions: return {"the regions", {".csv", ".vtu"}};
    case OutputKind::picture: return {"a picture", {".svg", ".png"}};
  }
  return {"", {}};
}

std::string joined(const std::vector<std::string>& words, const char* last) {
  std::string text;
  for (std::size_t i = 0; i < words.size(); ++i)
    text += (i == 0 ? "" : i + 1 == words.size() ? last : ", ") + words[i];
  return text;
}

void refuse_if_input(const std::filesystem::path& output, const std::string& shown,
                     const std::vector<CommandInput>& inputs) {
  for (const auto& input : inputs) {
    if (input.path.empty() || !same_file(output, input.path)) continue;
    const std::string spelled =
        input.path.string() == shown ? "" : " (" + input.path.string() + ")";
    throw UsageError(shown + ": is also the input " + input.role + spelled +
                     "; writing would replace it, choose another output");
  }
}

}  // namespace

void check_output_file(const std::filesystem::path& output, OutputKind kind,
                       const std::vector<CommandInput>& inputs) {
  const std::string shown = output.string();
  refuse_if_input(output, shown, inputs);
  const OutputRule rule = output_rule(kind);
  const std::string ext = lower_extension(output);
  if (std::find(rule.allowed.begin(), rule.allowed.end(), ext) == rule.allowed.end()) {
    const std::string other = kind_of_extension(ext);
    throw UsageError(shown + ": " + rule.what + " is written as " + joined(rule.allowed, " or ") +
                     ", not " + (ext.empty() ? std::string("a file without extension") : ext) +
                     (other.empty() ? "" : " (" + other + ")"));
  }
  std::error_code ec;
  if (std::filesystem::is_directory(output, ec))
    throw UsageError(shown + ": is a directory, expected a file name");
}

void check_output_directory(const std::filesystem::path& directory,
                            const std::vector<std::string>& written_files,
                            const std::vector<std::string>& written_trees,
                            const std::vector<CommandInput>& inputs) {
  const std::string shown = directory.string();
  refuse_if_input(directory, shown, inputs);
  std::error_code ec;
  if (std::filesystem::exists(directory, ec) && !std::filesystem::is_directory(directory, ec))
    throw UsageError(shown + ": is a file, expected a directory");
  for (const auto& name : written_files)
    refuse_if_input(directory / name, (directory / name).string(), inputs);
  for (const auto& tree : written_trees) {
    const auto root = std::filesystem::weakly_canonical(directory / tree, ec);
    if (ec) continue;
    for (const auto& input : inputs) {
      const auto where = std::filesystem::weakly_canonical(input.path, ec);
      if (ec) continue;
      const auto relative = where.lexically_relative(root);
      if (!relative.empty() && *relative.begin() != "..")
        throw UsageError((directory / tree).string() + ": holds the input " + input.role + " (" +
                         input.path.string() + "), which the command would replace; write to "
                         "another directory");
    }
  }
}

CLI::Option* add_threads_option(CLI::App& command, unsigned& threads, const std::string& help) {
  threads = 0;
  return command.add_option("--threads", threads, help + " (0, the default: all hardware threads this process may run on)")
      ->check(CLI::Range(0u, max_threads))
      ->capture_default_str();
}

unsigned resolved_threads(unsigned threads) { return resolve_thread_count(threads); }

CLI::Option* add_dimension_option(CLI::App& command, int& dimension) {
  return command
      .add_option("--dim", dimension,
                  "Surface dimension: 1 (curves in the plane) or 2 (triangle surfaces); by default "
                  "derived from the file format")
      ->check(CLI::IsMember({1, 2}));
}

}  // namespace plmap::cli
