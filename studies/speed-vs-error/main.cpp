// Study speed-vs-error: the 1D velocity-jump problem [Powell2012, ch. 2 §3.1, (2.68)] on a 1 cm bar with free
// ends, solved with linear SPH (total- and updated-Lagrangian) and compared with the exact d'Alembert solution.
// Writes runs.csv, error_history.csv, profiles.csv, stability.csv, rates.csv, powell.csv, ul_linearised.csv,
// ul_tensile_seed.csv and summary.json to --out (see README.md); the prose of summary.md is in summary.md.in.
#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "common/study.hpp"
#include "sphstab/forms/elastic_bar.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/progress.hpp"
#include "sphstab/problems/bar_wave_exact.hpp"

using namespace sphstab;
using study::Clock;
using study::fixed;
using study::md_row;
using study::seconds_since;
using study::sig;

namespace {

struct Formulation {
  std::string name;
  LagrangianFrame frame;
  StrainGradient gradient;
  StressDivergence divergence;
  double xsph_eps = 0;      ///< > 0: XSPH velocity smoothing (Powell 2.71, Replace mode)
  double amplitude = 0.01;  ///< v0 (Powell: 0.01 cm/µs); errors are normalised by v0
};

const std::vector<Formulation>& formulations() {
  static const std::vector<Formulation> f = {
      {"tl-plain", LagrangianFrame::Total, StrainGradient::Plain, StressDivergence::Plain},
      {"tl-minus", LagrangianFrame::Total, StrainGradient::Minus, StressDivergence::Minus},
      {"tl-corrected", LagrangianFrame::Total, StrainGradient::Corrected, StressDivergence::Adjoint},
      {"tl-plain-xsph", LagrangianFrame::Total, StrainGradient::Plain, StressDivergence::Plain, 0.1},
      {"ul-plain", LagrangianFrame::Updated, StrainGradient::Plain, StressDivergence::Plain},
      {"ul-minus-plus", LagrangianFrame::Updated, StrainGradient::Minus, StressDivergence::Plus}};
  return f;
}

struct RunRecord {
  std::string kernel, boundary, form;
  double h_over_dx = 0;
  int n = 0;
  double dt = 0;
  long steps = 0;
  std::string status, message;
  double setup_s = 0, run_s = 0, total_s = 0, us_per_particle_step = NAN;
  double l1 = NAN, l2 = NAN, l1_mean = NAN, momentum_error = NAN, energy_change = NAN;
  long builds = 0;
  double max_u_over_dx = NAN;  ///< max |u_i| / dx at the end (or at the blow-up)
};

/// Velocity errors over the particles, normalised by v0 = 0.01 and the bar length:
/// L1 = Σ |v_i - v(X_i, t)| V_i / (v0 L), L2 = sqrt(Σ (v_i - v(X_i, t))² V_i / L) / v0.
std::pair<double, double> velocity_errors(const ElasticBar1D& bar, const BarJumpExact& ex, const Eigen::VectorXd& v,
                                          double t) {
  double l1 = 0, l2 = 0;
  const double v0 = std::abs(ex.problem().velocity_left), L = ex.problem().length;
  for (int i = 0; i < bar.size(); ++i) {
    const double e = v[i] - ex.velocity(bar.positions()[i], t);
    l1 += std::abs(e) * bar.volumes()[i];
    l2 += e * e * bar.volumes()[i];
  }
  return {l1 / (v0 * L), std::sqrt(l2 / L) / v0};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"speed-vs-error: 1D velocity-jump bar, SPH error against particle count and wall time"};
  std::string out = "results/speed-vs-error";
  bool quick = false;
  double courant = kDefaultCourant;
  app.add_option("--out", out, "output directory");
  app.add_flag("--quick", quick, "small smoke-test sweep (N <= 200, one kernel)");
  app.add_option("--courant", courant, "CFL number C in dt = C h / c");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out);
  const auto wall0 = Clock::now();

  BarJumpProblem problem;  // L = 1 cm, rho = 7.8, E = 2.1, jump at 0.35, ±0.01 cm/µs, free ends
  const BarJumpExact exact(problem);
  const double t_end = 1.5, c = exact.wave_speed();
  const std::vector<int> ns = quick ? std::vector<int>{50, 100, 200} : std::vector<int>{50, 100, 200, 400, 800, 1600};
  const std::vector<KernelType> kernels =
      quick ? std::vector<KernelType>{KernelType::CubicSpline}
            : std::vector<KernelType>{KernelType::CubicSpline, KernelType::WendlandC2};
  const std::vector<double> ratios = {1.0, 1.3, 2.0};
  const std::vector<BarBoundary> boundaries = {BarBoundary::Mirror, BarBoundary::None};

  CsvWriter runs_csv(out + "/runs.csv",
                     {"kernel", "h_over_dx", "boundary", "formulation", "n", "dt", "steps", "status", "setup_s",
                      "run_s", "total_s", "l1_final", "l2_final", "l1_time_mean", "momentum_drift", "energy_rel_change",
                      "neighbour_builds", "us_per_particle_step", "max_u_over_dx"});
  CsvWriter hist_csv(out + "/error_history.csv",
                     {"kernel", "h_over_dx", "boundary", "formulation", "n", "t", "l1", "l2"}, false);
  CsvWriter prof_csv(out + "/profiles.csv", {"kernel", "h_over_dx", "boundary", "formulation", "n", "x", "v"}, false);
  CsvWriter stab_csv(out + "/stability.csv",
                     {"kernel", "h_over_dx", "boundary", "formulation", "n", "method", "lambda_max", "dominant_re",
                      "dominant_im", "min_re", "dt_limit", "courant_max", "dt_cfl", "m1_interior"});
  struct StabRow {
    std::string key;  // kernel | h/dx | boundary | formulation, as in stability.csv
    int n;
    double lambda_max, min_re, courant_max, m1;
  };
  std::vector<StabRow> stab_rows;
  // Exact profile for the plots.
  for (int k = 0; k <= 2000; ++k) {
    const double x = k / 2000.0;
    prof_csv.row({"exact", 0.0, "-", "exact", 0L, x, exact.velocity(x, t_end)});
  }

  std::vector<RunRecord> records;
  long total_runs =
      static_cast<long>(ns.size() * kernels.size() * ratios.size() * boundaries.size() * formulations().size());
  ProgressLine progress("speed-vs-error", 1.0);
  for (KernelType kt : kernels)
    for (double hr : ratios)
      for (BarBoundary bnd : boundaries)
        for (const auto& form : formulations()) {
          // Linear stability limit of the semi-discrete operator (TL forms; UL linearised at u = 0 and XSPH share
          // tl-plain's operator).
          std::vector<int> n_stab = {200};
          if (ns.back() != 200) n_stab.push_back(ns.back());
          for (int n_st : n_stab) {
            if (form.frame != LagrangianFrame::Total || form.xsph_eps > 0) break;
            ElasticBar1D sb({.particles = n_st,
                             .kernel = kt,
                             .h_over_dx = hr,
                             .gradient = form.gradient,
                             .divergence = form.divergence,
                             .boundary = bnd});
            auto est = estimate_stability_limit(sb.system().acceleration, sb.size());
            const double m1 = (sb.strain_matrix() * sb.positions())[n_st / 2];
            stab_csv.row({kernel_name(kt), hr, bar_boundary_name(bnd), form.name, static_cast<long>(n_st), est.method,
                          est.lambda_max, est.dominant.real(), est.dominant.imag(), est.min_real, est.dt_limit,
                          est.dt_limit * c / sb.h(), cfl_time_step(courant, sb.h(), c), m1});
            stab_rows.push_back(
                {kernel_name(kt) + " | " + format_csv_cell(hr) + " | " + bar_boundary_name(bnd) + " | " + form.name,
                 n_st, est.lambda_max, est.min_real, est.dt_limit * c / sb.h(), m1});
          }
          for (int n : ns) {
            RunRecord rec;
            rec.kernel = kernel_name(kt);
            rec.boundary = bar_boundary_name(bnd);
            rec.form = form.name;
            rec.h_over_dx = hr;
            rec.n = n;
            const auto t0 = Clock::now();
            const ElasticBarOptions o{.particles = n,
                                      .kernel = kt,
                                      .h_over_dx = hr,
                                      .gradient = form.gradient,
                                      .divergence = form.divergence,
                                      .boundary = bnd,
                                      .frame = form.frame};
            ElasticBar1D bar(o);
            auto sys = bar.system();
            if (form.xsph_eps > 0) {
              sys.velocity_hook = bar.xsph_hook(form.xsph_eps);
              sys.hook_mode = VelocityHookMode::Replace;
            }
            BarJumpProblem pf = problem;
            pf.velocity_left = form.amplitude;
            pf.velocity_right = -form.amplitude;
            const BarJumpExact ex(pf);
            Eigen::VectorXd u0 = Eigen::VectorXd::Zero(n), v0(n);
            for (int i = 0; i < n; ++i) v0[i] = ex.initial_velocity(bar.positions()[i]);
            rec.setup_s = seconds_since(t0);

            LeapfrogOptions opt;
            opt.dt = cfl_time_step(courant, bar.h(), c);
            opt.t_end = t_end;
            const long nsteps = static_cast<long>(std::ceil(t_end / opt.dt - 1e-9));
            opt.observe_every = static_cast<int>(std::max(1L, nsteps / 60));
            opt.record_every = 0;  // first and last only
            opt.limits.check_every = 10;
            opt.limits.max_displacement = 0.5;  // 50 x the physical displacement scale
            opt.limits.energy_growth = 10.0;
            double observe_s = 0, l1_sum = 0;
            int l1_count = 0;
            opt.observer = [&](const StepView& s) {
              const auto q0 = Clock::now();
              auto [l1, l2] = velocity_errors(bar, ex, s.v, s.time);
              if (s.step > 0) {
                l1_sum += l1;
                ++l1_count;
              }
              hist_csv.row({rec.kernel, hr, rec.boundary, rec.form, static_cast<long>(n), s.time, l1, l2});
              observe_s += seconds_since(q0);
            };
            auto res = run_leapfrog(sys, u0, v0, opt);
            rec.run_s = std::max(0.0, res.wall_seconds - observe_s);
            if (rec.run_s < 0.05) {  // short runs: best of up to 5 unobserved repeats for a stable time
              LeapfrogOptions topt = opt;
              topt.observer = nullptr;
              topt.observe_every = 0;
              for (int rep = 0; rep < 5; ++rep) {
                ElasticBar1D tb(o);  // fresh UL caches
                auto tsys = tb.system();
                if (form.xsph_eps > 0) {
                  tsys.velocity_hook = tb.xsph_hook(form.xsph_eps);
                  tsys.hook_mode = VelocityHookMode::Replace;
                }
                rec.run_s = std::min(rec.run_s, run_leapfrog(tsys, u0, v0, topt).wall_seconds);
              }
            }
            rec.total_s = rec.setup_s + rec.run_s;
            if (res.steps > 0) rec.us_per_particle_step = 1e6 * rec.run_s / (static_cast<double>(res.steps) * n);
            rec.dt = res.dt;
            rec.steps = res.steps;
            rec.status = run_status_name(res.status);
            rec.message = res.message;
            rec.builds = bar.neighbour_builds();
            rec.max_u_over_dx = res.u.cwiseAbs().maxCoeff() / bar.spacing();
            if (res.completed()) {
              auto [l1, l2] = velocity_errors(bar, ex, res.v, res.time);
              rec.l1 = l1;
              rec.l2 = l2;
              rec.l1_mean = l1_count ? l1_sum / l1_count : NAN;
              const double p0 = bar.masses().dot(v0);
              rec.momentum_error = std::abs(bar.masses().dot(res.v) - p0) / std::abs(p0);
              const auto& h0 = res.history.front();
              const auto& h1 = res.history.back();
              rec.energy_change = (h1.total - h0.total) / h0.total;
              if (kt == KernelType::CubicSpline && hr == 1.3 && (n == 100 || n == 400))
                for (int i = 0; i < n; ++i)
                  prof_csv.row({rec.kernel, hr, rec.boundary, rec.form, static_cast<long>(n), bar.positions()[i],
                                res.v[i] * (0.01 / form.amplitude)});
            }
            runs_csv.row({rec.kernel, hr, rec.boundary, rec.form, static_cast<long>(n), rec.dt, rec.steps, rec.status,
                          rec.setup_s, rec.run_s, rec.total_s, rec.l1, rec.l2, rec.l1_mean, rec.momentum_error,
                          rec.energy_change, rec.builds, rec.us_per_particle_step, rec.max_u_over_dx});
            records.push_back(rec);
            progress.update(static_cast<double>(records.size()), static_cast<double>(total_runs),
                            rec.kernel + " h/dx=" + sig(hr, 4) + " " + rec.boundary + " " + rec.form +
                                " N=" + std::to_string(n) + " " + rec.status);
          }
        }
  progress.finish(std::to_string(records.size()) + " runs");

  // Convergence rates: slope of L1(t = 1.5) against N over N >= 200 (asymptotic range) and against seconds.
  CsvWriter rates_csv(out + "/rates.csv", {"kernel", "h_over_dx", "boundary", "formulation", "l1_rate_vs_n",
                                           "l1_mean_rate_vs_n", "l1_vs_seconds_slope", "l1_at_nmax", "completed"});
  struct RateRow {
    std::string key;
    double rate, rate_mean, slope_s, l1_max;
    int completed;
  };
  std::vector<RateRow> rate_rows;
  for (KernelType kt : kernels)
    for (double hr : ratios)
      for (BarBoundary bnd : boundaries)
        for (const auto& form : formulations()) {
          std::vector<double> n, e, em, s;
          int done = 0;
          double l1max = NAN;
          for (const auto& r : records)
            if (r.kernel == kernel_name(kt) && r.h_over_dx == hr && r.boundary == bar_boundary_name(bnd) &&
                r.form == form.name) {
              if (r.status == "completed") ++done;
              if (r.n == ns.back()) l1max = r.l1;
              if (r.n < 200 && ns.back() > 200) continue;
              n.push_back(r.n);
              e.push_back(r.l1);
              em.push_back(r.l1_mean);
              s.push_back(r.total_s);
            }
          // study::loglog_slope skips the NaN errors of runs that blew up (L1 >= 0, wall seconds > 0), so the rates
          // use completed runs only.
          const double rate = -study::loglog_slope(n, e), rate_m = -study::loglog_slope(n, em),
                       slope_s = study::loglog_slope(s, e);
          rates_csv.row({kernel_name(kt), hr, bar_boundary_name(bnd), form.name, rate, rate_m, slope_s, l1max,
                         static_cast<long>(done)});
          rate_rows.push_back(
              {kernel_name(kt) + " | " + sig(hr, 4) + " | " + bar_boundary_name(bnd) + " | " + form.name, rate, rate_m,
               slope_s, l1max, done});
        }

  // Powell Table 2.1 "Reference" row, qualitatively: semi-infinite bar (8 cm, 800 particles, h = 1.3 dx, cubic
  // B-spline), mean relative velocity error (2.72) at particle 80 (x = 0.795) over 3 < t < 20 µs, where the exact
  // velocity is -0.01 cm/µs.
  struct PowellCase {
    std::string name;
    Formulation form;
    double eps;
    VelocityHookMode mode;
    double powell_pct;
    std::string powell_label;
  };
  const auto& F = formulations();
  std::vector<PowellCase> pcases = {
      {"SPH (tl-plain)", F[0], 0.0, VelocityHookMode::DriftOnly, 0.3474, "SPH"},
      {"SPH (ul-plain)", F[4], 0.0, VelocityHookMode::DriftOnly, 0.3474, "SPH"},
      {"SPH (ul-minus-plus)", F[5], 0.0, VelocityHookMode::DriftOnly, 0.3474, "SPH"},
      {"XSPH drift-only (tl-plain)", F[0], 0.1, VelocityHookMode::DriftOnly, 0.0300, "XSPH"},
      {"XSPH replace (tl-plain)", F[0], 0.1, VelocityHookMode::Replace, 0.0300, "XSPH"},
      {"corrected (tl-corrected)", F[2], 0.0, VelocityHookMode::DriftOnly, 0.2243, "NCSPH"},
      {"corrected + XSPH replace", F[2], 0.1, VelocityHookMode::Replace, 0.0056, "NCXSPH"}};
  CsvWriter powell_csv(out + "/powell.csv", {"case", "formulation", "xsph_eps", "xsph_mode", "mean_rel_error_pct",
                                             "powell_label", "powell_pct", "status"});
  std::vector<std::pair<std::string, std::pair<double, double>>> powell_rows;
  for (const auto& pc : pcases) {
    BarJumpProblem pp = problem;
    pp.length = 8.0;
    BarJumpExact pex(pp);
    ElasticBar1D bar({.particles = 800,
                      .length = 8.0,
                      .h_over_dx = 1.3,
                      .gradient = pc.form.gradient,
                      .divergence = pc.form.divergence,
                      .frame = pc.form.frame});
    auto sys = bar.system();
    if (pc.eps > 0) {
      sys.velocity_hook = bar.xsph_hook(pc.eps);
      sys.hook_mode = pc.mode;
    }
    Eigen::VectorXd v0(bar.size());
    for (int i = 0; i < bar.size(); ++i) v0[i] = pex.initial_velocity(bar.positions()[i]);
    LeapfrogOptions opt;
    opt.dt = cfl_time_step(courant, bar.h(), c);
    opt.t_end = 20.0;
    opt.observe_every = 1;
    opt.limits.energy_growth = 10.0;
    opt.limits.check_every = 50;
    double sum = 0;
    long count = 0;
    opt.observer = [&](const StepView& s) {
      if (s.time <= 3.0) return;
      const double ve = pex.velocity(bar.positions()[79], s.time);  // particle 80 (1-based)
      sum += std::abs(s.v[79] - ve) / std::abs(ve);
      ++count;
    };
    auto res = run_leapfrog(sys, Eigen::VectorXd::Zero(bar.size()), v0, opt);
    const double pct = res.completed() ? 100.0 * sum / count : NAN;
    powell_csv.row({pc.name, pc.form.name, pc.eps,
                    pc.eps > 0 ? (pc.mode == VelocityHookMode::Replace ? "replace" : "drift-only") : "-", pct,
                    pc.powell_label, pc.powell_pct, run_status_name(res.status)});
    powell_rows.push_back({pc.name + " | " + pc.powell_label, {pct, pc.powell_pct}});
    std::fprintf(stderr, "[speed-vs-error] Powell case %s: %.4f %% (Powell %s %.4f %%)\n", pc.name.c_str(), pct,
                 pc.powell_label.c_str(), pc.powell_pct);
  }
  // UL (minus gradient + plus divergence, the consistent pair) linearised about a uniform strain of ±2 % (the strain
  // scale v0/c of this problem), n = 100, no ghosts (a uniformly strained free bar is consistent there):
  // A = -da/du by finite differences (dense), min Re of its eigenvalues. Negative = exponentially growing mode of
  // ü = -A u for every dt (tensile / compressive instability, Swegle; Powell ch. 3). TL has no such term.
  CsvWriter lin_csv(out + "/ul_linearised.csv",
                    {"kernel", "h_over_dx", "strain", "min_re_mu", "growth_rate_per_us", "max_abs_mu"});
  struct LinRow {
    std::string kernel;
    double hr, strain, minre, growth;
  };
  std::vector<LinRow> lin_rows;
  for (KernelType kt : kernels)
    for (double hr : ratios)
      for (double strain : {0.02, 0.0, -0.02}) {
        // skin 5 dx: no neighbour rebuilds between the probes
        ElasticBar1D ul({.particles = 100,
                         .kernel = kt,
                         .h_over_dx = hr,
                         .gradient = StrainGradient::Minus,
                         .divergence = StressDivergence::Plus,
                         .boundary = BarBoundary::None,
                         .frame = LagrangianFrame::Updated,
                         .skin_over_dx = 5.0});
        const int n = ul.size();
        Eigen::VectorXd u0 = strain * (ul.positions().array() - 0.5).matrix(), a0(n), a1(n);
        ul.acceleration(u0, a0);
        Eigen::MatrixXd A(n, n);
        const double eps = 1e-7 * ul.spacing();
        for (int j = 0; j < n; ++j) {
          Eigen::VectorXd u = u0;
          u[j] += eps;
          ul.acceleration(u, a1);
          A.col(j) = -(a1 - a0) / eps;
        }
        Eigen::VectorXcd mu = Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
        const double minre = mu.real().minCoeff(), maxab = mu.cwiseAbs().maxCoeff();
        // Below 1e-9 |mu|max the sign is finite-difference noise.
        const double growth = minre < -1e-9 * maxab ? std::sqrt(-minre) : 0.0;
        lin_csv.row({kernel_name(kt), hr, strain, minre, growth, maxab});
        lin_rows.push_back({kernel_name(kt), hr, strain, minre, growth});
      }

  // Second route to the same growth rate: seed the sawtooth mode (amplitude 1e-8 dx) on the uniformly stretched
  // (+2 %) bar, cubic, h/dx = 1, n = 100, UL minus/plus, and measure the growth of its interior amplitude.
  double seeded_rate = NAN, seeded_saturation = 0, lin_rate_h1 = NAN;
  for (const auto& l : lin_rows)
    if (l.kernel == "cubic" && l.hr == 1.0 && l.strain == 0.02) lin_rate_h1 = l.growth;
  {
    CsvWriter seed_csv(out + "/ul_tensile_seed.csv", {"t", "sawtooth_amplitude_over_dx"});
    ElasticBar1D ul({.particles = 100,
                     .h_over_dx = 1.0,
                     .gradient = StrainGradient::Minus,
                     .divergence = StressDivergence::Plus,
                     .boundary = BarBoundary::None,
                     .frame = LagrangianFrame::Updated});
    const int n = ul.size();
    Eigen::VectorXd base = 0.02 * (ul.positions().array() - 0.5).matrix(), saw(n);
    for (int i = 0; i < n; ++i) saw[i] = (i % 2) ? 1.0 : -1.0;
    LeapfrogStepper st(ul.system(), base + 1e-8 * ul.spacing() * saw, Eigen::VectorXd::Zero(n));
    const double dt = cfl_time_step(courant, ul.h(), c);
    double t_a = NAN, t_b = NAN;
    SnapshotFunction seed([&](const StepView& s) {
      if (s.time >= 0.9) return;  // the state the last step reached is not part of the record
      const Eigen::VectorXd d = s.u - base;
      const double amp = std::abs(d.segment(30, 40).dot(saw.segment(30, 40))) / 40.0 / ul.spacing();
      seed_csv.row({s.time, amp});
      if (std::isnan(t_a) && amp > 1e-7) t_a = s.time;
      if (std::isnan(t_b) && amp > 1e-5) t_b = s.time;
      seeded_saturation = std::max(seeded_saturation, amp);
    });
    study::run_probed(st, dt, 0.9, seed);
    seeded_rate = std::log(1e-5 / 1e-7) / (t_b - t_a);
  }

  const double wall = seconds_since(wall0);

  // ---- Key numbers for summary.md.in ----
  auto find = [&](const std::string& k, double hr, const std::string& b, const std::string& f,
                  int n) -> const RunRecord* {
    for (const auto& r : records)
      if (r.kernel == k && r.h_over_dx == hr && r.boundary == b && r.form == f && r.n == n) return &r;
    return nullptr;
  };
  auto rate_of = [&](const std::string& k, double hr, const std::string& b, const std::string& f) -> double {
    const std::string key = k + " | " + sig(hr, 4) + " | " + b + " | " + f;
    for (const auto& r : rate_rows)
      if (r.key == key) return r.rate;
    return NAN;
  };
  const int nmax = ns.back();
  auto l1_of = [&](const std::string& k, double hr, const std::string& b, const std::string& f) -> double {
    const RunRecord* r = find(k, hr, b, f, nmax);
    return r ? r->l1 : NAN;
  };
  const std::string k0 = "cubic", k1 = quick ? "cubic" : "wendland-c2";
  study::Summary sum;
  sum.set("out", out);
  sum.set("quick_flag", quick ? " --quick" : "");
  sum.set("wall_seconds", fixed(wall, 1));
  sum.set("c", fixed(c, 6));
  sum.set("kernels", quick ? "cubic B-spline" : "cubic B-spline and Wendland C2");
  std::string n_list;
  for (int n : ns) n_list += (n_list.empty() ? "" : ", ") + std::to_string(n);
  sum.set("n_list", n_list);
  sum.set("runs_per_config", static_cast<int>(ns.size()));
  sum.set("courant", courant, 6);
  sum.set("nmax", nmax);
  sum.set("k1", k1);

  // Findings 1-3: rates and L1 at n = nmax.
  sum.set("rate_plain_1", fixed(rate_of(k0, 1.0, "mirror", "tl-plain"), 2));
  sum.set("rate_plain_2", fixed(rate_of(k0, 2.0, "mirror", "tl-plain"), 2));
  sum.set("rate_xsph_1", fixed(rate_of(k0, 1.0, "mirror", "tl-plain-xsph"), 2));
  sum.set("rate_xsph_2", fixed(rate_of(k0, 2.0, "mirror", "tl-plain-xsph"), 2));
  sum.set("l1_plain_1", l1_of(k0, 1.0, "mirror", "tl-plain"), 4);
  sum.set("l1_xsph_1", l1_of(k0, 1.0, "mirror", "tl-plain-xsph"), 4);
  sum.set("rate_plain_13", fixed(rate_of(k0, 1.3, "mirror", "tl-plain"), 2));
  sum.set("l1_plain_13", l1_of(k0, 1.3, "mirror", "tl-plain"), 4);
  sum.set("rate_plain_k1_1", fixed(rate_of(k1, 1.0, "mirror", "tl-plain"), 2));
  sum.set("l1_plain_k1_1", l1_of(k1, 1.0, "mirror", "tl-plain"), 4);
  sum.set("rate_corrected_13", fixed(rate_of(k0, 1.3, "mirror", "tl-corrected"), 2));
  sum.set("l1_corrected_13", l1_of(k0, 1.3, "mirror", "tl-corrected"), 4);
  sum.set("l1_corrected_k1_1", l1_of(k1, 1.0, "mirror", "tl-corrected"), 4);
  sum.set("l1_plain_none_13", fixed(l1_of(k0, 1.3, "none", "tl-plain"), 2));
  sum.set("l1_minus_none_13", fixed(l1_of(k0, 1.3, "none", "tl-minus"), 2));
  sum.set("l1_corrected_none_13", l1_of(k0, 1.3, "none", "tl-corrected"), 4);

  // Finding 4: updated Lagrangian.
  int ul_done = 0, ul_total = 0, ump_done = 0, ump_total = 0;
  long smin = 1L << 40, smax = 0;
  double dmin = INFINITY, dmax = 0;
  std::string ump_fail;
  for (const auto& r : records) {
    if (r.form == "ul-plain") {
      ++ul_total;
      if (r.status == "completed") {
        ++ul_done;
      } else {
        smin = std::min(smin, r.steps);
        smax = std::max(smax, r.steps);
        const double drift = 0.01 * r.dt * r.steps * r.n;  // rigid drift v0 t in units of dx = 1/n
        dmin = std::min(dmin, drift);
        dmax = std::max(dmax, drift);
      }
    }
    if (r.form == "ul-minus-plus") {
      ++ump_total;
      if (r.status == "completed")
        ++ump_done;
      else
        ump_fail += (ump_fail.empty() ? "" : ", ") + r.kernel + " " + sig(r.h_over_dx, 4) + " " + r.boundary +
                    " n=" + std::to_string(r.n);
    }
  }
  sum.set("ul_plain_completed", ul_done);
  sum.set("ul_plain_runs", ul_total);
  sum.set("ul_plain_steps_min", smin);
  sum.set("ul_plain_steps_max", smax);
  sum.set("ul_plain_drift_min", fixed(dmin, 1));
  sum.set("ul_plain_drift_max", fixed(dmax, 1));
  sum.set("ul_minus_plus_completed", ump_done);
  sum.set("ul_minus_plus_runs", ump_total);
  sum.set("ul_minus_plus_failed", ump_fail.empty() ? "" : " (failed: " + ump_fail + ")");
  const RunRecord* um = find(k0, 1.3, "mirror", "ul-minus-plus", nmax);
  const RunRecord* ts = find(k0, 1.3, "mirror", "tl-plain", nmax);
  sum.set("l1_ul_minus_plus_13", um ? sig(um->l1, 4) : "-");
  sum.set("l1_tl_plain_13", ts ? sig(ts->l1, 4) : "-");
  sum.set("lin_rate_h1", fixed(lin_rate_h1, 1));
  sum.set("seeded_rate", fixed(seeded_rate, 1));
  sum.set("seeded_saturation", seeded_saturation, 2);

  // Findings 5-6: cost and time step.
  const RunRecord* tl13 = find(k0, 1.3, "mirror", "tl-plain", nmax);
  const RunRecord* ul13 = find(k0, 1.3, "mirror", "ul-minus-plus", nmax);
  const double tl_us = tl13 ? tl13->us_per_particle_step : NAN, ul_us = ul13 ? ul13->us_per_particle_step : NAN;
  sum.set("tl_us", fixed(tl_us, 3));
  sum.set("ul_us", fixed(ul_us, 3));
  sum.set("ul_over_tl", fixed(ul_us / tl_us, 1));
  double cmax_min = INFINITY, cmax_diff = 0;  // C_max at n = 200 (dense) vs n = nmax (Spectra)
  std::string table;
  for (std::size_t k = 0; k < stab_rows.size(); ++k) {
    const StabRow& r = stab_rows[k];
    if (std::isfinite(r.courant_max)) cmax_min = std::min(cmax_min, r.courant_max);
    if (k + 1 < stab_rows.size() && r.n == 200 && stab_rows[k + 1].n == nmax && nmax != 200)
      cmax_diff = std::max(cmax_diff, std::abs(r.courant_max - stab_rows[k + 1].courant_max) / r.courant_max);
    if (r.n == 200)
      md_row(table, {r.key, sig(r.lambda_max, 4), fixed(r.courant_max, 3), sig(r.min_re, 3), fixed(r.m1, 6)});
  }
  sum.set("courant_max_min", fixed(cmax_min, 2));
  sum.set("courant_pct", fixed(courant / cmax_min * 100, 0));
  sum.set("courant_max_diff_pct", fixed(100 * cmax_diff, 3));
  sum.set("stability_table", table);

  table.clear();
  for (const auto& l : lin_rows)
    md_row(table, {l.kernel, sig(l.hr, 6), fixed(l.strain, 2, true), sig(l.minre, 3), sig(l.growth, 3)});
  sum.set("ul_linearised_table", table);

  table.clear();
  for (const auto& r : rate_rows)
    md_row(table, {r.key, sig(r.l1_max, 4), fixed(r.rate, 2), fixed(r.rate_mean, 2), fixed(r.slope_s, 2),
                   std::to_string(r.completed)});
  sum.set("rates_table", table);

  // Pareto front: completed runs not beaten in both error and time, fastest first.
  std::vector<const RunRecord*> ok;
  for (const auto& r : records)
    if (r.status == "completed") ok.push_back(&r);
  std::sort(ok.begin(), ok.end(), [](auto a, auto b) { return a->total_s < b->total_s; });
  table.clear();
  double best = INFINITY;
  for (const auto* r : ok)
    if (r->l1 < best) {
      best = r->l1;
      md_row(table, {fixed(r->total_s, 4), sig(r->l1, 4), r->kernel, sig(r->h_over_dx, 6), r->boundary, r->form,
                     std::to_string(r->n)});
    }
  sum.set("pareto_table", table);

  table.clear();
  for (double hr : ratios) {
    const RunRecord* tl = find(k0, hr, "mirror", "tl-plain", nmax);
    const RunRecord* ul = find(k0, hr, "mirror", "ul-minus-plus", nmax);
    const RunRecord* up = find(k0, hr, "mirror", "ul-plain", nmax);
    if (tl && ul && up)
      md_row(table,
             {sig(hr, 6), fixed(tl->us_per_particle_step, 4), fixed(up->us_per_particle_step, 4),
              fixed(ul->us_per_particle_step, 4), fixed(ul->us_per_particle_step / tl->us_per_particle_step, 1)});
  }
  sum.set("cost_table", table);

  // Powell Table 2.1.
  table.clear();
  for (const auto& [k, v] : powell_rows) {
    auto sep = k.find(" | ");
    md_row(table,
           {k.substr(0, sep), k.substr(sep + 3), std::isnan(v.first) ? "blew up" : sig(v.first, 4), sig(v.second, 4)});
    for (auto [prefix, key] : {std::pair{"SPH (tl-plain)", "powell_sph"},
                               {"XSPH replace", "powell_xsph_replace"},
                               {"XSPH drift-only", "powell_xsph_drift"},
                               {"corrected (tl", "powell_corrected"},
                               {"corrected + XSPH", "powell_corrected_xsph"}})
      if (k.rfind(prefix, 0) == 0) sum.set(key, v.first, 4);
  }
  sum.set("powell_table", table);

  table.clear();
  for (const auto& r : records)
    if (r.status != "completed")
      table += (table.empty() ? "- " : "\n- ") + r.kernel + " h/Δx = " + sig(r.h_over_dx, 6) + ", " + r.boundary +
               ", " + r.form + ", n = " + std::to_string(r.n) + ": " + r.message;
  sum.set("blowups", table.empty() ? "- none" : table);
  sum.write(out);
  std::fprintf(stderr, "[speed-vs-error] wrote %s/summary.json (wall %.1f s)\n", out.c_str(), wall);
  return 0;
}
