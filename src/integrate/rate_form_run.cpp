#include "sphstab/integrate/rate_form_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/integrate/xsph.hpp"
#include "sphstab/models/von_mises.hpp"

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

/// Von Mises radial return of every stored deviator in y (models/von_mises.hpp).
template <int Dim>
void return_to_yield_surface(const RateFormScheme<Dim>& s, const VonMises& model, Eigen::VectorXd& y) {
  static_assert(RateFormScheme<Dim>::kStress == kDeviatorEntries<Dim>);
  for (int i = 0; i < s.discretisation().size(); ++i) {
    const int so = s.stress_offset(i);
    if (so < 0) continue;
    const RadialReturn<Dim> r = radial_return<Dim>(model, y.template segment<kDeviatorEntries<Dim>>(so));
    if (r.yielded) y.template segment<kDeviatorEntries<Dim>>(so) = r.deviator;
  }
}

/// What the integrators share: the options, the step, the state, the neighbour rebuilds and the evaluation count.
template <int Dim>
struct RunBook {
  const RateFormScheme<Dim>& base;  // the caller's scheme
  const RateFormRunOptions& o;
  double dt;
  Eigen::VectorXd y{};                          // the synchronised state
  long evaluations = 0, builds = 0;             // rate evaluations; neighbour lists built (the one at y0 included)
  const RateFormScheme<Dim>* scheme = nullptr;  // base, or `own` with a neighbour skin (replaced at every rebuild)
  std::unique_ptr<RateFormScheme<Dim>> own{};
  Eigen::MatrixXd x_build{};  // N x Dim: the positions of the last build (the discretisation's without a skin)

  /// Builds the run's own list (radius support + skin) at the positions of y.
  void build(const Eigen::VectorXd& at) {
    const Discretisation<Dim>& d = base.discretisation();
    auto next =
        std::make_unique<RateFormScheme<Dim>>(base.rebuilt(at, d.kernel.support_radius(d.h) + o.neighbour_skin));
    if (own) next->take_scratch(*own);  // the previous list's buffers: no new pages per build
    own = std::move(next);
    scheme = own.get();
    x_build = d.particles.x;
    for (int i = 0; i < d.size(); ++i)
      if (base.position_offset(i) >= 0) x_build.row(i) = at.segment(base.position_offset(i), Dim).transpose();
    ++builds;
  }
  /// Verlet rule: rebuilds at `at` when a free particle has moved more than skin / 2 (Euclidean) since the last
  /// build. Non-finite positions are left to the state check.
  void maybe_rebuild(const Eigen::VectorXd& at) {
    if (!(o.neighbour_skin > 0)) return;
    const double limit2 = 0.25 * o.neighbour_skin * o.neighbour_skin;
    bool move = false;
    for (int i = 0; i < x_build.rows(); ++i) {
      const int xo = base.position_offset(i);
      if (xo < 0) continue;
      const double d2 = (at.segment(xo, Dim).transpose() - x_build.row(i)).squaredNorm();
      if (!std::isfinite(d2)) return;
      move = move || d2 > limit2;
    }
    if (move) build(at);
  }
  /// F(at) on a list valid at `at`: every rate evaluation of the run goes through here.
  void rate(const Eigen::VectorXd& at, Eigen::VectorXd& dydt) {
    maybe_rebuild(at);
    scheme->rate(at, dydt);
  }
};

/// [GMS2001, (6.14)-(6.18)] (rate_form_run.hpp), one step at a time so that the run and the step matrix
/// (rate_form_step_matrix) execute the same code. Between steps it holds b.y and, with reuse_corrector_rate, the
/// carried rate f0 (the previous corrector's evaluation F(x, v_p, rho_p, S_p)).
template <int Dim>
struct PredictorCorrector {
  RunBook<Dim>& b;
  const VonMises* plastic;
  Eigen::VectorXd f0{}, f1{}, yp{}, y{};
  // Per state entry: 1 where it is a position x_a of a free particle, so that each update is one pass over the state
  // (one barrier with threads) with the positions' own formula where the mask says; the offsets are the base
  // scheme's, the same for every build.
  std::vector<unsigned char> position{};

  // With reuse_corrector_rate the next step's predictor needs only this step's corrected state and F^1, so the
  // corrector's pass computes it too (one pass over the state and one parallel region fewer per step); it is held in
  // yp for a step with this dt, and used only by a step of the stepper's own sequence (own_state below).
  double predicted_dt = std::numeric_limits<double>::quiet_NaN();

