// The run loop (integrate/run.hpp): its schedule, its stop rules and the failures it turns into results, on a
// stepper whose every step is known in advance (u_{n+1} = u_n + 1 per step, energy u^2), and on the leap-frog.
#include "sphstab/integrate/run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/integrate/leapfrog.hpp"

namespace sphstab {
namespace run_test {

/// Counts: u grows by one per step; throws at step `throw_at` (0: never); records its steps.
class CountingStepper final : public Stepper {
 public:
  explicit CountingStepper(long throw_at = 0) : m_throw_at(throw_at) {}
  void step(double dt) override {
    if (m_steps + 1 == m_throw_at) throw std::domain_error("model refused the state");
    ++m_steps;
    m_t += dt;
    m_u += 1;
  }
  long steps() const override { return m_steps; }
  double time() const override { return m_t; }
  long evaluations() const override { return m_steps; }
  StateFault check(const BlowUpLimits& limits) const override {
    if (m_u > limits.max_displacement) return {.status = RunStatus::DisplacementLimit, .particle = 0, .why = "moved"};
    return {};
  }
  double energy() const override { return (1 + m_u) * (1 + m_u); }
  void record(long step, const std::vector<RunObserver*>&) override { recorded.push_back(step); }
  void snapshot(long step, const std::vector<RunObserver*>& observers) override {
    snapshots.push_back(step);
    const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, m_u), zero = Eigen::VectorXd::Zero(1);
    for (RunObserver* o : observers) o->snapshot(StepView{step, m_t, u, zero, zero});
  }
  std::vector<long> recorded, snapshots;

