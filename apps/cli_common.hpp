#pragma once
/// \file
/// What the subcommands of the `plmap` tool share: loading surfaces and maps of either
/// dimension, printing JSON or text, and the exit codes.

#include <plmap/core/io/map_file.hpp>
#include <plmap/core/surface.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <variant>

namespace plmap::cli {

/// JSON that keeps keys in insertion order, so the text and JSON outputs read top-down.
using Json = nlohmann::ordered_json;

/// Exit codes of the tool (also listed in `plmap --help`).
namespace exit_code {
inline constexpr int success = 0;
inline constexpr int check_failed = 1;   ///< `plmap check`: the map violates an invariant
inline constexpr int input_error = 2;    ///< bad input: unreadable file, unknown name, ...
inline constexpr int usage_error = 64;   ///< bad command line (as in sysexits.h)
inline constexpr int internal_error = 70;
}  // namespace exit_code

/// A surface of either dimension.
using AnySurface = std::variant<Surface<1>, Surface<2>>;

/// Reads a surface. The dimension is `forced_dimension` if nonzero (1 or 2), otherwise derived from
/// the format: curves for `.curve`, triangle surfaces for OFF/OBJ/STL/PLY, and for Gmsh files
/// triangles if the file has any, else line elements.
AnySurface read_any_surface(const std::filesystem::path& path,
                            int forced_dimension = 0);

/// True if the file starts with the map-file magic word (it is a `.plmap` map, not a surface).
bool looks_like_map_file(const std::filesystem::path& path);

/// Fails with plmap::Error naming the file if it does not exist or is not a regular file, so
/// that the message is the same for every reader.
void require_readable_file(const std::filesystem::path& path);

/// Prints JSON on stdout (two-space indentation, one trailing newline).
void print_json(const Json& value);

/// Prints the same content as readable text: one `key: value` line per entry, nested objects
/// indented, arrays of numbers on one line.
void print_text(const Json& value);

/// print_json or print_text.
inline void print_result(const Json& value, bool json) {
  if (json)
    print_json(value);
  else
    print_text(value);
}

/// JSON array of a fixed-size Eigen vector.
template <class Vector>
Json json_vector(const Vector& v) {
  Json a = Json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i));
  return a;
}

/// Validator for options that must be a positive number, with a message that says so (the one of
/// CLI::PositiveNumber spells out the largest double: "not in range 0.000000 to 179769313486...").
inline const CLI::Validator positive_number(
    [](std::string& text) -> std::string {
      double value = 0.0;
      if (!CLI::detail::lexical_cast(text, value) || !(value > 0.0))
        return "must be a positive number, not '" + text + "'";
      return {};
    },
    "POSITIVE");

/// A subcommand's work, run after the whole command line has been parsed; returns the exit code.
using Action = std::function<int()>;

/// Each subcommand registers itself on the application and stores its action in `action` when
/// the command line selects it.
void register_info(CLI::App& app, Action& action);
void register_check(CLI::App& app, Action& action);
void register_eval(CLI::App& app, Action& action);
void register_regions(CLI::App& app, Action& action);
void register_export(CLI::App& app, Action& action);
void register_convert(CLI::App& app, Action& action);
void register_build(CLI::App& app, Action& action);
void register_generate(CLI::App& app, Action& action);
void register_experiment(CLI::App& app, Action& action);  // cmd_experiment.cpp
void register_draw(CLI::App& app, Action& action);        // cmd_draw.cpp
void register_project(CLI::App& app, Action& action);     // cmd_project.cpp
void register_simplify(CLI::App& app, Action& action);    // cmd_simplify.cpp
void register_refine(CLI::App& app, Action& action);      // cmd_refine.cpp

/// The dimension option shared by the commands that read surfaces.
/// 0 means: derive the dimension from the file.
CLI::Option* add_dimension_option(CLI::App& command, int& dimension);

}  // namespace plmap::cli
