#pragma once
/// \file csm3.hpp
/// The Turek & Hron CSM3 gravity run shared by the study drivers (studies/tl-csm3, studies/tl-csm3-hourglass): the
/// finite-strain TL form on the beam of problems/turek_hron_csm3.hpp, the leap-frog run from rest under gravity at a
/// fraction of the stability limit at rest, the displacement of A and its mean / amplitude / frequency.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/analysis/oscillation.hpp"
#include "sphstab/forms/body_force.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/forms/variational_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/run_output.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"
#include "sphstab/problems/cantilever_plate.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

namespace sphstab::study::csm3 {

using C = TurekHronCsm3;

/// CSM3's material: lambda = 2 mu nu / (1 - 2 nu) = 2 MPa, mu = 0.5 MPa (E = 1.4 MPa).
inline ElasticMaterial lame() {
  return ElasticMaterial::from_lame(2 * C::shear_modulus * C::poisson / (1 - 2 * C::poisson), C::shear_modulus, 1.0);
}

/// Linear beam theory for the cantilever from the attachment on the faces to the tip (plane-strain bending modulus
/// E / (1 - nu^2)): fundamental frequencies (Hz) and the static tip deflection under gravity (mm).
struct BeamTheory {
  double length = 0, f_euler_bernoulli = 0, f_timoshenko = 0, static_tip_mm = 0;
};
inline BeamTheory beam_theory() {
  const ElasticMaterial l = lame();
  const double young = l.young(), nu = l.poisson(), length = C::tip_x - C::attachment_x(C::bottom_y);
  BeamTheory b;
  b.length = length;
  b.f_euler_bernoulli = 1 / thin_plate_period(young, nu, C::density, C::thickness, length);
  b.f_timoshenko =
      1 / timoshenko_cantilever_period(young / (1 - nu * nu), l.mu(), 5.0 / 6.0, C::density, C::thickness, length);
  const double q = C::density * C::gravity * C::thickness, inertia = std::pow(C::thickness, 3) / 12;
  b.static_tip_mm = 1e3 * q * std::pow(length, 4) / (8 * young / (1 - nu * nu) * inertia);
  return b;
}

struct Measure {
  double mean = NAN, amplitude = NAN, frequency = NAN;
  double last_mean = NAN, last_amplitude = NAN;  ///< over the last full period only
  int half_cycles = 0;
};

/// Mean, amplitude over t >= t0 and the frequency from the zero crossings of y - mean; the last full period is the
/// interval between the last two crossings of the same direction.
inline Measure measure(const std::vector<double>& t, const std::vector<double>& y, double t0) {
  std::vector<double> tw, yw;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= t0) tw.push_back(t[k]), yw.push_back(y[k]);
  Measure m;
  if (tw.size() < 3) return m;
  const auto [lo, hi] = std::minmax_element(yw.begin(), yw.end());
  m.mean = 0.5 * (*hi + *lo);
  m.amplitude = 0.5 * (*hi - *lo);
  std::vector<double> d(yw.size());
  for (std::size_t k = 0; k < yw.size(); ++k) d[k] = yw[k] - m.mean;
  const OscillationMeasure osc = measure_oscillation(tw, d, true);
  m.frequency = 1 / osc.period;
  m.half_cycles = osc.half_cycles;
  const auto& c = osc.crossings;
  if (c.size() >= 3) {
    const double a = c[c.size() - 3], b = c[c.size() - 1];
    double mx = -1e300, mn = 1e300;
    for (std::size_t k = 0; k < tw.size(); ++k)
      if (tw[k] >= a && tw[k] <= b) mx = std::max(mx, yw[k]), mn = std::min(mn, yw[k]);
    m.last_mean = 0.5 * (mx + mn);
    m.last_amplitude = 0.5 * (mx - mn);
  }
  return m;
}

/// The form and its stress / deformation-gradient read-outs (Cauchy stress snapshots).
struct Form {
  std::shared_ptr<const ForceFunction> force;
  std::function<Eigen::MatrixXd(const Eigen::VectorXd&)> stresses, deformation_gradients;
};

/// gradient "ncsph-variational": VariationalTotalLagrangian with the NCSPH gradient (M a = -dU/du); "plain" / "ncsph":
/// FiniteStrainTotalLagrangian with that strain gradient and the given divergence ("plus", "minus", "plain").
/// hourglass: the [Ganzenmueller2015] coefficient c_HG (forms/hourglass_control.hpp; 0 = off).
inline Form make_form(const std::string& gradient, const std::string& divergence,
                      std::shared_ptr<const Discretisation<2>> disc, std::shared_ptr<const HyperelasticModel<2>> svk,
                      double hourglass = 0) {
  Form out;
  if (gradient == "ncsph-variational") {
    auto v = std::make_shared<VariationalTotalLagrangian<2>>(disc, svk, C::density,
                                                             make_gradient_provider<2>(Correction::Ncsph),
                                                             HourglassOptions{.coefficient = hourglass});
    out.stresses = [v](const Eigen::VectorXd& u) { return v->stresses(u); };
    out.deformation_gradients = [v](const Eigen::VectorXd& u) { return v->deformation_gradients(u); };
    out.force = v;
    return out;
  }
  if (gradient != "plain" && gradient != "ncsph")
    throw std::invalid_argument("csm3::make_form: gradient '" + gradient +
                                "' is not one of ncsph-variational, plain, ncsph");
  FiniteStrainOptions<2> opt;
  if (gradient == "ncsph") opt.gradient = make_gradient_provider<2>(Correction::Ncsph);
  opt.divergence = divergence == "plus"    ? StressDivergence::Plus
                   : divergence == "minus" ? StressDivergence::Minus
                                           : StressDivergence::Plain;
  opt.hourglass = hourglass;
  auto f = std::make_shared<FiniteStrainTotalLagrangian<2>>(disc, svk, C::density, opt);
  out.stresses = [f](const Eigen::VectorXd& u) { return f->stresses(u); };
  out.deformation_gradients = [f](const Eigen::VectorXd& u) { return f->deformation_gradients(u); };
  out.force = f;
  return out;
}

