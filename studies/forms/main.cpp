// Study forms: the four SPH momentum forms (uncorrected, plus, minus, conservative) in 1D, in tension AND compression
// [Powell2012, ch. 3 §3-4, (3.40), Theorem 3.8, Example 3.9, Theorem 3.10 and the conditions after it].
// Absorbs the former form_asymmetry study (Jacobian symmetry of each form, 1D and 2D, same configurations and code).
//
// Writes tcrit.csv, crosscheck.csv, compression_conditions.csv, asymmetry.csv, asymmetry_vs_amplitude.csv and
// summary.json to --out (see README.md); the prose of summary.md is in summary.md.in (scripts/render_summary.py).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/numerics/quadrature.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace {

using namespace sphstab;
using study::Clock;
using study::random_vector;
using study::seconds_since;
using study::sig;

std::string num(double v) { return format_number(v, 10); }

/// min over 0 <= k h <= 60 of F(k) / F(0), F(k) = 2 int_0^{2h} W(r) cos(k r) dr (h = 1), as in
/// tests/kernel/kernel_test.cpp.
double min_fourier_transform(KernelType type) {
  Kernel<1> w(type);
  auto f = [&](double k) {
    return 2 * integrate_gauss_legendre([&](double r) { return w.value(r, 1.0) * std::cos(k * r); }, 0.0,
                                        w.support_radius(1.0), 400);
  };
  const double f0 = f(0.0);
  double lo = 1e300;
  for (double k = 0.0; k <= 60.0; k += 0.01) lo = std::min(lo, f(k) / f0);
  return lo;
}

/// Lattice sum S(k) = sum_m W''(|m| dx) dx cos(k m dx) (m over all integers, m = 0 included: W''(0)), dx = 1.
double w2_symbol(const Kernel<1>& w, double h, double k) {
  double s = w.d2(0.0, h);
  for (int m = 1; m <= w.support_radius(h) + 1; ++m) s += 2 * w.d2(double(m), h) * std::cos(k * m);
  return s;
}

struct TcritRow {
  std::string kernel;
  double h;
  std::string form, direction;
  double tcrit, mode_k;
  std::string status, reason;
};

struct ConditionRow {
  std::string kernel;
  double h, ft_min, w2_lambda_max, w2_symbol_max, w2_row_sum, l_lambda_min, l_scale, l_symbol_min, tcrit_minus,
      tcrit_minus_infinite;
  bool cond1, cond3, cond1_infinite;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The 1D SPH momentum forms in tension and compression; Jacobian symmetry (Powell ch. 3)"};
  std::string out = "results/forms";
  int n = 30;
  bool quick = false;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles");
  app.add_flag("--quick", quick, "h/dx in steps of 0.25 (smoke run)");
  CLI11_PARSE(app, argc, argv);
  std::filesystem::create_directories(out);
  const auto start = Clock::now();
  std::vector<double> hs;
  for (int k = 0; k <= 30; k += quick ? 5 : 1) hs.push_back(1.0 + 0.05 * k);
  const std::vector<MomentumForm> forms = all_momentum_forms();

