#pragma once
// The artificial-stress thresholds of the k = (pi/dp, 0) modes on the square and face-centred lattices versus h/dp
// [GMS2001, §5.3], from the lattice sums and the dispersion relation of sphstab/spectral/lattice_dispersion.hpp:
// the GMS coefficient kappa = B/f of a mode [GMS2001, (5.22)], the critical epsilon of the full relation
// [GMS2001, (5.8), (5.9)] with R frozen [GMS2001, (5.13)] or perturbed, the sign changes of the sums in h/dp, and the
// CSV tables thresholds.csv, by_sign.csv, long_wave.csv [GMS2001, (5.10)] and n_dependence.csv.
// Units: rho0 = c0 = 1, dp = 1 (sums in 1/dp, 1/dp^2; stresses in rho0 c0^2).
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "sphstab/core/format.hpp"
#include "sphstab/spectral/lattice_dispersion.hpp"

namespace artificial_stress {

using namespace sphstab;

inline constexpr double inf = std::numeric_limits<double>::infinity();
inline const Eigen::Vector2d k_short(M_PI, 0);  // [GMS2001, §5.3]: k = (pi/dp, 0)
inline constexpr LatticeType lattice_types[2] = {LatticeType::Square, LatticeType::FaceCentred};

/// GMS coefficient of a mode rho omega^2/(1-beta) = 2B(P - S) - 2R rho^2 f (+ A^2 terms ignored, as in 5.22):
/// B/f when the mode is tension-unstable (B > 0) and R can cure it (f > 0); 0 when B <= 0 (no tensile
/// instability from this term); inf when B > 0 but f <= 0 (R makes it worse).
inline double coefficient(double B, double f) {
  if (B <= 0) return 0;
  return f > 0 ? B / f : inf;
}

inline double kappa_long(const LatticeSums& s) { return coefficient(s.Bx, s.fxx); }
inline double kappa_trans(const LatticeSums& s) { return coefficient(s.By, s.fyy); }

/// Smallest epsilon with omega^2 >= 0 of mode `mode` (0 longitudinal, 1 transverse) for k = (pi/dp, 0), where
/// R = R(epsilon) by the GMS rule. omega^2 is linear in epsilon (M diagonal, R and dR proportional to epsilon).
/// perturbed_r: include the perturbation of R through the stress (GMS 5.13 freezes R).
inline double critical_epsilon(LatticeType type, const Kernel<2>& w, double h, const UniformState& base, int mode,
                               bool perturbed_r = false) {
  auto omega2 = [&](double eps) {
    return lattice_dispersion(type, w, h, k_short, with_artificial_stress(base, eps),
                              {.perturbed_artificial_stress = perturbed_r})
        .omega2[mode]
        .real();
  };
  const double w0 = omega2(0), slope = omega2(1) - w0;
  if (w0 >= 0) return 0;
  return slope > 0 ? -w0 / slope : inf;
}

/// Roots of g on [a, b] from sign changes on a grid of step `step`, refined by bisection.
inline std::vector<double> roots(const std::function<double(double)>& g, double a, double b, double step) {
  std::vector<double> out;
  double x0 = a, g0 = g(a);
  for (double x1 = a + step; x1 <= b + 1e-12; x1 += step) {
    const double g1 = g(x1);
    if ((g0 < 0) != (g1 < 0)) {
      double lo = x0, hi = x1, glo = g0;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi), gm = g(mid);
        if ((gm < 0) == (glo < 0))
          lo = mid, glo = gm;
        else
          hi = mid;
      }
      out.push_back(0.5 * (lo + hi));
    }
    x0 = x1;
    g0 = g1;
  }
  return out;
}

/// The study's lattices: the kernel, the lattice-sum options (artificial-stress exponent n) and the shear modulus mu
/// of the material examples; the sums and coefficients at k = (pi/dp, 0) and the critical epsilon at h = dp.
struct Lattices {
  Kernel<2> w;
  LatticeSumOptions opt;
  double mu;

  LatticeSums sums(LatticeType t, double h) const { return lattice_sums(t, w, h, k_short, opt); }
  double kl(LatticeType t, double h) const { return kappa_long(sums(t, h)); }
  double kt(LatticeType t, double h) const { return kappa_trans(sums(t, h)); }
  UniformState isotropic_tension(double T) const {
    return UniformState{.density = 1, .sound_speed = 1, .shear_modulus = mu, .pressure = -T};
  }
  double eps_crit(LatticeType t, double T, int mode, bool dR = false) const {
    return critical_epsilon(t, w, 1.0, isotropic_tension(T), mode, dR);
  }
};

