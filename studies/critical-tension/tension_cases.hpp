#pragma once
// The cases of the critical-tension study [Powell2012, ch. 3, Fig. 3.2 and conclusions p. 99-100] and the computation
// of one case of each phase of main.cpp:
//   - the tables: kernels (support 2h, as in Fig. 3.2), h/dx grid, N of the versus-N sweep and its h/dx;
//   - the timed N = 30 sweep of one critical-load route (best of 3);
//   - one case of the N = 30 sweep: T_crit of A(T) = K - n T L [Powell2012, (3.40)] on the conservative form (both
//     routes, with the critical mode), the closed-form estimates (3.42), (3.49), (3.43), (3.51) and Swegle's, the
//     infinite-lattice limit, and T_crit of the uncorrected and plus forms;
//   - one case of T_crit versus N, and the exponent p of T_crit ~ N^-p fitted over those cases;
//   - the growth rates above T_crit (N = 30, dense nonsymmetric eigen).
// The CSV tables are written by tension_tables.hpp, the key numbers by tension_summary.hpp.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "common/study.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"
#include "sphstab/spectral/tension_estimates.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace tcrit {

using namespace sphstab;
using study::Clock;
using study::seconds_since;

inline const std::vector<KernelType> kKernels{KernelType::CubicSpline,   KernelType::QuarticSpline,
                                              KernelType::QuinticSpline, KernelType::WendlandC2,
                                              KernelType::WendlandC4,    KernelType::Gaussian};
inline const std::vector<int> kSizes{15, 30, 60, 120, 240, 480, 960};
inline const std::vector<double> kHVersusN{1.0, 1.2, 1.5, 2.0};

/// h/dx = 0.8 + 0.05 i, i = 0, stride, 2 stride, ... <= 44, computed exactly in decimal (no accumulated rounding).
inline std::vector<double> h_grid(int stride = 1) {
  std::vector<double> hs;
  for (int i = 0; i <= 44; i += stride) hs.push_back((80 + 5 * i) / 100.0);
  return hs;
}

/// CriticalLoadOptions::tension_1d() keeping the critical mode (its wavenumber is reported).
inline CriticalLoadOptions tension_1d_with_mode() {
  CriticalLoadOptions with_mode = CriticalLoadOptions::tension_1d();
  with_mode.want_mode = true;
  return with_mode;
}

/// Wall seconds of the N = 30 conservative sweep over kKernels x hs by `method` (jacobian assembly included), with
/// the first-minor estimate of each case; best of 3 (the machine is shared; the minimum is the least disturbed
/// measurement).
inline double timed_sweep(CriticalLoadMethod method, const std::vector<double>& hs, int n_cons) {
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
  return best;
}

/// One case of the N = 30 sweep (conservative form unless said otherwise).
struct SweepRow {
  KernelType kernel;
  double h;
  CriticalLoad r;
  TensionEstimates1D est;
  SymbolCriticalTension inf;
  double t_uncorrected = 0, t_plus = 0;
};

inline SweepRow sweep_case(KernelType type, double h, int n_cons) {
  Kernel<1> kernel(type);
  const ParticleSet<1> set = tension_lattice_1d(kernel, h, 30);
  return {type,
          h,
          critical_tension_1d(set, kernel, h, MomentumForm::Conservative, tension_1d_with_mode()),
          tension_estimates_1d(kernel, h, 1.0, n_cons),
          critical_tension_infinite_1d(kernel, h, 1.0, n_cons),
          critical_tension_1d(set, kernel, h, MomentumForm::Uncorrected).load,
          critical_tension_1d(set, kernel, h, MomentumForm::Plus).load};
}

/// One case of T_crit versus N (conservative form), with its wall time.
struct NRow {
  KernelType kernel;
  double h;
  int n;
  CriticalLoad r;
  double seconds;
};

inline NRow versus_n_case(KernelType type, double h, int n) {
  Kernel<1> kernel(type);
  const auto t0 = Clock::now();
  CriticalLoad r = critical_tension_1d(tension_lattice_1d(kernel, h, n), kernel, h, MomentumForm::Conservative,
                                       tension_1d_with_mode());
  return {type, h, n, std::move(r), seconds_since(t0)};
}

/// The exponents p of T_crit ~ N^-p and of T_crit - T_crit,inf ~ N^-p of one kernel and h/dx.
struct ExponentFit {
  KernelType kernel;
  double h;
  SymbolCriticalTension inf;
  double p, pe;
  int n_lo, n_hi;    ///< the N range of the fit (0 when empty)
  double t30, t960;  ///< T_crit at N = 30 and (successful) N = 960, NaN if absent
};

inline ExponentFit fit_exponents(const std::vector<NRow>& nrows, KernelType type, double h, int n_cons) {
  const SymbolCriticalTension inf = critical_tension_infinite_1d(Kernel<1>(type), h, 1.0, n_cons);
  // Fit over the three largest N whose T_crit is reliable (status successful: K positive definite and the
  // two routes within 1e-6). These T_crit are finite and positive, so study::loglog_slope skips none.
  std::vector<double> x, y, ye;
  double t30 = std::nan(""), t960 = std::nan("");
  for (const auto& r : nrows) {
    if (r.kernel != type || r.h != h) continue;
    if (r.n == 30) t30 = r.r.load;
    if (r.r.status != Status::Successful) continue;
    if (r.n == 960) t960 = r.r.load;
    if (!std::isfinite(r.r.load)) continue;
    x.push_back(r.n), y.push_back(r.r.load), ye.push_back(r.r.load - inf.tcrit);
  }
  for (auto* v : {&x, &y, &ye})
    if (v->size() > 3) v->erase(v->begin(), v->end() - 3);
  const double p = x.size() >= 2 ? -study::loglog_slope(x, y) : std::nan("");
  const bool excess_ok = inf.tcrit > 0 && std::all_of(ye.begin(), ye.end(), [](double v) { return v > 0; });
  const double pe = excess_ok && x.size() >= 2 ? -study::loglog_slope(x, ye) : std::nan("");
  const int n_lo = x.empty() ? 0 : int(x.front()), n_hi = x.empty() ? 0 : int(x.back());
  return {type, h, inf, p, pe, n_lo, n_hi, t30, t960};
}

/// The growth rate at T = factor x T_crit (N = 30, conservative form).
struct GrowthRow {
  KernelType kernel;
  double h, tcrit, factor, t;
  GrowthAnalysis g;
};

/// Growth rates at 0.5, 1.5 and 4 T_crit of one kernel (N = 30, h/dx = 1.2, dense nonsymmetric eigen).
inline std::vector<GrowthRow> growth_cases(KernelType type) {
  std::vector<GrowthRow> rows;
  Kernel<1> kernel(type);
  const double h = 1.2;
  const Linearisation jac =
      analytic_jacobian_1d(tension_lattice_1d(kernel, h, 30), kernel, h, MomentumForm::Conservative);
  const CriticalLoad r = critical_load(jac, LoadDirection::Tension, CriticalLoadOptions::tension_1d());
  for (double factor : {0.5, 1.5, 4.0}) {
    const double t = factor * r.load;
    rows.push_back({type, h, r.load, factor, t, growth_rate(Eigen::MatrixXd(jac.at(t)), jac.x.col(0))});
  }
  return rows;
}

}  // namespace tcrit
