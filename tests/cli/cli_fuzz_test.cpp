// Command-line robustness: every argument list either succeeds with well-formed output (exit 0) or fails with
// exactly one "sphstab: error:" line (exit 1) -- never a signal, a hang, or memory beyond the limit. Runs
// sphstab::cli::run in-process (forked per case, cli_harness.hpp): the issue's 23 failing cases as fixed regressions,
// then a seeded generator of extreme, malformed, unknown and duplicated options; and a determinism check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "sphstab/io/csv.hpp"

namespace sphstab {
namespace cli_fuzz_test {

#if defined(__SANITIZE_ADDRESS__)
constexpr double kMemoryLimit = 3e9;  // shadow memory and redzones
constexpr unsigned kTimeLimit = 120;
#else
constexpr double kMemoryLimit = 1e9;
constexpr unsigned kTimeLimit = 60;
#endif

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("sphstab_cli_fuzz_" + std::to_string(getpid())) / name;
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == '\n') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

/// The contract, checked on one outcome; returns "" or what was violated.
std::string violation(const std::vector<std::string>& args, const test::CliOutcome& r) {
  if (r.signal) return "killed by signal " + std::to_string(r.signal) + (r.signal == SIGALRM ? " (time limit)" : "");
  if (r.peak_rss_bytes > kMemoryLimit + 6e8) return "peak memory " + format_bytes(r.peak_rss_bytes);
  const std::vector<std::string> err = lines_of(r.err);
  if (r.exit_code == 1) {
    if (err.size() != 1 || err[0].rfind("sphstab: error: ", 0) != 0) return "exit 1 without exactly one error line";
    if (err[0].size() < 24) return "error line too short to name the problem";
    if (!r.out.empty() && (args[0] == "tcrit" || args[0] == "spectrum" || args[0] == "run"))
      return "printed rows before failing";
    return "";
  }
  if (r.exit_code != 0) return "exit code " + std::to_string(r.exit_code);
  for (const std::string& l : err)
    if (l.find("error") != std::string::npos) return "exit 0 with an error line: " + l;
  if (args[0] == "tcrit") {
    try {
      const CsvTable t = read_csv(r.out_path);  // throws on ragged rows
      if (t.rows.empty()) return "exit 0 with a CSV without rows";
      const int status = t.column_index("status");
      for (const auto& row : t.rows)
        if (row[status].empty()) return "a row without status";
    } catch (const std::exception& e) {
      return std::string("malformed CSV: ") + e.what();
    }
  } else if (args[0] == "operators") {
    if (r.out.find("\nwrote ") == std::string::npos) return "operators did not report its files";
  } else if (args[0] == "spectrum") {
    try {
      const CsvTable t = read_csv(r.out_path);
      if (t.rows.empty()) return "spectrum: a CSV without rows";
    } catch (const std::exception& e) {
      return std::string("malformed CSV: ") + e.what();
    }
  } else if (args[0] == "run") {
    try {  // rows "running" at increasing steps, then one row with the final status
      const CsvTable t = read_csv(r.out_path);
      if (t.rows.empty()) return "run: a CSV without rows";
      const std::vector<std::string> status = t.text_column("status");
      const std::vector<double> step = t.numeric_column("step");
      for (std::size_t k = 0; k < status.size(); ++k) {
        if ((k + 1 < status.size()) != (status[k] == "running"))
          return "run: status '" + status[k] + "' in row " + std::to_string(k);
        if (k > 0 && !(step[k] > step[k - 1])) return "run: steps not increasing";
      }
    } catch (const std::exception& e) {
      return std::string("malformed CSV: ") + e.what();
    }
  } else if (r.out.empty()) {
    return "exit 0 with no output";
  }
  return "";
}

void expect_contract(const std::vector<std::string>& args, const std::string& tag, int expect_exit = -1) {
  const test::CliOutcome r = test::run_cli_in_child(args, scratch(tag), kMemoryLimit, kTimeLimit);
  const std::string v = violation(args, r);
  EXPECT_EQ(v, "") << "sphstab " << test::join_args(args) << "\nstdout: " << r.out.substr(0, 400)
                   << "\nstderr: " << r.err.substr(0, 400);
  if (expect_exit >= 0)
    EXPECT_EQ(r.exit_code, expect_exit) << "sphstab " << test::join_args(args) << "\nstderr: " << r.err;
}

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == ' ') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

