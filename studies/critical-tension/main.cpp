// Study: critical tension of a 1D SPH bar (Powell 2012, ch. 3, Fig. 3.2 and conclusions p. 99-100).
//
// Writes to --out DIR:
//   fig32.csv       N = 30 free particles, 6 kernels, h/dx = 0.8..3.0 step 0.05, conservative form (n = 4):
//                   matrix T_crit by both routes, their disagreement, the estimates (3.42), (3.49), (3.43),
//                   (3.51), Swegle, the infinite-lattice limit and the critical mode's wavenumber
//   forms.csv       the same sweep for the uncorrected (n = 1) and plus (n = 2) forms: T_crit ratios to conservative
//   versus_n.csv    T_crit(N) for N = 15..960 free particles at selected h, and the infinite-lattice limit
//   exponents.csv   fitted decay exponents p of T_crit ~ N^-p (or of T_crit - T_inf)
//   growth.csv      growth rate and unstable-mode wavenumber at T = 1.5 T_crit (N = 30, dense dgeev)
//   timing.csv      wall time of the N = 30 sweep per method
//   summary.md      parameters, key numbers, wall time, comparison with Powell's conclusions
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sphstab/core/format.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"
#include "sphstab/spectral/tension_estimates.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace {

using namespace sphstab;
using Clock = std::chrono::steady_clock;

const std::vector<KernelType> kKernels{KernelType::CubicSpline, KernelType::QuarticSpline, KernelType::QuinticSpline,
                                       KernelType::WendlandC2,  KernelType::WendlandC4,    KernelType::Gaussian};
const std::vector<int> kSizes{15, 30, 60, 120, 240, 480, 960};
const std::vector<double> kHVersusN{1.0, 1.2, 1.5, 2.0};

std::string num(double v) { return format_number(v, 12); }

std::string sig(double v, int digits = 3) { return std::isinf(v) ? "inf" : format_number(v, digits); }

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// h/dx = 0.8 + 0.05 i, i = 0..44, computed exactly in decimal (no accumulated rounding).
std::vector<double> h_grid() {
  std::vector<double> hs;
  for (int i = 0; i <= 44; ++i) hs.push_back((80 + 5 * i) / 100.0);
  return hs;
}

struct SweepRow {
  KernelType kernel;
  double h;
  CriticalLoad r;
  TensionEstimates1d est;
  SymbolCriticalTension inf;
};