  /// From b.y to the next step's state in b.y. fresh: f0 = F(b.y) first (always without reuse_corrector_rate;
  /// the first step with it); otherwise f0 must hold the carried rate. own_state: b.y and f0 are those this object
  /// left at its previous step (not set from outside, as the step matrix sets them), so its prediction is valid.
  void step(bool fresh, bool own_state = false) {
    const RateFormRunOptions& o = b.o;
    const double dt = b.dt;
    const int n = b.base.discretisation().size();
    if (fresh) {
      b.rate(b.y, f0);
      b.evaluations += 1;
    }
    // The updates are element by element, so threads give the same bits as one: in a run with threads they would
    // otherwise be serial work between the threaded evaluations.
    const Eigen::Index size = b.y.size();
    if (static_cast<Eigen::Index>(position.size()) != size) {
      position.assign(size, 0);
      for (int i = 0; i < n; ++i)
        if (const int xo = b.base.position_offset(i); xo >= 0)
          for (int a = 0; a < Dim; ++a) position[xo + a] = 1;
    }
    const bool predicted = own_state && !fresh && predicted_dt == dt && yp.size() == size;
    predicted_dt = std::numeric_limits<double>::quiet_NaN();
    yp.resize(size);
    y.resize(size);
    const int threads = threads_for(n);
    const double half_dt2 = 0.5 * dt * dt, half_dt = 0.5 * dt;
    const bool gms = o.positions == PositionUpdate::Gms;
    // Predictor for v, rho, S: y + dt F0; for x, x0 + dt vhat0 + dt^2/2 a0, not corrected [GMS2001, (6.15)] (the
    // acceleration a0 is the rate of the velocity entry Dim after x_a).
    const auto predict = [&](const Eigen::VectorXd& from, const Eigen::VectorXd& f, Eigen::Index k) {
      return position[k] ? from[k] + dt * f[k] + half_dt2 * f[k + Dim] : from[k] + dt * f[k];
    };
    if (!predicted) {
#pragma omp parallel for schedule(static) num_threads(threads)
      for (Eigen::Index k = 0; k < size; ++k) yp[k] = predict(b.y, f0, k);
    }
    b.rate(yp, f1);
    b.evaluations += 1;
    // Corrector [GMS2001, (6.16)-(6.18)]; entry k reads yp[k] only, so the next prediction may overwrite it.
    const bool predict_next = o.reuse_corrector_rate && !plastic;
#pragma omp parallel for schedule(static) num_threads(threads)
    for (Eigen::Index k = 0; k < size; ++k) {
      y[k] = !position[k] ? yp[k] + half_dt * (f1[k] - f0[k]) : gms ? yp[k] : b.y[k] + half_dt * (f0[k] + f1[k]);
      if (predict_next) yp[k] = predict(y, f1, k);
    }
    if (plastic) return_to_yield_surface(b.base, *plastic, y);
    b.y.swap(y);
    if (o.reuse_corrector_rate) f0.swap(f1);  // the next step's F^0: F(x, v_p, rho_p, S_p) of this step
    if (predict_next) predicted_dt = dt;
  }
};

/// [Powell2012, algorithm 1.1, (1.40)], staggered; the numbered steps are those of rate_form_run.hpp. Between steps
/// it holds y = (x^n, v*^n, q^n), fe = F(y), vh = v^{n+1/2} and ve = a^n (the acceleration the step uses; with
/// absorbing_half_step the boundary particles' entries come from H, not from fe).
template <int Dim>
struct Leapfrog {
  RunBook<Dim>& b;
  const VonMises* plastic;
  const Discretisation<Dim>& d0;  // free numbering and offsets: the same for every build
  std::vector<int> xoff;          // state offsets of the free particles in DOF order: x at xoff, v at xoff + Dim
  // Powell (2.71) through the XSPH hook of the second-order integrator (one smoothing code, kernel at x^n), on the
  // discretisation of the current list (attached again after a rebuild).
  const Discretisation<Dim>* d = nullptr;
  VelocityHook smooth;
  long attached = -1;  // the build d belongs to
  Eigen::VectorXd y, fe, fh, yh, vh, ve, u, vs;

