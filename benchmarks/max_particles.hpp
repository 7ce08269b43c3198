#pragma once
// The command line of the benchmarks that take a particle bound: --max-particles=N (a positive integer, default 10^6:
// the scenes above N are not registered) taken out, the rest handed to Google Benchmark.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sphstab/core/threads.hpp"

namespace sphstab::bench {

/// Reads --max-particles=N and initialises Google Benchmark with the other arguments. Returns N, or -1 after a bad
/// value ("<program>: --max-particles must be a positive integer (got '<value>')" on stderr) or an argument Google
/// Benchmark does not know (its message): the program then exits with status 2. First of all, the program's OpenMP
/// wait policy (core/threads.hpp), so that thread counts are measured as the CLI runs them, and fixed thread counts.
inline long initialize_with_max_particles(int argc, char** argv, const char* program) {
  set_program_wait_policy(argv);
  set_fixed_threads(true);  // a benchmark of N threads steps on N threads (core/adaptive_threads.hpp: not the faster)
  long max_particles = 1000000;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--max-particles=", 0) == 0) {
      char* end = nullptr;
      max_particles = std::strtol(a.c_str() + 16, &end, 10);
      if (*end != '\0' || max_particles < 1) {
        std::fprintf(stderr, "%s: --max-particles must be a positive integer (got '%s')\n", program, a.c_str() + 16);
        return -1;
      }
    } else {
      args.push_back(argv[i]);
    }
  }
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return -1;
  benchmark::AddCustomContext("wait_policy", wait_policy());
  return max_particles;
}

}  // namespace sphstab::bench
