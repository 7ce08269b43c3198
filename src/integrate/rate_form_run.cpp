#include "sphstab/integrate/rate_form_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
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

/// Bookkeeping shared by the integrators: records, stops, the final message, the neighbour rebuilds.
template <int Dim>
struct RunBook {
  const RateFormScheme<Dim>& base;  // the caller's scheme
  const RateFormRunOptions& o;
  long nsteps;
  double dt, ke0;
  RateFormRunResult r;
  const RateFormScheme<Dim>* scheme = nullptr;  // base, or `own` with a neighbour skin (replaced at every rebuild)
  std::unique_ptr<RateFormScheme<Dim>> own{};
  Eigen::MatrixXd x_build{};  // N x Dim: the positions of the last build (the discretisation's without a skin)

  /// Builds the run's own list (radius support + skin) at the positions of y.
  void build(const Eigen::VectorXd& y) {
    const Discretisation<Dim>& d = base.discretisation();
    own = std::make_unique<RateFormScheme<Dim>>(base.rebuilt(y, d.kernel.support_radius(d.h) + o.neighbour_skin));
    scheme = own.get();
    x_build = d.particles.x;
    for (int i = 0; i < d.size(); ++i)
      if (base.position_offset(i) >= 0) x_build.row(i) = y.segment(base.position_offset(i), Dim).transpose();
    ++r.neighbour_builds;
  }
  /// Verlet rule: rebuilds at y when a free particle of y has moved more than skin / 2 (Euclidean) since the last
  /// build. Non-finite positions are left to finish_step.
  void maybe_rebuild(const Eigen::VectorXd& y) {
    if (!(o.neighbour_skin > 0)) return;
    const double limit2 = 0.25 * o.neighbour_skin * o.neighbour_skin;
    bool move = false;
    for (int i = 0; i < x_build.rows(); ++i) {
      const int xo = base.position_offset(i);
      if (xo < 0) continue;
      const double d2 = (y.segment(xo, Dim).transpose() - x_build.row(i)).squaredNorm();
      if (!std::isfinite(d2)) return;
      move = move || d2 > limit2;
    }
    if (move) build(y);
  }
  /// F(y) on a list valid at y: every rate evaluation of the run goes through here.
  void rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
    maybe_rebuild(y);
    scheme->rate(y, dydt);
  }

  void record(long step) {
    r.times.push_back(step * dt);
    r.kinetic_energy.push_back(base.kinetic_energy(r.y));
    if (o.observer) o.observer(step, step * dt, r.y);
  }
  void stop(RunStatus status, int particle, long step, const std::string& why) {
    r.status = status;
    r.particle = particle;
    r.steps = step;
    r.time = step * dt;
    r.message = run_status_name(status) + ": " + why + " at step " + std::to_string(step) +
                ", t = " + format_number(r.time) + (particle >= 0 ? ", particle " + std::to_string(particle) : "");
  }
  /// After step `step` has put its synchronised state in r.y: checks, records; false when the run ends.
  bool finish_step(long step) {
    const auto [status, particle] = check_state(base, r.y);
    if (status != RunStatus::Completed) {
      stop(status, particle, step, status == RunStatus::NonFinite ? "non-finite state" : "density <= 0");
      return false;
    }
    if (std::isfinite(o.max_displacement)) {
      const auto& x0 = x_build;
      for (int i = 0; i < x_build.rows(); ++i) {
        const int xo = base.position_offset(i);
        if (xo < 0) continue;
        const double d = (r.y.segment(xo, Dim).transpose() - x0.row(i)).cwiseAbs().maxCoeff();
        if (d > o.max_displacement) {
          record(step);
          stop(RunStatus::DisplacementLimit, i, step,
               "moved " + format_number(d) + " > " + format_number(o.max_displacement) +
                   (o.neighbour_skin > 0 ? " since the last neighbour build"
                                         : " (the neighbour list is no longer valid)"));
          return false;
        }
      }
    }
    const bool last = step == nsteps;
    if (step % o.record_every == 0 || last) record(step);
    if (std::isfinite(o.energy_growth) && base.kinetic_energy(r.y) > o.energy_growth * ke0) {
      if (step % o.record_every != 0 && !last) record(step);
      stop(RunStatus::EnergyGrowth, -1, step,
           "kinetic energy grew by more than " + format_number(o.energy_growth) + "x");
      return false;
    }
    if (last) {
      r.steps = step;
      r.time = step * dt;
      r.message = "completed " + std::to_string(step) + " steps to t = " + format_number(r.time);
    }
    return true;
  }
};