TEST(CliFuzz, TheIssuesFailingCasesAreOneLineErrors) {
  const std::string out = scratch("D").string();
  const std::vector<std::string> cases = {
      // heap corruption (float-cast overflow, INT_MIN negation, n * 2 overflow, write past the end)
      "tcrit --h 1e308", "tcrit --h 1e10", "tcrit --dim 2 --h 1e10", "tcrit --h 1e10 --correction shepard",
      "operators --dim 1 --lattice line --n 10 --h 1e10 --out " + out,
      // signed overflow (vector::_M_default_append)
      "tcrit --h 6e8", "operators --dim 1 --lattice line --n 10 --h 1.2 --fixed-layers 2000000000 --out " + out,
      "operators --dim 1 --lattice line --n 10 --h 1.2 --fixed-layers 1073741824 --out " + out,
      // wrong results with exit 0 (radius^2 and h^-d under/overflow)
      "operators --dim 1 --lattice line --n 10 --h 1.2 --dx 1e-300 --out " + out,
      "operators --dim 1 --lattice line --n 10 --h 1.2 --dx 1e-200 --out " + out,
      "operators --dim 1 --lattice line --n 10 --h 1.2 --dx 1e200 --out " + out,
      "operators --dim 2 --lattice square --n 4 --h 1.2 --dx 1e-160 --out " + out,
      // memory spent before anything was checked
      "tcrit --h 1e6", "tcrit --n 100000000", "tcrit --dim 2 --n 3000", "tcrit --backend dense --n 30000",
      "operators --dim 1 --lattice line --n 1 --h 1e6 --out " + out, "tcrit --dim 2 --periodic --n 100000",
      // silently accepted
      "tcrit --kernel cubic,", "operators --dim 1 --lattice line --n 10 --h 1.2 --fixed-layers -5 --out " + out,
      "operators --dim 1 --lattice line --n 10 --h 1.2 --seed -1 --out " + out,
      "operators --dim 1 --lattice line --n 10 --h 1.2 --periodic --fixed-layers 3 --out " + out, "tcrit --h 1e-320"};
  for (size_t k = 0; k < cases.size(); ++k) expect_contract(words(cases[k]), "fixed" + std::to_string(k), 1);
}

TEST(CliFuzz, EmptyValuesAreOneLineErrors) {
  // Issue 36: empty values were taken as defaults (exit 0). Each is now one error line with exit 1.
  const std::string out = scratch("E").string();
  const std::vector<std::vector<std::string>> cases = {{"spectrum", "--n", "6", "--lattice", ""},
                                                       {"run", "--n", "5", "--lattice", ""},
                                                       {"scene", "plate", "--mu", ""},
                                                       {"scene", "plate", "--nu", ""},
                                                       {"run", "--n", "5", "--yield", ""},
                                                       {"scene", "rings", "--dp", ""},
                                                       {"run", "--n", "5", "--t-end", ""},
                                                       {"run", "--n", "5", "--t-end", "0.5", "--out", ""},
                                                       {""},
                                                       {"tcrit", ""}};
  for (size_t k = 0; k < cases.size(); ++k) expect_contract(cases[k], "empty" + std::to_string(k), 1);
}