  // 1. T_crit in tension and compression, analytic route.
  std::vector<TcritRow> tcrit;
  std::map<std::pair<std::string, double>, double> cons_minus;  // conservative T_crit^- per (kernel, h)
  for (KernelType type : all_kernel_types()) {
    Kernel<1> kernel(type);
    for (double h : hs) {
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, n);
      CriticalLoadOptions with_mode = CriticalLoadOptions::tension_1d();
      with_mode.want_mode = true;
      for (MomentumForm form : forms)
        for (int dir = 0; dir < 2; ++dir) {
          const LoadDirection d = dir == 0 ? LoadDirection::Tension : LoadDirection::Compression;
          const CriticalLoad r = critical_tension_1d(set, kernel, h, form, with_mode, d);
          const double t = r.load;
          tcrit.push_back({kernel_name(type), h, momentum_form_name(form), load_direction_name(d), t,
                           std::isfinite(r.load) ? r.mode_wavenumber.k_projection : NAN, status_name(r.status),
                           r.reason});
          if (dir == 1 && form == MomentumForm::Conservative) cons_minus[{kernel_name(type), h}] = t;
        }
    }
    std::cout << "tcrit " << kernel_name(type) << std::endl;
  }
  {
    std::ofstream csv(out + "/tcrit.csv");
    csv << "kernel,h_over_dx,form,direction,tcrit,mode_k_over_pi,status,reason\n";
    for (const TcritRow& r : tcrit)
      csv << r.kernel << "," << num(r.h) << "," << r.form << "," << r.direction << "," << num(r.tcrit) << ","
          << num(r.mode_k) << "," << r.status << ",\"" << r.reason << "\"\n";
  }

  // 2. Cross-check: general affine route from the force functions' complex-step Jacobians.
  double cross_max = 0;
  int cross_cases = 0, cross_class_mismatch = 0;
  {
    std::ofstream csv(out + "/crosscheck.csv");
    csv << "kernel,h_over_dx,form,direction,tcrit_analytic,tcrit_affine,relative_difference\n";
    for (KernelType type : all_kernel_types()) {
      Kernel<1> kernel(type);
      for (double h : {1.2, 1.6, 2.0, 2.4}) {
        auto disc = make_discretisation(tension_lattice_1d(kernel, h, n), kernel, h);
        for (MomentumForm form : forms) {
          Linearisation split = affine_jacobian(WaveForm1D(disc, form, 0.0), Eigen::VectorXd::Zero(disc->dofs()));
          split.x = disc->free_positions();
          for (LoadDirection dir : {LoadDirection::Tension, LoadDirection::Compression}) {
            const double affine = critical_loads(split, dir).front().load;
            const double analytic =
                critical_tension_1d(disc->particles, kernel, h, form, CriticalLoadOptions::tension_1d(), dir).load;
            double rel = 0;
            if (std::isinf(analytic) != std::isinf(affine)) {
              rel = INFINITY;
              ++cross_class_mismatch;
            } else if (std::isfinite(analytic)) {
              rel = std::abs(affine / analytic - 1);
            }
            if (std::isfinite(rel)) cross_max = std::max(cross_max, rel);  // both infinite: rel = 0
            ++cross_cases;
            csv << kernel_name(type) << "," << num(h) << "," << momentum_form_name(form) << ","
                << load_direction_name(dir) << "," << num(analytic) << "," << num(affine) << "," << num(rel) << "\n";
          }
        }
      }
    }
  }
  std::cout << "crosscheck: max relative difference " << cross_max << std::endl;

  // 3. Compression conditions (Powell, after Theorem 3.10).
  std::vector<ConditionRow> conditions;
  std::map<std::string, double> ft_min;
  for (KernelType type : all_kernel_types()) {
    Kernel<1> kernel(type);
    ft_min[kernel_name(type)] = min_fourier_transform(type);
    for (double h : hs) {
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, n);
      const Linearisation jac = analytic_jacobian_1d(set, kernel, h);  // uncorrected: A1 = -L
      const Eigen::MatrixXd l_dense = -Eigen::MatrixXd(jac.A1);
      // W''-matrix of the free block, diagonal W''(0) included (Powell's "W''_km" of condition 1).
      Eigen::MatrixXd m(jac.dofs(), jac.dofs());
      for (int a = 0; a < jac.dofs(); ++a)
        for (int b = 0; b < jac.dofs(); ++b) m(a, b) = kernel.d2(std::abs(jac.x(a, 0) - jac.x(b, 0)), h);
      const double w2_lmax = symmetric_eigen(m).values.maxCoeff();
      const double l_lmin = symmetric_eigen(l_dense).values.minCoeff();
      double sym_max = -1e300, l_sym_min = 1e300, t_inf = -INFINITY;
      for (int g = 0; g <= 4096; ++g) {
        const double k = std::numbers::pi * g / 4096;
        sym_max = std::max(sym_max, w2_symbol(kernel, h, k));
        if (g == 0) continue;
        const FourierSymbol1D s = fourier_symbol_1d(kernel, h, 1.0, k);
        l_sym_min = std::min(l_sym_min, s.l_hat);
        // conservative (n = 4); |L^| below 1e-12 is round-off of a vanishing symbol
        if (s.l_hat < -1e-12) t_inf = std::max(t_inf, -s.g_abs2 / (4 * -s.l_hat));
      }
      const double row_sum = w2_symbol(kernel, h, 0.0);
      const double l_scale = Eigen::VectorXd(l_dense.diagonal()).cwiseAbs().maxCoeff();
      conditions.push_back({kernel_name(type), h, ft_min[kernel_name(type)], w2_lmax, sym_max, row_sum, l_lmin, l_scale,
                            l_sym_min, cons_minus[{kernel_name(type), h}], t_inf, w2_lmax < 0.0, (row_sum > 0.0),
                            sym_max <= 1e-12});
    }
    std::cout << "conditions " << kernel_name(type) << std::endl;
  }
  {
    std::ofstream csv(out + "/compression_conditions.csv");
    csv << "kernel,h_over_dx,fourier_min_relative,w2_matrix_lambda_max,w2_symbol_max,w2_row_sum,cond1_w2_negative_"
           "definite,cond3_row_sum_positive,L_lambda_min,L_symbol_min,tcrit_minus_conservative,"
           "tcrit_minus_infinite_conservative,cond1_infinite_lattice\n";
    for (const ConditionRow& r : conditions)
      csv << r.kernel << "," << num(r.h) << "," << num(r.ft_min) << "," << num(r.w2_lambda_max) << ","
          << num(r.w2_symbol_max) << "," << num(r.w2_row_sum) << "," << r.cond1 << "," << r.cond3 << ","
          << num(r.l_lambda_min) << "," << num(r.l_symbol_min) << "," << num(r.tcrit_minus) << ","
          << num(r.tcrit_minus_infinite) << "," << r.cond1_infinite << "\n";
  }

  // 4. Jacobian symmetry (the former form_asymmetry study: same configurations, kernel cubic, h = 1.3).
  struct AsymRow {
    int dim;
    std::string config, form;
    double displacement, disorder, load;
    std::string prestrain;
    double asymmetry;
  };
  struct Config {
    std::string name;
    double displacement, disorder, load;
    PreStrainKind kind;
  };
  const std::vector<Config> configs = {
      {"equilibrium", 0.0, 0.0, 0.1, PreStrainKind::Isotropic},
      {"equilibrium-uniaxial", 0.0, 0.0, 0.1, PreStrainKind::UniaxialX},
      {"displaced-unloaded", 0.05, 0.0, 0.0, PreStrainKind::Isotropic},
      {"displaced-loaded", 0.05, 0.0, 0.1, PreStrainKind::Isotropic},
      {"displaced-small-load", 0.05, 0.0, 1e-3, PreStrainKind::Isotropic},
      {"displaced-compressed", 0.05, 0.0, -0.1, PreStrainKind::Isotropic},
      {"disordered-loaded", 0.0, 0.1, 0.1, PreStrainKind::Isotropic},
  };
  const double ha = 1.3;
  const int n1 = 40, n2 = 12;
  const ElasticMaterial material{.lambda = 1.0, .mu = 1.0, .rho = 1.0};
  std::vector<AsymRow> asym;
  for (int dim : {1, 2})
    for (const Config& c : configs) {
      if (dim == 1 && c.kind == PreStrainKind::UniaxialX) continue;
      for (MomentumForm form : forms) {
        double a = 0;
        if (dim == 1) {
          Kernel<1> k(KernelType::CubicSpline);
          auto d = make_discretisation(
              make_lattice<1>(
                  LatticeType::Line, n1,
                  {.spacing = 1.0, .support_radius = k.support_radius(ha), .perturbation = c.disorder, .seed = 5}),
              k, ha);
          WaveForm1D f(d, form, c.load);
          a = relative_asymmetry(jacobian(f, random_vector(f.dofs(), c.displacement, 9)));
        } else {
          Kernel<2> k(KernelType::CubicSpline);
          auto d = make_discretisation(
              make_lattice<2>(
                  LatticeType::Square, n2,
                  {.spacing = 1.0, .support_radius = k.support_radius(ha), .perturbation = c.disorder, .seed = 5}),
              k, ha);
          ElasticForm2D f(d, material, form, {c.kind, c.load});
          a = relative_asymmetry(jacobian(f, random_vector(f.dofs(), c.displacement, 9)));
        }
        asym.push_back({dim, c.name, momentum_form_name(form), c.displacement, c.disorder, c.load,
                        dim == 1 ? "tension" : (c.kind == PreStrainKind::Isotropic ? "isotropic" : "uniaxial-x"), a});
      }
    }
  {
    std::ofstream csv(out + "/asymmetry.csv");
    csv << "dim,config,form,displacement_dx,disorder_dx,load,prestrain,relative_asymmetry\n";
    for (const AsymRow& r : asym)
      csv << r.dim << "," << r.config << "," << r.form << "," << num(r.displacement) << "," << num(r.disorder) << ","
          << num(r.load) << "," << r.prestrain << "," << num(r.asymmetry) << "\n";
  }
  struct AmpRow {
    std::string kernel, form;
    double load, amplitude, asymmetry;
  };
  std::vector<AmpRow> amp;
  for (KernelType type : {KernelType::CubicSpline, KernelType::WendlandC2}) {
    Kernel<1> k(type);
    auto d = make_discretisation(tension_lattice_1d(k, ha, n1), k, ha);
    for (double load : {-0.1, 0.0, 0.1})
      for (MomentumForm form : forms)
        for (double a : {1e-4, 1e-3, 1e-2, 3e-2, 1e-1}) {
          WaveForm1D f(d, form, load);
          amp.push_back({kernel_name(type), momentum_form_name(form), load, a,
                         relative_asymmetry(jacobian(f, random_vector(f.dofs(), a, 9)))});
        }
  }
  {
    std::ofstream csv(out + "/asymmetry_vs_amplitude.csv");
    csv << "kernel,form,load,amplitude_dx,relative_asymmetry\n";
    for (const AmpRow& r : amp)
      csv << r.kernel << "," << r.form << "," << num(r.load) << "," << num(r.amplitude) << "," << num(r.asymmetry)
          << "\n";
  }
  const double seconds = seconds_since(start);

  // 5. Key numbers for summary.md.in.
  study::Summary sum;
  sum.set("n", n);
  sum.set("kernels", static_cast<int>(all_kernel_types().size()));
  sum.set("h_min", hs.front(), 6);
  sum.set("h_max", hs.back(), 6);
  sum.set("h_step", quick ? "0.25" : "0.05");
  sum.set("cross_cases", cross_cases);
  sum.set("cross_max", cross_max, 2);
  sum.set("cross_mismatch", cross_class_mismatch);
  sum.set("asym_h", ha, 6);
  sum.set("asym_n1", n1);
  sum.set("asym_n2", n2);
  sum.set("wall_seconds", seconds);

  auto tc = [&](const std::string& kernel, double h, const std::string& form, const std::string& dir) {
    for (const TcritRow& r : tcrit)
      if (r.kernel == kernel && std::abs(r.h - h) < 1e-9 && r.form == form && r.direction == dir) return r.tcrit;
    return std::numeric_limits<double>::quiet_NaN();
  };
  double ratio_dev = 0;
  bool minus_inf = true;
  for (const TcritRow& r : tcrit) {
    if (r.form == "minus") minus_inf = minus_inf && std::isinf(r.tcrit);
    if (r.form != "conservative" || !std::isfinite(r.tcrit)) continue;
    ratio_dev = std::max(ratio_dev, std::abs(tc(r.kernel, r.h, "uncorrected", r.direction) / r.tcrit - 4));
    ratio_dev = std::max(ratio_dev, std::abs(tc(r.kernel, r.h, "plus", r.direction) / r.tcrit - 2));
  }
  sum.set("ratio_dev", ratio_dev, 2);
  sum.set("minus_critical_load", minus_inf ? "no" : "SOME");

  // Conservative form per kernel: h/dx ranges stable in compression, T_crit^- and T_crit at h/dx = 1.2, 1.5, 2.
  std::string table;
  for (KernelType type : all_kernel_types()) {
    const std::string k = kernel_name(type);
    int stable = 0;
    std::string ranges;
    double run_start = NAN, prev = NAN;
    auto close_run = [&] {
      if (std::isnan(run_start)) return;
      ranges += (ranges.empty() ? "" : ", ") + sig(run_start) + (prev > run_start ? "-" + sig(prev) : "");
      run_start = NAN;
    };
    for (double h : hs) {
      if (std::isinf(tc(k, h, "conservative", "compression"))) {
        ++stable;
        if (std::isnan(run_start)) run_start = h;
        prev = h;
      } else {
        close_run();
      }
    }
    close_run();
    auto at = [&](const std::string& dir) {
      return sig(tc(k, 1.2, "conservative", dir)) + " / " + sig(tc(k, 1.5, "conservative", dir)) + " / " +
             sig(tc(k, 2.0, "conservative", dir));
    };
    table += (table.empty() ? "| " : "\n| ") + k + " | " + sig(ft_min[k], 2) + " | " +
             (ranges.empty() ? "none" : ranges) + " (" + std::to_string(stable) + "/" + std::to_string(hs.size()) +
             ") | " + at("compression") + " | " + at("tension") + " |";
  }
  sum.set("tension_compression_table", table);

  int cond1 = 0, cond3 = 0, both = 0, lpsd = 0, lpsd_stable = 0, total = 0, ft_pos_unstable = 0, ft_pos = 0;
  int cond1_inf = 0, both_inf = 0, unstable = 0, l_symbol_psd = 0, l_symbol_psd_stable = 0;
  std::string unstable_cases, both_cases;
  for (const ConditionRow& r : conditions) {
    ++total;
    cond1 += r.cond1;
    cond3 += r.cond3;
    both += r.cond1 && r.cond3;
    const bool psd = r.l_lambda_min >= -1e-12 * r.l_scale;  // round-off of the dense eigenvalues
    lpsd += psd;
    lpsd_stable += psd == std::isinf(r.tcrit_minus);
    cond1_inf += r.cond1_infinite;
    l_symbol_psd += r.l_symbol_min >= -1e-12;
    l_symbol_psd_stable += (r.l_symbol_min >= -1e-12) == std::isinf(r.tcrit_minus);
    both_inf += r.cond1_infinite && r.cond3;
    if (r.cond1 && r.cond3) both_cases += (both_cases.empty() ? "" : ", ") + r.kernel + " " + sig(r.h);
    if (std::isfinite(r.tcrit_minus)) {
      ++unstable;
      unstable_cases +=
          (unstable_cases.empty() ? "" : ", ") + r.kernel + " " + sig(r.h) + " (" + sig(r.tcrit_minus) + ")";
    }
    // Positive Fourier transform (analytically): the Wendland functions, and Lucy (= 1D Wendland C2 shape).
    if (r.kernel.rfind("wendland", 0) == 0 || r.kernel == "lucy") {
      ++ft_pos;
      ft_pos_unstable += std::isfinite(r.tcrit_minus);
    }
  }
  sum.set("cases", total);
  sum.set("cond1", cond1);
  sum.set("cond3", cond3);
  sum.set("both", both);
  sum.set("both_list", both_cases.empty() ? "" : " (" + both_cases + ")");
  sum.set("cond1_infinite", cond1_inf);
  sum.set("both_infinite", both_inf);
  sum.set("l_psd", lpsd);
  sum.set("l_psd_matching", lpsd_stable);
  sum.set("l_symbol_psd", l_symbol_psd);
  sum.set("l_symbol_psd_matching", l_symbol_psd_stable);
  sum.set("unstable", unstable);
  sum.set("unstable_list", unstable_cases.empty() ? "" : ": " + unstable_cases);
  sum.set("ft_positive_unstable", ft_pos_unstable);
  sum.set("ft_positive_stable", ft_pos - ft_pos_unstable);
  sum.set("ft_positive_cases", ft_pos);
  for (const char* k : {"gaussian", "cubic", "quintic", "quartic", "mollifier"})
    sum.set(std::string("ft_min_") + k, ft_min[k], 2);

  table.clear();
  for (size_t i = 0; i < asym.size(); i += 4) {
    table += (table.empty() ? "| " : "\n| ") + std::to_string(asym[i].dim) + " | " + asym[i].config + " | " +
             format_number(asym[i].load, 6) + " |";
    for (int f = 0; f < 4; ++f) table += " " + sig(asym[i + f].asymmetry, 2) + " |";
  }
  sum.set("asymmetry_table", table);
  double slope_max = 0, cons_max = 0;
  for (const AmpRow& r : amp) {
    if (r.form == "conservative") {
      cons_max = std::max(cons_max, r.asymmetry);
      continue;
    }
    for (const AmpRow& s : amp)
      if (s.kernel == r.kernel && s.form == r.form && s.load == r.load && s.amplitude == 10 * r.amplitude &&
          r.amplitude <= 1e-3 && r.asymmetry > 0)
        slope_max = std::max(slope_max, std::abs(std::log10(s.asymmetry / r.asymmetry) - 1));
  }
  sum.set("slope_deviation_max", slope_max, 2);
  sum.set("conservative_asymmetry_max", cons_max, 2);
  // The largest over both tables (asymmetry.csv and asymmetry_vs_amplitude.csv): what Theorem 3.8's check rests on.
  double cons_all = cons_max;
  for (const auto& a : asym)
    if (a.form == "conservative") cons_all = std::max(cons_all, a.asymmetry);
  sum.set("conservative_asymmetry_all", cons_all, 2);
  sum.write(out);
  std::cout << "wrote " << out << " (" << sig(seconds, 3) << " s)\n";
  return 0;
}
