// The `plmap` command line: parses the arguments, lets the selected subcommand call the library,
// and turns every error into one line on stderr and a non-zero exit code.

#include "cli_common.hpp"

#include <plmap/core/errors.hpp>

#include <exception>
#include <iostream>
#include <new>
#include <string>

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

}  // namespace

int main(int argc, char** argv) {
  using namespace plmap::cli;
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
  register_refine(app, action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success))
      return app.exit(e);  // --help and friends
    std::cerr << "plmap: " << one_line(e.what()) << " (run `plmap --help` for usage)\n";
    return exit_code::usage_error;
  }

  try {
    if (!action) {
      std::cerr << "plmap: no command given (run `plmap --help` for usage)\n";
      return exit_code::usage_error;
    }
    return action();
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