  Leapfrog(RunBook<Dim>& book, const VonMises* yield)
      : b(book), plastic(yield), d0(book.base.discretisation()), xoff(d0.free_count()) {
    for (int f = 0; f < d0.free_count(); ++f) xoff[f] = b.base.position_offset(d0.free[f]);
  }
  void set_velocities(Eigen::VectorXd& state, const Eigen::VectorXd& v) const {
    for (int f = 0; f < d0.free_count(); ++f)
      state.template segment<Dim>(xoff[f] + Dim) = v.template segment<Dim>(f * Dim);
  }
  void get_velocities(const Eigen::VectorXd& state, Eigen::VectorXd& v) const {
    v.resize(d0.dofs());
    for (int f = 0; f < d0.free_count(); ++f)
      v.template segment<Dim>(f * Dim) = state.template segment<Dim>(xoff[f] + Dim);
  }
  void attach() {
    if (attached == b.builds) return;
    attached = b.builds;
    d = &b.scheme->discretisation();
    if (b.o.leapfrog_xsph > 0)
      smooth = xsph_hook<Dim>(std::shared_ptr<const Discretisation<Dim>>(d, [](const Discretisation<Dim>*) {}),
                              {.epsilon = b.o.leapfrog_xsph, .current_positions = true, .include_fixed = true});
  }
  /// E_0 = F(y0), v^{1/2} = v^0 + dt/2 a^0.
  void start(const Eigen::VectorXd& y0) {
    y = y0;
    b.rate(y, fe);
    b.evaluations += 1;
    get_velocities(y, vh);
    get_velocities(fe, ve);  // the velocity slots of F hold a: ve = a^0
    vh += 0.5 * b.dt * ve;
  }
  /// Steps 1-5: from (y, fe, vh, ve) at n to n + 1; the synchronised y^{n+1} into b.y.
  void step() {
    const double dt = b.dt;
    // 1. Powell's XSPH on v^{n+1/2}, at the positions x^n (the list of E_n); driven particles keep their velocity.
    attach();
    if (smooth) {
      u.resize(d->dofs());
      for (int f = 0; f < d->free_count(); ++f)
        u.template segment<Dim>(f * Dim) =
            y.template segment<Dim>(xoff[f]) - d->particles.x.row(d->free[f]).transpose();
      smooth(u, vh, vs);
      vh.swap(vs);
      for (int i : b.base.driven_particles()) {
        const int f = d->free_slot[i];
        vh.template segment<Dim>(f * Dim) = vs.template segment<Dim>(f * Dim);
      }
    }
    // 2. The half-step state: q^n + dt/2 qdot^n, x^n + dt/2 (v^{n+1/2} + vhat^n - v*^n), v^{n+1/2}.
    yh = y + 0.5 * dt * fe;
    for (int f = 0; f < d0.free_count(); ++f) {
      const int xo = xoff[f];
      yh.template segment<Dim>(xo) =
          y.template segment<Dim>(xo) +
          0.5 * dt *
              (vh.template segment<Dim>(f * Dim) + fe.template segment<Dim>(xo) - y.template segment<Dim>(xo + Dim));
    }
    set_velocities(yh, vh);
    b.rate(yh, fh);
    // 3. x^{n+1}, q^{n+1} from the half-step rates (the velocity slots are overwritten below), radial return.
    y += dt * fh;
    if (plastic) return_to_yield_surface(b.base, *plastic, y);
    // 4. E_{n+1} at v*^{n+1} = v^{n+1/2} + dt/2 a^n.
    set_velocities(y, vh + 0.5 * dt * ve);
    b.rate(y, fe);
    b.evaluations += 2;
    get_velocities(fe, ve);       // a^{n+1}
    if (b.o.absorbing_half_step)  // Powell's algorithm 2.3: the boundary particles' a from H (forward Euler (2.66))
      for (int i : b.base.absorbing().particles) {
        const int f = d0.free_slot[i];
        ve.template segment<Dim>(f * Dim) = fh.template segment<Dim>(xoff[f] + Dim);
      }
    // Synchronised record y^{n+1} = (x^{n+1}, v^{n+1/2} + dt/2 a^{n+1}, q^{n+1}).
    b.y = y;
    set_velocities(b.y, vh + 0.5 * dt * ve);
    // 5. v^{n+3/2} = v^{n+1/2} + dt a^{n+1}.
    vh += dt * ve;
  }
};

