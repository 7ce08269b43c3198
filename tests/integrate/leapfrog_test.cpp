#include "sphstab/integrate/leapfrog.hpp"

#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <cmath>
#include <filesystem>
#include <random>

#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/run_output.hpp"

namespace sphstab {
namespace leapfrog_test {

SecondOrderSystem oscillator(double omega) {
  SecondOrderSystem s;
  s.acceleration = [omega](const Eigen::VectorXd& u, Eigen::VectorXd& a) { a = -omega * omega * u; };
  s.strain_energy = [omega](const Eigen::VectorXd& u) { return 0.5 * omega * omega * u.squaredNorm(); };
  return s;
}

/// Measured period of u(t) from upward and downward zero crossings (linear interpolation; the
/// interpolation error is O(dt^3) per crossing because cos has zero curvature at its zeros).
double measured_period(double omega, double dt, double t_end) {
  std::vector<double> crossings;
  LeapfrogOptions opt;
  opt.dt = dt;
  opt.t_end = t_end;
  opt.land_on_t_end = false;
  opt.observe_every = 1;
  double u_prev = 1, t_prev = 0;
  opt.observer = [&](const StepView& s) {
    const double u = s.u[0];
    if (s.step > 0 && ((u_prev > 0) != (u > 0)))
      crossings.push_back(t_prev + (s.time - t_prev) * u_prev / (u_prev - u));
    u_prev = u;
    t_prev = s.time;
  };
  run_leapfrog(oscillator(omega), Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1), opt);
  return 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

TEST(Leapfrog, StepCountFromTEndOverDtIsChecked) {
  LeapfrogOptions opt;
  opt.dt = 1e-300;
  opt.t_end = 1.0;  // 1e300 steps: a long overflow before, now a one-line error
  EXPECT_THROW(run_leapfrog(oscillator(1.0), Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1), opt),
               std::length_error);
}

TEST(Leapfrog, HarmonicOscillatorMatchesTheDiscreteExactSolution) {
  // For ü = -w² u, u0 = 1, v0 = 0, leap-frog gives u_n = cos(w~ n dt) exactly with cos(w~ dt) = 1 - (w dt)²/2.
  const double omega = 2.0, dt = 0.05;
  const double wt = std::acos(1.0 - 0.5 * omega * omega * dt * dt) / dt;
  LeapfrogStepper st(oscillator(omega), Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1));
  for (int n = 1; n <= 2000; ++n) {
    st.step(dt);
    ASSERT_NEAR(st.u()[0], std::cos(wt * n * dt), 1e-11) << "step " << n;  // round-off growth over 2000 steps
  }
  EXPECT_EQ(st.evaluations(), 2001);
}

TEST(Leapfrog, OscillatorPeriodErrorIsSecondOrder) {
  const double omega = 2.0, T = 2 * M_PI / omega;
  std::vector<double> dts = {0.1, 0.05, 0.025, 0.0125}, errs;
  for (double dt : dts) {
    const double period = measured_period(omega, dt, 40.0);
    errs.push_back(period / T - 1.0);
    // w~ = acos(1 - (w dt)²/2) / dt = w (1 + (w dt)²/24 + ...): the discrete period is T (1 - (w dt)²/24 + ...);
    // the next term is O(dt^4), < 2% of the leading one for w dt <= 0.2.
    EXPECT_NEAR(errs.back(), -omega * omega * dt * dt / 24.0, 0.02 * omega * omega * dt * dt / 24.0) << "dt " << dt;
  }
  for (std::size_t k = 1; k < dts.size(); ++k) {
    const double rate = std::log(errs[k - 1] / errs[k]) / std::log(dts[k - 1] / dts[k]);
    EXPECT_NEAR(rate, 2.0, 0.02) << "between dt " << dts[k - 1] << " and " << dts[k];
  }
}

