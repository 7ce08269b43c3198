#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"sphstab: stability, accuracy and speed of SPH formulations for elastic solids"};
  app.require_subcommand(1);
  sphstab::cli::register_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    std::cerr << "sphstab: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "sphstab: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
