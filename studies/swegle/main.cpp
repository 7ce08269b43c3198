// Study: the Swegle stability test [Powell2012, ch. 4 §2.2, Figs. 4.1/4.2] for every SPH formulation, with the
// linear-theory growth rate of the same force function next to the measured kinetic-energy growth, a 1D version,
// and the energy conservation of the conservative form. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, ke.csv, equilibrium.csv, energy.csv, energy_series.csv, onedim_runs.csv,
// onedim_ke.csv, modes/*.vtp, summary.json. Units: g, cm, us (stress in g cm^-1 us^-2 = 1e11 Pa = Mbar).
#include <malloc.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/artificial_stress_term.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/stabilised_sph.hpp"
#include "sphstab/forms/total_lagrangian.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/growth/class_growth.hpp"
#include "sphstab/growth/growth_run.hpp"
#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/growth/swegle_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/run_output.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/swegle.hpp"
#include "sphstab/spectral/dominant_wavenumber.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"
#include "sphstab/stability/equilibrium.hpp"

using namespace sphstab;
using study::sig;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Options of a run of the study (CLI) and the derived detection limit.
struct Config {
  std::string out = "results/swegle";
  double t_end = 45, t_end_1d = 400;
  std::vector<double> xis{0.96, 0.98, 0.99, 1.00, 1.01, 1.02, 1.04};
  std::vector<std::string> only;
  long energy_steps = 10000;
  int record_every = 5;
  double onset = GrowthWindowOptions{}.onset_factor;
  double detect = 0;  ///< slowest growth that reaches the onset within t_end: log(onset) / (2 t_end)
};

/// One 2D formulation of the study (described in summary.md.in and README.md).
struct Formulation {
  std::string name;   ///< key in the CSV files
  bool xsph = false;  ///< XSPH velocity smoothing ([Powell2012, (2.71)], eps = 0.1, Replace mode)
  std::function<std::shared_ptr<ForceFunction>(const SwegleScene&)> make;
  /// The force switches on the sign of the stress (S-SPH, GMS): at xi = 1 (zero stress) the lattice lies on the
  /// switching surface and the linearisation is not unique.
  bool switching = false;
};

std::vector<Formulation> formulations() {
  using Force = std::shared_ptr<ForceFunction>;
  auto plus = [](const SwegleScene& s) -> Force {
    return std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Plus, s.prestrain);
  };
  auto ssph = [](StabilisedSphOptions o) {
    return [o](const SwegleScene& s) -> Force {
      return make_stabilised_sph(s.discretisation, s.material, s.prestrain, o);
    };
  };
  std::vector<Formulation> f;
  f.push_back({"sph", false, plus});
  f.push_back({"sph-xsph", true, plus});
  f.push_back({"ncsph", false, [](const SwegleScene& s) -> Force {
                 auto force =
                     std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Plus, s.prestrain,
                                                     make_gradient_provider<2>(Correction::Ncsph));
                 force->set_corrected_strain(true);
                 return force;
               }});
  f.push_back({"tl", false, [](const SwegleScene& s) -> Force {
                 return std::make_shared<TotalLagrangianForm2D>(s.discretisation, s.material, s.prestrain);
               }});
  f.push_back({"cij", false, [](const SwegleScene& s) -> Force {
                 return std::make_shared<ElasticForm2D>(
                     s.discretisation, s.material, MomentumForm::Uncorrected, s.prestrain,
                     make_gradient_provider<2>(Correction::LocalPolish, {.counting = NeighbourCounting::BoundaryLevel,
                                                                         .first_step_shepard = true}));
               }});
  f.push_back({"ssph", true, ssph({}), true});
  f.push_back({"ssph-pp", true, ssph({.symmetrise = false}), true});
  f.push_back({"ssph-pp-noxsph", false, ssph({.symmetrise = false}), true});
  f.push_back({"ssph-printed", true, ssph({.rule = SwitchRule::AsPrinted}), true});
  f.push_back({"sph-gms", false,
               [](const SwegleScene& s) -> Force {
                 return make_artificial_stress_sph(s.discretisation, s.material, s.prestrain);
               },
               true});
  f.push_back({"conservative", false, [](const SwegleScene& s) -> Force {
                 return std::make_shared<ElasticForm2D>(s.discretisation, s.material, MomentumForm::Conservative,
                                                        s.prestrain);
               }});
  return f;
}

/// The four mirror classes of the Swegle block (the same for every xi) and the XSPH smoothing on the DOFs.
struct Classes {
  MirrorClasses mirror;
  Eigen::MatrixXd S_dof;  ///< XSPH smoothing (x) I_2 at x0
};

Classes make_classes(const SwegleScene& s) {
  Classes c;
  const double mid = 0.5 * s.options.n * s.options.spacing;
  c.mirror =
      mirror_classes(mirror_symmetry(s.free_positions(), Eigen::Vector2d(mid, mid), 1e-6 * s.options.spacing), s.v0);
  const SparseMatrix<> S = xsph_smoothing_matrix(*s.discretisation, {});
  const int n = s.discretisation->dofs();
  c.S_dof = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < S.outerSize(); ++i)
    for (SparseMatrix<>::InnerIterator it(S, i); it; ++it)
      for (int a = 0; a < 2; ++a) c.S_dof(2 * i + a, 2 * it.col() + a) = it.value();
  return c;
}

/// Linear theory of one force function at u: all four classes, the excited one, the leap-frog map with XSPH.
struct Linear {
  double gamma_all = kNaN, gamma_exc = kNaN, gamma_map = kNaN, lambda_max = kNaN;
  std::complex<double> mu_all{kNaN, kNaN}, mu_exc{kNaN, kNaN};
  double commutation = kNaN, asymmetry = kNaN;
  Eigen::VectorXd mode;  ///< fastest mode of the excited class (full DOFs, unit norm)
  int colours = 0;
  double seconds = 0;
};

