#include "sphstab/integrate/leapfrog.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "sphstab/core/checked_arithmetic.hpp"

namespace sphstab {

LeapfrogStepper::LeapfrogStepper(SecondOrderSystem system, Eigen::VectorXd u0, Eigen::VectorXd v0, double t0)
    : m_system(std::move(system)), m_u(std::move(u0)), m_v(std::move(v0)), m_t(t0) {
  m_system.validate(m_u.size(), "LeapfrogStepper");
  if (m_v.size() != m_u.size())
    throw std::invalid_argument("LeapfrogStepper: v0 has " + std::to_string(m_v.size()) + " entries, u0 has " +
                                std::to_string(m_u.size()));
  m_a.setZero(m_u.size());
  if (m_system.set_time) m_system.set_time(m_t);
  evaluate();
}

void LeapfrogStepper::evaluate() {
  m_system.acceleration(m_u, m_a);
  ++m_evaluations;
}

void LeapfrogStepper::step(double dt) {
  const double half = 0.5 * dt;
  m_v += half * m_a;  // kick
  if (m_system.velocity_hook) {
    m_w.resize(m_v.size());
    m_system.velocity_hook(m_u, m_v, m_w);
    if (m_system.hook_mode == VelocityHookMode::Replace) m_v = m_w;
    m_u += dt * m_w;  // drift with the hook's velocity
  } else {
    m_u += dt * m_v;  // drift
  }
  m_t += dt;
  ++m_steps;
  if (m_system.set_time) m_system.set_time(m_t);
  evaluate();
  m_v += half * m_a;  // kick
}

namespace {

double system_energy(const SecondOrderSystem& s, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  double e = 0;
  for (long k = 0; k < v.size(); ++k) e += 0.5 * s.dof_mass(k) * v[k] * v[k];
  if (s.strain_energy) e += s.strain_energy(u);
  return e;
}

}  // namespace

double LeapfrogStepper::energy() const { return system_energy(m_system, m_u, m_v); }

StateFault LeapfrogStepper::check(const BlowUpLimits& limits) const {
  const int dpp = m_system.dofs_per_particle;
  const bool use_box = limits.box_lo.size() || limits.box_hi.size();
  if (use_box) {
    if (limits.box_lo.size() != dpp || limits.box_hi.size() != dpp)
      throw std::invalid_argument("run_leapfrog: box_lo and box_hi need dofs_per_particle = " + std::to_string(dpp) +
                                  " entries each");
    if (m_system.reference_positions.size() == 0)
      throw std::invalid_argument("run_leapfrog: the box check needs system.reference_positions");
  }
  if (!m_u.allFinite() || !m_v.allFinite() || !m_a.allFinite())
    return {.status = RunStatus::NonFinite, .why = "non-finite state (NaN or inf in u, v or a)"};
  if (std::isfinite(limits.max_displacement)) {
    Eigen::Index k = 0;
    const double m = m_u.cwiseAbs().maxCoeff(&k);
    if (m > limits.max_displacement) {
      char buf[160];
      std::snprintf(buf, sizeof(buf), "displacement |u| = %.4g at particle %ld exceeds the limit %.4g", m,
                    static_cast<long>(k / dpp), limits.max_displacement);
      return {.status = RunStatus::DisplacementLimit, .why = buf};
    }
  }
  if (use_box) {
    for (long k = 0; k < m_u.size(); ++k) {
      const int a = static_cast<int>(k % dpp);
      const double x = m_system.reference_positions[k] + m_u[k];
      if (x < limits.box_lo[a] || x > limits.box_hi[a]) {
        char buf[160];
        std::snprintf(buf, sizeof(buf), "particle %ld left the box in axis %d (coordinate %.6g)", k / dpp, a, x);
        return {.status = RunStatus::LeftBox, .why = buf};
      }
    }
  }
  return {};
}

void LeapfrogStepper::record(long step, const std::vector<RunObserver*>& observers) {
  if (observers.empty()) return;
  const Diagnostics d = compute_diagnostics(m_system, m_u, m_v, step, m_t);
  for (RunObserver* o : observers) o->record(d);
}

void LeapfrogStepper::snapshot(long step, const std::vector<RunObserver*>& observers) {
  const StepView view{step, m_t, m_u, m_v, m_a};
  for (RunObserver* o : observers) o->snapshot(view);
}

namespace {

/// run_leapfrog's own observer: keeps the Diagnostics history and calls the state callback on its schedule.
class LeapfrogOutput final : public RunObserver {
 public:
  LeapfrogOutput(const LeapfrogStepper& stepper, const LeapfrogOptions& options, std::vector<Diagnostics>& history)
      : m_st(stepper), m_o(options), m_history(history) {}
  void record(const Diagnostics& d) override {
    if (m_o.keep_history) m_history.push_back(d);
  }
  void advanced(long n, long nsteps, double /*t*/) override {
    if (m_o.observe_every > 0 && (n % m_o.observe_every == 0 || n == nsteps)) observe();
  }
  void observe() const {
    if (m_o.observer && m_o.observe_every > 0)
      m_o.observer(StepView{m_st.steps(), m_st.time(), m_st.u(), m_st.v(), m_st.a()});
  }

 private:
  const LeapfrogStepper& m_st;
  const LeapfrogOptions& m_o;
  std::vector<Diagnostics>& m_history;
};

}  // namespace

LeapfrogResult run_leapfrog(const SecondOrderSystem& system, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0,
                            const LeapfrogOptions& opt) {
  system.validate(u0.size(), "run_leapfrog");
  if (opt.observe_every < 0) throw std::invalid_argument("run_leapfrog: output intervals must be >= 0");
  run_steps(opt, "run_leapfrog");  // bad durations before the first force evaluation
  LeapfrogStepper st(system, u0, v0, 0.0);
  LeapfrogResult res;
  LeapfrogOutput output(st, opt, res.history);
  RunOptions o = opt;
  o.observers.insert(o.observers.begin(), &output);
  output.observe();
  static_cast<RunResult&>(res) = run(st, o, "run_leapfrog");
  res.u = st.u();
  res.v = st.v();
  return res;
}

}  // namespace sphstab
