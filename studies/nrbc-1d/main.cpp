// Powell (2012) ch. 2 §3.1: the 1D non-reflecting boundary (2.69)-(2.70) on a semi-infinite elastic bar (2.68),
// Table 2.1 (SPH, XSPH, NCSPH, NCXSPH with the reference, 1-5 absorbing particles and upwind), the h-study of
// Fig. 2.12, and the time-step limits that explain the table's X entries.
//
// Writes to --out DIR: table.csv (every case: form, layers, timing, CFL, status, mean error (2.72), steps),
// series/<tag>.csv (t, v of particle 80, about 400 records), cfl_sweep.csv, dt_limit.csv, h_study.csv, summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

// Powell's units: g, cm, us (stress in Mbar). Steel: the thesis gives neither E nor rho for this test; the 2D tests'
// values give c = sqrt(E / rho) = 0.51887 cm/us.
constexpr double kRho = 7.8, kE = 2.1, kDx = 0.01, kV = 0.01, kSplit = 0.35;
constexpr int kProbe = 79;  // particle 80 (1-based), x = 0.795

double bar_speed() { return std::sqrt(kE / kRho); }

/// The exact velocity of (2.68) at x: d'Alembert with the even extension of the initial velocity (free end u_x = 0)
/// and zero initial stress, v = (v0(x - ct) + v0(x + ct)) / 2, v0(s) = +V for |s| < 0.35, -V otherwise.
double exact_velocity(double x, double t) {
  const auto v0 = [](double s) { return std::abs(s) < kSplit ? kV : -kV; };
  const double c = bar_speed();
  return 0.5 * (v0(x - c * t) + v0(x + c * t));
}

enum class Form { Sph, Xsph, Ncsph, Ncxsph };
const char* form_name(Form f) {
  switch (f) {
    case Form::Sph:
      return "SPH";
    case Form::Xsph:
      return "XSPH";
    case Form::Ncsph:
      return "NCSPH";
    case Form::Ncxsph:
      return "NCXSPH";
  }
  return "?";
}
bool normalised(Form f) { return f == Form::Ncsph || f == Form::Ncxsph; }
bool smoothed(Form f) { return f == Form::Xsph || f == Form::Ncxsph; }

struct BarCase {
  Form form = Form::Sph;
  int particles = 100;  ///< per side: 100 (truncated, 1 cm) or 800 (the 8 cm reference)
  /// The free end u_x(0) = 0 by symmetry: the bar on (-L, L) with the even initial velocity and absorbing particles at
  /// both ends (exact for every gradient); false: Powell's free end, particle 1 at x = 0.005 with nothing beyond.
  bool mirror = true;
  int layers = 0;          ///< absorbing particles at the right end (0: free end)
  bool upwind = false;     ///< Powell (2.67)
  bool half_step = true;   ///< Powell's algorithm 2.3 (forward Euler (2.66)); false: sphstab's whole-step a
  double h_over_dx = 1.3;  ///< Powell 1.3
  double cfl = 0.5;        ///< dt = cfl dx / c
  /// MCM's bulk viscosity (linear 0.06, quadratic 1.5; thesis App. B): Compression as MCM runs it; Always only for
  /// the damped linearisation (its linear term acts on every pair; the quadratic one vanishes at rest).
  ViscositySwitch viscosity = ViscositySwitch::Compression;
  double t_from = 3, t_to = 20;
  bool keep_series = false;
};

struct BarRun {
  BarCase c;
  std::string status;
  bool stable = false;
  double error = NAN;  ///< mean of (2.72) over the steps with t_from < t <= t_to
  long steps = 0;
  std::vector<double> t, v;
};

std::string tag_of(const BarCase& c) {
  std::string s = std::string(form_name(c.form)) + "_n" + std::to_string(c.particles) + "_";
  s += c.upwind ? "upwind" + std::to_string(c.layers) : "layers" + std::to_string(c.layers);
  s += std::string(c.half_step ? "_half" : "_whole") + "_h" + format_number(c.h_over_dx) + "_cfl" +
       format_number(c.cfl) +
       (c.viscosity == ViscositySwitch::Compression ? ""
        : c.viscosity == ViscositySwitch::Off       ? "_novisc"
                                                    : "_always") +
       (c.mirror ? "" : "_free");
  return s;
}