Linear analyse(const ForceFunction& f, const Eigen::VectorXd& u, const Classes& c, bool xsph, double dt) {
  const auto t0 = study::Clock::now();
  Linear L;
  ComplexStepJacobian jac(f);
  const SparseMatrix<> As = jac.compute(u);
  L.colours = jac.colours();
  if (jac.info() != Status::Successful) return L;
  L.asymmetry = relative_asymmetry(As);
  // gamma_map: the leap-frog's one-step map at dt, with XSPH as its velocity hook when the formulation smooths.
  const ClassGrowth g = class_growth(As, c.mirror, xsph ? c.S_dof : Eigen::MatrixXd(), dt);
  L.commutation = g.commutation;
  L.gamma_all = g.gamma_all;
  L.mu_all = g.mu_all;
  L.gamma_exc = g.gamma_excited;
  L.mu_exc = g.mu_excited;
  L.gamma_map = g.gamma_map;
  L.lambda_max = g.lambda_max;
  L.mode = g.mode;
  L.seconds = study::seconds_since(t0);
  return L;
}

/// Dominant wavevector of a displacement field (dominant_wavevector.hpp, structure-factor peak) and the share of its
/// squared norm in the x component.
struct ModeK {
  double kx = kNaN, ky = kNaN, peak = kNaN, x_share = kNaN;
  std::string component() const { return std::isnan(x_share) ? "-" : (x_share >= 0.5 ? "x" : "y"); }
};

struct Row {
  std::string form;
  bool xsph = false, switching = false;
  double xi = 0, strain = 0, sigma0 = 0, a0 = 0;
  bool equilibrium = true;
  std::string newton = "-";
  double ustar = kNaN;  ///< max |u*| / dx of the Newton equilibrium (out-of-equilibrium formulations)
  Linear lin, lin_star;
  double gamma_pred = kNaN;
  /// The verdict (growth/stability_verdict.hpp's classes) in the excited class at the run's state: gamma_J of
  /// u'' = a(u), gamma_M of the leap-frog map (with XSPH when the formulation smooths), against the floor.
  std::string verdict = "n/a";
  double gamma_j = kNaN, gamma_m = kNaN;
  GrowthRun run;
  double ratio = kNaN;
  std::string lin_verdict, run_verdict, agreement;
  ModeK k_mode, k_run;
  double wall = 0;
};

std::string linear_verdict(double gamma, double detect) {
  if (std::isnan(gamma)) return "n/a";
  if (gamma > detect) return "unstable";
  if (gamma > 1e-3) return "weakly unstable";
  return "stable";
}

ModeK mode_k(const Eigen::VectorXd& field, const SwegleScene& s) {
  ModeK m;
  if (!field.size() || !(field.cwiseAbs().maxCoeff() > 0)) return m;
  const WavevectorEstimate e = dominant_wavevector(field, Eigen::MatrixX2d(s.discretisation->free_positions()),
                                                   bravais_lattice_2d(LatticeType::Square, s.options.spacing));
  m.kx = e.kx_over_pi;
  m.ky = e.ky_over_pi;
  m.peak = e.peak_fraction;
  double sx = 0;
  for (Eigen::Index p = 0; 2 * p < field.size(); ++p) sx += field[2 * p] * field[2 * p];
  m.x_share = sx / field.squaredNorm();
  return m;
}

void write_mode_vtp(const std::string& path, const SwegleScene& s, const Eigen::VectorXd& field, const char* name) {
  const Eigen::MatrixX2d x = Eigen::MatrixX2d(s.discretisation->free_positions());
  Eigen::VectorXd f = field;
  const double m = f.cwiseAbs().maxCoeff();
  if (m > 0) f /= m;
  Eigen::VectorXd mag(x.rows());
  for (Eigen::Index p = 0; p < x.rows(); ++p) mag[p] = std::hypot(f[2 * p], f[2 * p + 1]);
  write_vtp(path, Eigen::MatrixXd(x), {{name, 2, f}, {"magnitude", 1, mag}});
}

// ---------------------------------------------------------------------------------------------------------- 2D runs