/// u_A (component c) extrapolated linearly to x = 0.6 from the means of the two tip columns' particles nearest
/// y = 0.2, u_A = 1.5 u(col 0) - 0.5 u(col 1), and u(col 0).
inline std::array<double, 2> tip(const TurekHronBeam& beam, const Eigen::VectorXd& u, int c) {
  double m[2] = {0, 0};
  for (int col = 0; col < 2; ++col) {
    for (int f : beam.tip[col]) m[col] += u[2 * f + c];
    m[col] /= static_cast<double>(beam.tip[col].size());
  }
  return std::array<double, 2>{1.5 * m[0] - 0.5 * m[1], m[0]};
}

struct RunOptions {
  std::string name;      ///< for progress lines
  std::string csv_path;  ///< tip history (t, u_A, the tip column's mean, total energy every ~20 ms), every ~5 ms
  double t_end = 6, t_measure = 2, cfl = 0.8;
};

struct Run {
  double dt = 0, dt_limit = 0, wall = 0, energy_drift = 0;
  long steps = 0;
  std::string status = "completed";
  Measure ux, uy;
};

/// Leap-frog (kick-drift-kick) from rest under gravity b = (0, -g) (BodyForce) at cfl x the stability limit at rest
/// (stable_time_step), landing on t_end. Samples every ~1 ms: u_A into the measures over t >= t_measure; the total
/// energy (kinetic + strain + gravity potential) every ~20 ms, its drift max |E - E0| over m g A. on_sample(t, u, uy_A)
/// is called at every ~1 ms sample.
inline Run gravity_run(std::shared_ptr<const ForceFunction> tl, const TurekHronBeam& beam, const RunOptions& o,
                       const std::function<void(double, const Eigen::VectorXd&, double)>& on_sample = {}) {
  const auto tr = Clock::now();
  const BodyForce force(tl, Eigen::Vector2d(0, -C::gravity));
  const StableTimeStep limit = stable_time_step(*tl, Eigen::VectorXd::Zero(tl->dofs()));
  Run r;
  r.dt_limit = limit.dt;
  const long nsteps = static_cast<long>(std::ceil(o.t_end / (o.cfl * limit.dt)));
  r.dt = o.t_end / nsteps;
  SecondOrderSystem sys;
  sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { force.acceleration(u, a); };
  sys.dofs_per_particle = 2;
  sys.mass.resize(tl->dofs() / 2);
  for (int f = 0; f < tl->dofs() / 2; ++f) sys.mass[f] = tl->dof_mass()[2 * f];
  const int nf = tl->dofs();
  LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(nf), Eigen::VectorXd::Zero(nf));
  CsvWriter csv(o.csv_path, {"t", "ux_A", "uy_A", "ux_tip_column", "uy_tip_column", "total_energy"}, false);
  std::vector<double> ts, uxs, uys;
  const long every = std::max(1L, static_cast<long>(std::round(1e-3 / r.dt)));  // ~1 ms
  const long energy_every = 20 * every;  // a multiple of 5 every: every energy sample is written
  const double e_scale = C::density * C::thickness * 0.35 * C::gravity * std::abs(C::uy_amplitude);  // ~ m g A
  double e0 = 0;
  SnapshotFunction sample([&](const StepView& view) {
    const long s = view.step;
    const double t = view.time;
    const auto ux = tip(beam, view.u, 0), uy = tip(beam, view.u, 1);
    double e = NAN;
    if (s % energy_every == 0 || s == nsteps) {
      e = total_energy(force, view.u, view.v);
      if (s == 0) e0 = e;
      r.energy_drift = std::max(r.energy_drift, std::abs(e - e0) / e_scale);
    }
    if (s % (5 * every) == 0 || s == nsteps) csv.row({t, ux[0], uy[0], ux[1], uy[1], e});  // CSV every ~5 ms
    ts.push_back(t);
    uxs.push_back(ux[0]);
    uys.push_back(uy[0]);
    if (on_sample) on_sample(t, view.u, uy[0]);
  });
  ProgressReport progress(o.name, 10.0);
  sphstab::RunOptions ro{.dt = r.dt, .max_steps = nsteps, .snapshot_every = static_cast<int>(every)};
  ro.observers = {&sample, &progress};
  const RunResult result = sphstab::run(stepper, ro);
  if (result.status == RunStatus::Exception)  // the TL stress refuses J <= 0
    r.status = "stopped: " + result.reason;
  else if (!result.completed())
    r.status = run_status_name(result.status);
  r.steps = stepper.steps();
  r.wall = seconds_since(tr);
  if (r.status == "completed") {
    r.ux = measure(ts, uxs, o.t_measure);
    r.uy = measure(ts, uys, o.t_measure);
  }
  return r;
}

}  // namespace sphstab::study::csm3