/// [GMS2001, (6.14)-(6.18)] (rate_form_run.hpp), one step at a time so that the run and the step matrix
/// (rate_form_step_matrix) execute the same code. Between steps it holds r.y and, with reuse_corrector_rate, the
/// carried rate f0 (the previous corrector's evaluation F(x, v_p, rho_p, S_p)).
template <int Dim>
struct PredictorCorrector {
  RunBook<Dim>& b;
  const VonMises* plastic;
  Eigen::VectorXd f0{}, f1{}, yp{}, y{};

  /// From b.r.y to the next step's state in b.r.y. fresh: f0 = F(b.r.y) first (always without reuse_corrector_rate;
  /// the first step with it); otherwise f0 must hold the carried rate.
  void step(bool fresh) {
    const RateFormRunOptions& o = b.o;
    const double dt = b.dt;
    const int n = b.base.discretisation().size();
    RateFormRunResult& r = b.r;
    if (fresh) {
      b.rate(r.y, f0);
      r.rate_evaluations += 1;
    }
    yp = r.y + dt * f0;  // predictor for v, rho, S (and a first-order x, replaced below)
    for (int i = 0; i < n; ++i) {
      const int xo = b.base.position_offset(i);
      if (xo >= 0)  // x = x0 + dt vhat0 + dt^2/2 a0, not corrected [GMS2001, (6.15)]
        yp.segment(xo, Dim) =
            r.y.segment(xo, Dim) + dt * f0.segment(xo, Dim) + 0.5 * dt * dt * f0.segment(xo + Dim, Dim);
    }
    b.rate(yp, f1);
    r.rate_evaluations += 1;
    y = yp + 0.5 * dt * (f1 - f0);
    for (int i = 0; i < n; ++i) {
      const int xo = b.base.position_offset(i);
      if (xo < 0) continue;
      if (o.positions == PositionUpdate::Gms)
        y.segment(xo, Dim) = yp.segment(xo, Dim);
      else
        y.segment(xo, Dim) = r.y.segment(xo, Dim) + 0.5 * dt * (f0.segment(xo, Dim) + f1.segment(xo, Dim));
    }
    if (plastic) return_to_yield_surface(b.base, *plastic, y);
    r.y.swap(y);
    if (o.reuse_corrector_rate) f0.swap(f1);  // the next step's F^0: F(x, v_p, rho_p, S_p) of this step
  }
};