/// One Swegle run of formulation f at volume strain xi and the linear analysis of the same force function; appends
/// to ke.csv and (out of equilibrium) equilibrium.csv, writes mode snapshots; prints a progress line.
Row run_2d_case(const Formulation& f, double xi, const Config& c, const Classes& classes, double dt, CsvWriter& ke_csv,
                CsvWriter& eq_csv, const std::string& progress) {
  const auto t0 = study::Clock::now();
  Row r{.form = f.name, .xsph = f.xsph, .switching = f.switching, .xi = xi};
  const SwegleScene scene = make_swegle_scene({.area_ratio = xi});
  const double dx = scene.options.spacing;
  r.strain = scene.prestrain.strain;
  r.sigma0 = scene.prestrain.stress(scene.material)(0, 0);
  const std::shared_ptr<ForceFunction> force = f.make(scene);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(force->dofs());
  Eigen::VectorXd a;
  force->acceleration(zero, a);
  r.a0 = a.cwiseAbs().maxCoeff();
  // In equilibrium when the imbalance is far below the perturbation's accelerations (omega v0 ~ 5e-9).
  r.equilibrium = r.a0 <= 1e-12;
  r.lin = analyse(*force, zero, classes, f.xsph, dt);
  r.gamma_pred = f.xsph ? r.lin.gamma_map : r.lin.gamma_exc;
  if (!r.equilibrium) {
    // Not in equilibrium at the lattice (symmetrised S-SPH in tension): find the nearby equilibrium u*, which the
    // run (damped by XSPH) approaches; the linear prediction is taken there.
    const double scale = std::abs(r.sigma0) / (scene.material.rho * dx);
    const Equilibrium eq =
        find_equilibrium(*force, zero, {.max_iterations = 15, .accel_scale = scale, .load_steps = 4});
    r.newton = eq.status == Status::Successful ? "converged" : eq.message;
    double ga = kNaN, gm = kNaN, ge = kNaN;
    if (eq.status == Status::Successful) {
      r.ustar = eq.u.cwiseAbs().maxCoeff() / dx;
      r.lin_star = analyse(*force, eq.u, classes, f.xsph, dt);
      ge = r.lin_star.gamma_exc;
      gm = r.lin_star.gamma_map;
      ga = r.lin_star.gamma_all;
      r.gamma_pred = f.xsph ? gm : ge;
    } else {
      r.gamma_pred = kNaN;
    }
    eq_csv.row({f.name, xi, r.a0, r.newton, eq.iterations, eq.residual, r.ustar, r.lin.gamma_exc, ge, gm, ga});
  }
  {
    const Linear& L = r.equilibrium ? r.lin : r.lin_star;
    r.gamma_j = L.gamma_exc;
    r.gamma_m = L.gamma_map;
    if (std::isfinite(r.gamma_j) && std::isfinite(r.gamma_m) && !(f.switching && r.sigma0 == 0))
      r.verdict = verdict_letter(classify_verdict(r.gamma_j, r.gamma_m, c.detect));
  }
  SwegleRunOptions ro;
  ro.t_end = c.t_end;
  ro.run.record_every = c.record_every;
  ro.run.xsph = f.xsph;
  ro.run.reference_time = r.equilibrium ? 0.0 : 1.0;  // out of equilibrium: KE reference = response in 1 us
  ro.run.window.envelope_time = 1.0;  // follow the bottom of XSPH-damped KE (>= the slowest period, ~0.7 us)
  r.run = run_swegle(scene, force, ro);
  const ExponentialGrowthFit& fit = r.run.fit;
  if (fit.grew && r.gamma_pred > 0) r.ratio = fit.gamma / r.gamma_pred;
  r.lin_verdict = f.switching && r.sigma0 == 0 ? "switching surface" : linear_verdict(r.gamma_pred, c.detect);
  // "late growth": no qualifying window, but after the bottom of the XSPH-damped transient log KE rises steadily
  // (fit r^2 > 0.9) by more than a factor 3 -- a growth too slow to reach the onset within the run.
  const bool late = !fit.grew && fit.gamma_late > 0 && fit.late.r2 > 0.9 && fit.late_ratio > 3;
  if (r.run.blew_up())
    r.run_verdict = "blow-up";
  else
    r.run_verdict = fit.grew ? "growth" : (late ? "late growth" : "bounded");
  const bool lin_unstable = r.lin_verdict == "unstable";
  const bool run_unstable = r.run_verdict != "bounded";
  if (late && r.gamma_pred > 0) r.ratio = fit.gamma_late / r.gamma_pred;
  if (r.lin_verdict == "n/a" || r.lin_verdict == "switching surface")
    r.agreement = "n/a";
  else if (r.lin_verdict == "weakly unstable")
    r.agreement = run_unstable ? "agree" : "below detection";
  else
    r.agreement = lin_unstable == run_unstable
                      ? "agree"
                      : (run_unstable ? "run grows, linear stable" : "linear unstable, run bounded");
  r.k_mode = mode_k(r.lin.mode, scene);
  const Eigen::VectorXd& ur =
      r.run.u_linear.size() && r.run.u_linear.cwiseAbs().maxCoeff() > 0 ? r.run.u_linear : r.run.u_end;
  r.k_run = mode_k(ur, scene);
  // Mode snapshots: every disagreement, and the tension/compression extremes of formulations whose excited
  // class is linearly unstable there (run displacement in the linear regime next to the linear mode).
  const bool key = f.name == "sph" || f.name == "ncsph" || f.name == "cij" || f.name == "conservative";
  const bool extreme = key && (xi == c.xis.front() || xi == c.xis.back()) && r.lin.gamma_exc > 1e-3;
  if ((r.agreement != "agree" && r.agreement != "n/a") || extreme) {
    char tag[64];
    std::snprintf(tag, sizeof(tag), "%s_xi%.2f", f.name.c_str(), xi);
    if (ur.size() && ur.cwiseAbs().maxCoeff() > 0)
      write_mode_vtp(c.out + "/modes/" + tag + "_run.vtp", scene, ur, "displacement");
    if (r.lin.mode.size()) write_mode_vtp(c.out + "/modes/" + tag + "_linear.vtp", scene, r.lin.mode, "mode");
  }
  // KE series (every 4th sample, 20 steps = 0.13 us, keeps the file small; the fit used all of them)
  for (std::size_t k = 0; k < r.run.t.size(); k += 4)
    ke_csv.row({f.name, xi, r.run.t[k], r.run.kinetic[k], r.run.max_displacement[k]});
  r.wall = study::seconds_since(t0);
  std::printf("%s %-15s xi = %.2f: %-9s t = %6.3g  gamma meas %-8s pred %-8s ratio %-6s (%s; %.1f s)\n",
              progress.c_str(), f.name.c_str(), xi, r.run_verdict.c_str(), r.run.t_stop,
              sig(late ? fit.gamma_late : fit.gamma, 4).c_str(), sig(r.gamma_pred, 4).c_str(), sig(r.ratio, 3).c_str(),
              r.agreement.c_str(), r.wall);
  std::fflush(stdout);
  return r;
}

