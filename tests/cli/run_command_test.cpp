// `sphstab run` in-process (cli_harness.hpp): the printed series is the library's run (independent set-up of the same
// scene), a stable compressed bar stays bounded while a periodic bar in tension grows at the spectral rate, a run that
// blows up keeps its rows and ends with its status, step, time and particle, and bad input is one error line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/growth/rate_form_time_step.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace run_command_test {

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("sphstab_run_test_" + std::to_string(getpid())) / name;
}

test::CliOutcome run(const std::vector<std::string>& args, const std::string& tag = "case") {
  return test::run_cli_in_child(args, scratch(tag), 2e9, 60);
}

/// The default scene of `sphstab run --dim 1` built from the library directly: a line of n free particles, dx = 0.01,
/// cubic spline, h = 1.3 dx, fixed layers out to the support (or periodic), E = 2.1, nu = 0.3, rho0 = 7.8, density
/// rho0 / xi, plain SPH.
/// The command's scene; `loop`: the command's default (auto) takes the pair loop for the plain symmetric scheme.
RateFormScheme<1> bar(int n, double xi, bool periodic, PairLoop loop = PairLoop::Pairs) {
  const Kernel<1> kernel(KernelType::CubicSpline);
  const double dx = 0.01, h = 1.3 * dx;
  auto disc = make_discretisation(
      make_lattice<1>(LatticeType::Line, n,
                      {.spacing = dx, .support_radius = kernel.support_radius(h), .periodic = periodic}),
      kernel, h);
  return RateFormScheme<1>(disc, ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8), {.pair_loop = loop}, 7.8 / xi);
}

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

/// Least-squares slope of log(values) against times over the rows whose value lies in (lo, hi) x values[0].
double log_slope(const std::vector<double>& times, const std::vector<double>& values, double lo, double hi) {
  double st = 0, sy = 0, stt = 0, sty = 0, m = 0;
  for (std::size_t k = 0; k < times.size(); ++k)
    if (values[k] > lo * values[0] && values[k] < hi * values[0]) {
      const double y = std::log(values[k]);
      st += times[k], sy += y, stt += times[k] * times[k], sty += times[k] * y, m += 1;
    }
  return (m * sty - st * sy) / (m * stt - st * st);
}

TEST(RunCommand, SeriesIsTheLibrarysRunOfTheSameScene) {
  // A 15-particle bar in slight tension, kicked at its centre particle 7 (free particles come first); the leap-frog
  // at the default dt (0.5 x the leap-frog limit of the spectrum at rest) and the predictor-corrector at a given dt.
  const RateFormScheme<1> scheme = bar(15, 1.01, false);
  Eigen::VectorXd y = scheme.uniform_state();
  const double dt_default = 0.5 * rate_form_time_step(scheme, y).leapfrog;
  scheme.set_velocity(y, 7, Eigen::Matrix<double, 1, 1>(1e-10));
  struct Case {
    std::vector<std::string> args;
    RateFormRunOptions options;
  };
  const std::vector<Case> cases = {
      {{"run", "--dim", "1", "--n", "15", "--xi", "1.01", "--t-end", "2", "--record-every", "7"},
       {.dt = dt_default, .t_end = 2, .record_every = 7, .integrator = RateFormIntegrator::Leapfrog}},
      {{"run", "--dim", "1", "--n", "15", "--xi", "1.01", "--t-end", "1.5", "--record-every", "3", "--integrator", "pc",
        "--dt", "0.007"},
       {.dt = 0.007, .t_end = 1.5, .record_every = 3, .integrator = RateFormIntegrator::PredictorCorrector}}};
  for (const Case& c : cases) {
    const RateFormRunResult direct = run_rate_form(scheme, y, c.options);
    ASSERT_TRUE(direct.completed());
    const test::CliOutcome r = run(c.args);
    ASSERT_EQ(r.exit_code, 0) << test::join_args(c.args) << ": " << r.err;
    const CsvTable t = read_csv(r.out_path);
    ASSERT_EQ(t.rows.size(), direct.times.size()) << test::join_args(c.args);
    const std::vector<double> time = t.numeric_column("time"), ke = t.numeric_column("kinetic_energy"),
                              dt = t.numeric_column("dt"), step = t.numeric_column("step");
    double ke_max = 0;
    for (double e : direct.kinetic_energy) ke_max = std::max(ke_max, e);
    for (std::size_t k = 0; k < time.size(); ++k) {
      EXPECT_EQ(time[k], direct.times[k]) << k;  // printed in the shortest round-trip form
      EXPECT_EQ(dt[k], direct.dt) << k;
      EXPECT_DOUBLE_EQ(step[k] * direct.dt, direct.times[k]) << k;
      // Same operations in the same order: equal to rounding (1e-13 of the series' scale allows for nothing more).
      EXPECT_NEAR(ke[k], direct.kinetic_energy[k], 1e-13 * ke_max) << test::join_args(c.args) << " row " << k;
    }
    EXPECT_GT(ke_max, 0);
    EXPECT_NE(ke[1], ke[0]);  // the bar moves: the comparison is not of constants
    EXPECT_EQ(t.rows.back()[t.column_index("status")], "completed");
    EXPECT_EQ(t.rows.front()[t.column_index("status")], "running");
  }
}