/// Checks the run options (rate_form_run.hpp) and the state size.
template <int Dim>
void check_run_options(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0, const RateFormRunOptions& o,
                       const std::string& who) {
  if (!(o.dt > 0) || !std::isfinite(o.dt))
    throw std::invalid_argument(who + ": dt must be finite and > 0 (got " + format_number(o.dt) + ")");
  if (!(o.t_end > 0) || !std::isfinite(o.t_end))
    throw std::invalid_argument(who + ": t_end must be finite and > 0 (got " + format_number(o.t_end) + ")");
  if (o.record_every < 1) throw std::invalid_argument(who + ": record_every must be >= 1");
  if (y0.size() != scheme.size())
    throw std::invalid_argument(who + ": state has " + std::to_string(y0.size()) + " entries, expected " +
                                std::to_string(scheme.size()));
  if (!(o.leapfrog_xsph >= 0) || !std::isfinite(o.leapfrog_xsph))
    throw std::invalid_argument(who + ": leapfrog_xsph must be finite and >= 0 (got " + format_number(o.leapfrog_xsph) +
                                ")");
  if (o.leapfrog_xsph > 0 && o.integrator != RateFormIntegrator::Leapfrog)
    throw std::invalid_argument(who +
                                ": leapfrog_xsph needs the leap-frog integrator (the predictor-corrector's XSPH is "
                                "RateFormOptions::xsph)");
  if (o.absorbing_half_step && o.integrator != RateFormIntegrator::Leapfrog)
    throw std::invalid_argument(who +
                                ": absorbing_half_step needs the leap-frog integrator (it is Powell's algorithm 2.3)");
  if (o.reuse_corrector_rate && o.integrator != RateFormIntegrator::PredictorCorrector)
    throw std::invalid_argument(who + ": reuse_corrector_rate needs the predictor-corrector integrator");
  if (o.reuse_corrector_rate && std::isfinite(o.yield_stress))
    throw std::invalid_argument(who +
                                ": reuse_corrector_rate with a yield stress: the radial return changes S after the "
                                "corrector's rate evaluation, so that rate is not the next step's");
  if (!(o.yield_stress > 0))
    throw std::invalid_argument(who + ": yield_stress must be > 0 (+infinity: elastic; got " +
                                format_number(o.yield_stress) + ")");
  if (!(o.max_displacement > 0))
    throw std::invalid_argument(who + ": max_displacement must be > 0 (+infinity: unchecked; got " +
                                format_number(o.max_displacement) + ")");
  if (!(o.neighbour_skin >= 0) || !std::isfinite(o.neighbour_skin))
    throw std::invalid_argument(who + ": neighbour_skin must be finite and >= 0 (0: no rebuild; got " +
                                format_number(o.neighbour_skin) + ")");
}

}  // namespace

/// The stepper's state: the shared book and the integrator it drives.
template <int Dim>
struct RateFormStepper<Dim>::Impl {
  RateFormRunOptions o;
  VonMises plastic;
  RunBook<Dim> b;
  PredictorCorrector<Dim> pc;
  std::unique_ptr<Leapfrog<Dim>> lf{};
  long steps = 0;
  bool started = false;
  std::vector<double> times{}, kinetic_energy{};

  Impl(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0, const RateFormRunOptions& options)
      : o(options), plastic(options.yield_stress), b{.base = scheme, .o = o, .dt = 0}, pc{.b = b, .plastic = yield()} {
    b.y = y0;
    if (o.neighbour_skin > 0) {
      b.build(y0);  // RateFormScheme::rebuilt rejects non-finite positions
    } else {
      b.scheme = &scheme;
      b.x_build = scheme.discretisation().particles.x;
    }
    if (o.integrator == RateFormIntegrator::Leapfrog) lf = std::make_unique<Leapfrog<Dim>>(b, yield());
  }
  const VonMises* yield() const { return std::isfinite(o.yield_stress) ? &plastic : nullptr; }
};

template <int Dim>
RateFormStepper<Dim>::RateFormStepper(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0,
                                      const RateFormRunOptions& options) {
  check_run_options(scheme, y0, options, "RateFormStepper");
  m = std::make_unique<Impl>(scheme, y0, options);
}

template <int Dim>
RateFormStepper<Dim>::~RateFormStepper() = default;