void write_runs_csv(const std::string& path, const std::vector<Row>& rows) {
  // clang-format off
  CsvWriter csv(path, {"formulation", "xsph", "xi", "prestrain", "sigma0", "a0_max", "in_equilibrium", "status",
                       "t_stop", "steps", "dt", "t_linear_end", "grew", "gamma_measured", "fit_t_begin", "fit_t_end",
                       "fit_r2", "ke_max_ratio", "gamma_bound", "gamma_late", "late_r2", "late_ratio",
                       "gamma_linear_all", "gamma_linear_excited", "mu_excited_re", "mu_excited_im", "gamma_map",
                       "gamma_predicted", "ratio", "linear_verdict", "run_verdict", "agreement", "verdict",
                       "verdict_gamma_j", "verdict_gamma_m", "commutation_error",
                       "asymmetry", "colours", "mode_kx", "mode_ky", "run_kx", "run_ky", "run_k_peak_fraction",
                       "run_x_share", "max_abs_ustar_over_dx", "wall_seconds"});
  for (const Row& r : rows)
    csv.row({r.form, r.xsph ? 1 : 0, r.xi, r.strain, r.sigma0, r.a0, r.equilibrium ? 1 : 0,
             run_status_name(r.run.status), r.run.t_stop, r.run.steps, r.run.dt, r.run.t_linear_end,
             r.run.fit.grew ? 1 : 0, r.run.fit.gamma, r.run.fit.fit.t_begin, r.run.fit.fit.t_end, r.run.fit.fit.r2,
             r.run.fit.max_ratio, r.run.fit.gamma_bound, r.run.fit.gamma_late, r.run.fit.late.r2, r.run.fit.late_ratio,
             r.lin.gamma_all, r.lin.gamma_exc, r.lin.mu_exc.real(), r.lin.mu_exc.imag(), r.lin.gamma_map,
             r.gamma_pred, r.ratio, r.lin_verdict, r.run_verdict, r.agreement, r.verdict, r.gamma_j, r.gamma_m,
             r.lin.commutation, r.lin.asymmetry,
             r.lin.colours, r.k_mode.kx, r.k_mode.ky, r.k_run.kx, r.k_run.ky, r.k_run.peak, r.k_run.x_share, r.ustar,
             r.wall});
  // clang-format on
}

/// Every (formulation, xi) run; writes ke.csv, equilibrium.csv, runs.csv and modes/.
std::vector<Row> run_2d(const std::vector<Formulation>& forms, const Config& c, const Classes& classes, double dt) {
  CsvWriter ke_csv(c.out + "/ke.csv", {"formulation", "xi", "t", "kinetic", "max_abs_u"});
  CsvWriter eq_csv(c.out + "/equilibrium.csv",
                   {"formulation", "xi", "a0_max", "newton", "iterations", "residual", "max_abs_ustar_over_dx",
                    "gamma_exc_lattice", "gamma_exc_ustar", "gamma_map_ustar", "gamma_all_ustar"});
  std::vector<Row> rows;
  const int total = static_cast<int>(forms.size() * c.xis.size());
  char progress[32];
  for (const Formulation& f : forms)
    for (double xi : c.xis) {
      std::snprintf(progress, sizeof progress, "[%2d/%2d]", static_cast<int>(rows.size()) + 1, total);
      rows.push_back(run_2d_case(f, xi, c, classes, dt, ke_csv, eq_csv, progress));
    }
  write_runs_csv(c.out + "/runs.csv", rows);
  return rows;
}

// ------------------------------------------------------------------------------------------- energy conservation

struct EnergyRow {
  std::string form;
  double dt;
  long steps;
  double max_dev, end_drift, slope_drift, wall;
};

/// Conservative form (and TL, linear) at xi = 1 (stable), a finite kick v0 = 0.01 cm/us so that the kernel really
/// moves (max |u| ~ 1e-2 dx); T = energy_steps * dt0 at dt0 (CFL 0.3), 2 dt0, dt0/2. Writes energy_series.csv and
/// energy.csv.
std::vector<EnergyRow> energy_conservation(const Config& c, double dt) {
  std::cout << "energy conservation: " << c.energy_steps << " steps at the CFL step, plus 2 dt and dt/2\n";
  std::vector<EnergyRow> energy;
  CsvWriter series(c.out + "/energy_series.csv", {"formulation", "dt", "t", "relative_energy_error"});
  const SwegleScene es = make_swegle_scene({.area_ratio = 1.0, .velocity = 0.01});
  const double T = c.energy_steps * dt;
  for (std::string name : {"conservative", "tl"}) {
    std::shared_ptr<ForceFunction> force;
    if (name == "conservative")
      force = std::make_shared<ElasticForm2D>(es.discretisation, es.material, MomentumForm::Conservative, es.prestrain);
    else
      force = std::make_shared<TotalLagrangianForm2D>(es.discretisation, es.material, es.prestrain);
    for (double h : {2 * dt, dt, dt / 2}) {
      const auto t0 = study::Clock::now();
      SecondOrderSystem sys;
      sys.acceleration = acceleration_function(force);
      sys.strain_energy = [force](const Eigen::VectorXd& u) { return force->strain_energy(u); };
      sys.dofs_per_particle = 2;
      sys.mass = es.material.rho * es.discretisation->particles.volume.head(es.discretisation->free_count());
      LeapfrogOptions o;
      o.dt = h;
      o.t_end = T;
      o.record_every = std::max<long>(1, static_cast<long>(std::llround(T / h)) / 1000);
      ProgressReport progress("energy " + name);
      o.observers = {&progress};
      const LeapfrogResult rr = run_leapfrog(sys, Eigen::VectorXd::Zero(force->dofs()), es.v0, o);
      const double e0 = rr.history.front().total;
      double dev = 0, st = 0, se = 0, stt = 0, ste = 0;
      for (const Diagnostics& d : rr.history) {
        const double e = (d.total - e0) / e0;
        dev = std::max(dev, std::abs(e));
        st += d.time, se += e, stt += d.time * d.time, ste += d.time * e;
        if (name == "conservative") series.row({name, h, d.time, e});
      }
      const double n = static_cast<double>(rr.history.size());
      const double slope = (ste / n - st / n * se / n) / (stt / n - st / n * st / n);
      energy.push_back(
          {name, h, rr.steps, dev, (rr.history.back().total - e0) / e0, slope * T, study::seconds_since(t0)});
      std::printf("  %-12s dt = %.4g (%ld steps): max |dE|/E0 = %.3e, end %.3e, fitted drift over T %.3e (%.1f s)\n",
                  name.c_str(), h, rr.steps, dev, energy.back().end_drift, energy.back().slope_drift,
                  energy.back().wall);
    }
  }
  CsvWriter csv(c.out + "/energy.csv", {"formulation", "dt", "steps", "max_rel_energy_error", "end_rel_energy_error",
                                        "fitted_drift_over_T", "wall_seconds"});
  for (const EnergyRow& e : energy) csv.row({e.form, e.dt, e.steps, e.max_dev, e.end_drift, e.slope_drift, e.wall});
  return energy;
}