TEST(CliFuzz, RunsThatCannotFinishAreRefusedBeforeTheyStart) {
  // Issue 36: step counts that cannot finish ran until killed. Each is one error line with exit 1, in well under the
  // harness's time limit (the refusal comes before the first step).
  const std::vector<std::vector<std::string>> cases = {
      {"run", "--n", "5", "--t-end", "1e12", "--record-every", "1000000000"},
      {"run", "--n", "5", "--dt", "1e-9", "--t-end", "1e6"},
      {"scene", "plate", "--t-end", "1e12", "--record-every", "1000000000"},
      {"scene", "rings", "--t-end", "1e9"},
      // 4.9 M and 0.75 M particles: refused before they are built (inside the time limit, under the memory limit).
      {"scene", "rings", "--dp", "0.003"},
      {"scene", "slab", "--dp", "0.002"}};
  for (size_t k = 0; k < cases.size(); ++k) {
    const test::CliOutcome r =
        test::run_cli_in_child(cases[k], scratch("long" + std::to_string(k)), kMemoryLimit, kTimeLimit);
    EXPECT_EQ(r.exit_code, 1) << test::join_args(cases[k]) << "\nstderr: " << r.err;
    EXPECT_NE(r.err.find("particle-steps"), std::string::npos) << test::join_args(cases[k]) << "\nstderr: " << r.err;
  }
}

