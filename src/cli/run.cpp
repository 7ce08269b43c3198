#include "run.hpp"

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <iostream>
#include <new>
#include <stdexcept>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/threads.hpp"

namespace sphstab::cli {

namespace {

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

}  // namespace

int run(int argc, const char* const* argv) {
  CLI::App app{"sphstab: stability, accuracy and speed of SPH formulations for elastic solids"};
  app.require_subcommand(1);
  app.fallthrough();  // --max-memory also after the subcommand
  std::string max_memory;
  app.add_option("--max-memory", max_memory,
                 "Memory limit for size checks, e.g. 8G or 512M (default: this machine's memory); a case whose "
                 "estimated memory exceeds it is refused before anything is allocated")
      ->each([](const std::string& text) { set_memory_limit_bytes(parse_memory_size(text)); });
  const int threads_before = max_threads();
  app.add_option_function<int>(
         "--threads", [](const int& threads) { set_threads(threads); },
         "OpenMP threads of the rate-form evaluation and the operator products (default: OMP_NUM_THREADS, else one; "
         "results are the same bits for any count")
      ->check(CLI::Range(1, 4096));
  const bool fixed_before = fixed_threads();
  app.add_flag_callback(
      "--fixed-threads", [] { set_fixed_threads(true); },
      "step on exactly --threads threads (default: a run with several measures its steps with them and with one thread "
      "and steps with the faster, core/adaptive_threads.hpp; the same bits either way)");
  // What a timing or a result was produced with: the version, the threads and the wait policy (core/threads.hpp).
  app.set_version_flag("--version", [] {
    const int threads = max_threads();
    std::ostringstream text;
    text << "sphstab " << SPHSTAB_VERSION << ", OpenMP " << (threads_available() ? "on" : "off") << ", " << threads
         << (threads == 1 ? " thread" : fixed_threads() ? " threads (fixed)" : " threads (adaptive)") << ", wait policy "
         << wait_policy();
    return text.str();
  });
  register_commands(app);
  int code = 0;
  try {
    // One rule for every subcommand: an empty argument is never a value (CLI11 would store '' and the option would
    // silently fall back to a default or an empty name, e.g. --lattice '' or --out '').
    for (int i = 1; i < argc; ++i)
      if (argv[i] == nullptr || argv[i][0] == '\0')
        throw std::invalid_argument(i > 1 ? std::string("empty value after '") + argv[i - 1] +
                                                "' (give a value or leave the option out)"
                                          : std::string("empty argument (give a subcommand)"));
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {
      app.exit(e);  // --help
    } else {
      std::cerr << "sphstab: error: " << one_line(e.what()) << " (see --help)\n";
      code = 1;
    }
  } catch (const std::bad_alloc&) {
    std::cerr << "sphstab: error: out of memory (an allocation failed that the size estimates did not foresee; "
                 "reduce --n or --h, or report the case)\n";
    code = 1;
  } catch (const std::exception& e) {
    std::cerr << "sphstab: error: " << one_line(e.what()) << "\n";
    code = 1;
  }
  // A result that did not reach its reader is not a success (stdout on a full disk, /dev/full, a closed file): both the
  // C++ stream and C stdio are flushed and checked. A reader that closed a pipe early (`| head -1`) is not an error.
  errno = 0;
  std::cout.flush();
  const bool stream_failed = !std::cout;
  const bool stdio_failed = std::fflush(stdout) != 0 || std::ferror(stdout);
  if ((stream_failed || stdio_failed) && errno != EPIPE && code == 0) {
    std::cerr << "sphstab: error: cannot write the output to standard output (disk full or stream closed)\n";
    code = 1;
  }
  std::cout.clear();
  std::clearerr(stdout);
  set_memory_limit_bytes(0);  // process-wide: leave both as found for the next in-process call
  set_threads(threads_before);
  set_fixed_threads(fixed_before);
  return code;
}

}  // namespace sphstab::cli