// ------------------------------------------------------------------------------------------------------------ 1D
// WaveForm1D (u_tt = (u_x + T)_x, c = E = rho = 1, dx = 1), pre-strain T = xi - 1, centre particle kicked.

struct Row1D {
  std::string form;
  double T = 0;
  double gamma_cs = kNaN, gamma_analytic = kNaN, gamma_exc = kNaN;
  GrowthRun run;
  double ratio = kNaN;
  std::string lin_verdict, run_verdict;
  WavenumberEstimate k_mode;
};

/// The 1D version: every momentum form and the corrected kernels of the 2D study, 21 free particles, T = xi - 1;
/// writes onedim_ke.csv and onedim_runs.csv.
std::vector<Row1D> run_1d(const Config& c) {
  std::cout << "1D: WaveForm1D, 21 free particles, T = xi - 1\n";
  std::vector<Row1D> rows1;
  Kernel<1> k(KernelType::CubicSpline);
  const double h = 1.3;
  auto set = make_lattice<1>(LatticeType::Line, 21, {.spacing = 1.0, .support_radius = k.support_radius(h)});
  auto disc = make_discretisation(set, k, h);
  const int centre = 10;
  Eigen::VectorXd v0 = Eigen::VectorXd::Zero(disc->dofs());
  v0[centre] = 1e-10;
  // Excited class: reflection about the centre, (T f)_i = -f_{20 - i}; the kick has T v0 = -v0.
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(21, 11);
  for (int i = 0; i <= 10; ++i) {
    Q(i, i) = 1;
    Q(20 - i, i) = 1;  // T f = -f  <=>  f_{20-i} = f_i
    Q.col(i).normalize();
  }
  const Eigen::VectorXd x1 = disc->free_positions().col(0);
  CsvWriter ke1(c.out + "/onedim_ke.csv", {"form", "T", "t", "kinetic"});
  const double detect1 = std::log(c.onset) / (2 * c.t_end_1d);
  // The four momentum forms (analytic Jacobian of Powell 3.40 available) and the corrected kernels of the 2D study.
  struct Form1D {
    std::string name;
    MomentumForm form;
    std::shared_ptr<const GradientProvider<1>> provider;
    CorrectedOperator corrected;
  };
  std::vector<Form1D> forms1;
  for (MomentumForm form : all_momentum_forms())
    forms1.push_back({momentum_form_name(form), form, nullptr, CorrectedOperator::Auto});
  forms1.push_back(
      {"ncsph", MomentumForm::Plus, make_gradient_provider<1>(Correction::Ncsph), CorrectedOperator::Both});
  forms1.push_back({"cij", MomentumForm::Uncorrected,
                    make_gradient_provider<1>(Correction::LocalPolish, {.counting = NeighbourCounting::BoundaryLevel,
                                                                        .first_step_shepard = true}),
                    CorrectedOperator::Divergence});
  for (const Form1D& f1 : forms1)
    for (double xi : c.xis) {
      Row1D r{.form = f1.name, .T = xi - 1};
      auto force =
          std::make_shared<WaveForm1D>(disc, f1.form, r.T, f1.provider, WaveForm1DOptions{.corrected = f1.corrected});
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(force->dofs());
      const Eigen::MatrixXd A(jacobian(*force, zero));
      r.gamma_cs = matrix_growth(A).gamma;
      if (!f1.provider)
        r.gamma_analytic = matrix_growth(Eigen::MatrixXd(analytic_jacobian_1d(set, k, h, f1.form).at(r.T))).gamma;
      const LinearGrowth ge = matrix_growth(Q.transpose() * A * Q, true);
      r.gamma_exc = ge.gamma;
      if (ge.mode.size()) r.k_mode = dominant_wavenumber(Q * ge.mode, x1, false);
      GrowthRunOptions o;
      o.dt = 0.3 * h;  // c = 1
      o.t_end = c.t_end_1d;
      o.displacement_limit = 0.1;
      o.linear_limit = 1e-3;
      o.record_every = 2;
      r.run = run_growth_test<1>(disc, force, Eigen::VectorXd(), v0, o);
      if (r.run.fit.grew && r.gamma_exc > 0) r.ratio = r.run.fit.gamma / r.gamma_exc;
      r.lin_verdict = linear_verdict(r.gamma_exc, detect1);
      r.run_verdict = r.run.blew_up() ? "blow-up" : (r.run.fit.grew ? "growth" : "bounded");
      for (std::size_t q = 0; q < r.run.t.size(); q += 4) ke1.row({r.form, r.T, r.run.t[q], r.run.kinetic[q]});
      std::printf("  1D %-12s T = %+.2f: %-8s gamma meas %-8s pred %-8s (cs %s, analytic %s) ratio %s\n",
                  r.form.c_str(), r.T, r.run_verdict.c_str(), sig(r.run.fit.gamma, 4).c_str(),
                  sig(r.gamma_exc, 4).c_str(), sig(r.gamma_cs, 4).c_str(), sig(r.gamma_analytic, 4).c_str(),
                  sig(r.ratio, 3).c_str());
      rows1.push_back(std::move(r));
    }
  CsvWriter csv(c.out + "/onedim_runs.csv", {"form", "T", "status", "t_stop", "grew", "gamma_measured", "fit_r2",
                                             "gamma_linear_all_cs", "gamma_linear_all_analytic", "gamma_linear_excited",
                                             "ratio", "linear_verdict", "run_verdict", "mode_k_dx_over_pi"});
  for (const Row1D& r : rows1)
    csv.row({r.form, r.T, run_status_name(r.run.status), r.run.t_stop, r.run.fit.grew ? 1 : 0, r.run.fit.gamma,
             r.run.fit.fit.r2, r.gamma_cs, r.gamma_analytic, r.gamma_exc, r.ratio, r.lin_verdict, r.run_verdict,
             r.k_mode.k_projection});
  return rows1;
}

