#pragma once
// Powell's sufficient conditions for stability in compression [Powell2012, ch. 3, the conditions after Theorem 3.10],
// checked per kernel and h/dx against the conservative form's T_crit^- (tension_compression.hpp):
// - condition 1: the W''-matrix of the free block (diagonal W''(0) included) negative definite, and its
// infinite-lattice
//   version, the symbol S(k) = sum_m W''(|m| dx) dx cos(k m dx) <= 0;
// - condition 3: the row sum S(0) > 0;
// - the eigenvalues and the symbol L^(k) of L (the uncorrected form's A1 = -L), the relative minimum of the kernel's
//   Fourier transform, and the conservative T_crit^- of the infinite lattice from the symbols (fourier_symbol.hpp).
// Holds the per-case computation, the CSV writer (compression_conditions.csv) and the counts of the summary.
#include <Eigen/Core>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/numerics/quadrature.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"
#include "tension_compression.hpp"

namespace forms_study {

using namespace sphstab;
using study::sig;

/// min over 0 <= k h <= 60 (in steps of dk) of F(k) / F(0), F(k) = 2 int_0^{2h} W(r) cos(k r) dr (h = 1), as in
/// tests/kernel/kernel_test.cpp.
inline double min_fourier_transform(KernelType type, double dk = 0.01) {
  Kernel<1> w(type);
  auto f = [&](double k) {
    return 2 * integrate_gauss_legendre([&](double r) { return w.value(r, 1.0) * std::cos(k * r); }, 0.0,
                                        w.support_radius(1.0), 400);
  };
  const double f0 = f(0.0);
  double lo = 1e300;
  for (double k = 0.0; k <= 60.0; k += dk) lo = std::min(lo, f(k) / f0);
  return lo;
}

/// Lattice sum S(k) = sum_m W''(|m| dx) dx cos(k m dx) (m over all integers, m = 0 included: W''(0)), dx = 1.
inline double w2_symbol(const Kernel<1>& w, double h, double k) {
  double s = w.d2(0.0, h);
  for (int m = 1; m <= w.support_radius(h) + 1; ++m) s += 2 * w.d2(double(m), h) * std::cos(k * m);
  return s;
}

struct ConditionRow {
  std::string kernel;
  double h, ft_min, w2_lambda_max, w2_symbol_max, w2_row_sum, l_lambda_min, l_scale, l_symbol_min, tcrit_minus,
      tcrit_minus_infinite;
  bool cond1, cond3, cond1_infinite;
};

/// The conditions for one kernel and h/dx on n free particles; ft_min and tcrit_minus (the conservative T_crit^-)
/// are copied into the row.
inline ConditionRow compression_condition(KernelType type, double h, int n, double ft_min, double tcrit_minus) {
  Kernel<1> kernel(type);
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
  return {kernel_name(type), h,         ft_min,      w2_lmax, sym_max,       row_sum,         l_lmin,
          l_scale,           l_sym_min, tcrit_minus, t_inf,   w2_lmax < 0.0, (row_sum > 0.0), sym_max <= 1e-12};
}

struct Conditions {
  std::vector<ConditionRow> rows;
  std::map<std::string, double> ft_min;  ///< per kernel name: min_fourier_transform
};

/// The conditions for every kernel and h/dx in `hs`; progress on stdout, one line per kernel. dk: the step of
/// min_fourier_transform (--quick: 0.1).
inline Conditions compression_conditions(const std::vector<double>& hs, int n, const TcritTable& tcrit,
                                         double dk = 0.01) {
  Conditions c;
  for (KernelType type : all_kernel_types()) {
    c.ft_min[kernel_name(type)] = min_fourier_transform(type, dk);
    for (double h : hs)
      c.rows.push_back(
          compression_condition(type, h, n, c.ft_min[kernel_name(type)], tcrit.cons_minus.at({kernel_name(type), h})));
    std::cout << "conditions " << kernel_name(type) << std::endl;
  }
  return c;
}

inline void write_compression_conditions(const std::string& path, const std::vector<ConditionRow>& rows) {
  std::ofstream csv(path);
  csv << "kernel,h_over_dx,fourier_min_relative,w2_matrix_lambda_max,w2_symbol_max,w2_row_sum,cond1_w2_negative_"
         "definite,cond3_row_sum_positive,L_lambda_min,L_symbol_min,tcrit_minus_conservative,"
         "tcrit_minus_infinite_conservative,cond1_infinite_lattice\n";
  for (const ConditionRow& r : rows)
    csv << r.kernel << "," << format_number(r.h, 10) << "," << format_number(r.ft_min, 10) << ","
        << format_number(r.w2_lambda_max, 10) << "," << format_number(r.w2_symbol_max, 10) << ","
        << format_number(r.w2_row_sum, 10) << "," << r.cond1 << "," << r.cond3 << ","
        << format_number(r.l_lambda_min, 10) << "," << format_number(r.l_symbol_min, 10) << ","
        << format_number(r.tcrit_minus, 10) << "," << format_number(r.tcrit_minus_infinite, 10) << ","
        << r.cond1_infinite << "\n";
}

/// Key numbers of the conditions: how many cases meet each, how many of them are stable in compression, the
/// unstable cases, and the relative minimum of the Fourier transform per kernel.
inline void summarise_conditions(study::Summary& sum, const Conditions& c) {
  int cond1 = 0, cond3 = 0, both = 0, lpsd = 0, lpsd_stable = 0, total = 0, ft_pos_unstable = 0, ft_pos = 0;
  int cond1_inf = 0, both_inf = 0, unstable = 0, l_symbol_psd = 0, l_symbol_psd_stable = 0;
  std::string unstable_cases, both_cases;
  for (const ConditionRow& r : c.rows) {
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
    sum.set(std::string("ft_min_") + k, c.ft_min.at(k), 2);
}

}  // namespace forms_study
