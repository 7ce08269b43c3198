// Turek & Hron (2006) CSM3: the elastic beam clamped to a rigid cylinder, oscillating under gravity from rest, with
// finite-strain total-Lagrangian SPH (St Venant-Kirchhoff, plane strain) plus a constant body force
// (forms/body_force.hpp). Geometry and reference: problems/turek_hron_csm3.hpp. Forms (--gradient):
//   ncsph-variational  forms/variational_total_lagrangian.hpp with the NCSPH reference gradient (M a = -dU/du);
//   plain              forms/finite_strain_total_lagrangian.hpp, plain G, difference strain, plus divergence;
//   ncsph              the same with the NCSPH strain gradient (its divergence stays the plain G).
// Runs: the chosen form at the resolutions --across (the last three give the observed order), the two other forms
// and a 1 dx clamp at the coarsest one. Leap-frog at --cfl of the stability limit of the linearisation at rest.
// The displacement of A = (0.6, 0.2) is extrapolated linearly to x = 0.6 from the means of the two tip columns'
// particles nearest y = 0.2: u_A = 1.5 u(col 0) - 0.5 u(col 1). Mean = (max + min) / 2 and amplitude
// = (max - min) / 2 over the window t >= --t-measure, frequency = 1 / period from the zero crossings of u - mean.
// Writes to --out DIR: tip_<run>.csv, table.csv, runs.csv, snapshot.csv (finest run, largest deflection of the last
// period), summary.json.
#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <numbers>
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
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"
#include "sphstab/problems/cantilever_plate.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

using namespace sphstab;
namespace fs = std::filesystem;
using C = TurekHronCsm3;