// ------------------------------------------------------------------------------------------------ summary.json
// Key numbers and computed Markdown tables/lists for summary.md.in (the prose lives there).

const Row* find_row(const std::vector<Row>& rows, const std::string& form, double xi) {
  for (const Row& r : rows)
    if (r.form == form && std::abs(r.xi - xi) < 1e-12) return &r;
  return nullptr;
}

/// Header of a Markdown table with one column per label.
std::string table_header(const std::string& first, const std::vector<std::string>& labels) {
  std::string s = "| " + first + " |", rule = "|---|";
  for (const std::string& l : labels) s += " " + l + " |", rule += "---|";
  return s + "\n" + rule;
}

std::string xi_label(double xi) { return "xi = " + sig(xi, 6); }

/// Stable/unstable table, linear-versus-nonlinear table and the ratio range of the 2D runs.
void summarise_2d_tables(study::Summary& s, const std::vector<Row>& rows, const std::vector<Formulation>& forms,
                         const Config& c) {
  std::vector<std::string> labels;
  for (double xi : c.xis) labels.push_back(xi_label(xi));
  std::string stable = table_header("formulation", labels), linear = stable;
  for (const Formulation& f : forms) {
    stable += "\n| " + f.name + " |";
    linear += "\n| " + f.name + " |";
    for (double xi : c.xis) {
      const Row* r = find_row(rows, f.name, xi);
      std::string cell, lin;
      if (r) {
        const bool late = r->run_verdict == "late growth";
        // Class, gamma_J / gamma_M, then the run: its measured rate, "late" growth, a blow-up without a fitted
        // window, or "–" (bounded).
        cell = (r->verdict == "S" || r->verdict == "n/a" ? r->verdict : "**" + r->verdict + "**") + " " +
               sig(std::max(r->gamma_j, 0.0), 2) + " / " + sig(std::max(r->gamma_m, 0.0), 2) + " · ";
        if (r->run.fit.grew)
          cell += sig(r->run.fit.gamma, 2);
        else if (late)
          cell += "late " + sig(r->run.fit.gamma_late, 2);
        else if (r->run.blew_up())
          cell += "blow-up";
        else
          cell += "–";
        if (r->run.blew_up()) cell += " (t " + sig(r->run.t_stop) + ")";
        lin = sig(r->gamma_pred) + " / " + sig(late ? r->run.fit.gamma_late : r->run.fit.gamma) +
              (late ? " late" : "") + " (" + sig(r->ratio) + ")";
      }
      stable += " " + cell + " |";
      linear += " " + lin + " |";
    }
  }
  s.set("stability_table", stable);
  s.set("linear_table", linear);
  double rmin = 1e300, rmax = 0;
  int nratio = 0;
  for (const Row& r : rows)
    if (!std::isnan(r.ratio) && r.equilibrium && r.run.fit.grew && !(r.switching && r.sigma0 == 0)) {
      rmin = std::min(rmin, r.ratio);
      rmax = std::max(rmax, r.ratio);
      ++nratio;
    }
  s.set("ratio_count", nratio), s.set("ratio_min", rmin, 4), s.set("ratio_max", rmax, 4);
}

/// Lists of the runs where linear theory and the run disagree, are below detection or are not comparable; the
/// dominant-wavevector table; the equilibrium of the S-SPH runs out of equilibrium.
void summarise_2d_lists(study::Summary& s, const std::vector<Row>& rows, const Config& c) {
  auto describe = [&](const Row& r) {
    std::ostringstream o;
    o << r.form << ", xi = " << r.xi << ": gamma_pred " << sig(r.gamma_pred) << " (without XSPH: excited class "
      << sig(r.lin.gamma_exc) << ", all classes " << sig(r.lin.gamma_all) << "); run " << r.run_verdict
      << ", KE max/KE0 " << sig(r.run.fit.max_ratio) << "; dominant wavevector k dx/pi of the run (" << sig(r.k_run.kx)
      << ", " << sig(r.k_run.ky) << "), component " << r.k_run.component() << ", of the linear mode ("
      << sig(r.k_mode.kx) << ", " << sig(r.k_mode.ky) << "); snapshots `modes/" << r.form << "_xi" << std::fixed
      << std::setprecision(2) << r.xi << "_{run,linear}.vtp`";
    return o.str();
  };
  std::string disagree, weak, na, k_rows, eq;
  auto add = [](std::string& list, const std::string& item) { list += (list.empty() ? "- " : "\n- ") + item; };
  for (const Row& r : rows) {
    if (r.agreement == "run grows, linear stable" || r.agreement == "linear unstable, run bounded")
      add(disagree, "[" + r.agreement + "] " + describe(r));
    if (r.agreement == "below detection") add(weak, describe(r));
    if (r.agreement == "n/a")
      add(na, r.form + ", xi = " + sig(r.xi, 6) + ": run " + r.run_verdict +
                  (r.run.fit.grew ? " (gamma " + sig(r.run.fit.gamma) + ")" : std::string()));
    if (r.run_verdict != "bounded" && (r.xi == c.xis.front() || r.xi == c.xis.back()))
      k_rows += "\n| " + r.form + " | " + sig(r.xi, 6) + " | (" + sig(r.k_run.kx) + ", " + sig(r.k_run.ky) + "), " +
                r.k_run.component() + ", " + sig(r.k_run.peak, 2) + " | (" + sig(r.k_mode.kx) + ", " +
                sig(r.k_mode.ky) + "), " + r.k_mode.component() + " |";
    if (!r.equilibrium)
      add(eq, r.form + ", xi = " + sig(r.xi, 6) + ": |a(0)|max = " + sig(r.a0) +
                  " cm/us^2 at the pre-strained lattice; Newton: " + r.newton +
                  (std::isnan(r.ustar) ? std::string()
                                       : ", max |u*| = " + sig(r.ustar) + " dx, gamma at u*: excited " +
                                             sig(r.lin_star.gamma_exc) + ", with XSPH map " +
                                             sig(r.lin_star.gamma_map) + ", all classes " + sig(r.lin_star.gamma_all)) +
                  "; linear at the lattice: excited " + sig(r.lin.gamma_exc));
  }
  s.set("disagreements", disagree.empty() ? "- none" : disagree);
  s.set("below_detection", weak.empty() ? "- none" : weak);
  s.set("not_comparable", na.empty() ? "- none" : na);
  s.set("wavevector_table",
        "| formulation | xi | run (kx, ky), component, peak | linear mode (kx, ky), component |\n"
        "|---|---|---|---|" +
            k_rows);
  s.set("ssph_equilibrium", eq.empty() ? "- none" : eq);
}