/// The bar's scheme and initial state (2.68).
struct BarScene {
  std::unique_ptr<RateFormScheme<1>> scheme;
  Eigen::VectorXd y0;
  int probe = kProbe;  ///< particle 80's index
  double x80 = 0;
};

BarScene make_bar(const BarCase& c) {
  const int n = c.mirror ? 2 * c.particles : c.particles, first = c.mirror ? c.particles : 0;  // x = 0.005: first
  ParticleSet<1> p;
  p.x.resize(n, 1);
  p.volume = Eigen::VectorXd::Constant(n, kDx);
  p.role.assign(n, Role::Free);
  p.spacing = kDx;
  for (int i = 0; i < n; ++i) p.x(i, 0) = (i - first + 0.5) * kDx;
  const double h = c.h_over_dx * kDx;
  auto disc = make_discretisation(p, Kernel<1>(KernelType::CubicSpline), h);
  // Uniaxial modulus E: K = E, mu = 0 (the 1D scheme's longitudinal modulus is K + 4 mu / 3).
  RateFormScheme<1> scheme(disc, {.density = kRho, .bulk_modulus = kE, .shear_modulus = 0},
                           {.continuity = ContinuityForm::Divergence,
                            .viscosity = c.viscosity,
                            .gradient = normalised(c.form) ? RateFormGradient::Ncsph : RateFormGradient::Plain});
  AbsorbingParticles<1> b{.upwind = c.upwind};
  for (int i = n - c.layers; i < n; ++i)
    b.particles.push_back(i), b.normals.emplace_back(Eigen::Matrix<double, 1, 1>(1.0));
  if (c.mirror)
    for (int i = 0; i < c.layers; ++i)
      b.particles.push_back(i), b.normals.emplace_back(Eigen::Matrix<double, 1, 1>(-1.0));
  scheme.set_absorbing(b);
  BarScene scene{.scheme = std::make_unique<RateFormScheme<1>>(std::move(scheme)),
                 .probe = first + kProbe,
                 .x80 = p.x(first + kProbe, 0)};
  scene.y0 = scene.scheme->uniform_state();
  for (int i = 0; i < n; ++i)  // (2.68), evenly extended
    scene.y0[scene.scheme->velocity_offset(i)] = std::abs(p.x(i, 0)) < kSplit ? kV : -kV;
  return scene;
}

/// The run options of a case at time step dt.
RateFormRunOptions run_options(const BarCase& c) {
  return {.dt = c.cfl * kDx / bar_speed(),
          .t_end = c.t_to,
          .energy_growth = 100,
          .integrator = RateFormIntegrator::Leapfrog,
          .leapfrog_xsph = smoothed(c.form) ? 0.1 : 0.0,
          .absorbing_half_step = c.half_step && c.layers > 0};
}

BarRun run_bar(const BarCase& c) {
  const BarScene scene = make_bar(c);
  const RateFormScheme<1>& scheme = *scene.scheme;
  BarRun r{.c = c};
  const double x80 = scene.x80;
  double sum = 0;
  long count = 0;
  RateFormRunOptions o = run_options(c);
  o.observer = [&](long, double t, const Eigen::VectorXd& y) {
    const double v = y[scheme.velocity_offset(scene.probe)];
    if (c.keep_series) r.t.push_back(t), r.v.push_back(v);
    if (t > c.t_from + 1e-12) {
      const double exact = exact_velocity(x80, t);
      sum += std::abs(exact - v) / std::abs(exact);  // (2.72); exact = -V for t > 2.21
      ++count;
    }
  };
  try {
    const RateFormRunResult res = run_rate_form(scheme, scene.y0, o);
    r.steps = res.steps;
    r.stable = res.completed();
    r.status = run_status_name(res.status);
  } catch (const std::domain_error&) {  // the NCSPH moment matrix of a particle that lost its neighbours: unstable
    r.status = "singular-ncsph";
    return r;
  }
  if (r.stable && count > 0) r.error = sum / count;
  return r;
}

std::vector<BarRun> run_all(const std::vector<BarCase>& cases, int threads) {
  std::vector<BarRun> runs(cases.size());
  study::parallel_for(cases.size(), threads, [&](std::size_t k) { runs[k] = run_bar(cases[k]); });
  return runs;
}