/// thresholds.csv: lattice sums, GMS coefficients and critical epsilon for isotropic tension (T = 0.01, 0.1; frozen
/// R, then _dR with the perturbation of R) on [h_min, h_max] step h_step.
inline void write_thresholds(const std::string& path, const Lattices& g, double h_min, double h_max, double h_step) {
  const double tensions[2] = {0.01, 0.1};
  std::ofstream f(path);
  f << std::setprecision(10);
  f << "lattice,h_over_dp,Ax,Bx,By,beta,fxx,fyy,kappa_long,kappa_trans,eps_crit_long_T0.01,eps_crit_trans_T0.01,"
       "eps_crit_long_T0.1,eps_crit_trans_T0.1,eps_crit_long_T0.01_dR,eps_crit_trans_T0.01_dR,eps_crit_long_T0.1_dR,"
       "eps_crit_trans_T0.1_dR\n";
  for (auto t : lattice_types) {
    for (double h = h_min; h <= h_max + 1e-9; h += h_step) {
      const auto s = g.sums(t, h);
      f << lattice_name(t) << "," << h << "," << s.A[0] << "," << s.Bx << "," << s.By << "," << s.beta << "," << s.fxx
        << "," << s.fyy << "," << format_number(kappa_long(s), 10) << "," << format_number(kappa_trans(s), 10);
      for (bool dR : {false, true})
        for (double T : tensions)
          for (int mode = 0; mode < 2; ++mode)
            f << "," << format_number(critical_epsilon(t, g.w, h, g.isotropic_tension(T), mode, dR), 10);
      f << "\n";
    }
    std::cout << "  " << lattice_name(t) << " done\n";
  }
}

/// Sign changes of B_x, B_y, f_yy on [h_min, h_max] and the range of f_yy (one lattice).
struct Roots {
  std::vector<double> Bx, By;
  double min_fyy = inf, max_fyy = -inf;
};

/// by_sign.csv (B_y and f_yy on a 0.001 h/dp grid) and the roots of B_y, B_x (sign changes) on [h_min, h_max], per
/// lattice of lattice_types.
inline std::array<Roots, 2> write_by_sign(const std::string& path, const Lattices& g, double h_min, double h_max) {
  std::array<Roots, 2> r;
  std::ofstream f(path);
  f << std::setprecision(10) << "lattice,h_over_dp,By,fyy\n";
  for (int l = 0; l < 2; ++l) {
    const auto t = lattice_types[l];
    r[l].Bx = roots([&](double h) { return g.sums(t, h).Bx; }, h_min, h_max, 0.01);
    r[l].By = roots([&](double h) { return g.sums(t, h).By; }, h_min, h_max, 0.01);
    for (double h = h_min; h <= h_max + 1e-9; h += 0.001) {
      const auto s = g.sums(t, h);
      r[l].min_fyy = std::min(r[l].min_fyy, s.fyy);
      r[l].max_fyy = std::max(r[l].max_fyy, s.fyy);
      f << lattice_name(t) << "," << h << "," << s.By << "," << s.fyy << "\n";
    }
  }
  return r;
}

/// long_wave.csv: the lattice moments behind the long-wave limit (GMS 5.10 assumes -A/k = B/k^2 = 1).
inline void write_long_wave(const std::string& path, const Lattices& g) {
  std::ofstream f(path);
  f << std::setprecision(10) << "lattice,h_over_dp,moment_A_error,moment_B_error\n";
  const double k = 1e-4;
  for (auto t : lattice_types)
    for (double h = 1.0; h <= 3.0 + 1e-9; h += 0.01) {
      const auto s = lattice_sums(t, g.w, h, Eigen::Vector2d(k, 0), g.opt);
      f << lattice_name(t) << "," << h << "," << (-s.A[0] / k - 1) << "," << (s.Bx / (k * k) - 1) << "\n";
    }
}

/// f_xx(n) at h = dp on the face-centred lattice against GMS's "4n + 3.7".
struct NFit {
  double slope = 0, icpt = 0, dev_lo = inf, dev_hi = -inf, dev_n0 = 0;
};

/// n_dependence.csv: f_xx(n) at h = dp (GMS: square 30(3n+2)/(7 pi), face-centred "proportional to 4n + 3.7").
inline NFit write_n_dependence(const std::string& path, const Kernel<2>& w) {
  NFit r;
  std::ofstream f(path);
  f << std::setprecision(10) << "n,fxx_square,fxx_square_nearest,fxx_face_centred\n";
  double sx = 0, sy = 0, sxx = 0, sxy = 0;  // least squares f_xx(face-centred) = slope n + icpt over n = 1..8
  for (int nn = 0; nn <= 8; ++nn) {
    const auto sq = lattice_sums(LatticeType::Square, w, 1.0, k_short, {.exponent = double(nn)});
    const auto sqn = lattice_sums(LatticeType::Square, w, 1.0, k_short, {.exponent = double(nn), .max_distance = 1.0});
    const auto fc = lattice_sums(LatticeType::FaceCentred, w, 1.0, k_short, {.exponent = double(nn)});
    f << nn << "," << sq.fxx << "," << sqn.fxx << "," << fc.fxx << "\n";
    const double dev = fc.fxx - (4 * nn + 3.7);
    if (nn == 0) r.dev_n0 = dev;
    if (nn >= 3) r.dev_lo = std::min(r.dev_lo, dev), r.dev_hi = std::max(r.dev_hi, dev);
    if (nn >= 1) sx += nn, sy += fc.fxx, sxx += double(nn) * nn, sxy += nn * fc.fxx;
  }
  const double m = 8;
  r.slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  r.icpt = (sy - r.slope * sx) / m;
  return r;
}

}  // namespace artificial_stress