/// Energy table and convergence orders; the 1D table.
void summarise_energy_1d(study::Summary& s, const std::vector<EnergyRow>& energy, const std::vector<Row1D>& rows1,
                         const Config& c) {
  std::string rows;
  for (const EnergyRow& e : energy)
    rows += (rows.empty() ? "| " : "\n| ") + e.form + " | " + sig(e.dt, 4) + " | " + std::to_string(e.steps) + " | " +
            sig(e.max_dev) + " | " + sig(e.end_drift) + " | " + sig(e.slope_drift) + " |";
  s.set("energy_rows", rows);
  for (std::string name : {"conservative", "tl"}) {
    std::vector<const EnergyRow*> es;
    for (const EnergyRow& e : energy)
      if (e.form == name) es.push_back(&e);  // 2 dt, dt, dt/2
    s.set("energy_" + name + "_ratio_2dt", es[0]->max_dev / es[1]->max_dev, 4);
    s.set("energy_" + name + "_ratio_dt", es[1]->max_dev / es[2]->max_dev, 4);
    s.set("energy_" + name + "_order", std::log2(es[1]->max_dev / es[2]->max_dev), 3);
  }
  double m = 0;
  for (const Row1D& r : rows1)
    if (r.gamma_analytic > 0) m = std::max(m, std::abs(r.gamma_cs / r.gamma_analytic - 1));
  s.set("onedim_cs_vs_analytic", m, 2);
  s.set("t_end_1d", c.t_end_1d, 6);
  std::vector<std::string> labels, names;
  for (double xi : c.xis) labels.push_back("T = " + sig(xi - 1, 2));
  for (const Row1D& r : rows1)
    if (std::find(names.begin(), names.end(), r.form) == names.end()) names.push_back(r.form);
  std::string table = table_header("form", labels);
  for (const std::string& name : names) {
    table += "\n| " + name + " |";
    for (const Row1D& r : rows1)
      if (r.form == name)
        table += std::string(" ") + (r.run_verdict == "bounded" ? "S" : "**U**") + " " + sig(r.run.fit.gamma) + " / " +
                 sig(r.gamma_exc) + " |";
  }
  s.set("onedim_table", table);
}

/// The numbers and verdicts of the comparison with [Powell2012, ch. 4 §2.2-2.3, Fig. 4.2].
void summarise_powell(study::Summary& s, const std::vector<Row>& rows, const Config& c) {
  struct Side {  // one formulation over tension (xi > 1) or compression (xi < 1)
    int runs = 0, unstable = 0;
    double gmax = 0;
    std::string list;
  };
  auto side = [&](const std::string& form, bool tension) {
    Side sd;
    for (const Row& r : rows)
      if (r.form == form && (tension ? r.xi > 1 : r.xi < 1)) {
        ++sd.runs;
        if (r.run_verdict != "bounded") {
          ++sd.unstable;
          sd.list += (sd.list.empty() ? "" : ", ") + sig(r.xi, 3);
          if (r.run.fit.grew) sd.gmax = std::max(sd.gmax, r.run.fit.gamma);
        }
      }
    return sd;
  };
  auto grow = [](const Side& sd, bool tension) {
    return std::to_string(sd.unstable) + " of " + std::to_string(sd.runs) + (tension ? " tension" : " compression") +
           " runs grow";
  };
  auto fastest = [](const Side& sd) { return sd.gmax > 0 ? ", fastest gamma " + sig(sd.gmax) + "/us" : ""; };
  // "**agrees**" etc. with Powell's claim that the runs are unstable (claim_unstable) or stable, and the counts.
  auto verdict = [&](const std::string& form, bool tension, bool claim_unstable) -> std::string {
    const Side sd = side(form, tension);
    if (sd.runs == 0) return "not run";
    const bool all = sd.unstable == sd.runs, none = sd.unstable == 0;
    return std::string(claim_unstable ? (all ? "**agrees**" : (none ? "**disagrees**" : "**partly agrees**"))
                                      : (none ? "**agrees**" : (all ? "**disagrees**" : "**partly agrees**"))) +
           " (" + grow(sd, tension) + (sd.list.empty() ? "" : ": xi = " + sd.list) + fastest(sd) + ")";
  };
  auto counts = [&](const std::string& form, bool tension) -> std::string {
    const Side sd = side(form, tension);
    if (sd.runs == 0) return "not run";
    return grow(sd, tension) + (sd.list.empty() ? "" : " (xi = " + sd.list + ")") + fastest(sd);
  };
  auto k_of = [&](const std::string& form, double xi) -> std::string {
    const Row* r = find_row(rows, form, xi);
    if (!r || std::isnan(r->k_run.kx)) return "-";
    return "(" + sig(r->k_run.kx, 2) + ", " + sig(r->k_run.ky, 2) + ") " + r->k_run.component() + "-component";
  };
  auto ratio_of = [&](const std::string& a, const std::string& b, double xi) {
    const Row *ra = find_row(rows, a, xi), *rb = find_row(rows, b, xi);
    return ra && rb && ra->run.fit.grew && rb->run.fit.grew ? ra->run.fit.gamma / rb->run.fit.gamma : kNaN;
  };
  const double lo = c.xis.front(), hi = c.xis.back();
  s.set("xi_min", lo, 6), s.set("xi_max", hi, 6);
  s.set("powell_sph_tension", verdict("sph", true, true)), s.set("powell_sph_compression", counts("sph", false));
  s.set("k_sph_xi_max", k_of("sph", hi)), s.set("k_sph_xi_min", k_of("sph", lo));
  s.set("powell_ncsph_tension", verdict("ncsph", true, true));
  s.set("powell_ncsph_compression", counts("ncsph", false));
  s.set("powell_cij_tension", verdict("cij", true, false)),
      s.set("powell_cij_compression", verdict("cij", false, true));
  s.set("powell_sph-xsph_tension", verdict("sph-xsph", true, true));
  s.set("xsph_over_sph_1.01", ratio_of("sph-xsph", "sph", 1.01)),
      s.set("xsph_over_sph_1.04", ratio_of("sph-xsph", "sph", 1.04));
  s.set("powell_tl_tension", counts("tl", true)), s.set("powell_tl_compression", counts("tl", false));
  s.set("powell_ssph_tension", verdict("ssph", true, false));
  s.set("powell_ssph_compression", verdict("ssph", false, false));
  s.set("powell_ssph-pp_tension", verdict("ssph-pp", true, false));
  s.set("powell_ssph-pp_compression", verdict("ssph-pp", false, false));
  s.set("powell_ssph-printed_tension", counts("ssph-printed", true));
  s.set("powell_ssph-printed_compression", counts("ssph-printed", false));
  s.set("powell_sph-gms_tension", counts("sph-gms", true));
  s.set("gms_over_sph_1.04", ratio_of("sph-gms", "sph", 1.04)), s.set("k_sph-gms_xi_max", k_of("sph-gms", hi));
  const Row* gms1 = find_row(rows, "sph-gms", 1.0);
  s.set("sph-gms_xi1_run", gms1 ? gms1->run_verdict : std::string("-"));
}

}  // namespace

