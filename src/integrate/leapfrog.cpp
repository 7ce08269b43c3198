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

std::string run_status_name(RunStatus s) {
  switch (s) {
    case RunStatus::Completed:
      return "completed";
    case RunStatus::NonFinite:
      return "non-finite";
    case RunStatus::DisplacementLimit:
      return "displacement-limit";
    case RunStatus::LeftBox:
      return "left-box";
    case RunStatus::EnergyGrowth:
      return "energy-growth";
    case RunStatus::NonPositiveDensity:
      return "non-positive-density";
  }
  return "?";
}

namespace {

std::string at_step(long step, double t) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), " at step %ld, t = %.6g", step, t);
  return buf;
}

double check_energy(const SecondOrderSystem& s, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  double e = 0;
  for (long k = 0; k < v.size(); ++k) e += 0.5 * s.dof_mass(k) * v[k] * v[k];
  if (s.strain_energy) e += s.strain_energy(u);
  return e;
}

}  // namespace

RunResult run_leapfrog(const SecondOrderSystem& system, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0,
                       const LeapfrogOptions& opt) {
  const char* who = "run_leapfrog";
  system.validate(u0.size(), who);
  if (!(opt.dt > 0) || !std::isfinite(opt.dt))
    throw std::invalid_argument("run_leapfrog: dt must be finite and > 0 (got " + std::to_string(opt.dt) + ")");
  if (!(opt.t_end > 0) && opt.max_steps < 0)
    throw std::invalid_argument("run_leapfrog: give t_end > 0 or max_steps >= 0");
  if (opt.diagnostics_every < 0 || opt.snapshot_every < 0 || opt.observe_every < 0)
    throw std::invalid_argument("run_leapfrog: output intervals must be >= 0");
  if (opt.limits.check_every < 1)
    throw std::invalid_argument("run_leapfrog: limits.check_every must be >= 1 (got " +
                                std::to_string(opt.limits.check_every) + ")");
  const int dpp = system.dofs_per_particle;
  const bool use_box = opt.limits.box_lo.size() || opt.limits.box_hi.size();
  if (use_box) {
    if (opt.limits.box_lo.size() != dpp || opt.limits.box_hi.size() != dpp)
      throw std::invalid_argument("run_leapfrog: box_lo and box_hi need dofs_per_particle = " + std::to_string(dpp) +
                                  " entries each");
    if (system.reference_positions.size() == 0)
      throw std::invalid_argument("run_leapfrog: the box check needs system.reference_positions");
  }
  for (const RunObserver* o : opt.observers)
    if (o == nullptr) throw std::invalid_argument("run_leapfrog: null observer");
  const bool energy_check = std::isfinite(opt.limits.energy_growth);
  if (energy_check && !(opt.limits.energy_growth > 1))
    throw std::invalid_argument("run_leapfrog: limits.energy_growth must be > 1 (got " +
                                std::to_string(opt.limits.energy_growth) + ")");

  double dt = opt.dt;
  long nsteps = opt.max_steps;
  if (opt.t_end > 0) {
    nsteps = checked_floor_count(std::ceil(opt.t_end / dt - 1e-9), 1L << 53, "run_leapfrog: steps t_end / dt");
    if (nsteps < 1) nsteps = 1;
    if (opt.land_on_t_end) dt = opt.t_end / static_cast<double>(nsteps);
  }

  const auto wall0 = std::chrono::steady_clock::now();
  RunResult res;
  res.dt = dt;
  LeapfrogStepper st(system, u0, v0, 0.0);

  auto record = [&](long step) {
    Diagnostics d = compute_diagnostics(system, st.u(), st.v(), step, st.time());
    for (RunObserver* o : opt.observers) o->record(d);
    if (opt.keep_history) res.history.push_back(std::move(d));
  };
  auto snapshot = [&](long step) {
    const StepView view{step, st.time(), st.u(), st.v(), st.a()};
    for (RunObserver* o : opt.observers) o->snapshot(view);
  };
  auto observe = [&]() {
    if (opt.observer && opt.observe_every > 0) opt.observer(StepView{st.steps(), st.time(), st.u(), st.v(), st.a()});
  };

  double e_ref = 0;
  if (energy_check) {
    e_ref = std::max(std::abs(check_energy(system, st.u(), st.v())), opt.limits.energy_floor);
    if (!(e_ref > 0))
      throw std::invalid_argument(
          "run_leapfrog: the energy-growth check needs a nonzero initial energy or "
          "limits.energy_floor > 0");
  }

  // Returns a failure status for the current state (Completed = fine).
  auto check = [&](std::string& why) -> RunStatus {
    const Eigen::VectorXd& u = st.u();
    if (!u.allFinite() || !st.v().allFinite() || !st.a().allFinite()) {
      why = "non-finite state (NaN or inf in u, v or a)";
      return RunStatus::NonFinite;
    }
    if (std::isfinite(opt.limits.max_displacement)) {
      Eigen::Index k = 0;
      const double m = u.cwiseAbs().maxCoeff(&k);
      if (m > opt.limits.max_displacement) {
        char buf[160];
        std::snprintf(buf, sizeof(buf), "displacement |u| = %.4g at particle %ld exceeds the limit %.4g", m,
                      static_cast<long>(k / dpp), opt.limits.max_displacement);
        why = buf;
        return RunStatus::DisplacementLimit;
      }
    }
    if (use_box) {
      for (long k = 0; k < u.size(); ++k) {
        const int a = static_cast<int>(k % dpp);
        const double x = system.reference_positions[k] + u[k];
        if (x < opt.limits.box_lo[a] || x > opt.limits.box_hi[a]) {
          char buf[160];
          std::snprintf(buf, sizeof(buf), "particle %ld left the box in axis %d (coordinate %.6g)", k / dpp, a, x);
          why = buf;
          return RunStatus::LeftBox;
        }
      }
    }
    if (energy_check) {
      const double e = check_energy(system, u, st.v());
      if (!(std::abs(e) <= opt.limits.energy_growth * e_ref)) {
        char buf[160];
        std::snprintf(buf, sizeof(buf), "energy %.6g exceeds %.4g x the reference %.6g", e, opt.limits.energy_growth,
                      e_ref);
        why = buf;
        return RunStatus::EnergyGrowth;
      }
    }
    return RunStatus::Completed;
  };

  record(0);
  if (opt.snapshot_every > 0) snapshot(0);
  observe();
  std::string why;
  RunStatus status = check(why);
  while (status == RunStatus::Completed && st.steps() < nsteps) {
    st.step(dt);
    const long n = st.steps();
    const bool last = n == nsteps;
    if (n % opt.limits.check_every == 0 || last) status = check(why);
    if (status != RunStatus::Completed) break;
    if (last || (opt.diagnostics_every > 0 && n % opt.diagnostics_every == 0)) record(n);
    if (opt.snapshot_every > 0 && (n % opt.snapshot_every == 0 || last)) snapshot(n);
    if (opt.observe_every > 0 && (n % opt.observe_every == 0 || last)) observe();
    for (RunObserver* o : opt.observers) o->advanced(n, nsteps, st.time());
  }
  res.status = status;
  res.steps = st.steps();
  res.time = st.time();
  res.u = st.u();
  res.v = st.v();
  res.force_evaluations = st.force_evaluations();
  if (status == RunStatus::Completed) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "completed %ld steps of dt = %.6g to t = %.6g", res.steps, dt, res.time);
    res.message = buf;
  } else {
    res.message = run_status_name(status) + ": " + why + at_step(res.steps, res.time);
    // Keep the last (failing) state in the record when it is finite enough to write.
    record(res.steps);
    if (opt.snapshot_every > 0 && status != RunStatus::NonFinite) snapshot(res.steps);
  }
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  for (RunObserver* o : opt.observers) o->finished(res.message);
  return res;
}

}  // namespace sphstab