TEST(CliFuzz, KicksWhoseEnergyOverflowsAreRefused) {
  // Issue 36: --kick 1e200 ran with an infinite kinetic energy from step 0 (exit 0). One error line naming the kick;
  // a large but representable kick still runs.
  for (const char* kick : {"1e200", "-1e160", "1e308"}) {
    const std::vector<std::string> args = {"run", "--n", "5", "--t-end", "0.1", "--kick", kick};
    const test::CliOutcome r = test::run_cli_in_child(args, scratch("kick"), kMemoryLimit, kTimeLimit);
    EXPECT_EQ(r.exit_code, 1) << kick << "\nstderr: " << r.err;
    EXPECT_NE(r.err.find("--kick"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("overflows"), std::string::npos) << r.err;
  }
  const test::CliOutcome ok = test::run_cli_in_child({"run", "--n", "5", "--t-end", "0.1", "--kick", "1e100"},
                                                     scratch("kick"), kMemoryLimit, kTimeLimit);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(CliFuzz, NoNeighbourInsideTheSupportIsNanAndNumericalIssueOnEveryRoute) {
  for (const std::string c :
       {"tcrit --h 0.3", "tcrit --h 0.3 --form minus", "tcrit --h 0.3 --form plus --compression",
        "tcrit --h 0.3 --periodic", "tcrit --h 0.3 --correction shepard", "tcrit --h 0.3 --correction minus",
        "tcrit --h 0.3 --correction ncsph", "tcrit --dim 2 --n 4 --h 0.3", "tcrit --dim 2 --n 10 --h 0.3 --periodic",
        "tcrit --dim 2 --n 4 --h 0.3 --lattice hex"}) {
    const test::CliOutcome r = test::run_cli_in_child(words(c), scratch("nn"), kMemoryLimit, kTimeLimit);
    ASSERT_EQ(r.exit_code, 0) << c << ": " << r.err;
    const CsvTable t = read_csv(r.out_path);
    const std::string value = c.find("--dim 2") == std::string::npos ? "tcrit" : "ecrit";
    for (const auto& row : t.rows) {
      EXPECT_EQ(row[t.column_index(value)], "nan") << c;
      EXPECT_EQ(row[t.column_index("status")], "numerical-issue") << c;
      for (const char* col : {"tcrit_symbol", "tcrit_infinite", "ecrit_symbol", "ecrit_infinite"}) {
        const auto& cols = t.columns;
        if (std::find(cols.begin(), cols.end(), col) != cols.end())
          EXPECT_NE(row[t.column_index(col)], "inf") << c << " " << col;
      }
    }
  }
}

/// One random argument list: a command, options drawn from pools of valid, extreme and malformed values, sometimes
/// an unknown option, an empty value or a duplicated option.
std::vector<std::string> random_case(std::mt19937_64& rng, const std::string& out) {
  auto pick = [&](const std::vector<std::string>& pool) {
    return pool[std::uniform_int_distribution<size_t>(0, pool.size() - 1)(rng)];
  };
  auto coin = [&](double p) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; };
  const std::vector<std::string> numbers = {"0",   "-1",    "1e308", "1e-320", "nan",  "inf", "-inf", "1e999",
                                            "abc", "",      "1,,2",  ",",      "3.5",  "1e6", "0x10", "2147483648",
                                            "-0",  "1e-61", "1e61",  " 1",     "1.2 ", "+1"};
  std::vector<std::string> a;
  const int command = std::uniform_int_distribution<int>(0, 9)(rng);
  if (command < 6) {
    a = {"tcrit"};
    const bool two = coin(0.3);
    if (coin(0.9)) a.insert(a.end(), {"--dim", coin(0.9) ? (two ? "2" : "1") : pick({"3", "0", "-1", "x", ""})});
    if (coin(0.7))
      a.insert(a.end(), {"--n", coin(0.6) ? pick(two ? std::vector<std::string>{"2", "4", "6", "9"}
                                                     : std::vector<std::string>{"1", "2", "7", "30", "200"})
                                          : pick({"100000000", "2147483648", "0", "-5", "1e3", "abc", "", "3000"})});
    if (coin(0.8))
      a.insert(a.end(),
               {"--h", coin(0.5) ? pick({"1.2", "1.3,1.7", "0.9:1.5:0.3", "0.3", "2.5", "20"})
                                 : pick({"1e10", "6e8", "1e6", "1:2", "2:1:0.1", "1:1e9:1e-9", "1e-61", "1e61"})});
    if (coin(0.2)) a.insert(a.end(), {"--h", pick(numbers)});
    if (coin(0.5))
      a.insert(a.end(), {"--kernel", pick({"cubic", "quintic,wendland-c4", "cubic,", "nope", "", ",", "gaussian", "hat",
                                           "mollifier", "cubic,cubic"})});
    if (coin(0.4))
      a.insert(a.end(), {"--form", pick({"conservative", "plus", "minus", "uncorrected", "plus,minus", "x", ""})});
    if (coin(0.3)) a.insert(a.end(), {"--method", pick({"eig", "bisect", "both", "none", ""})});
    if (coin(0.3)) a.insert(a.end(), {"--backend", pick({"auto", "dense", "spectra", "gpu"})});
    if (coin(0.3))
      a.insert(a.end(), {"--correction", pick({"none", "minus", "shepard", "ncsph", "mean-polish", "column-shepard",
                                               "local-polish", "x", ""})});
    if (coin(0.2)) a.insert(a.end(), {"--lattice", pick({"line", "square", "hex", "face-centred", "cubic", "tri"})});
    if (coin(0.2)) a.insert(a.end(), {"--prestrain", pick({"isotropic", "uniaxial", "shear"})});
    if (coin(0.15)) a.insert(a.end(), {pick({"--lambda", "--mu"}), coin(0.5) ? "1" : pick(numbers)});
    if (coin(0.15))
      a.insert(a.end(), {"--criterion", pick({"auto", "definiteness", "spectrum", "symmetric-part", "q"})});
    if (coin(0.3)) a.push_back("--compression");
    if (coin(0.3)) a.push_back("--periodic");
  } else if (command < 9) {
    a = {"operators"};
    const int dim = std::uniform_int_distribution<int>(1, 3)(rng);
    const std::vector<std::string> lat = {"", "line", "square", "cubic"};
    if (coin(0.95)) a.insert(a.end(), {"--dim", coin(0.9) ? std::to_string(dim) : pick({"0", "4", "x"})});
    if (coin(0.95))
      a.insert(a.end(), {"--lattice", coin(0.8) ? (dim == 2 ? pick({"square", "hex", "face-centred"}) : lat[dim])
                                                : pick({"line", "tri", ""})});
    if (coin(0.95))
      a.insert(a.end(),
               {"--n", coin(0.8) ? pick({"1", "2", "4", "6"}) : pick({"0", "-3", "100000", "2147483648", "x"})});
    if (coin(0.95)) a.insert(a.end(), {"--h", coin(0.7) ? pick({"1.2", "1.5", "0.4", "2"}) : pick(numbers)});
    if (coin(0.4))
      a.insert(a.end(), {"--dx", coin(0.5) ? pick({"1", "0.01", "1e-50", "1e50"})
                                           : pick({"1e-300", "1e-160", "1e200", "1e-61", "0", "-1", "nan"})});
    if (coin(0.3)) a.insert(a.end(), {"--fixed-layers", pick({"-1", "0", "2", "-5", "2000000000", "x"})});
    if (coin(0.2)) a.insert(a.end(), {"--seed", pick({"1", "-1", "18446744073709551615", "18446744073709551616", ""})});
    if (coin(0.2)) a.insert(a.end(), {"--perturb", pick({"0", "0.1", "-1", "nan", "1e308"})});
    if (coin(0.3))
      a.insert(a.end(), {"--correction", pick({"none", "shepard", "ncsph", "mean-polish", "local-polish", "x"})});
    if (coin(0.2)) a.push_back("--periodic");
    if (coin(0.2)) a.push_back("--hessian");
    if (coin(0.9)) a.insert(a.end(), {"--out", out});
  } else if (coin(0.5)) {
    a = {"kernels"};
    if (coin(0.5)) a.push_back("--native");
  } else {
    a = {"spectrum"};
    if (coin(0.5)) a.insert(a.end(), {"--dim", pick({"1", "2", "3", "0", "x"})});
    a.insert(a.end(), {"--n", coin(0.8) ? pick({"2", "4", "6"}) : pick({"1", "100000", "-2", ""})});
    if (coin(0.4)) a.push_back("--periodic");
    if (coin(0.5)) a.insert(a.end(), {"--xi", coin(0.7) ? pick({"0.98", "1", "1.02,1.04"}) : pick(numbers)});
    if (coin(0.3)) a.insert(a.end(), {"--poisson", pick({"0.3", "0.5", "-1", "0.49", "nan"})});
    if (coin(0.3)) a.insert(a.end(), {"--viscosity", pick({"off", "compression", "always", "on"})});
    if (coin(0.3)) a.insert(a.end(), {"--artificial-stress", pick({"0", "0.3", "-0.3", "inf"})});
    if (coin(0.3)) a.insert(a.end(), {"--xsph", pick({"0", "0.5", "-1"})});
    if (coin(0.3)) a.insert(a.end(), {"--h", coin(0.5) ? pick({"1.3", "1.0,1.5", "0.3"}) : pick(numbers)});
  }
  if (coin(0.1))
    a.insert(a.begin() + std::uniform_int_distribution<long>(1, a.size())(rng), pick({"--bogus", "-x", "--"}));
  if (coin(0.1) && a.size() > 2) a.push_back(a[1]), a.push_back(a.size() > 3 ? a[2] : "1");  // duplicated option
  if (coin(0.1)) a.insert(a.end(), {"--max-memory", pick({"2G", "10M", "0", "-1", "abc", "1e999"})});
  return a;
}

TEST(CliFuzz, SeededRandomArgumentListsKeepTheContract) {
  std::mt19937_64 rng(20261201);
  const std::string out = scratch("R").string();
  int ok = 0, errors = 0;
  for (int k = 0; k < 160; ++k) {
    const std::vector<std::string> args = random_case(rng, out);
    const test::CliOutcome r = test::run_cli_in_child(args, scratch("case"), kMemoryLimit, kTimeLimit);
    const std::string v = violation(args, r);
    EXPECT_EQ(v, "") << "case " << k << ": sphstab " << test::join_args(args) << "\nstdout: " << r.out.substr(0, 300)
                     << "\nstderr: " << r.err.substr(0, 300);
    (r.exit_code == 0 ? ok : errors) += 1;
    if (std::getenv("SPHSTAB_FUZZ_VERBOSE"))  // to read what the generator produced and what came back
      std::printf("%d %.2fs sphstab %s\n    -> %s\n", r.exit_code, r.seconds, test::join_args(args).c_str(),
                  r.exit_code ? r.err.substr(0, 220).c_str() : r.out.substr(0, 120).c_str());
  }
  // The generator must exercise both outcomes, or the contract is tested on one side only.
  EXPECT_GT(ok, 10);
  EXPECT_GT(errors, 40);
  std::printf("cli fuzz: %d successful, %d one-line errors\n", ok, errors);
}

/// One random `sphstab run` argument list. The pools keep every accepted run short (a few hundred particles, at most
/// ~1000 steps): the contract is checked, not the solver's speed.
std::vector<std::string> random_run_case(std::mt19937_64& rng, const std::string& out) {
  auto pick = [&](const std::vector<std::string>& pool) {
    return pool[std::uniform_int_distribution<size_t>(0, pool.size() - 1)(rng)];
  };
  auto coin = [&](double p) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; };
  const std::vector<std::string> bad = {"0", "-1", "nan", "inf", "1e999", "abc", "", ",", "1,2", " 1", "1e-320"};
  std::vector<std::string> a = {"run"};
  const bool two = coin(0.4);
  a.insert(a.end(), {"--dim", coin(0.95) ? (two ? "2" : "1") : pick({"3", "0", "x", ""})});
  if (two || coin(0.8))  // 2D without --n is the 21 x 21 default: seconds, not milliseconds
    a.insert(a.end(), {"--n", coin(0.9) ? (two ? pick({"3", "5", "7"}) : pick({"3", "5", "9", "20"}))
                                        : pick({"2", "1", "-3", "2147483648", "x", ""})});
  if (coin(0.3)) a.push_back("--periodic");
  if (coin(0.05)) a.push_back("--block");
  if (coin(0.1)) a.insert(a.end(), {"--lattice", pick({"line", "square", "hex", "face-centred", "cubic"})});
  if (coin(0.3)) a.insert(a.end(), {"--h", coin(0.85) ? pick({"1.3", "1.0", "2", "0.3"}) : pick({"1.3,1.5", "1e10"})});
  if (coin(0.2)) a.insert(a.end(), {"--kernel", pick({"cubic", "quintic", "wendland-c2", "gaussian", "nope"})});
  if (coin(0.6)) a.insert(a.end(), {"--xi", coin(0.85) ? pick({"0.98", "1", "1.02"}) : pick(bad)});
  if (coin(0.1)) a.insert(a.end(), {"--poisson", pick({"0.3", "0.5", "-1", "0.49", "nan"})});
  if (coin(0.3)) a.insert(a.end(), {"--integrator", coin(0.9) ? pick({"pc", "leapfrog"}) : pick({"rk4", ""})});
  if (coin(0.3))
    a.insert(a.end(), {"--dt", coin(0.8) ? pick({"0.001", "0.01", "0.06"}) : pick({"1e-61", "1e-300", "-0.01"})});
  else if (coin(0.2))
    a.insert(a.end(), {"--cfl", coin(0.8) ? pick({"0.5", "1.5"}) : pick(bad)});
  if (coin(0.6)) a.insert(a.end(), {"--t-end", coin(0.85) ? pick({"0.05", "0.2", "1"}) : pick(bad)});
  if (coin(0.3)) a.insert(a.end(), {"--record-every", pick({"1", "5", "10", "0", "x"})});
  if (coin(0.3)) a.insert(a.end(), {"--kick", pick({"1e-10", "0", "-1e-3", "0.01", "nan"})});
  if (coin(0.1)) a.insert(a.end(), {"--yield", pick({"0.001", "0.01", "0", "x"})});
  if (coin(0.1)) a.insert(a.end(), {"--energy-growth", pick({"10", "1e6", "1", "x"})});
  if (coin(0.1)) a.insert(a.end(), {"--max-displacement", pick({"1e-6", "off", "0.5", "0"})});
  if (coin(0.1)) a.insert(a.end(), {"--gradient", pick({"plain", "ncsph", "x"})});
  if (coin(0.1)) a.insert(a.end(), {"--momentum", pick({"symmetric", "antisymmetric", "cij", "ssph", "x"})});
  if (coin(0.1)) a.insert(a.end(), {"--continuity", pick({"summation", "divergence", "x"})});
  if (coin(0.1)) a.insert(a.end(), {"--viscosity", pick({"off", "compression", "always", "on"})});
  if (coin(0.1)) a.insert(a.end(), {"--xsph", pick({"0", "0.5", "-1"})});
  if (coin(0.1)) a.insert(a.end(), {"--artificial-stress", pick({"0", "0.3", "-0.3"})});
  if (coin(0.1)) a.insert(a.end(), {"--out", out});
  if (coin(0.05)) a.insert(a.begin() + std::uniform_int_distribution<long>(1, a.size())(rng), pick({"--bogus", "--"}));
  return a;
}

