// The `plmap` command line: parses the arguments, lets the selected subcommand call the library,
// and turns every error into one line on stderr and a non-zero exit code.

#include "cli_common.hpp"

#include <plmap/core/errors.hpp>
#include <plmap/core/io/atomic_file.hpp>

#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string>

namespace plmap::cli {
// Declared here rather than in cli_common.hpp, which every command includes: a new command then
// does not recompile all the others (cmd_smooth.cpp).
void register_smooth(CLI::App& app, Action& action);
}  // namespace plmap::cli

namespace {

constexpr const char* description =
    "plmap — piecewise-linear maps between simplicial surfaces (curves in the plane, triangle "
    "surfaces in space).\n"
    "A map file (.plmap) holds both surfaces and the map; build one from surfaces, check it, "
    "evaluate it, and export its regions (the remote intersections) for ParaView or a "
    "spreadsheet.";

constexpr const char* footer =
    "Surface formats: .off .obj .stl .ply .msh (Gmsh 2.2/4.1) and .curve (plane curves).\n"
    "Exit codes: 0 success; 1 `check` found violations; 2 bad input (unreadable file, malformed "
    "data, unknown name); 64 bad command line; 70 internal error.\n"
    "Run `plmap COMMAND --help` for the options of one command.";

/// Error messages go on one line, whatever the library put in them.
std::string one_line(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  return message;
}

std::string command_names(CLI::App& level) {
  std::string names;
  for (const CLI::App* sub : level.get_subcommands([](CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

/// When the command line fails to parse, says what is wrong with the command words: which word
/// is not a command, or that a command needs one, with the valid names. CLI11 only says "A
/// subcommand is required" in both cases. Empty if the command words are fine.
std::string command_word_error(CLI::App& app, int argc, char** argv) {
  CLI::App* level = &app;
  std::string parent;  // the command words so far, without "plmap"
  for (int i = 1;; ++i) {
    if (level->get_subcommands([](CLI::App*) { return true; }).empty()) return {};
    const std::string of = parent.empty() ? "the commands are " : "the commands of '" + parent + "' are ";
    if (i < argc && argv[i][0] == '-') {
      // An option where a command is expected: CLI11 would only say that a command is missing.
      const std::string option(argv[i], std::strcspn(argv[i], "="));
      if (level->get_option_no_throw(option) != nullptr) return {};
      return "plmap: unknown option '" + option + "'" +
             (parent.empty() ? "" : " for '" + parent + "'") + "; " + of + command_names(*level);
    }
    if (i >= argc) {
      if (level->get_require_subcommand_min() == 0) return {};
      return "plmap: no command given" + (parent.empty() ? "" : " after '" + parent + "'") + "; " +
             of + command_names(*level);
    }
    const std::string word = argv[i];
    const auto match = level->get_subcommands([&](CLI::App* sub) { return sub->check_name(word); });
    if (match.empty())
      return "plmap: unknown command '" + (parent.empty() ? word : parent + " " + word) + "'; " + of +
             command_names(*level);
    level = match.front();
    parent += (parent.empty() ? "" : " ") + word;
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace plmap::cli;
  // Ctrl-C while a file is written leaves no temporary file behind.
  plmap::remove_temporaries_on_signals();
  CLI::App app(description, "plmap");
  app.footer(footer);
  app.require_subcommand(1);
  app.fallthrough(false);

  Action action;
  register_info(app, action);
  register_check(app, action);
  register_eval(app, action);
  register_regions(app, action);
  register_export(app, action);
  register_convert(app, action);
  register_build(app, action);
  register_generate(app, action);
  register_draw(app, action);
  register_experiment(app, action);
  register_project(app, action);
  register_simplify(app, action);
  register_smooth(app, action);
  register_refine(app, action);
  reject_bad_numbers(app);  // after every command is registered: it sweeps all their options

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success))
      return app.exit(e);  // --help and friends
    std::string message = command_word_error(app, argc, argv);
    if (message.empty()) message = "plmap: " + one_line(e.what());
    std::cerr << message << " (run `plmap --help` for usage)\n";
    return exit_code::usage_error;
  }

  try {
    if (!action) {
      std::cerr << "plmap: no command given (run `plmap --help` for usage)\n";
      return exit_code::usage_error;
    }
    return action();
  } catch (const UsageError& e) {
    std::cerr << "plmap: " << one_line(e.what()) << '\n';
    return exit_code::usage_error;
  } catch (const plmap::Error& e) {
    std::cerr << "plmap: " << one_line(e.what()) << '\n';
    return exit_code::input_error;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "plmap: " << one_line(e.what()) << '\n';
    return exit_code::input_error;
  } catch (const std::bad_alloc&) {
    std::cerr << "plmap: out of memory\n";
    return exit_code::internal_error;
  } catch (const std::exception& e) {
    std::cerr << "plmap: internal error: " << one_line(e.what()) << '\n';
    return exit_code::internal_error;
  }
}
