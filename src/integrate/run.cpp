#include "sphstab/integrate/run.hpp"

#include <chrono>
#include <cmath>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "sphstab/core/adaptive_threads.hpp"
#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/core/threads.hpp"

namespace sphstab {

constexpr NamedValue<RunStatus> kRunStatusNames[] = {{RunStatus::Completed, "completed"},
                                                     {RunStatus::NonFinite, "non-finite"},
                                                     {RunStatus::DisplacementLimit, "displacement-limit"},
                                                     {RunStatus::LeftBox, "left-box"},
                                                     {RunStatus::EnergyGrowth, "energy-growth"},
                                                     {RunStatus::NonPositiveDensity, "non-positive-density"},
                                                     {RunStatus::Exception, "exception"},
                                                     {RunStatus::Stopped, "stopped"}};

std::string run_status_name(RunStatus s) { return name_of(s, kRunStatusNames); }

std::pair<long, double> run_steps(const RunOptions& o, const std::string& who) {
  if (!(o.dt > 0) || !std::isfinite(o.dt))
    throw std::invalid_argument(who + ": dt must be finite and > 0 (got " + format_number(o.dt) + ")");
  if (!(o.t_end > 0) && o.max_steps < 0) throw std::invalid_argument(who + ": give t_end > 0 or max_steps >= 0");
  if (!(o.t_end > 0)) return {o.max_steps, o.dt};
  if (!std::isfinite(o.t_end))
    throw std::invalid_argument(who + ": t_end must be finite and > 0 (got " + format_number(o.t_end) + ")");
  const long n = std::max(
      1L, checked_floor_count(std::ceil(o.t_end / o.dt - 1e-9), 1L << 53, (who + ": steps t_end / dt").c_str()));
  return {n, o.land_on_t_end ? o.t_end / static_cast<double>(n) : o.dt};
}

RunResult run(Stepper& stepper, const RunOptions& o, const std::string& who) {
  const std::pair<long, double> steps_dt = run_steps(o, who);
  const long nsteps = steps_dt.first;  // named variables, not a structured binding: the lambdas below capture them
  const double dt = steps_dt.second;
  if (o.record_every < 0 || o.snapshot_every < 0) throw std::invalid_argument(who + ": output intervals must be >= 0");
  if (o.limits.check_every < 1)
    throw std::invalid_argument(who + ": limits.check_every must be >= 1 (got " + std::to_string(o.limits.check_every) +
                                ")");
  for (const RunObserver* obs : o.observers)
    if (obs == nullptr) throw std::invalid_argument(who + ": null observer");
  const bool energy_rule = std::isfinite(o.limits.energy_growth);
  if (energy_rule && !(o.limits.energy_growth > 1))
    throw std::invalid_argument(who + ": limits.energy_growth must be > 1 (got " +
                                format_number(o.limits.energy_growth) + ")");
  double e_ref = 0;
  if (energy_rule) {
    e_ref = std::max(std::abs(stepper.energy()), o.limits.energy_floor);
    if (!(e_ref > 0))
      throw std::invalid_argument(
          who + ": the energy-growth check needs a nonzero initial energy or limits.energy_floor > 0");
  }

  const auto wall0 = std::chrono::steady_clock::now();
  // The stepper's state rules, then the energy rule (energy: a growth factor over the reference, NaN included).
  auto check = [&]() -> StateFault {
    StateFault f = stepper.check(o.limits);
    if (f || !energy_rule) return f;
    const double e = stepper.energy();
    if (!(std::abs(e) <= o.limits.energy_growth * e_ref))
      f = {.status = RunStatus::EnergyGrowth,
           .why = "energy " + format_number(e) + " exceeds " + format_number(o.limits.energy_growth, 4) +
                  " x the reference " + format_number(e_ref)};
    return f;
  };

  // Without land_on_t_end the steps have exactly dt and the run goes on while the stepper's clock is short of t_end
  // (nsteps is then the estimate the observers are told; the cap guards a clock that no longer advances).
  const bool by_clock = o.t_end > 0 && !o.land_on_t_end;
  auto more = [&]() {
    return by_clock ? stepper.time() < o.t_end && stepper.steps() <= 2 * nsteps : stepper.steps() < nsteps;
  };
  // A step, a record or snapshot (an observer's measurement included) that throws ends the run as a result;
  // std::bad_alloc is not a result of the scheme and propagates.
  auto guarded = [](auto&& f) -> StateFault {
    try {
      f();
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      return {.status = RunStatus::Exception, .why = e.what(), .record = false};
    }
    return {};
  };
  auto output = [&](long n, bool last) {
    if (n == 0 || last || (o.record_every > 0 && n % o.record_every == 0)) stepper.record(n, o.observers);
    if (o.snapshot_every > 0 && (n % o.snapshot_every == 0 || last)) stepper.snapshot(n, o.observers);
  };
  auto requested = [&]() -> StateFault {
    for (RunObserver* obs : o.observers)
      if (std::string why = obs->stop_request(); !why.empty())
        return {.status = RunStatus::Stopped, .why = std::move(why), .record = false};
    return {};
  };

  StateFault fault = guarded([&] { output(0, false); });
  if (!fault) fault = check();
  if (!fault) fault = requested();
  // A run asked for several threads measures its steps with them and with one, and steps with the faster: on a
  // shared machine a second thread can cost more than it brings, and the count does not change the result.
  const int asked_threads = max_threads();
  const bool adaptive = asked_threads > 1 && !fixed_threads();
  AdaptiveThreads threads(adaptive ? asked_threads : 1);
  while (!fault && more()) {
    threads.before_step();
    fault = guarded([&] { stepper.step(dt); });
    threads.after_step();
    if (fault) break;
    const long n = stepper.steps();
    const bool last = !more();
    if (n % o.limits.check_every == 0 || last) fault = check();
    if (fault) break;
    fault = guarded([&] { output(n, last); });
    if (!fault) fault = requested();
    if (fault) break;
    for (RunObserver* obs : o.observers) obs->advanced(n, nsteps, stepper.time());
  }

  RunResult r;
  r.status = fault.status;
  r.steps = stepper.steps();
  r.time = stepper.time();
  r.dt = dt;
  r.particle = fault.particle;
  r.reason = fault.why;
  if (!fault) {
    r.message = "completed " + std::to_string(r.steps) + " steps of dt = " + format_number(dt) +
                " to t = " + format_number(r.time);
  } else {
    r.message = run_status_name(fault.status) + ": " + fault.why + " at step " + std::to_string(r.steps) +
                ", t = " + format_number(r.time) +
                (fault.particle >= 0 ? ", particle " + std::to_string(fault.particle) : "");
    if (fault.record) {  // the failing state, once (a scheduled record of this step was not written: the check came
                         // first)
      stepper.record(r.steps, o.observers);
      if (o.snapshot_every > 0 && fault.status != RunStatus::NonFinite) stepper.snapshot(r.steps, o.observers);
    }
  }
  r.evaluations = stepper.evaluations();
  r.threads = asked_threads;
  r.steps_on_one_thread = adaptive ? threads.steps_with_one() : (asked_threads == 1 ? r.steps : 0);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  for (RunObserver* obs : o.observers) obs->finished(r.message);
  return r;
}

}  // namespace sphstab
