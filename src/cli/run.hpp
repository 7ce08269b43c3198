#pragma once
// The sphstab program as a function: parses argv, runs one subcommand, prints CSV/results on stdout and at most one
// "sphstab: error: ..." line on stderr. Returns the exit code (0 success, 1 error). main() is a one-line call, and
// tests call it in-process (tests/cli/cli_fuzz_test.cpp).
namespace sphstab::cli {

int run(int argc, const char* const* argv);

}  // namespace sphstab::cli