/// Largest CFL in [lo, hi] for which stable(cfl) holds, by geometric bisection to relative resolution 1e-2 (stability
/// assumed monotone in dt: sampling, not proof). Returns hi when hi is stable, 0 when lo is not.
template <class Stable>
double largest_stable_cfl(double lo, double hi, Stable&& stable) {
  if (stable(hi)) return hi;
  if (!stable(lo)) return 0;
  while (hi / lo - 1 > 1e-2) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
  }
  return lo;
}

/// Largest CFL at which the case runs stably to t_to.
double stable_cfl_limit(BarCase c, double lo, double hi) {
  c.keep_series = false;
  return largest_stable_cfl(lo, hi, [&](double cfl) {
    c.cfl = cfl;
    return run_bar(c).stable;
  });
}

/// Spectral radius of the leap-frog's linearised step at rest (integrate/rate_form_run.hpp, leapfrog_step_matrix):
/// > 1 + 1e-6 means small perturbations grow at this dt (the threshold sits far above the central differences' noise,
/// ~1e-8, and far below the growth of the unstable cases, >= 1e-4 per step).
/// The compression switch of the viscosity is not differentiable at rest (v_ij . r_ij = 0), so the scheme as run lies
/// between two linearisations: undamped (viscosity off) and damped (the linear term on every pair, Always).
double step_radius(BarCase c, ViscositySwitch viscosity) {
  c.viscosity = viscosity;
  if (c.mirror) c.particles /= 2;  // the same 1 cm in all: a 600 x 600 step matrix
  const BarScene scene = make_bar(c);
  const RateFormScheme<1>& s = *scene.scheme;
  const RateFormRunOptions o = run_options(c);
  const DenseGeneralEigen e = general_eigen(leapfrog_step_matrix(s, s.uniform_state(), o.dt, o));
  if (e.lapack_info != 0) throw std::runtime_error("nrbc-1d: dgeev did not converge for " + tag_of(c));
  return e.values.cwiseAbs().maxCoeff();
}
constexpr double kRadiusTolerance = 1e-6;

/// Largest CFL with step radius <= 1 + kRadiusTolerance.
double linear_cfl_limit(BarCase c, ViscositySwitch viscosity, double lo, double hi) {
  return largest_stable_cfl(lo, hi, [&](double cfl) {
    c.cfl = cfl;
    return step_radius(c, viscosity) <= 1 + kRadiusTolerance;
  });
}