template <int Dim>
void RateFormStepper<Dim>::step(double dt) {
  Impl& s = *m;
  s.b.dt = dt;
  if (s.lf) {
    if (!s.started) s.lf->start(s.b.y);  // E_0 = F(y0), v^{1/2} = v^0 + dt/2 a^0
    s.lf->step();
  } else {
    s.pc.step(!s.o.reuse_corrector_rate || !s.started, /*own_state=*/true);
  }
  s.started = true;
  ++s.steps;
}

template <int Dim>
long RateFormStepper<Dim>::steps() const {
  return m->steps;
}
template <int Dim>
double RateFormStepper<Dim>::time() const {
  return m->steps * m->b.dt;
}
template <int Dim>
long RateFormStepper<Dim>::evaluations() const {
  return m->b.evaluations;
}
template <int Dim>
long RateFormStepper<Dim>::neighbour_builds() const {
  return m->b.builds;
}
template <int Dim>
const Eigen::VectorXd& RateFormStepper<Dim>::state() const {
  return m->b.y;
}
template <int Dim>
const std::vector<double>& RateFormStepper<Dim>::times() const {
  return m->times;
}
template <int Dim>
const std::vector<double>& RateFormStepper<Dim>::kinetic_energy() const {
  return m->kinetic_energy;
}

template <int Dim>
StateFault RateFormStepper<Dim>::check(const BlowUpLimits& limits) const {
  if (limits.box_lo.size() || limits.box_hi.size())
    throw std::invalid_argument("run_rate_form: no box check (limits.box_lo, box_hi) for the rate form");
  const RunBook<Dim>& b = m->b;
  const auto [status, particle] = check_state(b.base, b.y);
  if (status != RunStatus::Completed)
    return {.status = status,
            .particle = particle,
            .why = status == RunStatus::NonFinite ? "non-finite state" : "density <= 0",
            .record = false};
  if (std::isfinite(limits.max_displacement))
    for (int i = 0; i < b.x_build.rows(); ++i) {
      const int xo = b.base.position_offset(i);
      if (xo < 0) continue;
      const double d = (b.y.segment(xo, Dim).transpose() - b.x_build.row(i)).cwiseAbs().maxCoeff();
      if (d > limits.max_displacement)
        return {.status = RunStatus::DisplacementLimit,
                .particle = i,
                .why = "moved " + format_number(d) + " > " + format_number(limits.max_displacement) +
                       (b.o.neighbour_skin > 0 ? " since the last neighbour build"
                                               : " (the neighbour list is no longer valid)")};
    }
  return {};
}

template <int Dim>
double RateFormStepper<Dim>::energy() const {
  return m->b.base.kinetic_energy(m->b.y);
}

template <int Dim>
void RateFormStepper<Dim>::record(long step, const std::vector<RunObserver*>& /*observers*/) {
  Impl& s = *m;
  s.times.push_back(step * s.b.dt);
  s.kinetic_energy.push_back(s.b.base.kinetic_energy(s.b.y));
  if (s.o.observer) s.o.observer(step, step * s.b.dt, s.b.y);
}

template <int Dim>
RateFormRunResult run_rate_form(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0,
                                const RateFormRunOptions& o) {
  check_run_options(scheme, y0, o, "run_rate_form");
  RateFormStepper<Dim> stepper(scheme, y0, o);
  RunOptions ro{.dt = o.dt, .t_end = o.t_end, .record_every = o.record_every};
  ro.observers = o.observers;
  ro.limits.max_displacement = o.max_displacement;
  ro.limits.energy_growth = o.energy_growth;
  RateFormRunResult r;
  static_cast<RunResult&>(r) = run(stepper, ro, "run_rate_form");
  r.times = stepper.times();
  r.kinetic_energy = stepper.kinetic_energy();
  r.y = stepper.state();
  r.neighbour_builds = stepper.neighbour_builds();
  return r;
}