int main(int argc, char** argv) {
  // Force evaluations allocate and free operator matrices every step; keep glibc from returning (and re-faulting)
  // those pages each time (as in benchmarks/jacobian_benchmark.cpp). Affects speed only.
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);

  CLI::App app{"Swegle test (Powell ch. 4 Fig. 4.1/4.2): every formulation, linear vs nonlinear growth"};
  Config c;
  app.add_option("--out", c.out, "output directory");
  app.add_option("--t-end", c.t_end, "2D run length (us)")->check(CLI::PositiveNumber);
  app.add_option("--t-end-1d", c.t_end_1d, "1D run length (dx / c)")->check(CLI::PositiveNumber);
  app.add_option("--xi", c.xis, "volume strains xi = V/V0");
  app.add_option("--forms", c.only, "formulations to run (default: all available)");
  app.add_option("--energy-steps", c.energy_steps, "steps of the energy-conservation run at the CFL step")
      ->check(CLI::PositiveNumber);
  app.add_option("--record-every", c.record_every, "kinetic-energy sample interval (steps)")
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  for (double xi : c.xis)
    if (!(xi > 0)) {
      std::cerr << "study_swegle: xi must be > 0 (got " << xi << ")\n";
      return 2;
    }
  std::filesystem::create_directories(c.out + "/modes");
  const auto wall0 = study::Clock::now();
  c.detect = std::log(c.onset) / (2 * c.t_end);

  std::vector<Formulation> forms;
  for (const Formulation& f : formulations())
    if (c.only.empty() || std::find(c.only.begin(), c.only.end(), f.name) != c.only.end()) forms.push_back(f);
  const SwegleScene base = make_swegle_scene({});
  const Classes classes = make_classes(base);
  const double dx = base.options.spacing, dt = 0.3 * base.h / base.wave_speed;
  std::cout << "Swegle block: " << base.options.n << " x " << base.options.n << " free particles + "
            << fixed_layers_needed(base.discretisation->kernel.support_radius(base.h), dx)
            << " fixed layers, dx = " << dx << " cm, h = 1.3 dx, dt = " << dt << " us, t_end = " << c.t_end
            << " us; excited class (px, py) = (" << classes.mirror.parity[classes.mirror.excited].first << ", "
            << classes.mirror.parity[classes.mirror.excited].second << ")\n";
  const std::vector<Row> rows = run_2d(forms, c, classes, dt);
  const double wall_2d = study::seconds_since(wall0);
  const std::vector<EnergyRow> energy = energy_conservation(c, dt);
  const std::vector<Row1D> rows1 = run_1d(c);
  const double wall_total = study::seconds_since(wall0);

  study::Summary s;
  s.set("lambda", base.material.lambda, 5), s.set("mu", base.material.mu, 5), s.set("c_P", base.wave_speed, 5);
  std::string xis;
  for (double xi : c.xis) xis += (xis.empty() ? "" : ", ") + sig(xi, 6);
  s.set("xi_list", xis);
  s.set("sigma0_xi_max", make_swegle_scene({.area_ratio = c.xis.back()}).prestrain.stress(base.material)(0, 0), 3);
  s.set("ke0", base.initial_kinetic_energy(), 3);
  s.set("dt", dt, 4), s.set("t_end", c.t_end, 6), s.set("steps", static_cast<long>(std::ceil(c.t_end / dt)));
  s.set("record_every", c.record_every), s.set("onset", c.onset, 6), s.set("detect", c.detect, 3);
  double commutation = 0;
  for (const Row& r : rows) commutation = std::max(commutation, r.lin.commutation);
  s.set("commutation_max", commutation, 2);
  s.set("wall_2d", wall_2d, 3), s.set("wall_rest", wall_total - wall_2d, 3), s.set("wall_total", wall_total, 3);
  summarise_2d_tables(s, rows, forms, c);
  summarise_2d_lists(s, rows, c);
  summarise_energy_1d(s, energy, rows1, c);
  summarise_powell(s, rows, c);
  s.write(c.out);
  std::cout << "wrote " << c.out << "/summary.json; total " << sig(wall_total) << " s\n";
  return 0;
}