void write_table(const std::string& path, const std::vector<BarRun>& runs) {
  CsvWriter w(path, {"form", "particles", "layers", "upwind", "timing", "h_over_dx", "cfl", "viscosity", "mirror",
                     "status", "mean_error", "steps"});
  for (const BarRun& r : runs)
    w.row({form_name(r.c.form), r.c.particles, r.c.layers, r.c.upwind ? 1 : 0, r.c.half_step ? "half" : "whole",
           r.c.h_over_dx, r.c.cfl, r.c.viscosity == ViscositySwitch::Compression ? 1 : 0, r.c.mirror ? 1 : 0, r.status,
           r.error, r.steps});
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"Powell 2012 ch. 2: 1D non-reflecting boundary, Table 2.1, h-study, time-step limits"};
  std::string out = "results/nrbc-1d";
  double cfl = 0.5, tssfac = 0.8;
  int threads = 2;
  bool quick = false;
  std::vector<double> sweep = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8};
  std::vector<double> h_values = {1.1, 1.2, 1.3, 1.5, 1.7, 2.0, 2.5, 3.0};
  app.add_option("--out", out, "output directory");
  app.add_option("--cfl", cfl, "the tuned dt = cfl dx / c of the Table 2.1 sensitivity (the value at which the "
                 "symmetric bar reproduces Powell's X pattern)")->check(CLI::Range(0.01, 2.0));
  app.add_option("--tssfac", tssfac, "the headline dt = tssfac h / c (MCM deck TSSFAC 0.8, DYNA's rule at rest)")
      ->check(CLI::Range(0.01, 1.5));
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--cfl-sweep", sweep, "CFL values of the sweep")->delimiter(',')->check(CLI::Range(0.01, 2.0));
  app.add_option("--h", h_values, "h / dx of the h-study")->delimiter(',')->check(CLI::Range(1.0, 4.0));
  app.add_flag("--quick", quick, "pipeline check: Table 2.1 in full, the sweep at the tuned step only, h / dx 1.3 "
               "only, and the step limits of the half-step timing with one absorbing layer and the upwind eight");
  CLI11_PARSE(app, argc, argv);
  if (quick) sweep = {cfl}, h_values = {1.3};
  const auto t0 = study::Clock::now();
  fs::create_directories(out + "/series");
  study::Summary sum;
  const std::vector<Form> forms = {Form::Sph, Form::Xsph, Form::Ncsph, Form::Ncxsph};

  // 1. Table 2.1. Headline: Powell's geometry (free end) and timing (half) at MCM's time step, dt = TSSFAC h / c
  // (the deck's TSSFAC 0.8 with DYNA's step rule h / c at rest: c dt/dx = 1.04). Sensitivities: the symmetric bar at
  // that step, and the tuned c dt/dx = 0.5 (the value at which the symmetric bar reproduces Powell's X pattern) on the
  // symmetric bar with both timings and on the free end.
  const double cfl_mcm = tssfac * 1.3;
  struct Variant {
    bool half, mirror;
    double cfl;
    const char* key;
  };
  const std::vector<Variant> variants = {{true, false, cfl_mcm, "table_headline"},
                                         {true, true, cfl_mcm, "table_mcm_mirror"},
                                         {true, true, cfl, "table_half"},
                                         {false, true, cfl, "table_whole"},
                                         {true, false, cfl, "table_free"}};
  std::vector<BarCase> table;
  for (const Variant& v : variants)
    for (Form f : forms) {
      // The reference has no absorbing particles: its timing flag is moot, run once per left end.
      if (v.half)
        table.push_back(
            {.form = f, .particles = 800, .mirror = v.mirror, .half_step = true, .cfl = v.cfl, .keep_series = true});
      for (int layers = 1; layers <= 5; ++layers)
        table.push_back(
            {.form = f, .mirror = v.mirror, .layers = layers, .half_step = v.half, .cfl = v.cfl, .keep_series = true});
      table.push_back({.form = f,
                       .mirror = v.mirror,
                       .layers = 8,
                       .upwind = true,
                       .half_step = v.half,
                       .cfl = v.cfl,
                       .keep_series = true});
    }
  for (Form f : forms)  // the references without MCM's viscosity
    table.push_back({.form = f, .particles = 800, .cfl = cfl, .viscosity = ViscositySwitch::Off, .keep_series = true});
  const std::vector<BarRun> runs = run_all(table, threads);
  write_table(out + "/table.csv", runs);
  for (const BarRun& r : runs) {
    CsvWriter w(out + "/series/" + tag_of(r.c) + ".csv", {"t", "v80", "exact"});
    const std::size_t every = std::max<std::size_t>(1, r.t.size() / 400);  // plots need ~400 points, not every step
    for (std::size_t k = 0; k < r.t.size(); k += every) w.row({r.t[k], r.v[k], exact_velocity(0.795, r.t[k])});
  }
  const auto find = [&](Form f, int particles, int layers, bool upwind, bool half, double c, bool mirror = true,
                        ViscositySwitch viscosity = ViscositySwitch::Compression) -> const BarRun& {
    for (const BarRun& r : runs)
      if (r.c.form == f && r.c.particles == particles && r.c.layers == layers && r.c.upwind == upwind &&
          (particles == 800 || r.c.half_step == half) && r.c.mirror == mirror && r.c.viscosity == viscosity &&
          r.c.cfl == c)
        return r;
    throw std::logic_error("missing case");
  };
  // Powell's Table 2.1 (x 10^2); NaN: X (unstable).
  const double paper[7][4] = {{0.3474, 0.0300, 0.2243, 0.0056}, {5.9729, 1.3790, 3.2605, 0.8531},
                              {1.5015, 0.1808, 1.3068, 0.0867}, {1.7273, 0.0763, 1.5451, 0.0726},
                              {NAN, 0.1401, 7.5314, 0.0733},    {NAN, NAN, NAN, 13.7708},
                              {30.9198, 3.0328, 1.2380, 0.1078}};
  const auto cell = [](const BarRun& r) { return r.stable ? study::sig(100 * r.error, 3) : std::string("X"); };
  const auto paper_cell = [](double v) { return std::isnan(v) ? std::string("X") : study::sig(v, 5); };
  const auto row_run = [&](int row, int k, const Variant& v) -> const BarRun& {
    return row == 0   ? find(forms[k], 800, 0, false, v.half, v.cfl, v.mirror)
           : row == 6 ? find(forms[k], 100, 8, true, v.half, v.cfl, v.mirror)
                      : find(forms[k], 100, row, false, v.half, v.cfl, v.mirror);
  };
  for (const Variant& v : variants) {
    std::string md;
    int agree = 0;  // the X pattern of the truncated rows against Powell's, cell by cell
    for (int row = 0; row < 7; ++row) {
      std::vector<std::string> cells = {row == 0 ? "Reference" : row == 6 ? "Upwind (8)" : std::to_string(row)};
      for (int k = 0; k < 4; ++k) {
        const BarRun& r = row_run(row, k, v);
        cells.push_back(cell(r) + " (" + paper_cell(paper[row][k]) + ")");
        if (row > 0) agree += r.stable == !std::isnan(paper[row][k]);
      }
      study::md_row(md, cells);
    }
    sum.set(v.key, md);
    sum.set(std::string(v.key) + "_x_agree", agree);
  }
  {
    std::string md;
    std::vector<std::string> cells = {"Reference without viscosity"};
    for (int k = 0; k < 4; ++k)
      cells.push_back(cell(find(forms[k], 800, 0, false, true, cfl, true, ViscositySwitch::Off)) + " (" +
                      paper_cell(paper[0][k]) + ")");
    study::md_row(md, cells);
    sum.set("table_inviscid", md);
  }

  // 2. CFL sweep: stable or not, and the error, for the truncated bars at each dt (both timings).
  std::vector<BarCase> sweep_cases;
  for (double s : sweep)
    for (bool half : {true, false})
      for (Form f : forms)
        for (int layers = 1; layers <= 5; ++layers)
          sweep_cases.push_back({.form = f, .layers = layers, .half_step = half, .cfl = s});
  const std::vector<BarRun> sweep_runs = run_all(sweep_cases, threads);
  write_table(out + "/cfl_sweep.csv", sweep_runs);

  // 3. The largest stable CFL of every truncated configuration (bisection on whole runs to 20 us).
  std::vector<BarCase> limit_cases;
  for (bool half : {true, false})
    for (Form f : forms) {
      if (quick && !half) continue;
      if (!quick) limit_cases.push_back({.form = f, .particles = 800, .half_step = half});
      for (int layers = 1; layers <= (quick ? 1 : 5); ++layers)
        limit_cases.push_back({.form = f, .layers = layers, .half_step = half});
      limit_cases.push_back({.form = f, .layers = 8, .upwind = true, .half_step = half});
    }
  // Both from runs (bisection on whole runs to 20 us) and from the linearised step (spectral radius at rest; not for
  // the 800-particle reference, whose dense step matrix would be 4800 x 4800).
  // Linearisations undamped (viscosity off) and damped (linear viscosity on every pair).
  const std::size_t nl = limit_cases.size();
  std::vector<double> limits(nl), linear_off(nl, NAN), linear_on(nl, NAN), radius_off(nl, NAN), radius_on(nl, NAN);
  study::parallel_for(nl, threads, [&](std::size_t k) {
    limits[k] = stable_cfl_limit(limit_cases[k], 0.05, 2.0);
    if (limit_cases[k].particles == 800) return;
    linear_off[k] = linear_cfl_limit(limit_cases[k], ViscositySwitch::Off, 0.05, 2.0);
    linear_on[k] = linear_cfl_limit(limit_cases[k], ViscositySwitch::Always, 0.05, 2.0);
    BarCase at = limit_cases[k];
    at.cfl = cfl;
    radius_off[k] = step_radius(at, ViscositySwitch::Off);
    radius_on[k] = step_radius(at, ViscositySwitch::Always);
  });
  {
    CsvWriter w(out + "/dt_limit.csv",
                {"form", "particles", "layers", "upwind", "timing", "max_stable_cfl", "linear_max_cfl_undamped",
                 "linear_max_cfl_damped", "step_radius_at_cfl_undamped", "step_radius_at_cfl_damped"});
    std::string md;
    for (bool half : {true, false}) {
      for (int row = 0; row < 7; ++row) {
        std::vector<std::string> cells = {std::string(half ? "half" : "whole"), row == 0   ? "Reference"
                                                                                : row == 6 ? "Upwind (8)"
                                                                                           : std::to_string(row)};
        for (Form f : forms)
          for (std::size_t k = 0; k < limit_cases.size(); ++k) {
            const BarCase& c = limit_cases[k];
            const bool match = c.form == f && c.half_step == half &&
                               (row == 0   ? c.particles == 800
                                : row == 6 ? c.upwind
                                           : c.particles == 100 && !c.upwind && c.layers == row);
            if (match)
              cells.push_back(study::sig(limits[k], 3) + " / " + study::sig(linear_off[k], 3) + " / " +
                              study::sig(linear_on[k], 3));
          }
        study::md_row(md, cells);
      }
    }
    for (std::size_t k = 0; k < limit_cases.size(); ++k) {
      const BarCase& c = limit_cases[k];
      w.row({form_name(c.form), c.particles, c.layers, c.upwind ? 1 : 0, c.half_step ? "half" : "whole", limits[k],
             linear_off[k], linear_on[k], radius_off[k], radius_on[k]});
    }
    sum.set("dt_limit", md);
    std::string rmd;  // spectral radius - 1 at the table's CFL, undamped / damped
    for (bool half : {true, false})
      for (int layers : {1, 2, 3, 4, 5, 8}) {
        std::vector<std::string> cells = {half ? "half" : "whole", layers == 8 ? "Upwind (8)" : std::to_string(layers)};
        for (Form f : forms)
          for (std::size_t k = 0; k < nl; ++k) {
            const BarCase& c = limit_cases[k];
            if (c.form == f && c.half_step == half && c.particles == 100 && c.layers == layers)
              cells.push_back(study::sig(radius_off[k] - 1, 2) + " / " + study::sig(radius_on[k] - 1, 2));
          }
        study::md_row(rmd, cells);
      }
    sum.set("step_radius", rmd);
  }

  // 4. Fig. 2.12: NCXSPH, floor(2h/dx) + 1 absorbing particles, error over 3 < t < 10 us, reference and truncated.
  std::vector<BarCase> hcases;
  for (double hd : h_values) {
    const int layers = static_cast<int>(std::floor(2 * hd + 1e-9)) + 1;
    hcases.push_back({.form = Form::Ncxsph, .particles = 800, .h_over_dx = hd, .cfl = cfl, .t_to = 10});
    for (bool half : {true, false})
      hcases.push_back(
          {.form = Form::Ncxsph, .layers = layers, .half_step = half, .h_over_dx = hd, .cfl = cfl, .t_to = 10});
  }
  const std::vector<BarRun> hruns = run_all(hcases, threads);
  {
    CsvWriter w(out + "/h_study.csv",
                {"h_over_dx", "layers", "reference_error", "half_error", "half_status", "whole_error", "whole_status"});
    std::string md;
    for (std::size_t k = 0; k < hruns.size(); k += 3) {
      const BarRun &ref = hruns[k], &half = hruns[k + 1], &whole = hruns[k + 2];
      w.row({ref.c.h_over_dx, half.c.layers, ref.error, half.error, half.status, whole.error, whole.status});
      study::md_row(
          md, {study::sig(ref.c.h_over_dx, 3), std::to_string(half.c.layers), cell(ref), cell(half), cell(whole)});
    }
    sum.set("h_study", md);
  }
  sum.set("cfl", cfl, 3);
  sum.set("cfl_mcm", cfl_mcm, 3);
  sum.set("tssfac", tssfac, 3);
  sum.set("c", bar_speed(), 5);
  sum.set("runs", static_cast<long>(runs.size() + sweep_runs.size() + hruns.size()));
  sum.set("wall_seconds", study::seconds_since(t0), 3);
  sum.write(out);
  return 0;
} catch (const std::exception& e) {
  std::cerr << "nrbc-1d: " << e.what() << "\n";
  return 1;
}
