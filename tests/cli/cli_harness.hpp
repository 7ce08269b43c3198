#pragma once
// Runs sphstab::cli::run in a forked child of the test process (in-process code, isolated state): stdout and stderr
// to files, a memory limit through the size checks (core/memory_budget.hpp), a wall-clock limit by SIGALRM. Reports
// the exit code or the signal, the outputs, the time and the child's peak resident memory.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "run.hpp"
#include "sphstab/core/memory_budget.hpp"

namespace sphstab::test {

struct CliOutcome {
  int exit_code = -1;  ///< -1 if killed by a signal
  int signal = 0;
  std::string out, err;
  double seconds = 0;
  double peak_rss_bytes = 0;
  std::string out_path;  ///< stdout as a file (for read_csv)
};

inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline CliOutcome run_cli_in_child(const std::vector<std::string>& args, const std::filesystem::path& dir,
                                   double memory_limit_bytes, unsigned time_limit_seconds) {
  std::filesystem::create_directories(dir);
  CliOutcome r;
  r.out_path = (dir / "stdout").string();
  const std::string err_path = (dir / "stderr").string();
  std::fflush(stdout);
  std::fflush(stderr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    std::FILE* o = std::freopen(r.out_path.c_str(), "w", stdout);
    std::FILE* e = std::freopen(err_path.c_str(), "w", stderr);
    if (!o || !e) _exit(99);
    alarm(time_limit_seconds);
    set_memory_limit_bytes(memory_limit_bytes);
    std::vector<const char*> argv{"sphstab"};
    for (const std::string& a : args) argv.push_back(a.c_str());
    const int code = sphstab::cli::run(static_cast<int>(argv.size()), argv.data());
    std::fflush(stdout);
    std::fflush(stderr);
    _exit(code);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.peak_rss_bytes = 1024.0 * static_cast<double>(usage.ru_maxrss);
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  r.out = slurp(r.out_path);
  r.err = slurp(err_path);
  return r;
}

inline std::string join_args(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) s += (s.empty() ? "" : " ") + (a.empty() ? std::string("''") : a);
  return s;
}

/// Bad-input cases (arguments, text the error must contain): each exits 1 with exactly one stderr line containing
/// the text. `run` maps the arguments to a CliOutcome. Call from a test body (uses gtest's EXPECT_*).
template <class Run>
void expect_one_line_errors(const std::vector<std::pair<std::vector<std::string>, std::string>>& cases, Run&& run) {
  for (const auto& [args, what] : cases) {
    const CliOutcome r = run(args);
    EXPECT_EQ(r.exit_code, 1) << join_args(args);
    EXPECT_NE(r.err.find(what), std::string::npos) << join_args(args) << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace sphstab::test
