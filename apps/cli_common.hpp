#pragma once
/// \file
/// What the subcommands of the `plmap` tool share: loading surfaces and maps of either
/// dimension, printing JSON or text, and the exit codes.

#include <plmap/core/errors.hpp>
#include <plmap/core/io/map_file.hpp>
#include <plmap/core/projection_rules.hpp>
#include <plmap/core/surface.hpp>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

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

/// A command line that is wrong whatever the files hold (an output path that is an input, an
/// extension of another kind of file): main() prints it and exits with usage_error (64).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A surface of either dimension.
using AnySurface = std::variant<Surface<1>, Surface<2>>;

/// Reads a surface. The dimension is `forced_dimension` if nonzero (1 or 2), otherwise derived from
/// the format: curves for `.curve`, triangle surfaces for OFF/OBJ/STL/PLY, and for Gmsh files
/// triangles if the file has any, else line elements.
AnySurface read_any_surface(const std::filesystem::path& path,
                            int forced_dimension = 0);

/// True if the file starts with the map-file magic word (it is a `.plmap` map, not a surface).
/// Fails with plmap::Error for a pipe, socket or character device: the peek would consume what
/// the reader after it needs.
bool looks_like_map_file(const std::filesystem::path& path);

/// Text map files above this size get a hint to use the binary format (docs/map-format.md,
/// "Which format is written").
inline constexpr std::uintmax_t large_text_map_bytes = 64'000'000;

/// After a map was written to `output`: prints a one-line hint on stderr if it is a large text
/// file, which the binary format (.plmapb) would store in under a quarter of the space.
void hint_if_large_text_map(const std::filesystem::path& output);

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

/// Validator for options that must not be negative (a tolerance), with a message that says so.
inline const CLI::Validator non_negative_number(
    [](std::string& text) -> std::string {
      double value = 0.0;
      if (!CLI::detail::lexical_cast(text, value) || !(value >= 0.0))
        return "must be a number >= 0, not '" + text + "'";
      return {};
    },
    "NON-NEGATIVE");

/// Validator of integer options: rejects negative values, which CLI11 would otherwise wrap around
/// to 2^64 - k for unsigned options. Every integer option of plmap is a count, an index, a level
/// or a seed, so main() adds it to all of them (see reject_bad_numbers).
extern const CLI::Validator non_negative_integer;

/// Validator of floating-point options: rejects nan and inf (and numbers that overflow to inf),
/// which would otherwise reach the library and come out as "-nan" in the output. main() adds it
/// to every floating-point option.
extern const CLI::Validator finite_number;

/// Adds non_negative_integer to every integer option and finite_number to every floating-point
/// option of `app` and all its subcommands, by the type CLI11 records for each option, so that
/// an option added later is covered without anyone remembering to.
void reject_bad_numbers(CLI::App& app);

/// What a command writes, for the extension check of its output path.
enum class OutputKind {
  map,      ///< .plmap
  surface,  ///< .off .obj .stl .ply .msh .curve
  regions,  ///< .csv or .vtu (`plmap regions`)
  picture,  ///< .svg or .png (`plmap draw`)
};

/// A file a command reads, with the name the command line gives it (for the message).
struct CommandInput {
  std::string role;  ///< e.g. "MAP", "S2", "--directions"
  std::filesystem::path path;
};

/// The normal check named by --normal-check (none, facing, aligned); Error naming the valid
/// names for any other (`project` and `check --against-rays` take the same option).
NormalCheck normal_check_named(const std::string& name);

/// The extension in lower case, with the dot ("" if none).
std::string lower_extension(const std::filesystem::path& path);

/// True if both paths name the same file: the same device and inode where both exist (hard
/// links, symbolic links, `./a.off` and `a.off`), else the same canonical path.
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// Refuses, with a UsageError naming the path, an output file that
///  - is one of `inputs` (the command would replace what it reads),
///  - is an existing directory, or
///  - has an extension that is not one of `kind` (e.g. a map written to .off).
/// Commands call it before they read anything, so a refused command line costs nothing.
void check_output_file(const std::filesystem::path& output, OutputKind kind,
                       const std::vector<CommandInput>& inputs);

/// Refuses an output directory that is one of `inputs`, or one into which the command would
/// write over an input: `written_files` are the names written directly in it, `written_trees`
/// the subdirectories written (an input anywhere below one is refused).
void check_output_directory(const std::filesystem::path& directory,
                            const std::vector<std::string>& written_files,
                            const std::vector<std::string>& written_trees,
                            const std::vector<CommandInput>& inputs);

/// More worker threads than this is a typo, not a wish: each one is a system thread.
inline constexpr unsigned max_threads = 1024;

/// The `--threads` option: 0 (the default) means all hardware threads, those the process may run
/// on (its affinity mask: plmap::available_threads; DESIGN §6).
CLI::Option* add_threads_option(CLI::App& command, unsigned& threads, const std::string& help);

/// The thread count a `--threads` value stands for (0: all hardware threads the process may run on).
unsigned resolved_threads(unsigned threads);

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

/// Runs an algorithm on what the user named in `input`; what it refuses about that input (an
/// isolated vertex, a map that is no parametrization, ...) is about the file, so its message
/// starts with the file's name, as the loaders' messages do.
template <class Run>
auto naming_the_input(const std::string& input, Run&& run) {
  try {
    return run();
  } catch (const Error& e) {
    throw Error(input + ": " + e.what());
  }
}

/// The dimension option shared by the commands that read surfaces.
/// 0 means: derive the dimension from the file.
CLI::Option* add_dimension_option(CLI::App& command, int& dimension);

}  // namespace plmap::cli