template <int Dim>
void predictor_corrector(RunBook<Dim>& b, const VonMises* plastic) {
  PredictorCorrector<Dim> pc{.b = b, .plastic = plastic};
  for (long step = 1; step <= b.nsteps; ++step) {
    pc.step(!b.o.reuse_corrector_rate || step == 1);
    if (!b.finish_step(step)) break;
  }
}

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
    if (attached == b.r.neighbour_builds) return;
    attached = b.r.neighbour_builds;
    d = &b.scheme->discretisation();
    if (b.o.leapfrog_xsph > 0)
      smooth = xsph_hook<Dim>(std::shared_ptr<const Discretisation<Dim>>(d, [](const Discretisation<Dim>*) {}),
                              {.epsilon = b.o.leapfrog_xsph, .current_positions = true, .include_fixed = true});
  }
  /// E_0 = F(y0), v^{1/2} = v^0 + dt/2 a^0.
  void start(const Eigen::VectorXd& y0) {
    y = y0;
    b.rate(y, fe);
    b.r.rate_evaluations += 1;
    get_velocities(y, vh);
    get_velocities(fe, ve);  // the velocity slots of F hold a: ve = a^0
    vh += 0.5 * b.dt * ve;
  }
  /// Steps 1-5: from (y, fe, vh, ve) at n to n + 1; the synchronised y^{n+1} into b.r.y.
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
    b.r.rate_evaluations += 2;
    get_velocities(fe, ve);       // a^{n+1}
    if (b.o.absorbing_half_step)  // Powell's algorithm 2.3: the boundary particles' a from H (forward Euler (2.66))
      for (int i : b.base.absorbing().particles) {
        const int f = d0.free_slot[i];
        ve.template segment<Dim>(f * Dim) = fh.template segment<Dim>(xoff[f] + Dim);
      }
    // Synchronised record y^{n+1} = (x^{n+1}, v^{n+1/2} + dt/2 a^{n+1}, q^{n+1}).
    b.r.y = y;
    set_velocities(b.r.y, vh + 0.5 * dt * ve);
    // 5. v^{n+3/2} = v^{n+1/2} + dt a^{n+1}.
    vh += dt * ve;
  }
};

template <int Dim>
void leapfrog(RunBook<Dim>& b, const VonMises* plastic) {
  Leapfrog<Dim> lf(b, plastic);
  lf.start(b.r.y);
  for (long step = 1; step <= b.nsteps; ++step) {
    lf.step();
    if (!b.finish_step(step)) break;
  }
}

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

template <int Dim>
RateFormRunResult run_rate_form(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0,
                                const RateFormRunOptions& o) {
  check_run_options(scheme, y0, o, "run_rate_form");
  const VonMises plastic(o.yield_stress);
  const auto wall0 = std::chrono::steady_clock::now();
  const long nsteps =
      std::max(1L, checked_floor_count(std::ceil(o.t_end / o.dt - 1e-9), 1L << 53, "run_rate_form: steps t_end / dt"));
  const double dt = o.t_end / static_cast<double>(nsteps);

  RunBook<Dim> b{.base = scheme, .o = o, .nsteps = nsteps, .dt = dt, .ke0 = scheme.kinetic_energy(y0), .r = {}};
  b.r.dt = dt;
  b.r.y = y0;
  if (o.neighbour_skin > 0) {
    b.build(y0);  // RateFormScheme::rebuilt rejects non-finite positions
  } else {
    b.scheme = &scheme;
    b.x_build = scheme.discretisation().particles.x;
  }
  b.record(0);
  const VonMises* yield = std::isfinite(o.yield_stress) ? &plastic : nullptr;
  if (o.integrator == RateFormIntegrator::Leapfrog)
    leapfrog(b, yield);
  else
    predictor_corrector(b, yield);
  b.r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return std::move(b.r);
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
  RunBook<Dim> b{.base = scheme, .o = o, .nsteps = 1, .dt = dt, .ke0 = 0, .r = {}};
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
      b.r.y = z.head(ny);
      pc.f0 = z.tail(ny);
      pc.step(false);
      Eigen::VectorXd out(z.size());
      out << b.r.y, pc.f0;
      return out;
    };
  } else {
    z0 = y;
    step = [&](const Eigen::VectorXd& z) {
      b.r.y = z;
      pc.step(true);
      return Eigen::VectorXd(b.r.y);
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
template RateFormRunResult run_rate_form<1>(const RateFormScheme<1>&, const Eigen::VectorXd&,
                                            const RateFormRunOptions&);
template RateFormRunResult run_rate_form<2>(const RateFormScheme<2>&, const Eigen::VectorXd&,
                                            const RateFormRunOptions&);

}  // namespace sphstab