namespace {

/// Central differences of one step of the integrator's own code (rate_form_step_matrix); `who` names the caller in
/// the error messages.
template <int Dim>
Eigen::MatrixXd step_matrix(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y, double dt,
                            const RateFormRunOptions& options, double delta, const std::string& who) {
  RateFormRunOptions o = options;
  o.dt = dt, o.t_end = dt;
  check_run_options(scheme, y, o, who);
  if (o.neighbour_skin > 0 || std::isfinite(o.yield_stress))
    throw std::invalid_argument(
        who + ": needs the scheme's own neighbour list and an elastic run (no skin, no yield stress)");
  if (!(delta > 0) || !std::isfinite(delta))
    throw std::invalid_argument(who + ": delta must be finite and > 0 (got " + format_number(delta) + ")");
  RunBook<Dim> b{.base = scheme, .o = o, .dt = dt};
  b.scheme = &scheme;
  b.x_build = scheme.discretisation().particles.x;
  const Eigen::Index ny = y.size(), nv = scheme.discretisation().dofs();
  Eigen::VectorXd z0, f0;
  b.rate(y, f0);
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> step;
  Leapfrog<Dim> lf(b, nullptr);
  PredictorCorrector<Dim> pc{.b = b, .plastic = nullptr};
  if (o.integrator == RateFormIntegrator::Leapfrog) {
    // z0 = (y, v^{n+1/2} = v of y, a^n = F(y)'s acceleration).
    Eigen::VectorXd v0, a0;
    lf.get_velocities(y, v0);
    lf.get_velocities(f0, a0);
    z0.resize(ny + 2 * nv);
    z0 << y, v0, a0;
    step = [&](const Eigen::VectorXd& z) {
      lf.y = z.head(ny);
      lf.vh = z.segment(ny, nv);
      lf.ve = z.tail(nv);
      b.rate(lf.y, lf.fe);
      lf.step();
      Eigen::VectorXd out(z.size());
      out << lf.y, lf.vh, lf.ve;
      return out;
    };
  } else if (o.reuse_corrector_rate) {
    // z0 = (y, F^0 = F(y)): the carried rate is state (docs/conventions.md §7, "One rate per step").
    z0.resize(2 * ny);
    z0 << y, f0;
    step = [&](const Eigen::VectorXd& z) {
      b.y = z.head(ny);
      pc.f0 = z.tail(ny);
      pc.step(false);
      Eigen::VectorXd out(z.size());
      out << b.y, pc.f0;
      return out;
    };
  } else {
    z0 = y;
    step = [&](const Eigen::VectorXd& z) {
      b.y = z;
      pc.step(true);
      return Eigen::VectorXd(b.y);
    };
  }
  Eigen::MatrixXd M(z0.size(), z0.size());
  for (Eigen::Index k = 0; k < z0.size(); ++k) {
    const double e = delta * std::max(1.0, std::abs(z0[k]));
    Eigen::VectorXd zp = z0, zm = z0;
    zp[k] += e, zm[k] -= e;
    M.col(k) = (step(zp) - step(zm)) / (2 * e);
  }
  return M;
}

}  // namespace

template <int Dim>
Eigen::MatrixXd rate_form_step_matrix(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y, double dt,
                                      const RateFormRunOptions& options, double delta) {
  return step_matrix(scheme, y, dt, options, delta, "rate_form_step_matrix");
}

template <int Dim>
Eigen::MatrixXd leapfrog_step_matrix(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y, double dt,
                                     const RateFormRunOptions& options, double delta) {
  if (options.integrator != RateFormIntegrator::Leapfrog)
    throw std::invalid_argument("leapfrog_step_matrix: options.integrator must be the leap-frog");
  return step_matrix(scheme, y, dt, options, delta, "leapfrog_step_matrix");
}

template Eigen::MatrixXd rate_form_step_matrix<1>(const RateFormScheme<1>&, const Eigen::VectorXd&, double,
                                                  const RateFormRunOptions&, double);
template Eigen::MatrixXd rate_form_step_matrix<2>(const RateFormScheme<2>&, const Eigen::VectorXd&, double,
                                                  const RateFormRunOptions&, double);
template Eigen::MatrixXd leapfrog_step_matrix<1>(const RateFormScheme<1>&, const Eigen::VectorXd&, double,
                                                 const RateFormRunOptions&, double);
template Eigen::MatrixXd leapfrog_step_matrix<2>(const RateFormScheme<2>&, const Eigen::VectorXd&, double,
                                                 const RateFormRunOptions&, double);
template class RateFormStepper<1>;
template class RateFormStepper<2>;
template RateFormRunResult run_rate_form<1>(const RateFormScheme<1>&, const Eigen::VectorXd&,
                                            const RateFormRunOptions&);
template RateFormRunResult run_rate_form<2>(const RateFormScheme<2>&, const Eigen::VectorXd&,
                                            const RateFormRunOptions&);

}  // namespace sphstab
