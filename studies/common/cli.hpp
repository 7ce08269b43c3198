#pragma once
/// \file cli.hpp
/// The command line a study driver starts with, the same in every driver that uses it: CLI11's app, --out (the output
/// directory, first in --help, created once parsed) and --quick (the study's test case, last in --help), parsed as
/// CLI11_PARSE parses; and --threads for a driver that runs its cases side by side.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace sphstab::study {

/// The app, its --out and its --quick. A driver adds its own options to `app` (or by add_quick_option) between the two.
struct DriverCli {
  CLI::App app;
  std::string out;
  bool quick = false;
  std::string quick_help;

  /// The app described by `description`, with --out (default `default_out`) as its first option; `quick_help` is what
  /// --help says of --quick.
  DriverCli(std::string description, std::string default_out, std::string quick_help)
      : app{std::move(description)}, out{std::move(default_out)}, quick_help{std::move(quick_help)} {
    app.add_option("--out", out, "output directory");
  }

  /// Adds a driver's option (CLI11's add_option) whose --quick case has a default of its own: with --quick and without
  /// the option, parse() sets `value` to `quick_value`.
  template <class T>
  CLI::Option* add_quick_option(const std::string& name, T& value, std::type_identity_t<T> quick_value,
                                const std::string& help) {
    quick_defaults.emplace_back(name, [&value, quick_value] { value = quick_value; });
    return app.add_option(name, value, help);
  }

  /// Adds --threads: how many runs go side by side (parallel_for, run_costliest_first), 1 to 64.
  CLI::Option* add_threads(int& threads, const std::string& help = "concurrent runs") {
    return app.add_option("--threads", threads, help)->check(CLI::Range(1, 64));
  }

  /// Adds --quick, parses the command line, sets the --quick defaults of add_quick_option and creates the directory
  /// --out. Returns the exit code of the app after --help or a command-line error (the message and code of CLI11_PARSE;
  /// nothing created), else none.
  std::optional<int> parse(int argc, char** argv) {
    app.add_flag("--quick", quick, quick_help);
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return app.exit(e);
    }
    if (quick)
      for (const auto& [name, set] : quick_defaults)
        if (app.count(name) == 0) set();
    std::filesystem::create_directories(out);
    return std::nullopt;
  }

 private:
  std::vector<std::pair<std::string, std::function<void()>>> quick_defaults;  ///< add_quick_option's
};

}  // namespace sphstab::study