TEST(CliFuzz, SeededRandomRunArgumentListsKeepTheContract) {
  std::mt19937_64 rng(20261202);
  const std::string out = scratch("run").string();
  int ok = 0, errors = 0;
  for (int k = 0; k < 60; ++k) {
    const std::vector<std::string> args = random_run_case(rng, out);
    const test::CliOutcome r = test::run_cli_in_child(args, scratch("runcase"), kMemoryLimit, kTimeLimit);
    const std::string v = violation(args, r);
    EXPECT_EQ(v, "") << "case " << k << ": sphstab " << test::join_args(args) << "\nstdout: " << r.out.substr(0, 300)
                     << "\nstderr: " << r.err.substr(0, 300);
    (r.exit_code == 0 ? ok : errors) += 1;
    if (std::getenv("SPHSTAB_FUZZ_VERBOSE"))
      std::printf(
          "%d %.2fs sphstab %s\n    -> %s\n", r.exit_code, r.seconds, test::join_args(args).c_str(),
          r.exit_code ? r.err.substr(0, 220).c_str() : r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1).c_str());
  }
  EXPECT_GT(ok, 10);
  EXPECT_GT(errors, 15);
  std::printf("cli fuzz (run): %d successful, %d one-line errors\n", ok, errors);
}

TEST(CliFuzz, OutputIsDeterministic) {
  const std::string out = scratch("det").string();
  for (const std::string c :
       {"tcrit --h 1.2,1.5 --kernel cubic,wendland-c4 --form plus,conservative",
        "tcrit --dim 2 --n 6 --h 1.3 --form plus,conservative", "tcrit --h 1.3 --correction shepard --form plus",
        "run --n 5 --xi 1.02 --t-end 1 --record-every 7"}) {
    const test::CliOutcome a = test::run_cli_in_child(words(c), scratch("det1"), kMemoryLimit, kTimeLimit);
    const test::CliOutcome b = test::run_cli_in_child(words(c), scratch("det2"), kMemoryLimit, kTimeLimit);
    ASSERT_EQ(a.exit_code, 0) << c << ": " << a.err;
    EXPECT_EQ(a.out, b.out) << c;
  }
  const std::string ops = "operators --dim 2 --lattice hex --n 6 --h 1.3 --perturb 0.1 --correction ncsph --out ";
  const test::CliOutcome a = test::run_cli_in_child(words(ops + out + "1"), scratch("det3"), kMemoryLimit, kTimeLimit);
  const test::CliOutcome b = test::run_cli_in_child(words(ops + out + "2"), scratch("det4"), kMemoryLimit, kTimeLimit);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  for (const char* f : {"W.mtx", "G_x.mtx", "G_ncsph_y.mtx", "particles.csv"}) {
    const std::string x = test::slurp(out + "1/" + f), y = test::slurp(out + "2/" + f);
    EXPECT_FALSE(x.empty()) << f;
    EXPECT_EQ(x, y) << f;  // the header's command line does not include --out
  }
}

}  // namespace cli_fuzz_test
}  // namespace sphstab