 private:
  long m_throw_at, m_steps = 0;
  double m_t = 0, m_u = 0;
};

TEST(RunLoop, RecordsAtStartEveryKStepsAndTheLastStep) {
  CountingStepper s;
  const RunResult r = run(s, {.dt = 0.5, .t_end = 5.0, .record_every = 4, .snapshot_every = 3});
  EXPECT_TRUE(r.completed()) << r.message;
  EXPECT_EQ(r.steps, 10);
  EXPECT_EQ(s.recorded, (std::vector<long>{0, 4, 8, 10}));
  EXPECT_EQ(s.snapshots, (std::vector<long>{0, 3, 6, 9, 10}));
  EXPECT_EQ(r.message, "completed 10 steps of dt = 0.5 to t = 5");
}

TEST(RunLoop, WithoutLandingTheStepsHaveExactlyDtUntilTheClockPassesTEnd) {
  // 0.1 added ten times is 0.9999999999999999 < 1: a hand-written "step while t < t_end" loop takes 11 steps, and so
  // does the run; landing on t_end takes 10 steps of 0.1.
  double t = 0;
  long manual = 0;
  while (t < 1.0) t += 0.1, ++manual;
  CountingStepper clock;
  const RunResult r = run(clock, {.dt = 0.1, .t_end = 1.0, .land_on_t_end = false});
  EXPECT_EQ(r.steps, manual);
  EXPECT_EQ(r.steps, 11);
  EXPECT_EQ(r.dt, 0.1);
  CountingStepper landed;
  EXPECT_EQ(run(landed, {.dt = 0.1, .t_end = 1.0}).steps, 10);
}

TEST(RunLoop, AStepThatThrowsIsAResultNotAnException) {
  CountingStepper s(/*throw_at=*/7);
  const RunResult r = run(s, {.dt = 1.0, .t_end = 20.0, .record_every = 5});
  EXPECT_EQ(r.status, RunStatus::Exception);
  EXPECT_EQ(r.steps, 6);  // the state the step started from
  EXPECT_EQ(r.message, "exception: model refused the state at step 6, t = 6");
  EXPECT_EQ(s.recorded, (std::vector<long>{0, 5}));  // the failing state is not recorded
}

TEST(RunLoop, StateAndEnergyRulesStopWithTheFailingStateRecordedOnce) {
  CountingStepper moved;
  BlowUpLimits limits{.max_displacement = 3.5};
  RunResult r = run(moved, {.dt = 1.0, .t_end = 10.0, .record_every = 2, .limits = limits});
  EXPECT_EQ(r.status, RunStatus::DisplacementLimit);
  EXPECT_EQ(r.steps, 4);
  EXPECT_EQ(r.particle, 0);
  EXPECT_EQ(r.message, "displacement-limit: moved at step 4, t = 4, particle 0");
  EXPECT_EQ(moved.recorded, (std::vector<long>{0, 2, 4}));  // step 4: once, as the failing state
  CountingStepper grows;
  // energy (1 + n)^2 over the reference 1: exceeds 30 first at n = 5 (36)
  r = run(grows, {.dt = 1.0, .t_end = 10.0, .limits = {.energy_growth = 30}});
  EXPECT_EQ(r.status, RunStatus::EnergyGrowth);
  EXPECT_EQ(r.steps, 5);
  EXPECT_EQ(grows.recorded, (std::vector<long>{0, 5}));
  // check_every 3: the rule is applied at steps 3, 6 (and the last), so the stop comes at 6
  CountingStepper sparse;
  r = run(sparse, {.dt = 1.0, .t_end = 10.0, .limits = {.check_every = 3, .energy_growth = 30}});
  EXPECT_EQ(r.steps, 6);
}

TEST(RunLoop, AnObserverStopsTheRunWithItsReason) {
  CountingStepper s;
  SnapshotFunction gap([&](const StepView&) {});
  SnapshotFunction probe([&](const StepView& v) {
    if (v.u[0] >= 3) probe.stop("particles within 0.05 spacing");
  });
  RunOptions o{.dt = 0.25, .t_end = 10.0, .snapshot_every = 1};
  o.observers = {&gap, &probe};
  const RunResult r = run(s, o);
  EXPECT_EQ(r.status, RunStatus::Stopped);
  EXPECT_EQ(r.steps, 3);
  EXPECT_EQ(r.message, "stopped: particles within 0.05 spacing at step 3, t = 0.75");
  EXPECT_EQ(s.snapshots, (std::vector<long>{0, 1, 2, 3}));
}

TEST(RunLoop, InconsistentOptionsAreErrors) {
  CountingStepper s;
  EXPECT_THROW(run(s, {.dt = 0.0, .t_end = 1.0}), std::invalid_argument);
  EXPECT_THROW(run(s, {.dt = NAN, .t_end = 1.0}), std::invalid_argument);
  EXPECT_THROW(run(s, {.dt = 0.1}), std::invalid_argument);  // neither t_end nor max_steps
  EXPECT_THROW(run(s, {.dt = 0.1, .t_end = 1.0, .record_every = -1}), std::invalid_argument);
  EXPECT_THROW(run(s, {.dt = 0.1, .t_end = 1.0, .limits = {.check_every = 0}}), std::invalid_argument);
  EXPECT_THROW(run(s, {.dt = 0.1, .t_end = 1.0, .limits = {.energy_growth = 0.5}}), std::invalid_argument);
  RunOptions null_observer{.dt = 0.1, .t_end = 1.0};
  null_observer.observers = {nullptr};
  EXPECT_THROW(run(s, null_observer), std::invalid_argument);
  EXPECT_EQ(s.steps(), 0);
}

TEST(RunLoop, TheLeapfrogRunIsTheLoopOverItsStepper) {
  // run_leapfrog and run(LeapfrogStepper) take the same steps: bitwise equal states.
  SecondOrderSystem sys;
  sys.acceleration = [](const Eigen::VectorXd& u, Eigen::VectorXd& a) { a = -4.0 * u - 0.1 * u.array().cube().matrix(); };
  const Eigen::VectorXd u0 = Eigen::VectorXd::LinSpaced(3, 0.1, 0.3), v0 = Eigen::VectorXd::Zero(3);
  LeapfrogOptions lo;
  lo.dt = 0.01;
  lo.t_end = 3.0;
  const LeapfrogResult a = run_leapfrog(sys, u0, v0, lo);
  LeapfrogStepper st(sys, u0, v0);
  const RunResult b = run(st, {.dt = 0.01, .t_end = 3.0});
  ASSERT_TRUE(a.completed() && b.completed());
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.u, st.u());
  EXPECT_EQ(a.v, st.v());
  EXPECT_EQ(a.evaluations, b.evaluations);
  EXPECT_EQ(a.evaluations, a.steps + 1);
}

}  // namespace
}  // namespace sphstab
