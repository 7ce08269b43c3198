// `sphstab spectrum` in-process (cli_harness.hpp): the growth rate agrees with the library and with the lattice
// dispersion value in GMS units; bad input is one error line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "cli_harness.hpp"
#include "sphstab/io/csv.hpp"

namespace sphstab {
namespace {

// One directory per test process: ctest runs the tests of this file in parallel processes, and a shared stdout file
// let one test read another's output (a CI failure of BadInputIsOneErrorLine).
test::CliOutcome run(const std::vector<std::string>& args) {
  return test::run_cli_in_child(
      args, std::filesystem::temp_directory_path() / ("sphstab_spectrum_test_" + std::to_string(getpid())), 2e9, 120);
}

TEST(SpectrumCommand, GrowthRateInGmsUnits) {
  // K = 1, mu = 0.3, rho0 = 1 (E = 9 K mu / (3K + mu), nu = (3K - 2mu) / (2 (3K + mu))), dx = 1: basic SPH on a
  // periodic 8 x 8 square lattice at xi = 1.02 grows at 0.1868 (= the lattice dispersion relation, rate_form_test).
  const test::CliOutcome r =
      run({"spectrum", "--periodic", "--n", "8", "--h", "1.3", "--xi", "1.02,1", "--dx", "1", "--youngs",
           "0.8181818181818182", "--poisson", "0.36363636363636365", "--density", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = read_csv(r.out_path);
  ASSERT_EQ(t.rows.size(), 2u);
  const auto gamma = t.numeric_column("growth_rate");
  EXPECT_NEAR(gamma[0], 0.1868, 2e-4);
  EXPECT_LT(gamma[1], 1e-6);  // xi = 1: neutral
  EXPECT_LT(t.numeric_column("equilibrium_residual")[0], 1e-12);
  EXPECT_EQ(t.rows[0][t.column_index("status")], "successful");
  EXPECT_GE(t.numeric_column("mode_kx_over_pi")[0], 0.0);
}

TEST(SpectrumCommand, BadInputIsOneErrorLine) {
  for (const std::vector<std::string>& a : {std::vector<std::string>{"spectrum", "--poisson", "0.5"},
                                            {"spectrum", "--xi", "0"},
                                            {"spectrum", "--xi", ","},
                                            {"spectrum", "--viscosity", "on"},
                                            {"spectrum", "--youngs", "-1"},
                                            {"spectrum", "--lattice", "cubic"},
                                            {"spectrum", "--dim", "3"},
                                            {"spectrum", "--artificial-stress", "-0.3"},
                                            {"spectrum", "--continuity", "x"},
                                            {"spectrum", "--n", "100000"},
                                            {"spectrum", "--dx", "1e-300"},
                                            {"spectrum", "--threads", "0"},
                                            {"--threads", "two", "spectrum"}}) {
    const test::CliOutcome r = run(a);
    EXPECT_EQ(r.exit_code, 1) << test::join_args(a) << ": " << r.out;
    EXPECT_EQ(r.err.rfind("sphstab: error: ", 0), 0u) << test::join_args(a);
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << test::join_args(a) << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << test::join_args(a);
  }
}

}  // namespace
}  // namespace sphstab