namespace {

struct RunSpec {
  int across;
  std::string gradient;  ///< "ncsph" or "plain"
  int clamp_layers;
  std::string name() const {
    return "n" + std::to_string(across) + "-" + gradient + "-clamp" + std::to_string(clamp_layers);
  }
};

struct Measure {
  double mean = NAN, amplitude = NAN, frequency = NAN;
  double last_mean = NAN, last_amplitude = NAN;  ///< over the last full period only
  int half_cycles = 0;
};

/// Mean, amplitude over t >= t0 and the frequency from the zero crossings of y - mean; the last full period is the
/// interval between the last two crossings of the same direction.
Measure measure(const std::vector<double>& t, const std::vector<double>& y, double t0) {
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

/// Observed order p of three values at spacings h1 > h2 > h3: (f1 - f2) / (f2 - f3) = (h1^p - h2^p) / (h2^p - h3^p),
/// by bisection on p in [0.05, 8]; NaN when the differences change sign (no monotone convergence) or no root lies
/// there.
double observed_order(double h1, double h2, double h3, double f1, double f2, double f3) {
  const double r = (f1 - f2) / (f2 - f3);
  if (!(r > 0) || !std::isfinite(r)) return NAN;
  auto g = [&](double p) { return (std::pow(h1, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h3, p)) - r; };
  double a = 0.05, b = 8;
  if (g(a) * g(b) > 0) return NAN;
  for (int it = 0; it < 100; ++it) {
    const double c = 0.5 * (a + b);
    (g(a) * g(c) <= 0 ? b : a) = c;
  }
  return 0.5 * (a + b);
}

struct CaseResult {
  RunSpec spec;
  int particles = 0, free = 0, clamp = 0;
  double dx = 0, dt = 0, dt_limit = 0, wall = 0, energy_drift = 0;
  double f_linear = NAN;  ///< lowest eigenfrequency of the linearisation at rest (Hz); NaN when not computed
  double growth = NAN;    ///< max Re sqrt(-mu), mu in eig(A), A = -da/du at rest (1/s); NaN when not computed
  long steps = 0;
  std::string status = "completed";
  Measure ux, uy;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Turek & Hron CSM3: elastic beam under gravity, finite-strain TL SPH (St Venant-Kirchhoff)"};
  std::string out = "results/tl-csm3", gradient = "ncsph-variational", divergence = "plus";
  std::vector<int> across{4, 8, 12, 16};
  double t_end = 6, t_measure = 2, cfl = 0.8, h_over_dx = 1.5;
  int clamp_layers = 4, wide_clamp = 1;
  app.add_option("--out", out, "output directory");
  app.add_option("--across", across, "particles through the thickness, coarsest first (the last three give the order)");
  app.add_option(
         "--gradient", gradient,
         "strain gradient and form: ncsph-variational, plain or ncsph (the latter two: FiniteStrainTotalLagrangian)")
      ->check(CLI::IsMember({"ncsph", "plain", "ncsph-variational"}));
  app.add_option("--divergence", divergence, "stress divergence: plus, minus or plain")
      ->check(CLI::IsMember({"plus", "minus", "plain"}));
  app.add_option("--t-end", t_end, "physical time (s)")->check(CLI::PositiveNumber);
  app.add_option("--t-measure", t_measure, "start of the measuring window (s)")->check(CLI::NonNegativeNumber);
  app.add_option("--cfl", cfl, "fraction of the leap-frog limit")->check(CLI::Range(0.05, 0.9));
  app.add_option("--h", h_over_dx, "h / dx (Wendland C2, support 2h)")->check(CLI::Range(1.0, 3.0));
  app.add_option("--clamp", clamp_layers, "clamp width in dx")->check(CLI::Range(1, 20));
  app.add_option("--clamp-sensitivity", wide_clamp, "clamp width of the sensitivity run at the coarsest resolution")
      ->check(CLI::Range(1, 20));
  CLI11_PARSE(app, argc, argv);
  if (across.empty()) throw std::invalid_argument("tl-csm3: --across needs at least one resolution");
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  std::vector<std::string> others;
  for (const std::string g : {"plain", "ncsph", "ncsph-variational"})
    if (g != gradient) others.push_back(g);
  const std::string other = others[0] + " and " + others[1];
  std::vector<RunSpec> specs;
  for (int n : across) specs.push_back({n, gradient, clamp_layers});
  for (const std::string& g : others) specs.push_back({across.front(), g, clamp_layers});
  specs.push_back({across.front(), gradient, wide_clamp});

  const LameParameters lame{.lambda = 2 * C::shear_modulus * C::poisson / (1 - 2 * C::poisson), .mu = C::shear_modulus};
  auto svk = std::make_shared<StVenantKirchhoff<2>>(lame);
  const Kernel<2> kernel(KernelType::WendlandC2);
  std::vector<CaseResult> results;
  Eigen::MatrixXd snapshot_x;  // finest chosen run: x + u, sigma (Cauchy) at the largest deflection of the last period
  Eigen::MatrixXd snapshot_sigma;
  double snapshot_t = NAN, snapshot_uy = 1e300;
  for (const RunSpec& spec : specs) {
    const auto tr = study::Clock::now();
    const TurekHronBeam beam = turek_hron_beam({.across = spec.across, .clamp_layers = spec.clamp_layers});
    const double h = h_over_dx * beam.dx;
    const auto disc = make_discretisation(beam.particles, kernel, h);
    // the form: FiniteStrainTotalLagrangian (plain or NCSPH strain, divergence of the plain G) or the variational
    // form with the NCSPH strain and its transpose as divergence ("ncsph-variational")
    std::shared_ptr<const ForceFunction> tl;
    std::function<Eigen::MatrixXd(const Eigen::VectorXd&)> stresses, deformation_gradients;
    if (spec.gradient == "ncsph-variational") {
      auto v = std::make_shared<VariationalTotalLagrangian<2>>(disc, svk, C::density,
                                                               make_gradient_provider<2>(Correction::Ncsph));
      stresses = [v](const Eigen::VectorXd& u) { return v->stresses(u); };
      deformation_gradients = [v](const Eigen::VectorXd& u) { return v->deformation_gradients(u); };
      tl = v;
    } else {
      FiniteStrainOptions<2> opt;
      if (spec.gradient == "ncsph") opt.gradient = make_gradient_provider<2>(Correction::Ncsph);
      opt.divergence = divergence == "plus"    ? StressDivergence::Plus
                       : divergence == "minus" ? StressDivergence::Minus
                                               : StressDivergence::Plain;
      auto f = std::make_shared<FiniteStrainTotalLagrangian<2>>(disc, svk, C::density, opt);
      stresses = [f](const Eigen::VectorXd& u) { return f->stresses(u); };
      deformation_gradients = [f](const Eigen::VectorXd& u) { return f->deformation_gradients(u); };
      tl = f;
    }
    const BodyForce force(tl, Eigen::Vector2d(0, -C::gravity));
    const StableTimeStep limit = stable_time_step(*tl, Eigen::VectorXd::Zero(tl->dofs()));
    CaseResult r;
    r.spec = spec;
    r.particles = beam.particles.size();
    r.free = beam.free_count;
    r.clamp = beam.clamp_count;
    r.dx = beam.dx;
    r.dt_limit = limit.dt;
    if (tl->dofs() <= 1200) {  // dense nonsymmetric eigenvalues of the linearisation at rest (coarse runs only)
      const Eigen::EigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(jacobian(*tl, Eigen::VectorXd::Zero(tl->dofs()))),
                                                   false);
      r.growth = 0;
      for (const auto& mu : es.eigenvalues()) r.growth = std::max(r.growth, std::sqrt(-mu).real());
    }
    if (tl->dofs() <= 2500 && tl->conservative()) {  // M A symmetric, equal masses: A symmetric; lowest mode
      const Eigen::MatrixXd A = Eigen::MatrixXd(jacobian(*tl, Eigen::VectorXd::Zero(tl->dofs())));
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()), Eigen::EigenvaluesOnly);
      r.f_linear = std::sqrt(es.eigenvalues()[0]) / (2 * std::numbers::pi);
    }
    const long nsteps = static_cast<long>(std::ceil(t_end / (cfl * limit.dt)));
    r.dt = t_end / nsteps;
    SecondOrderSystem sys;
    sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { force.acceleration(u, a); };
    sys.dofs_per_particle = 2;
    sys.mass.resize(tl->dofs() / 2);
    for (int f = 0; f < tl->dofs() / 2; ++f) sys.mass[f] = tl->dof_mass()[2 * f];
    const int nf = tl->dofs();
    LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(nf), Eigen::VectorXd::Zero(nf));
    auto tip = [&](const Eigen::VectorXd& u, int c) {
      double m[2] = {0, 0};
      for (int col = 0; col < 2; ++col) {
        for (int f : beam.tip[col]) m[col] += u[2 * f + c];
        m[col] /= static_cast<double>(beam.tip[col].size());
      }
      return std::array<double, 2>{1.5 * m[0] - 0.5 * m[1], m[0]};
    };
    const bool finest = spec.across == across.back() && spec.gradient == gradient && spec.clamp_layers == clamp_layers;
    CsvWriter csv(out + "/tip_" + spec.name() + ".csv",
                  {"t", "ux_A", "uy_A", "ux_tip_column", "uy_tip_column", "total_energy"}, false);
    std::vector<double> ts, uxs, uys;
    const long every = std::max(1L, static_cast<long>(std::round(1e-3 / r.dt)));  // ~1 ms
    const long energy_every = 20 * every;  // a multiple of 5 every: every energy sample is written
    const double e_scale = C::density * C::thickness * 0.35 * C::gravity * std::abs(C::uy_amplitude);  // ~ m g A
    double e0 = 0;
    for (long s = 0;; ++s) {
      const double t = stepper.time();
      if (s % every == 0 || s == nsteps) {
        const auto ux = tip(stepper.u(), 0), uy = tip(stepper.u(), 1);
        double e = NAN;
        if (s % energy_every == 0 || s == nsteps) {
          e = total_energy(force, stepper.u(), stepper.v());
          if (s == 0) e0 = e;
          r.energy_drift = std::max(r.energy_drift, std::abs(e - e0) / e_scale);
        }
        if (s % (5 * every) == 0 || s == nsteps) csv.row({t, ux[0], uy[0], ux[1], uy[1], e});  // CSV every ~5 ms
        ts.push_back(t);
        uxs.push_back(ux[0]);
        uys.push_back(uy[0]);
        if (finest && t >= t_end - 1 / C::frequency && uy[0] < snapshot_uy) {
          snapshot_uy = uy[0];
          snapshot_t = t;
          const Eigen::MatrixXd P = stresses(stepper.u()), F = deformation_gradients(stepper.u());
          snapshot_x.resize(disc->size(), 2);
          snapshot_sigma.resize(disc->size(), 3);
          for (int i = 0; i < disc->size(); ++i) {
            const int f = disc->free_slot[i];
            snapshot_x.row(i) = disc->particles.x.row(i);
            if (f >= 0) snapshot_x.row(i) += Eigen::RowVector2d(stepper.u()[2 * f], stepper.u()[2 * f + 1]);
            Deformation<double, 2> Fi, Pi;
            Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
            Pi << P(i, 0), P(i, 1), P(i, 2), P(i, 3);
            const Deformation<double, 2> sigma = Pi * Fi.transpose() / Fi.determinant();
            snapshot_sigma.row(i) << sigma(0, 0), sigma(1, 1), sigma(0, 1);
          }
        }
      }
      if (s == nsteps) break;
      if (s % 20000 == 0)
        std::cerr << spec.name() << ": t = " << t << " s of " << t_end << " (" << s << "/" << nsteps << " steps)\n";
      try {
        stepper.step(r.dt);
      } catch (const std::invalid_argument& e) {
        r.status = std::string("stopped: ") + e.what();
        break;
      }
      if (!stepper.u().allFinite()) {
        r.status = "non-finite";
        break;
      }
    }
    r.steps = stepper.steps();
    r.wall = study::seconds_since(tr);
    if (r.status == "completed") {
      r.ux = measure(ts, uxs, t_measure);
      r.uy = measure(ts, uys, t_measure);
    }
    std::cout << spec.name() << ": " << r.particles << " particles (" << r.free << " free), dt = " << r.dt << " s ("
              << r.dt / r.dt_limit << " of the limit), growth at rest " << r.growth << " 1/s, f_linear " << r.f_linear
              << " Hz, " << r.steps << " steps, " << r.wall << " s wall, " << r.status << "; ux " << r.ux.mean << " +- "
              << r.ux.amplitude << " [" << r.ux.frequency << "], uy " << r.uy.mean << " +- " << r.uy.amplitude << " ["
              << r.uy.frequency << "]\n";
    results.push_back(r);
  }

  // tables
  study::Summary summary;
  CsvWriter rcsv(
      out + "/runs.csv",
      {"run",           "across",       "gradient",     "clamp_layers",      "dx",           "particles",
       "free",          "clamp",        "dt",           "dt_limit",          "steps",        "wall_seconds",
       "status",        "energy_drift", "ux_mean",      "ux_amplitude",      "ux_frequency", "uy_mean",
       "uy_amplitude",  "uy_frequency", "ux_last_mean", "ux_last_amplitude", "uy_last_mean", "uy_last_amplitude",
       "uy_half_cycles"});
  std::string md_runs, md_table;
  auto rel = [](double v, double ref) { return study::fixed(100 * (v / ref - 1), 2, true) + " %"; };
  for (const CaseResult& r : results) {
    rcsv.row({r.spec.name(),
              r.spec.across,
              r.spec.gradient,
              r.spec.clamp_layers,
              r.dx,
              r.particles,
              r.free,
              r.clamp,
              r.dt,
              r.dt_limit,
              r.steps,
              r.wall,
              r.status,
              r.energy_drift,
              r.ux.mean,
              r.ux.amplitude,
              r.ux.frequency,
              r.uy.mean,
              r.uy.amplitude,
              r.uy.frequency,
              r.ux.last_mean,
              r.ux.last_amplitude,
              r.uy.last_mean,
              r.uy.last_amplitude,
              r.uy.half_cycles});
    study::md_row(md_runs, {r.spec.name(), std::to_string(r.particles), std::to_string(r.free), std::to_string(r.clamp),
                            study::sig(r.dt * 1e6, 4), study::fixed(r.dt / r.dt_limit, 3), std::to_string(r.steps),
                            study::fixed(r.wall, 1), study::sig(r.energy_drift, 2), study::sig(r.growth, 3),
                            study::fixed(r.f_linear, 4), r.status});
    study::md_row(
        md_table,
        {r.spec.name(), study::fixed(1e3 * r.ux.mean, 3), study::fixed(1e3 * r.ux.amplitude, 3),
         study::fixed(r.ux.frequency, 4), study::fixed(1e3 * r.uy.mean, 3), study::fixed(1e3 * r.uy.amplitude, 3),
         study::fixed(r.uy.frequency, 4), rel(r.ux.mean, C::ux_mean), rel(r.ux.amplitude, C::ux_amplitude),
         rel(r.uy.mean, C::uy_mean), rel(r.uy.amplitude, C::uy_amplitude), rel(r.uy.frequency, C::frequency)});
  }
  study::md_row(md_table, {"**reference**", study::fixed(1e3 * C::ux_mean, 3), study::fixed(1e3 * C::ux_amplitude, 3),
                           study::fixed(C::frequency, 4), study::fixed(1e3 * C::uy_mean, 3),
                           study::fixed(1e3 * C::uy_amplitude, 3), study::fixed(C::frequency, 4), "", "", "", "", ""});
  // observed order over the three resolutions of the chosen gradient
  std::string md_order;
  CsvWriter ocsv(out + "/order.csv", {"quantity", "value_1", "value_2", "value_3", "reference", "observed_order",
                                      "loglog_slope_of_error", "richardson_extrapolated"});
  if (across.size() >= 3) {
    const CaseResult &a = results[across.size() - 3], &b = results[across.size() - 2], &c = results[across.size() - 1];
    const std::vector<std::tuple<std::string, std::array<double, 3>, double>> qs{
        {"ux mean", {a.ux.mean, b.ux.mean, c.ux.mean}, C::ux_mean},
        {"ux amplitude", {a.ux.amplitude, b.ux.amplitude, c.ux.amplitude}, C::ux_amplitude},
        {"uy mean", {a.uy.mean, b.uy.mean, c.uy.mean}, C::uy_mean},
        {"uy amplitude", {a.uy.amplitude, b.uy.amplitude, c.uy.amplitude}, C::uy_amplitude},
        {"uy frequency", {a.uy.frequency, b.uy.frequency, c.uy.frequency}, C::frequency},
        {"ux frequency", {a.ux.frequency, b.ux.frequency, c.ux.frequency}, C::frequency}};
    for (const auto& [name, v, ref] : qs) {
      const double p = observed_order(a.dx, b.dx, c.dx, v[0], v[1], v[2]);
      const double slope = study::loglog_slope({a.dx, b.dx, c.dx}, {v[0] - ref, v[1] - ref, v[2] - ref});
      // Richardson: f_h = f + C h^p, so f = f3 + (f3 - f2) / ((h2 / h3)^p - 1); NaN without an order
      const double ext = v[2] + (v[2] - v[1]) / (std::pow(b.dx / c.dx, p) - 1);
      ocsv.row({name, v[0], v[1], v[2], ref, p, slope, ext});
      study::md_row(md_order, {name, study::sig(v[0], 5), study::sig(v[1], 5), study::sig(v[2], 5), study::sig(ref, 5),
                               study::sig(p, 3), study::sig(slope, 3), study::sig(ext, 5),
                               std::isnan(ext) ? std::string("-") : rel(ext, ref)});
    }
  }
  if (snapshot_x.rows()) {
    CsvWriter scsv(out + "/snapshot.csv", {"x", "y", "sigma_xx", "sigma_yy", "sigma_xy", "fixed"});
    const auto disc_free = turek_hron_beam({.across = across.back(), .clamp_layers = clamp_layers});
    for (int i = 0; i < snapshot_x.rows(); ++i)
      scsv.row({snapshot_x(i, 0), snapshot_x(i, 1), snapshot_sigma(i, 0), snapshot_sigma(i, 1), snapshot_sigma(i, 2),
                disc_free.particles.role[i] == Role::Fixed ? 1 : 0});
  }
  // objectivity: a rigid rotation u = (R - I) X of every particle (free and clamp) gives F = R exactly for a
  // first-order consistent gradient (NCSPH), so the Green strain E = (F^T F - I) / 2 must vanish; the plain gradient
  // gives F = I + M (R - I) with the moment matrix M != I at the free surfaces: spurious strain
  CsvWriter rotcsv(out + "/rotation.csv", {"across", "gradient", "theta", "max_green_strain_all",
                                           "max_green_strain_surface_row", "max_green_strain_interior"});
  std::string md_rot;
  for (int n : across)
    for (const std::string g : {"plain", "ncsph"})
      for (double theta : {0.1, 0.3}) {
        const TurekHronBeam beam = turek_hron_beam({.across = n, .clamp_layers = clamp_layers});
        const auto disc = make_discretisation(beam.particles, kernel, h_over_dx * beam.dx);
        FiniteStrainOptions<2> opt;
        if (g == "ncsph") opt.gradient = make_gradient_provider<2>(Correction::Ncsph);
        FiniteStrainTotalLagrangian<2> tl(disc, svk, C::density, opt);
        Eigen::Matrix2d R;
        R << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
        Eigen::VectorXd u(tl.dofs()), d(2 * (disc->size() - disc->free_count()));
        for (int i = 0, k = 0; i < disc->size(); ++i) {
          const Eigen::Vector2d X = disc->particles.x.row(i).transpose();
          const Eigen::Vector2d w = (R - Eigen::Matrix2d::Identity()) * X;
          const int f = disc->free_slot[i];
          if (f >= 0)
            u.segment<2>(2 * f) = w;
          else
            d.segment<2>(2 * k++) = w;
        }
        tl.set_fixed_displacement(d);
        const Eigen::MatrixXd F = tl.deformation_gradients(u);
        double all = 0, surface = 0, interior = -1;  // -1: no particle 3 layers deep
        for (int f = 0; f < disc->free_count(); ++f) {
          const int i = disc->free[f];
          Eigen::Matrix2d Fi;
          Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
          const double e = (0.5 * (Fi.transpose() * Fi - Eigen::Matrix2d::Identity())).cwiseAbs().maxCoeff();
          all = std::max(all, e);
          if (beam.particles.depth[i] == 0) surface = std::max(surface, e);
          if (beam.particles.depth[i] >= 3) interior = std::max(interior, e);
        }
        if (interior < 0) interior = NAN;
        rotcsv.row({n, g, theta, all, surface, interior});
        study::md_row(md_rot, {std::to_string(n), g, study::fixed(theta, 1), study::sig(all, 3), study::sig(surface, 3),
                               study::sig(interior, 3)});
      }
  summary.set("rotation", md_rot);
  summary.set("runs", md_runs);
  summary.set("table", md_table);
  summary.set("order", md_order);
  summary.set("gradient", gradient);
  summary.set("other_gradient", other);
  summary.set("h_over_dx", h_over_dx, 3);
  summary.set("cfl", cfl, 3);
  summary.set("t_end", t_end, 3);
  summary.set("t_measure", t_measure, 3);
  summary.set("clamp_layers", clamp_layers);
  summary.set("wide_clamp", wide_clamp);
  summary.set("lambda", lame.lambda, 4);
  summary.set("snapshot_t", snapshot_t, 4);
  summary.set("snapshot_uy_mm", 1e3 * snapshot_uy, 4);
  summary.set("load", study::load_average());
  {  // linear beam theory for the 0.35 m cantilever (plane strain bending modulus E / (1 - nu^2))
    const double young = lame.young(), nu = lame.poisson(), length = C::tip_x - C::attachment_x(C::bottom_y);
    summary.set("f_euler_bernoulli", 1 / thin_plate_period(young, nu, C::density, C::thickness, length), 4);
    summary.set(
        "f_timoshenko",
        1 / timoshenko_cantilever_period(young / (1 - nu * nu), lame.mu, 5.0 / 6.0, C::density, C::thickness, length),
        4);
    const double q = C::density * C::gravity * C::thickness, inertia = std::pow(C::thickness, 3) / 12;
    summary.set("static_tip_mm", 1e3 * q * std::pow(length, 4) / (8 * young / (1 - nu * nu) * inertia), 4);
    summary.set("beam_length", length, 6);
  }
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