/// Chain of n unit masses, springs to the walls: A = k tridiag(-1, 2, -1), lambda_max = 4k sin²(n pi / (2(n+1))).
SecondOrderSystem chain(int n, double k, Eigen::SparseMatrix<double>* Aout = nullptr) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2 * k);
    if (i > 0) t.emplace_back(i, i - 1, -k);
    if (i + 1 < n) t.emplace_back(i, i + 1, -k);
  }
  auto A = std::make_shared<Eigen::SparseMatrix<double>>(n, n);
  A->setFromTriplets(t.begin(), t.end());
  if (Aout) *Aout = *A;
  SecondOrderSystem s;
  s.acceleration = [A](const Eigen::VectorXd& u, Eigen::VectorXd& a) { a.noalias() = -(*A * u); };
  s.strain_energy = [A](const Eigen::VectorXd& u) { return 0.5 * u.dot(*A * u); };
  return s;
}

double chain_lambda_max(int n, double k) {
  const double s = std::sin(n * M_PI / (2.0 * (n + 1)));
  return 4 * k * s * s;
}

TEST(StabilityLimit, MatchesTheAnalyticChainSpectrum) {
  for (int n : {40, 600}) {
    const double k = 3.0;
    auto sys = chain(n, k);
    const double exact = chain_lambda_max(n, k);
    for (bool sym : {true, false}) {
      StabilityOptions so;
      so.symmetric = sym;
      auto est = estimate_stability_limit(sys.acceleration, n, so);
      ASSERT_TRUE(est.converged) << est.method;
      EXPECT_NEAR(est.lambda_max, exact, 1e-8 * exact) << est.method << " n=" << n;
      EXPECT_TRUE(est.dominant_real_positive) << est.method;
      EXPECT_NEAR(est.dt_limit, 2.0 / std::sqrt(exact), 1e-8) << est.method;
    }
  }
  EXPECT_THROW(estimate_stability_limit({}, 3), std::invalid_argument);
  EXPECT_THROW(cfl_time_step(0.3, 0.0, 1.0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(cfl_time_step(0.3, 0.013, 0.5), 0.3 * 0.013 / 0.5);
}

TEST(StabilityLimit, LeapfrogIsStableJustBelowAndUnstableJustAboveTheLimit) {
  const int n = 30;
  auto sys = chain(n, 1.0);
  auto est = estimate_stability_limit(sys.acceleration, n, {.symmetric = true});
  std::mt19937_64 rng(7);
  std::normal_distribution<double> nd;
  Eigen::VectorXd u0(n);
  for (int i = 0; i < n; ++i) u0[i] = nd(rng);
  LeapfrogOptions opt;
  opt.max_steps = 20000;
  opt.limits.energy_growth = 1e6;
  opt.dt = 0.99 * est.dt_limit;
  auto ok = run_leapfrog(sys, u0, Eigen::VectorXd::Zero(n), opt);
  EXPECT_EQ(ok.status, RunStatus::Completed) << ok.message;
  opt.dt = 1.01 * est.dt_limit;
  auto bad = run_leapfrog(sys, u0, Eigen::VectorXd::Zero(n), opt);
  EXPECT_EQ(bad.status, RunStatus::EnergyGrowth) << bad.message;
}

/// Max relative deviation of the total energy from its initial value over `steps` steps.
double energy_deviation(const SecondOrderSystem& sys, const Eigen::VectorXd& u0, double dt, long steps,
                        double* drift = nullptr) {
  LeapfrogOptions opt;
  opt.dt = dt;
  opt.max_steps = steps;
  opt.record_every = 1;
  auto r = run_leapfrog(sys, u0, Eigen::VectorXd::Zero(u0.size()), opt);
  const double e0 = r.history.front().total;
  double dev = 0, first = 0, last = 0;
  const std::size_t m = r.history.size(), tenth = m / 10;
  for (std::size_t k = 0; k < m; ++k) {
    const double e = r.history[k].total;
    dev = std::max(dev, std::abs(e - e0) / e0);
    if (k < tenth) first += e / tenth;
    if (k >= m - tenth) last += e / tenth;
  }
  if (drift) *drift = std::abs(last - first) / e0;
  return dev;
}

TEST(Leapfrog, EnergyErrorIsSecondOrderWithoutSecularDrift) {
  const int n = 50;
  auto sys = chain(n, 1.0);
  const double dt_limit = 2.0 / std::sqrt(chain_lambda_max(n, 1.0));
  Eigen::VectorXd u0(n);
  for (int i = 0; i < n; ++i)
    u0[i] = std::sin(3.0 * M_PI * (i + 1) / (n + 1)) + 0.3 * std::sin(17.0 * M_PI * (i + 1) / (n + 1));
  std::vector<double> dts = {0.2 * dt_limit, 0.1 * dt_limit, 0.05 * dt_limit}, devs;
  for (double dt : dts) {
    double drift = 0;
    devs.push_back(energy_deviation(sys, u0, dt, 10000, &drift));
    // No secular drift: the mean energy over the last tenth equals that over the first tenth to a small fraction
    // of the O(dt²) oscillation amplitude.
    EXPECT_LT(drift, 0.1 * devs.back()) << "dt " << dt;
  }
  for (std::size_t k = 1; k < dts.size(); ++k) {
    const double rate = std::log(devs[k - 1] / devs[k]) / std::log(dts[k - 1] / dts[k]);
    EXPECT_NEAR(rate, 2.0, 0.1) << "dt " << dts[k];  // max over a finite sample of the oscillation: ±0.1
  }
}

TEST(BlowUp, UnstableSystemStopsAtThePredictedStep) {
  // ü = +u from u0 = 1e-3: the continuous solution 1e-3 cosh t reaches 1 at t = acosh(1000) = 7.6009.
  SecondOrderSystem s;
  s.acceleration = [](const Eigen::VectorXd& u, Eigen::VectorXd& a) { a = u; };
  const double dt = 0.01, u0 = 1e-3;
  // Independent prediction: leap-frog's position recurrence u_{n+1} = (2 + dt²) u_n - u_{n-1}, u_1 = u0 (1 + dt²/2).
  long predicted = 1;
  double um = u0, un = u0 * (1 + 0.5 * dt * dt);
  while (std::abs(un) <= 1.0) {
    double next = (2 + dt * dt) * un - um;
    um = un;
    un = next;
    ++predicted;
  }
  const auto dir = std::filesystem::temp_directory_path() / "sphstab_blowup_test";
  std::filesystem::create_directories(dir);
  LeapfrogOptions opt;
  opt.dt = dt;
  opt.t_end = 100;
  opt.record_every = 50;
  const std::string csv_path = (dir / "diag.csv").string();
  DiagnosticsCsv csv(csv_path, 1);
  opt.observers = {&csv};
  opt.limits.max_displacement = 1.0;
  auto r = run_leapfrog(s, Eigen::VectorXd::Constant(1, u0), Eigen::VectorXd::Zero(1), opt);
  EXPECT_EQ(r.status, RunStatus::DisplacementLimit);
  EXPECT_EQ(r.steps, predicted);
  EXPECT_NEAR(r.time, std::acosh(1.0 / u0), 0.02);  // discrete vs continuous crossing time
  EXPECT_NE(r.message.find("step " + std::to_string(predicted)), std::string::npos) << r.message;
  // Everything written before the stop is on disk: step 0, every 50th step, and the failing step.
  auto t = read_csv(csv_path);
  auto steps = t.numeric_column("step");
  ASSERT_EQ(static_cast<long>(steps.size()), predicted / 50 + 2);
  EXPECT_EQ(steps.back(), predicted);
  EXPECT_GT(t.numeric_column("max_abs_u").back(), 1.0);
  std::filesystem::remove_all(dir);
}

TEST(BlowUp, NonFiniteEnergyGrowthAndBoxAreReported) {
  {  // NaN appears in the 37th force evaluation after the initial one, i.e. at step 37.
    int calls = 0;
    SecondOrderSystem s;
    s.acceleration = [&calls](const Eigen::VectorXd& u, Eigen::VectorXd& a) {
      a = -u;
      if (calls++ == 37) a[0] = std::nan("");
    };
    LeapfrogOptions opt;
    opt.dt = 0.1;
    opt.max_steps = 100;
    auto r = run_leapfrog(s, Eigen::VectorXd::Ones(2), Eigen::VectorXd::Zero(2), opt);
    EXPECT_EQ(r.status, RunStatus::NonFinite);
    EXPECT_EQ(r.steps, 37);
    EXPECT_NEAR(r.time, 3.7, 1e-12);
  }
  {  // Oscillator with w dt = 2.2 > 2: |amplification| = 2.428 per step; energy passes 100 x E0 quickly.
    auto s = oscillator(1.0);
    LeapfrogOptions opt;
    opt.dt = 2.2;
    opt.max_steps = 1000;
    opt.limits.energy_growth = 100;
    auto r = run_leapfrog(s, Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1), opt);
    EXPECT_EQ(r.status, RunStatus::EnergyGrowth);
    // Independent prediction of the first step with E > 100 E0 (E0 = 0.5).
    double u = 1, v = 0, a = -1;
    long n = 0;
    while (0.5 * v * v + 0.5 * u * u <= 100 * 0.5) {
      v += 1.1 * a;
      u += 2.2 * v;
      a = -u;
      v += 1.1 * a;
      ++n;
    }
    EXPECT_EQ(r.steps, n);
  }
  {  // Constant velocity 1 from X = 0: leaves [-1, 1] at the first step with u > 1 (u_10 = 10 x 0.1 < 1 in doubles).
    SecondOrderSystem s;
    s.acceleration = [](const Eigen::VectorXd&, Eigen::VectorXd& a) { a.setZero(); };
    s.reference_positions = Eigen::VectorXd::Zero(1);
    LeapfrogOptions opt;
    opt.dt = 0.1;
    opt.max_steps = 100;
    opt.limits.box_lo = Eigen::VectorXd::Constant(1, -1.0);
    opt.limits.box_hi = Eigen::VectorXd::Constant(1, 1.0);
    auto r = run_leapfrog(s, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1), opt);
    EXPECT_EQ(r.status, RunStatus::LeftBox) << r.message;
    EXPECT_EQ(r.steps, 11);
  }
}

