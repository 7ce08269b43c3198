#include "sphstab/integrate/rate_form_run.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"

namespace sphstab {

namespace {

/// First particle whose state entries are non-finite or whose density is <= 0: (status, particle).
template <int Dim>
std::pair<RunStatus, int> check_state(const RateFormScheme<Dim>& s, const Eigen::VectorXd& y) {
  const int n = s.discretisation().size();
  for (int i = 0; i < n; ++i) {
    const int xo = s.position_offset(i), ro = s.density_offset(i);
    if (xo >= 0 && !y.segment(xo, 2 * Dim).allFinite()) return {RunStatus::NonFinite, i};
    if (ro >= 0) {
      if (!y.segment(ro, 1 + RateFormScheme<Dim>::kStress).allFinite()) return {RunStatus::NonFinite, i};
      if (!(y[ro] > 0)) return {RunStatus::NonPositiveDensity, i};
    }
  }
  return {RunStatus::Completed, -1};
}

}  // namespace

template <int Dim>
RateFormRunResult run_rate_form(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0,
                                const RateFormRunOptions& o) {
  if (!(o.dt > 0) || !std::isfinite(o.dt))
    throw std::invalid_argument("run_rate_form: dt must be finite and > 0 (got " + format_number(o.dt) + ")");
  if (!(o.t_end > 0) || !std::isfinite(o.t_end))
    throw std::invalid_argument("run_rate_form: t_end must be finite and > 0 (got " + format_number(o.t_end) + ")");
  if (o.record_every < 1) throw std::invalid_argument("run_rate_form: record_every must be >= 1");
  if (y0.size() != scheme.size())
    throw std::invalid_argument("run_rate_form: state has " + std::to_string(y0.size()) + " entries, expected " +
                                std::to_string(scheme.size()));
  const auto wall0 = std::chrono::steady_clock::now();
  const long nsteps =
      std::max(1L, checked_floor_count(std::ceil(o.t_end / o.dt - 1e-9), 1L << 53, "run_rate_form: steps t_end / dt"));
  const double dt = o.t_end / static_cast<double>(nsteps);
  const int n = scheme.discretisation().size();

  RateFormRunResult r;
  r.dt = dt;
  r.y = y0;
  const double ke0 = scheme.kinetic_energy(y0);
  auto record = [&](long step) {
    r.times.push_back(step * dt);
    r.kinetic_energy.push_back(scheme.kinetic_energy(r.y));
    if (o.observer) o.observer(step, step * dt, r.y);
  };
  auto stop = [&](RunStatus status, int particle, long step, const std::string& why) {
    r.status = status;
    r.particle = particle;
    r.steps = step;
    r.time = step * dt;
    r.message = run_status_name(status) + ": " + why + " at step " + std::to_string(step) +
                ", t = " + format_number(r.time) + (particle >= 0 ? ", particle " + std::to_string(particle) : "");
  };
  record(0);
  Eigen::VectorXd f0, f1, yp;
  for (long step = 1; step <= nsteps; ++step) {
    scheme.rate(r.y, f0);
    yp = r.y + dt * f0;  // predictor for v, rho, S (and a first-order x, replaced below)
    for (int i = 0; i < n; ++i) {
      const int xo = scheme.position_offset(i);
      if (xo >= 0)  // x = x0 + dt vhat0 + dt^2/2 a0, not corrected [GMS2001, (6.15)]
        yp.segment(xo, Dim) =
            r.y.segment(xo, Dim) + dt * f0.segment(xo, Dim) + 0.5 * dt * dt * f0.segment(xo + Dim, Dim);
    }
    scheme.rate(yp, f1);
    r.rate_evaluations += 2;
    Eigen::VectorXd y = yp + 0.5 * dt * (f1 - f0);
    for (int i = 0; i < n; ++i) {
      const int xo = scheme.position_offset(i);
      if (xo < 0) continue;
      if (o.positions == PositionUpdate::Gms)
        y.segment(xo, Dim) = yp.segment(xo, Dim);
      else
        y.segment(xo, Dim) = r.y.segment(xo, Dim) + 0.5 * dt * (f0.segment(xo, Dim) + f1.segment(xo, Dim));
    }
    r.y.swap(y);
    const auto [status, particle] = check_state(scheme, r.y);
    if (status != RunStatus::Completed) {
      stop(status, particle, step, status == RunStatus::NonFinite ? "non-finite state" : "density <= 0");
      break;
    }
    const bool last = step == nsteps;
    if (step % o.record_every == 0 || last) record(step);
    if (std::isfinite(o.energy_growth) && scheme.kinetic_energy(r.y) > o.energy_growth * ke0) {
      if (step % o.record_every != 0 && !last) record(step);
      stop(RunStatus::EnergyGrowth, -1, step,
           "kinetic energy grew by more than " + format_number(o.energy_growth) + "x");
      break;
    }
    if (last) {
      r.steps = step;
      r.time = step * dt;
      r.message = "completed " + std::to_string(step) + " steps to t = " + format_number(r.time);
    }
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return r;
}

template RateFormRunResult run_rate_form<1>(const RateFormScheme<1>&, const Eigen::VectorXd&,
                                            const RateFormRunOptions&);
template RateFormRunResult run_rate_form<2>(const RateFormScheme<2>&, const Eigen::VectorXd&,
                                            const RateFormRunOptions&);

}  // namespace sphstab