TEST(RunCommand, PairLoopRunsTheSameSeriesToRounding) {
  // --pair-loop pairs against the library's row loop on the same kicked bar: the rates agree to rounding
  // (rate_form_pair_loop_test), so over 300 predictor-corrector steps the kinetic energy agrees to far below its
  // scale, and the two are not bitwise equal (the option reaches the scheme). The command's default (auto) is the
  // pair loop here; --pair-loop rows is the library's row loop to the bit.
  const RateFormScheme<1> scheme = bar(15, 1.01, false, PairLoop::Rows);
  Eigen::VectorXd y = scheme.uniform_state();
  scheme.set_velocity(y, 7, Eigen::Matrix<double, 1, 1>(1e-3));  // a kick far above the positions' rounding
  const RateFormRunResult direct = run_rate_form(
      scheme, y, {.dt = 0.005, .t_end = 1.5, .record_every = 10, .integrator = RateFormIntegrator::PredictorCorrector});
  ASSERT_TRUE(direct.completed());
  const std::vector<std::string> args = {
      "run", "--dim",        "1",  "--n",  "15",    "--xi",        "1.01",  "--t-end", "1.5", "--record-every",
      "10",  "--integrator", "pc", "--dt", "0.005", "--pair-loop", "pairs", "--kick",  "1e-3"};
  const test::CliOutcome r = run(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<double> ke = read_csv(r.out_path).numeric_column("kinetic_energy");
  ASSERT_EQ(ke.size(), direct.kinetic_energy.size());
  double ke_max = 0, diff = 0;
  for (std::size_t k = 0; k < ke.size(); ++k) {
    ke_max = std::max(ke_max, direct.kinetic_energy[k]);
    diff = std::max(diff, std::abs(ke[k] - direct.kinetic_energy[k]));
  }
  EXPECT_GT(ke_max, 0);
  EXPECT_LT(diff, 1e-9 * ke_max);
  EXPECT_GT(diff, 0);
  std::vector<std::string> rows_args = args, auto_args = args;
  rows_args[rows_args.size() - 3] = "rows";
  auto_args.erase(auto_args.end() - 4, auto_args.end() - 2);  // no --pair-loop: the default
  const test::CliOutcome rows = run(rows_args, "rows"), automatic = run(auto_args, "auto");
  ASSERT_EQ(rows.exit_code, 0) << rows.err;
  ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
  EXPECT_EQ(read_csv(rows.out_path).numeric_column("kinetic_energy"), direct.kinetic_energy);
  EXPECT_EQ(read_csv(automatic.out_path).numeric_column("kinetic_energy"), ke);  // auto = pairs
}

TEST(RunCommand, CompressedBarStaysBoundedAndTensionGrowsAtTheSpectralRate) {
  // Plain SPH in 1D is stable in compression (xi = 0.98: every lambda imaginary): 2000 leap-frog steps at the default
  // dt keep the kinetic energy at or below its initial value (energy moves into strain energy and back).
  const test::CliOutcome s =
      run({"run", "--dim", "1", "--n", "21", "--xi", "0.98", "--t-end", "40", "--record-every", "5"}, "stable");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const CsvTable st = read_csv(s.out_path);
  const std::vector<double> ke_s = st.numeric_column("kinetic_energy");
  ASSERT_GT(ke_s.size(), 300u);
  for (double e : ke_s) EXPECT_LE(e, 1.05 * ke_s[0]);  // leap-frog: its modified energy, not KE, is conserved
  EXPECT_EQ(st.rows.back()[st.column_index("status")], "completed");

  // In tension (xi = 1.02) a periodic bar's sawtooth v_i = V0 sin(pi (i + 1/2)) = +-V0 is the most unstable mode
  // (k dx = pi); the kinetic energy grows as exp(2 gamma t) with gamma the spectrum's growth rate.
  const RateFormScheme<1> scheme = bar(20, 1.02, true);
  const RateFormSpectrum sp = rate_form_spectrum(scheme, scheme.uniform_state());
  ASSERT_EQ(sp.status, Status::Successful);
  ASSERT_GT(sp.growth_rate, 1.0);
  const test::CliOutcome u = run({"run", "--dim", "1", "--n", "20", "--periodic", "--xi", "1.02", "--record-every", "1",
                                  "--energy-growth", "1e14"},
                                 "unstable");
  ASSERT_EQ(u.exit_code, 0) << u.err;
  const CsvTable ut = read_csv(u.out_path);
  const std::vector<double> ke = ut.numeric_column("kinetic_energy"), time = ut.numeric_column("time");
  // Every particle carries the amplitude: KE(0) = 1/2 N m V0^2, m = rho dx.
  EXPECT_NEAR(ke[0], 0.5 * 20 * (7.8 / 1.02 * 0.01) * 1e-20, 1e-12 * ke[0]);
  // Fit over KE / KE0 in (1e3, 1e12): past the cosh transient, still linear (speeds below 2e-4 c).
  const double gamma = 0.5 * log_slope(time, ke, 1e3, 1e12);
  // Leap-frog's growth for lambda = gamma real: cosh(dt gamma') = 1 + (dt gamma)^2 / 2, 0.1 % slower here.
  EXPECT_NEAR(gamma / sp.growth_rate, 1.0, 0.02);
  EXPECT_EQ(ut.rows.back()[ut.column_index("status")], "energy-growth");
  EXPECT_EQ(ut.rows.back()[ut.column_index("particle")], "-1");
  EXPECT_GT(ke.back(), 1e14 * ke[0]);
}

TEST(RunCommand, BlowUpEndsWithStatusStepTimeAndParticleAndKeepsTheRows) {
  // Leap-frog at 1.44 x its stability limit (about 0.0415 for this bar): the fastest mode's amplitude grows ~ 6-fold
  // per step until a density turns negative or the state non-finite (the library's checks: the command's displacement
  // limit is switched off).
  const std::vector<std::string> args =
      words("run --dim 1 --n 21 --xi 0.98 --dt 0.06 --t-end 30 --record-every 1 --max-displacement off");
  const test::CliOutcome r = run(args, "blowup");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = read_csv(r.out_path);
  ASSERT_GE(t.rows.size(), 5u);
  const std::vector<double> step = t.numeric_column("step"), time = t.numeric_column("time"),
                            ke = t.numeric_column("kinetic_energy");
  const std::vector<std::string> status = t.text_column("status");
  const long last = static_cast<long>(step.back());
  EXPECT_LT(last, 500);  // stopped long before t_end = 30 (500 steps)
  for (std::size_t k = 0; k + 1 < status.size(); ++k) {
    EXPECT_EQ(status[k], "running") << k;
    EXPECT_EQ(step[k], static_cast<double>(k));  // every earlier record kept
  }
  EXPECT_EQ(step.back(), static_cast<double>(t.rows.size() - 1));
  EXPECT_TRUE(status.back() == "non-positive-density" || status.back() == "non-finite") << status.back();
  EXPECT_GE(std::stoi(t.rows.back()[t.column_index("particle")]), 0);
  EXPECT_NEAR(time.back(), last * 0.06, 1e-12);
  EXPECT_GT(ke[ke.size() - 2], 1e6 * ke[0]);  // it did blow up before stopping
  EXPECT_NE(r.err.find("at step " + std::to_string(last)), std::string::npos) << r.err;

  // The command's own limit: a particle that moves more than --max-displacement dx stops the run at that record.
  const test::CliOutcome d = run({"run", "--dim", "1", "--n", "21", "--kick", "1e-3", "--max-displacement", "1e-3",
                                  "--t-end", "1", "--record-every", "2"},
                                 "displacement");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const CsvTable dt = read_csv(d.out_path);
  ASSERT_GE(dt.rows.size(), 2u);
  EXPECT_EQ(dt.rows.back()[dt.column_index("status")], "displacement-limit");
  EXPECT_EQ(dt.rows.back()[dt.column_index("particle")], "10");  // the kicked centre particle moves first
  EXPECT_GT(dt.numeric_column("max_displacement").back(), 1e-3 * 0.01);
}

TEST(RunCommand, AModelThatRefusesTheStateEndsTheRunAsAResult) {
  // At three times the CFL step the artificial stress meets rho < 0 inside the threaded stress pass (it throws
  // there): the run loop reports it as status "exception" with the step, keeping every row; it used to abort
  // (an exception leaving an OpenMP region is std::terminate).
  const test::CliOutcome r = run(words("run --n 5 --artificial-stress 0.3 --cfl 3 --t-end 20 --record-every 1"),
                                 "refused");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = read_csv(r.out_path);
  ASSERT_GE(t.rows.size(), 3u);
  const std::vector<std::string> status = t.text_column("status");
  EXPECT_EQ(status.back(), "exception");
  for (std::size_t k = 0; k + 1 < status.size(); ++k) EXPECT_EQ(status[k], "running") << k;
  const long last = static_cast<long>(t.numeric_column("step").back());
  EXPECT_NE(r.err.find("artificial_stress: density must be finite and > 0"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("at step " + std::to_string(last)), std::string::npos) << r.err;
}

TEST(RunCommand, AHugeButFiniteDisplacementIsReportedAsItIs) {
  // dt = 1e300 moves the kicked particle by ~1e290 in a step: finite, so the stop is the displacement limit with that
  // distance (its squared norm would overflow to inf), not "moved inf".
  const test::CliOutcome r = run(words("run --n 5 --dt 1e300 --t-end 1e301"), "huge");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("displacement-limit"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("moved 1e+"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("moved inf"), std::string::npos) << r.err;
}

TEST(RunCommand, SnapshotsFollowTheRows) {
  const std::string out = scratch("vtk").string();
  std::filesystem::remove_all(out);
  const test::CliOutcome r =
      run({"run", "--dim", "1", "--n", "5", "--t-end", "0.1", "--dt", "0.01", "--record-every", "5", "--out", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = read_csv(r.out_path);
  ASSERT_EQ(t.rows.size(), 3u);  // steps 0, 5, 10
  const VtpData first = read_vtp(out + "/run_000000.vtp");
  const VtpData last = read_vtp(out + "/run_000010.vtp");
  const VtkField& v = first.field("velocity");
  EXPECT_EQ(v.values[v.components * 2], 1e-10);  // centre particle 2
  EXPECT_EQ(first.field("density").values.size(), first.points.rows());
  EXPECT_EQ(last.field("fixed").values.sum(), first.points.rows() - 5.0);
  EXPECT_TRUE(std::filesystem::exists(out + "/run.pvd"));
}

TEST(RunCommand, BadInputIsOneErrorLine) {
  for (const std::vector<std::string>& a : {std::vector<std::string>{"run", "--poisson", "0.5"},
                                            {"run", "--poisson", "-1"},
                                            {"run", "--youngs", "0"},
                                            {"run", "--density", "-7.8"},
                                            {"run", "--xi", "0"},
                                            {"run", "--xi", "1,1.02"},
                                            {"run", "--h", "-1.3"},
                                            {"run", "--dt", "0"},
                                            {"run", "--dt", "-0.01"},
                                            {"run", "--t-end", "0"},
                                            {"run", "--t-end", "-1"},
                                            {"run", "--cfl", "0"},
                                            {"run", "--dt", "0.01", "--cfl", "0.3"},
                                            {"run", "--continuity", "sum"},
                                            {"run", "--viscosity", "on"},
                                            {"run", "--gradient", "shepard"},
                                            {"run", "--momentum", "plus"},
                                            {"run", "--switch-rule", "x"},
                                            {"run", "--counting", "x"},
                                            {"run", "--pair-loop", "half"},
                                            {"run", "--pair-loop", "pairs", "--gradient", "ncsph"},
                                            {"run", "--pair-loop", "pairs", "--momentum", "cij"},
                                            {"run", "--integrator", "rk4"},
                                            {"run", "--integrator", "pc1", "--yield", "0.1"},
                                            {"run", "--kernel", "nope"},
                                            {"run", "--lattice", "cubic"},
                                            {"run", "--n", "2"},
                                            {"run", "--dim", "1", "--n", "1"},
                                            {"run", "--record-every", "0"},
                                            {"run", "--yield", "0"},
                                            {"run", "--energy-growth", "1"},
                                            {"run", "--energy-growth", "10", "--kick", "0"},
                                            {"run", "--block", "--periodic"},
                                            {"run", "--xsph", "-0.5"},
                                            {"run", "--dim", "1", "--dt", "1e-300", "--t-end", "1"},
                                            {"run", "--dim", "2", "--n", "10000"}}) {
    const test::CliOutcome r = run(a);
    EXPECT_EQ(r.exit_code, 1) << test::join_args(a) << ": " << r.out;
    EXPECT_EQ(r.err.rfind("sphstab: error: ", 0), 0u) << test::join_args(a) << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << test::join_args(a) << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << test::join_args(a);
  }
}

TEST(RunCommand, OptionsThatDoNothingAreRefused) {
  // Issue 36: each was accepted and ignored. The message names the option and the combination it does nothing in.
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"run", "--alpha", "1"}, "--alpha has no effect with --viscosity off"},
      {{"spectrum", "--viscosity", "off", "--beta", "2"}, "--beta has no effect with --viscosity off"},
      {{"run", "--switch-rule", "never"}, "--switch-rule has no effect without --momentum ssph"},
      {{"spectrum", "--counting", "boundary-level", "--momentum", "antisymmetric"},
       "--counting has no effect without --momentum cij or ssph"}};
  for (const auto& [args, message] : cases) {
    const test::CliOutcome r = run(args);
    EXPECT_EQ(r.exit_code, 1) << test::join_args(args);
    EXPECT_NE(r.err.find(message), std::string::npos) << test::join_args(args) << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  }
  // Where they do act, they are accepted.
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", "--n", "5", "--viscosity", "compression", "--alpha", "1", "--t-end", "0.02"},
        {"run", "--n", "5", "--momentum", "ssph", "--switch-rule", "never", "--t-end", "0.02"},
        {"run", "--n", "5", "--momentum", "cij", "--counting", "boundary-level", "--t-end", "0.02"}}) {
    const test::CliOutcome r = run(args);
    EXPECT_EQ(r.exit_code, 0) << test::join_args(args) << ": " << r.err;
  }
}

}  // namespace
}  // namespace sphstab