TEST(Leapfrog, HookModesLandOnTEndAndObserverSchedule) {
  SecondOrderSystem s;
  s.acceleration = [](const Eigen::VectorXd&, Eigen::VectorXd& a) { a.setZero(); };
  s.velocity_hook = [](const Eigen::VectorXd&, const Eigen::VectorXd& v, Eigen::VectorXd& w) { w = 2 * v; };
  {
    LeapfrogStepper st(s, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1));
    for (int k = 0; k < 5; ++k) st.step(0.5);
    EXPECT_DOUBLE_EQ(st.u()[0], 5.0);  // drift with 2v, v unchanged
    EXPECT_DOUBLE_EQ(st.v()[0], 1.0);
  }
  s.hook_mode = VelocityHookMode::Replace;
  {
    LeapfrogStepper st(s, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1));
    for (int k = 0; k < 3; ++k) st.step(1.0);
    EXPECT_DOUBLE_EQ(st.v()[0], 8.0);  // v doubles every step
    EXPECT_DOUBLE_EQ(st.u()[0], 2.0 + 4.0 + 8.0);
  }
  LeapfrogOptions opt;
  opt.dt = 0.3;
  opt.t_end = 1.0;  // 4 steps of 0.25
  opt.observe_every = 2;
  std::vector<long> seen;
  opt.observer = [&](const StepView& v) { seen.push_back(v.step); };
  auto r = run_leapfrog(oscillator(1.0), Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1), opt);
  EXPECT_EQ(r.steps, 4);
  EXPECT_DOUBLE_EQ(r.dt, 0.25);
  EXPECT_NEAR(r.time, 1.0, 1e-15);
  EXPECT_EQ(seen, (std::vector<long>{0, 2, 4}));
  EXPECT_EQ(r.history.size(), 2u);  // step 0 and the last step
  EXPECT_THROW(run_leapfrog(oscillator(1.0), Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(2), opt),
               std::invalid_argument);
}

TEST(Leapfrog, ProgressLineReportsOnStderr) {
  LeapfrogOptions opt;
  opt.dt = 0.01;
  opt.max_steps = 50;
  ProgressReport progress("osc-test", 0.0);  // report every step
  opt.observers = {&progress};
  testing::internal::CaptureStderr();
  auto r = run_leapfrog(oscillator(1.0), Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1), opt);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(r.completed());
  EXPECT_NE(err.find("[osc-test]"), std::string::npos);
  EXPECT_NE(err.find("step 50/50"), std::string::npos);
  EXPECT_NE(err.find("done completed 50 steps"), std::string::npos) << err.substr(0, 300);
}

}  // namespace
}  // namespace sphstab
