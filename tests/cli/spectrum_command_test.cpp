// `sphstab spectrum` in-process (cli_harness.hpp): the growth rate agrees with the library and with the lattice
// dispersion value in GMS units; bad input is one error line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "cli_harness.hpp"
#include "sphstab/io/csv.hpp"

namespace sphstab {
namespace spectrum_command_test {

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

// --bulk-viscosity Q1,Q2 (MCM's QBVC,LBVC) reaches the scheme: its switch is off at rest (d = 0), so the spectrum is
// the same to the last bit; malformed or negative values are one error line.
TEST(SpectrumCommand, BulkViscosityIsOffAtRestAndCheckedOnInput) {
  const std::vector<std::string> base = {"spectrum", "--periodic", "--n", "8", "--xi", "1.02"};
  std::vector<std::string> with = base;
  with.insert(with.end(), {"--bulk-viscosity", "1.5,0.06"});
  const test::CliOutcome a = run(base), b = run(with);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const double ga = read_csv(a.out_path).numeric_column("growth_rate")[0];
  const double gb = read_csv(b.out_path).numeric_column("growth_rate")[0];
  EXPECT_GT(ga, 0.0);
  EXPECT_EQ(ga, gb);
  for (const char* bad : {"1.5", "1.5,0.06,1", "-1,0", "0,nan", ""}) {
    std::vector<std::string> args = base;
    args.insert(args.end(), {"--bulk-viscosity", bad});
    const test::CliOutcome r = run(args);
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_NE(r.err.find("--bulk-viscosity"), std::string::npos) << bad << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
  }
}

// Issue 36: with no neighbour inside the support (2h = 0.6 dx, 1.0 dx) every particle is decoupled; the spectrum is
// not "0, successful" but NaN with numerical-issue and the reason (README), exit 0; at h = 0.8 it is computed.
// The same lattice at dx = 1e-40 and 1e58 gives the dx = 1 growth rate divided by dx (the complex step scales with
// the positions, jacobian/complex_step_jacobian.hpp).
TEST(SpectrumCommand, NoNeighbourIsNanAndScaleIsExact) {
  const test::CliOutcome r = run({"spectrum", "--periodic", "--n", "6", "--h", "0.3,0.5,0.8"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = read_csv(r.out_path);
  ASSERT_EQ(t.rows.size(), 3u);
  const auto gamma = t.numeric_column("growth_rate");
  for (int k : {0, 1}) {
    EXPECT_TRUE(std::isnan(gamma[k])) << k;
    EXPECT_EQ(t.rows[k][t.column_index("status")], "numerical-issue");
    EXPECT_NE(t.rows[k][t.column_index("reason")].find("kernel support"), std::string::npos);
  }
  EXPECT_EQ(t.rows[2][t.column_index("status")], "successful");
  EXPECT_TRUE(std::isfinite(gamma[2]));
  double at_one = 0;
  for (const char* dx : {"1", "1e-40", "1e58"}) {
    const test::CliOutcome s = run({"spectrum", "--periodic", "--n", "8", "--xi", "0.9", "--dx", dx});
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const CsvTable u = read_csv(s.out_path);
    const double scaled = u.numeric_column("growth_rate")[0] * std::stod(dx);
    if (std::string(dx) == "1") at_one = scaled;
    EXPECT_NEAR(scaled, at_one, 1e-10 * at_one) << "dx " << dx;
    EXPECT_EQ(u.rows[0][u.column_index("mode_kx_over_pi")], "1") << "dx " << dx;  // the zone corner, as at dx = 1
  }
}

TEST(SpectrumCommand, VerdictColumns) {
  // 1D periodic, GMS units (K = 1, mu = 0.3, rho0 = 1, dx = 1). Leap-frog at dt = 0.2 (below its limit): xi = 1 is
  // neutral (S), xi = 1.05 in tension grows (U, the map at the semi-discrete rate). The predictor-corrector at xi = 1:
  // the map grows at ln(1 + (omega dt)^4 / 4) / (2 dt), which only a long enough run detects (S, then I).
  const std::vector<std::string> base{"spectrum",  "--dim",
                                      "1",         "--periodic",
                                      "--n",       "12",
                                      "--h",       "1.3",
                                      "--dx",      "1",
                                      "--youngs",  "0.8181818181818182",
                                      "--poisson", "0.36363636363636365",
                                      "--density", "1",
                                      "--dt",      "0.2"};
  std::vector<std::string> lf = base;
  lf.insert(lf.end(), {"--xi", "1,1.05", "--integrator", "leapfrog", "--t-end", "100"});
  const test::CliOutcome r = run(lf);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = read_csv(r.out_path);
  ASSERT_EQ(t.rows.size(), 2u);
  const auto verdict = t.column_index("verdict");
  EXPECT_EQ(t.rows[0][verdict], "S");
  EXPECT_EQ(t.rows[1][verdict], "U");
  EXPECT_NEAR(t.numeric_column("floor")[0], std::log(100.0) / 200, 1e-9);
  EXPECT_EQ(t.rows[0][t.column_index("integrator")], "leapfrog");
  EXPECT_EQ(t.rows[1][t.column_index("verdict_status")], "successful");
  // U: the map's growth is the semi-discrete one to within the floor.
  EXPECT_NEAR(t.numeric_column("map_growth")[1], t.numeric_column("growth_rate")[1], t.numeric_column("floor")[1]);
  // The PC's growth at omega dt = 0.18 is ~7e-4: below the 100-unit run's floor 0.023 (S), above a 10^4-unit run's
  // 2.3e-4 (I).
  std::vector<std::string> pc = base;
  pc.insert(pc.end(), {"--xi", "1", "--integrator", "pc"});
  std::vector<std::string> pc_short = pc;
  pc_short.insert(pc_short.end(), {"--t-end", "100"});
  const test::CliOutcome short_run = run(pc_short);
  ASSERT_EQ(short_run.exit_code, 0) << short_run.err;
  EXPECT_EQ(read_csv(short_run.out_path).rows[0][verdict], "S");
  pc.insert(pc.end(), {"--t-end", "10000"});
  const test::CliOutcome q = run(pc);
  ASSERT_EQ(q.exit_code, 0) << q.err;
  const CsvTable u = read_csv(q.out_path);
  ASSERT_EQ(u.rows.size(), 1u);
  EXPECT_EQ(u.rows[0][u.column_index("verdict")], "I") << u.rows[0][u.column_index("verdict_reason")];
  EXPECT_GT(u.numeric_column("map_mode_kx_over_pi")[0], 0.0);  // the integrator's growth is located
  // Without --integrator the columns are the spectrum's alone.
  const test::CliOutcome plain = run({"spectrum", "--dim", "1", "--periodic", "--n", "8", "--dx", "1"});
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const CsvTable p = read_csv(plain.out_path);
  EXPECT_EQ(std::find(p.columns.begin(), p.columns.end(), "verdict"), p.columns.end());
}

TEST(SpectrumCommand, BadInputIsOneErrorLine) {
  for (const std::vector<std::string>& a :
       {std::vector<std::string>{"spectrum", "--poisson", "0.5"},
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
        {"spectrum", "--dt", "0.1"},
        {"spectrum", "--integrator", "rk4", "--dt", "0.1", "--t-end", "1"},
        {"spectrum", "--integrator", "pc", "--dt", "0.1"},
        {"spectrum", "--integrator", "pc", "--dt", "0", "--t-end", "1"},
        {"spectrum", "--integrator", "pc", "--dt", "0.1", "--t-end", "1", "--energy-ratio", "1"},
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