/// Least-squares slope of log y against log x.
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const int n = static_cast<int>(x.size());
  for (int i = 0; i < n; ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? std::nan("") : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Critical tension study (Powell Fig. 3.2)"};
  std::string out_dir = "results/critical-tension";
  app.add_option("--out", out_dir, "Output directory");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out_dir);
  const auto t_start = Clock::now();
  const std::vector<double> hs = h_grid();
  const int n_cons = initial_stress_multiplier(MomentumForm::Conservative);

  // ---- Fig. 3.2: N = 30, conservative. Timed sweeps per method (jacobian assembly included). ----
  std::cout << "critical-tension: N = 30 sweep, " << kKernels.size() << " kernels x " << hs.size() << " h\n";
  std::map<std::string, double> timing;
  for (auto [name, method] :
       {std::pair{"eig", CriticalLoadMethod::Eigen}, std::pair{"bisect", CriticalLoadMethod::Bisection},
        std::pair{"both", CriticalLoadMethod::Both}}) {
    // Best of 3 (the machine is shared; the minimum is the least disturbed measurement).
    double best = 1e300;
    for (int rep = 0; rep < 3; ++rep) {
      const auto t0 = Clock::now();
      double sink = 0;
      for (KernelType type : kKernels) {
        Kernel<1> kernel(type);
        for (double h : hs) {
          CriticalLoadOptions o = CriticalLoadOptions::tension_1d();
          o.method = method;
          sink += critical_tension_1d(tension_lattice_1d(kernel, h, 30), kernel, h, MomentumForm::Conservative, o).load;
          sink += tension_estimates_1d(kernel, h, 1.0, n_cons).first_minor;
        }
      }
      best = std::min(best, seconds_since(t0));
      if (!(sink > 0)) std::cerr << "unexpected sweep sum\n";
    }
    timing[name] = best;
  }

  std::vector<SweepRow> sweep;
  std::vector<std::array<double, 3>> form_rows;  // tcrit uncorrected, plus, conservative
  for (KernelType type : kKernels) {
    Kernel<1> kernel(type);
    for (double h : hs) {
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, 30);
      CriticalLoadOptions with_mode = CriticalLoadOptions::tension_1d();
      with_mode.want_mode = true;
      SweepRow row{type, h, critical_tension_1d(set, kernel, h, MomentumForm::Conservative, with_mode),
                   tension_estimates_1d(kernel, h, 1.0, n_cons), critical_tension_infinite_1d(kernel, h, 1.0, n_cons)};
      const CriticalLoad u = critical_tension_1d(set, kernel, h, MomentumForm::Uncorrected);
      const CriticalLoad p = critical_tension_1d(set, kernel, h, MomentumForm::Plus);
      form_rows.push_back({u.load, p.load, row.r.load});
      sweep.push_back(std::move(row));
    }
  }
  {
    std::ofstream f(out_dir + "/fig32.csv");
    f << "kernel,h_over_dx,tcrit,tcrit_eig,tcrit_bisect,rel_diff,t_first_minor,ratio_first_minor,t_second_minor,"
         "t_nn,t_nn_minor,t_swegle,tcrit_infinite,l_hat_sawtooth,k_infinite_over_pi,mode_k_over_pi,"
         "mode_k_sign_changes,k_rcond,status,reason\n";
    for (const auto& s : sweep)
      f << kernel_name(s.kernel) << "," << num(s.h) << "," << num(s.r.load) << "," << num(s.r.load_eigen) << ","
        << num(s.r.load_bisection) << "," << num(s.r.relative_difference) << "," << num(s.est.first_minor) << ","
        << num(s.est.first_minor / s.r.load) << "," << num(s.est.second_minor) << "," << num(s.est.nearest_neighbour)
        << "," << num(s.est.nearest_neighbour_minor) << "," << num(s.est.swegle) << "," << num(s.inf.tcrit) << ","
        << num(s.inf.l_hat_sawtooth) << "," << num(s.inf.k_over_pi) << "," << num(s.r.mode_wavenumber.k_projection)
        << "," << num(s.r.mode_wavenumber.k_sign_changes) << "," << num(s.r.a0_rcond) << "," << status_name(s.r.status)
        << "," << s.r.reason << "\n";
  }
  double max_form_dev = 0;
  {
    std::ofstream f(out_dir + "/forms.csv");
    f << "kernel,h_over_dx,tcrit_uncorrected,tcrit_plus,tcrit_conservative,ratio_uncorrected,ratio_plus\n";
    for (size_t i = 0; i < sweep.size(); ++i) {
      const auto& t = form_rows[i];
      const double ru = t[0] / t[2], rp = t[1] / t[2];
      max_form_dev = std::max({max_form_dev, std::abs(ru / 4 - 1), std::abs(rp / 2 - 1)});
      f << kernel_name(sweep[i].kernel) << "," << num(sweep[i].h) << "," << num(t[0]) << "," << num(t[1]) << ","
        << num(t[2]) << "," << num(ru) << "," << num(rp) << "\n";
    }
  }

  // ---- T_crit versus N. ----
  std::cout << "critical-tension: T_crit versus N (" << kSizes.front() << " .. " << kSizes.back() << ")\n";
  struct NRow {
    KernelType kernel;
    double h;
    int n;
    CriticalLoad r;
    double seconds;
  };
  std::vector<NRow> nrows;
  const auto t_n = Clock::now();
  for (KernelType type : kKernels) {
    Kernel<1> kernel(type);
    for (double h : kHVersusN)
      for (int n : kSizes) {
        const auto t0 = Clock::now();
        CriticalLoadOptions with_mode = CriticalLoadOptions::tension_1d();
        with_mode.want_mode = true;
        CriticalLoad r =
            critical_tension_1d(tension_lattice_1d(kernel, h, n), kernel, h, MomentumForm::Conservative, with_mode);
        nrows.push_back({type, h, n, std::move(r), seconds_since(t0)});
      }
  }
  const double versus_n_seconds = seconds_since(t_n);
  struct Exponent {
    KernelType kernel;
    double h, tinf, l_pi, slope, slope_excess;
    int n_lo, n_hi;
  };
  std::vector<Exponent> exps;
  {
    std::ofstream f(out_dir + "/versus_n.csv");
    f << "kernel,h_over_dx,N,tcrit,tcrit_eig,tcrit_bisect,rel_diff,tcrit_infinite,mode_k_over_pi,backend,k_rcond,"
         "seconds,status,reason\n";
    for (const auto& row : nrows) {
      const SymbolCriticalTension inf = critical_tension_infinite_1d(Kernel<1>(row.kernel), row.h, 1.0, n_cons);
      f << kernel_name(row.kernel) << "," << num(row.h) << "," << row.n << "," << num(row.r.load) << ","
        << num(row.r.load_eigen) << "," << num(row.r.load_bisection) << "," << num(row.r.relative_difference) << ","
        << num(inf.tcrit) << "," << num(row.r.mode_wavenumber.k_projection) << "," << row.r.eigen_backend << ","
        << num(row.r.a0_rcond) << "," << num(row.seconds) << "," << status_name(row.r.status) << "," << row.r.reason
        << "\n";
    }
    std::ofstream g(out_dir + "/exponents.csv");
    g << "kernel,h_over_dx,tcrit_infinite,l_hat_sawtooth,p_tcrit,p_excess,fit_n_min,fit_n_max\n";
    for (KernelType type : kKernels)
      for (double h : kHVersusN) {
        std::vector<double> x, y, ye;
        const SymbolCriticalTension inf = critical_tension_infinite_1d(Kernel<1>(type), h, 1.0, n_cons);
        // The three largest N whose T_crit is reliable (status successful: K positive definite and the two
        // routes within 1e-6).
        std::vector<const NRow*> ok;
        for (const auto& row : nrows)
          if (row.kernel == type && row.h == h && row.r.status == Status::Successful && std::isfinite(row.r.load))
            ok.push_back(&row);
        if (ok.size() > 3) ok.erase(ok.begin(), ok.end() - 3);
        for (const NRow* row : ok) {
          x.push_back(row->n);
          y.push_back(row->r.load);
          ye.push_back(row->r.load - inf.tcrit);
        }
        const double p = x.size() >= 2 ? -loglog_slope(x, y) : std::nan("");
        const bool excess_ok = inf.tcrit > 0 && std::all_of(ye.begin(), ye.end(), [](double v) { return v > 0; });
        const double pe = excess_ok && x.size() >= 2 ? -loglog_slope(x, ye) : std::nan("");
        const int n_lo = x.empty() ? 0 : int(x.front()), n_hi = x.empty() ? 0 : int(x.back());
        exps.push_back({type, h, inf.tcrit, inf.l_hat_sawtooth, p, pe, n_lo, n_hi});
        g << kernel_name(type) << "," << num(h) << "," << num(inf.tcrit) << "," << num(inf.l_hat_sawtooth) << ","
          << num(p) << "," << num(pe) << "," << n_lo << "," << n_hi << "\n";
      }
  }

  // ---- Growth rates above T_crit (N = 30, dense nonsymmetric eigen, h = 1.2). ----
  std::ofstream gr(out_dir + "/growth.csv");
  gr << "kernel,h_over_dx,tcrit,T,growth_rate,unstable_modes,mode_k_over_pi,mode_k_sign_changes\n";
  for (KernelType type : kKernels) {
    Kernel<1> kernel(type);
    const double h = 1.2;
    const Linearisation jac =
        analytic_jacobian_1d(tension_lattice_1d(kernel, h, 30), kernel, h, MomentumForm::Conservative);
    const CriticalLoad r = critical_load(jac, LoadDirection::Tension, CriticalLoadOptions::tension_1d());
    for (double factor : {0.5, 1.5, 4.0}) {
      const double t = factor * r.load;
      const GrowthAnalysis g = growth_rate(Eigen::MatrixXd(jac.at(t)), jac.x.col(0));
      gr << kernel_name(type) << "," << num(h) << "," << num(r.load) << "," << num(t) << "," << num(g.growth_rate)
         << "," << g.unstable.size() << "," << (g.unstable.empty() ? "nan" : num(g.unstable[0].wavenumber.k_projection))
         << "," << (g.unstable.empty() ? "nan" : num(g.unstable[0].wavenumber.k_sign_changes)) << "\n";
    }
  }
  gr.close();

  {
    std::ofstream f(out_dir + "/timing.csv");
    f << "what,seconds\n";
    for (auto& [k, v] : timing) f << "n30_sweep_" << k << "," << num(v) << "\n";
    f << "versus_n_all," << num(versus_n_seconds) << "\n";
  }

  // ---- Key numbers for the summary. ----
  double max_rel_diff = 0, max_rel_diff_h = 0;
  std::string max_rel_diff_kernel;
  std::map<KernelType, std::vector<double>> ratio_by_kernel, ratio_small_h;
  std::map<KernelType, std::pair<double, double>> peak;  // (tcrit max, h at max)
  std::map<KernelType, std::pair<double, double>> band;  // tcrit min/max over 1.2 <= h <= 2
  int finite_count = 0, total = 0, successful = 0, above_1e8 = 0;
  double min_tcrit_above_1e8 = 1e300, max_tcrit_above_1e8 = 0;
  for (const auto& s : sweep) {
    ++total;
    if (std::isfinite(s.r.load)) ++finite_count;
    if (s.r.status == Status::Successful) ++successful;
    if (s.r.relative_difference > 1e-8) {
      ++above_1e8;
      min_tcrit_above_1e8 = std::min(min_tcrit_above_1e8, s.r.load);
      max_tcrit_above_1e8 = std::max(max_tcrit_above_1e8, s.r.load);
    }
    if (s.r.relative_difference > max_rel_diff) {
      max_rel_diff = s.r.relative_difference;
      max_rel_diff_h = s.h;
      max_rel_diff_kernel = kernel_name(s.kernel);
    }
    const double ratio = s.est.first_minor / s.r.load;
    ratio_by_kernel[s.kernel].push_back(ratio);
    if (s.h <= 1.0 + 1e-12) ratio_small_h[s.kernel].push_back(ratio);
    auto& pk = peak[s.kernel];
    if (s.r.load > pk.first) pk = {s.r.load, s.h};
    if (s.h >= 1.2 - 1e-12 && s.h <= 2.0 + 1e-12) {
      auto& b = band[s.kernel];
      if (b.first == 0 && b.second == 0) b = {s.r.load, s.r.load};
      b.first = std::min(b.first, s.r.load);
      b.second = std::max(b.second, s.r.load);
    }
  }
  double all_ratio_min = 1e300, all_ratio_max = 0;
  std::vector<double> all_ratios;
  for (auto& [k, v] : ratio_by_kernel)
    for (double r : v) {
      all_ratio_min = std::min(all_ratio_min, r);
      all_ratio_max = std::max(all_ratio_max, r);
      all_ratios.push_back(r);
    }
  const double all_ratio_median = median(all_ratios);

  // ---- summary.md ----
  std::ostringstream md;
  md << "# Critical tension of a 1D SPH bar (Powell 2012, ch. 3, Fig. 3.2)\n\n"
     << "Generated by `studies/critical-tension/main.cpp` (`scripts/main.sh critical-tension`); plots by `plot.py`.\n\n"
     << "## Parameters\n\n"
     << "- Regular line lattice, spacing dx = 1 (T is dimensionless and does not depend on dx), N free particles "
        "plus fixed layers at every m dx < 2h (complete neighbourhoods), equal volumes dx.\n"
     << "- A(T) = K - n T L on the free block (Powell (3.40)): K = G_f G_f^T (sum over free and fixed neighbours), "
        "L = diag(sum_j H_ij) - H; n = 4 conservative (Fig. 3.2), 2 plus, 1 uncorrected.\n"
     << "- Kernels (support radius 2h for all, as in Fig. 3.2): cubic, quartic, quintic B-splines, Wendland C2 and "
        "C4 (1D forms), Gaussian truncated at 2h. h/dx = 0.80, 0.85, ..., 3.00 (45 values).\n"
     << "- T_crit = smallest T > 0 with A(T) not positive definite, by (i) bisection with CHOLMOD Cholesky (bracket "
        "by doubling, geometric bisection to hi/lo - 1 <= 1e-13) and (ii) the generalised eigenproblem "
        "L x = lambda K x, T_crit = 1/(n lambda_max) (dense LAPACK dsygv up to 200 unknowns, Spectra Cholesky mode "
        "above).\n"
     << "- Infinite-lattice (von Neumann) limit from the Fourier symbols: T_crit,inf = inf_k |g^(k)|^2/(n L^(k)); "
        "g^(pi/dx) = 0 for every kernel, so T_crit,inf = 0 whenever L^(pi/dx) > 0.\n\n";

  md << "## Wall time\n\n"
     << "| N = 30 sweep (270 cases: lattice, operators, K and L, T_crit, estimates) | seconds |\n|---|---|\n"
     << "| eigen route only (dense dsygv) | " << sig(timing["eig"]) << " |\n"
     << "| bisection only (CHOLMOD simplicial LL^T) | " << sig(timing["bisect"]) << " |\n"
     << "| both routes | " << sig(timing["both"]) << " |\n\n"
     << "Best of 3 runs on a shared 2-core machine with the reference BLAS. The brief's target (whole N = 30 sweep "
        "< 1 s) is "
     << (timing["both"] < 1.0 ? "met" : "NOT met") << ". T_crit versus N (" << nrows.size()
     << " cases up to N = 960): " << sig(versus_n_seconds) << " s. Whole study: " << sig(seconds_since(t_start))
     << " s (before plotting).\n\n";

  md << "## Key numbers (N = 30, conservative form)\n\n"
     << "- Bisection and eigen route: largest relative difference " << sig(max_rel_diff, 2) << " ("
     << max_rel_diff_kernel << ", h/dx = " << num(max_rel_diff_h) << "); " << above_1e8 << " of " << total
     << " cases differ by more than 1e-8"
     << (above_1e8 ? " (all with T_crit between " + sig(min_tcrit_above_1e8) + " and " + sig(max_tcrit_above_1e8) +
                         ", where K is ill-conditioned; see Numerical reliability)"
                   : std::string())
     << ". " << finite_count << " of " << total << " cases have a finite T_crit; " << successful << " of " << total
     << " have status successful. Timing of the routes up to N = 30000: benchmark.md.\n"
     << "- Form scaling: T_crit(uncorrected) / T_crit(conservative) = 4 and T_crit(plus) / T_crit(conservative) = 2 "
        "with largest relative deviation "
     << sig(max_form_dev, 2) << " over all 270 cases (exact: T_crit = tau_crit / n).\n\n"
     << "| kernel | max T_crit | at h/dx | T_crit range for 1.2 <= h/dx <= 2 | (3.42)/T_crit for h/dx <= 1 | "
        "(3.42)/T_crit median (all h) | (3.42)/T_crit max |\n|---|---|---|---|---|---|---|\n";
  for (KernelType type : kKernels) {
    const auto& v = ratio_by_kernel[type];
    const auto& vs = ratio_small_h[type];
    md << "| " << kernel_name(type) << " | " << sig(peak[type].first) << " | " << num(peak[type].second) << " | "
       << sig(band[type].first) << " .. " << sig(band[type].second) << " | "
       << sig(*std::min_element(vs.begin(), vs.end())) << " .. " << sig(*std::max_element(vs.begin(), vs.end()))
       << " | " << sig(median(v)) << " | " << sig(*std::max_element(v.begin(), v.end())) << " |\n";
  }
  md << "\nAll kernels: (3.42)/T_crit from " << sig(all_ratio_min) << " to " << sig(all_ratio_max) << ", median "
     << sig(all_ratio_median) << ".\n\n";

  md << "## T_crit versus N and the infinite-lattice limit\n\n"
     << "Fitted over the three largest N with a reliable T_crit (normally 240, 480, 960): T_crit ~ N^-p (p_tcrit), "
        "and where T_crit,inf > 0, T_crit - T_crit,inf ~ N^-p (p_excess).\n\n"
     << "| kernel | h/dx | L^(pi/dx) | T_crit,inf | T_crit(30) | T_crit(960) | p_tcrit | p_excess | fit N |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  std::vector<double> p_zero_limit;
  for (const auto& e : exps) {
    double t30 = std::nan(""), t960 = std::nan("");
    for (const auto& row : nrows)
      if (row.kernel == e.kernel && row.h == e.h) {
        if (row.n == 30) t30 = row.r.load;
        if (row.n == 960 && row.r.status == Status::Successful) t960 = row.r.load;
      }
    if (e.tinf == 0 && e.l_pi > 1e-12) p_zero_limit.push_back(e.slope);
    md << "| " << kernel_name(e.kernel) << " | " << num(e.h) << " | " << sig(e.l_pi) << " | " << sig(e.tinf) << " | "
       << sig(t30) << " | " << sig(t960) << " | " << sig(e.slope) << " | " << sig(e.slope_excess) << " | " << e.n_lo
       << "-" << e.n_hi << " |\n";
  }
  int zero_limit_cases = 0, positive_limit_cases = 0, neutral_cases = 0;
  for (const auto& s : sweep) {
    if (s.inf.tcrit == 0)
      ++zero_limit_cases;
    else if (s.inf.tcrit > 1e-12)
      ++positive_limit_cases;
    else
      ++neutral_cases;
  }
  std::sort(p_zero_limit.begin(), p_zero_limit.end());
  md << "\nOver the 270 (kernel, h) pairs of the sweep: T_crit,inf = 0 exactly (L^(pi/dx) > 0, the sawtooth is "
        "unstable under any tension on an infinite lattice) in "
     << zero_limit_cases << "; T_crit,inf > 1e-12 in " << positive_limit_cases
     << "; L^(pi/dx) = 0 to rounding with a limit below 1e-12 in " << neutral_cases
     << ". Where L^(pi/dx) > 0 the fitted exponents p lie in [" << sig(p_zero_limit.front()) << ", "
     << sig(p_zero_limit.back())
     << "] (expected 2: the critical mode is the sawtooth modulated by the lowest envelope, "
        "|g^|^2 ~ (pi/dx - k)^2 ~ 1/N^2).\n\n";

  // Numbers behind the statements.
  double r_small_min = 1e300, r_small_max = 0, r_mid_min = 1e300, r_mid_max = 0;
  std::map<KernelType, std::vector<double>> tcrit_large_h;  // h >= 1.5
  std::map<KernelType, std::vector<double>> window;         // h with T_crit,inf > 1e-12
  std::map<double, std::pair<double, double>> spread;       // h -> (min, max) over kernels
  std::map<double, std::pair<double, KernelType>> leader;   // h -> (max tcrit, kernel)
  double minor_ratio_min = 1e300, minor_ratio_max = 0;
  for (const auto& s : sweep) {
    const double ratio = s.est.first_minor / s.r.load;
    if (s.h <= 1.0 + 1e-12) r_small_min = std::min(r_small_min, ratio), r_small_max = std::max(r_small_max, ratio);
    if (s.h > 1.0 + 1e-12 && s.h <= 1.4 + 1e-12)
      r_mid_min = std::min(r_mid_min, ratio), r_mid_max = std::max(r_mid_max, ratio);
    if (s.h >= 1.5 - 1e-12) tcrit_large_h[s.kernel].push_back(s.r.load);
    if (s.inf.tcrit > 1e-12) window[s.kernel].push_back(s.h);
    auto& sp = spread[s.h];
    if (sp.first == 0 && sp.second == 0) sp = {s.r.load, s.r.load};
    sp.first = std::min(sp.first, s.r.load);
    sp.second = std::max(sp.second, s.r.load);
    minor_ratio_min = std::min(minor_ratio_min, s.est.first_minor / s.est.second_minor);
    minor_ratio_max = std::max(minor_ratio_max, s.est.first_minor / s.est.second_minor);
    auto& ld = leader[s.h];
    if (s.r.load > ld.first) ld = {s.r.load, s.kernel};
  }
  double spread_small_min = 1e300, spread_small_max = 0, spread_large_max = 0;
  for (auto& [h, sp] : spread) {
    const double f = sp.second / sp.first;
    if (h <= 1.4 + 1e-12)
      spread_small_min = std::min(spread_small_min, f), spread_small_max = std::max(spread_small_max, f);
    else
      spread_large_max = std::max(spread_large_max, f);
  }
  double c2_leads_up_to = 0;
  for (auto& [h, ld] : leader) {
    if (ld.second != KernelType::WendlandC2) break;
    c2_leads_up_to = h;
  }
  double growth_min = 1e300, growth_max = 0;
  {
    std::ifstream gin(out_dir + "/growth.csv");
    std::string line;
    std::getline(gin, line);
    while (std::getline(gin, line)) {
      std::vector<std::string> f;
      std::stringstream ss(line);
      std::string item;
      while (std::getline(ss, item, ',')) f.push_back(item);
      if (f.size() > 4 && std::abs(std::stod(f[3]) / std::stod(f[2]) - 1.5) < 1e-9) {
        growth_min = std::min(growth_min, std::stod(f[4]));
        growth_max = std::max(growth_max, std::stod(f[4]));
      }
    }
  }
  double cubic2_p = std::nan("");
  int cubic2_first_bad = 0;
  for (const auto& e : exps)
    if (e.kernel == KernelType::CubicSpline && std::abs(e.h - 2.0) < 1e-12) cubic2_p = e.slope;
  for (const auto& row : nrows)
    if (row.kernel == KernelType::CubicSpline && std::abs(row.h - 2.0) < 1e-12 && row.r.status != Status::Successful &&
        cubic2_first_bad == 0)
      cubic2_first_bad = row.n;
  double r960_min = 1e300, r960_max = 0, t960_min = 1e300, t960_max = 0;
  for (const auto& row : nrows)
    if (row.n == 960 && std::abs(row.h - 1.2) < 1e-12 && row.r.status == Status::Successful) {
      const double est = tension_estimates_1d(Kernel<1>(row.kernel), row.h, 1.0, n_cons).first_minor;
      r960_min = std::min(r960_min, est / row.r.load);
      r960_max = std::max(r960_max, est / row.r.load);
      t960_min = std::min(t960_min, row.r.load);
      t960_max = std::max(t960_max, row.r.load);
    }
  double band_max_min = 1e300, band_max_max = 0;
  int peaks_in_range = 0;
  std::string peak_list;
  for (KernelType type : kKernels) {
    band_max_min = std::min(band_max_min, band[type].second);
    band_max_max = std::max(band_max_max, band[type].second);
    if (peak[type].second >= 1.2 - 1e-12 && peak[type].second <= 2.0 + 1e-12) ++peaks_in_range;
    peak_list += (peak_list.empty() ? "" : ", ") + kernel_name(type) + " " + num(peak[type].second);
  }
  auto windows_text = [&](KernelType type) {
    const auto& w = window[type];
    if (w.empty()) return std::string("none");
    std::string t;
    size_t i = 0;
    while (i < w.size()) {
      size_t j = i;
      while (j + 1 < w.size() && std::abs(w[j + 1] - w[j] - 0.05) < 1e-9) ++j;
      t += (t.empty() ? "" : ", ") + num(w[i]) + (j > i ? "-" + num(w[j]) : "");
      i = j + 1;
    }
    return t;
  };

  md << "## Comparison with Powell's conclusions (p. 99-100, Fig. 3.2)\n\n"
     << "1. **\"(3.42) overestimates the tension needed for instability by a factor of about 100.\"** Holds for "
        "30 particles and h/dx up to about 1.4, and only there. At N = 30 the ratio (3.42)/T_crit is "
     << sig(r_small_min, 4) << " for every kernel at h/dx <= 1 (only nearest neighbours interact) and "
     << sig(r_mid_min) << "-" << sig(r_mid_max) << " for 1 < h/dx <= 1.4; over all h it ranges from "
     << sig(all_ratio_min) << " to " << sig(all_ratio_max) << " (median " << sig(all_ratio_median)
     << ") because T_crit collapses at some h. The factor depends on N: (3.42) does not depend on N while "
        "T_crit ~ N^-2, so at N = 960 and h/dx = 1.2 the ratio is "
     << sig(r960_min) << "-" << sig(r960_max)
     << ". The second-minor estimate (3.49) improves on (3.42) only by a factor " << sig(minor_ratio_min) << "-"
     << sig(minor_ratio_max) << " (fig32.csv).\n"
     << "2. **\"T_crit corresponds to stretching a bar of length 1 to less than 1.0005 (T about 5e-4).\"** The "
        "order of magnitude holds at N = 30: the largest T_crit over 1.2 <= h/dx <= 2 is "
     << sig(band_max_min) << "-" << sig(band_max_max)
     << " across kernels (per kernel in the table above). It depends on N: at N = 960 and h/dx = 1.2 it is "
     << sig(t960_min) << "-" << sig(t960_max)
     << " (T_crit ~ N^-2), and it vanishes on the infinite lattice except in the windows of item 4.\n"
     << "3. **\"A more stable sweet spot exists for h between 1.2 and 2 dx.\"** Mostly holds at N = 30: the "
        "maximum of T_crit(h) lies in [1.2, 2] for "
     << peaks_in_range << " of " << kKernels.size() << " kernels (h/dx at the maximum: " << peak_list
     << "). Where T_crit,inf = 0, T_crit ~ f(h)/N^2 (exponents near 2 at every sampled h), so the maximum "
        "should not move with N; but as N grows only the h with T_crit,inf > 0 (item 4) keep a finite critical "
        "tension, and those are kernel-specific.\n"
     << "4. **\"The performance of the kernels does not differ markedly.\"** Holds only loosely at N = 30 for "
        "h/dx <= 1.4: at a given h the six T_crit lie within a factor "
     << sig(spread_small_min, 2) << "-" << sig(spread_small_max, 2)
     << " of each other; for h/dx > 1.4 the factor reaches " << sig(spread_large_max, 2)
     << ". It fails in the large-N limit: T_crit,inf > 1e-12 only for cubic h/dx = "
     << windows_text(KernelType::CubicSpline) << "; quartic " << windows_text(KernelType::QuarticSpline) << "; quintic "
     << windows_text(KernelType::QuinticSpline) << "; Wendland C2 " << windows_text(KernelType::WendlandC2)
     << "; Wendland C4 " << windows_text(KernelType::WendlandC4) << "; Gaussian " << windows_text(KernelType::Gaussian)
     << ". For the cubic with 1.5 <= h/dx < 2.5, L^(pi/dx) = 0 exactly (W'' at the odd multiples of dx "
        "cancels), so the sawtooth is neutral rather than unstable.\n"
     << "5. **\"Wendland kernels may be slightly inferior.\"** Supported, more than slightly, for h/dx >= 1.5 at "
        "N = 30: median T_crit over 1.5 <= h/dx <= 3 is ";
  for (KernelType type : kKernels)
    md << kernel_name(type) << " " << sig(median(tcrit_large_h[type])) << (type == KernelType::Gaussian ? "" : ", ");
  md << ". Conversely, for h/dx <= " << num(c2_leads_up_to) << " Wendland C2 has the largest T_crit of the six.\n"
     << "6. **\"Conservative SPH needs exactly half the tension of the plus form\" (n = 4 against 2 in (3.40)).** "
        "Holds exactly (largest relative deviation "
     << sig(max_form_dev, 2) << ").\n"
     << "7. **Typos found in ch. 3 (checked numerically).** (3.41) prints W'_ij W'_ji in A_ii; the diagonal is "
        "sum_j W'_ij^2 > 0 (W'_ji = -W'_ij), as (3.42) then uses. (3.48) prints W_ij W_{i+1,j}; the entry "
        "A_{i,i+1} needs W'_ij W'_{i+1,j} (= K_{i,i+1}). (3.34b) prints S(-1) where the plus form S(1) is meant. "
        "The closed form A(T) = K - nT L and the conservative force (3.27) = -dU/du are both confirmed by "
        "complex-step differentiation (tests/jacobian/analytic_jacobian_1d_test.cpp).\n\n"
     << "## Critical mode and growth\n\n"
     << "Where L^(pi/dx) > 0 the critical mode is the sawtooth modulated by the lowest envelope: dominant "
        "wavenumber k dx/pi = N/(N+1) (0.968 for N = 30) by both the sine projection and the sign count "
        "(fig32.csv). Above T_crit the growth rate gamma = max Re sqrt(-mu) (dense dgeev) rises from 0; at "
        "h/dx = 1.2 and T = 1.5 T_crit, gamma = "
     << sig(growth_min, 2) << "-" << sig(growth_max, 2)
     << " (dx = 1, unit wave speed) for the six kernels, with the same sawtooth-like mode (growth.csv).\n\n"
     << "## Numerical reliability\n\n"
     << "Both routes see K = G_f G_f^T only through its rounded entries, so T_crit is resolved to about "
        "eps/rcond(K). The largest disagreement in the N = 30 sweep is "
     << sig(max_rel_diff, 2)
     << " (where T_crit < 1e-5 and K is ill-conditioned). In the N study, cubic h/dx = 2 has T_crit ~ N^-"
     << sig(cubic2_p, 2)
     << " (fitted on the small N that are reliable; the sawtooth is almost in the null space of G_f^T): from N = "
     << cubic2_first_bad
     << " on the two routes differ by more than 1e-6 and the status is numerical-issue; at N = 960 the Cholesky "
        "factorisation of K itself fails and no number is reported (versus_n.csv).\n";
  std::string text = md.str();
  std::ofstream(out_dir + "/summary.md") << text;
  std::cout << "critical-tension: wrote " << out_dir << " in " << sig(seconds_since(t_start)) << " s\n";
  return 0;
}
