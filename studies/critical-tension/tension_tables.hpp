#pragma once
// The CSV tables of the critical-tension study [Powell2012, ch. 3, Fig. 3.2], one line per case of tension_cases.hpp:
// fig32.csv (N = 30, conservative: T_crit by both routes, the estimates (3.42), (3.49), (3.43), (3.51), Swegle's,
// the infinite-lattice limit), forms.csv (uncorrected and plus against conservative), versus_n.csv, exponents.csv,
// growth.csv and timing.csv (columns: see README.md). Doubles are written with 12 significant digits.
#include <concepts>
#include <fstream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "sphstab/core/format.hpp"
#include "tension_cases.hpp"

namespace tcrit {

inline std::string num(double v) { return format_number(v, 12); }
inline std::string cell(double v) { return num(v); }
inline std::string cell(const std::string& s) { return s; }
inline std::string cell(const char* s) { return s; }
template <std::integral I>
std::string cell(I v) {
  return std::to_string(v);
}

/// One CSV line: doubles with 12 significant digits, integers and text as they are.
template <class... T>
void row(std::ostream& f, const T&... v) {
  bool first = true;
  ((f << (first ? "" : ",") << cell(v), first = false), ...);
  f << "\n";
}

inline void write_fig32(const std::string& out_dir, const std::vector<SweepRow>& sweep) {
  std::ofstream f(out_dir + "/fig32.csv");
  f << "kernel,h_over_dx,tcrit,tcrit_eig,tcrit_bisect,rel_diff,t_first_minor,ratio_first_minor,t_second_minor,"
       "t_nn,t_nn_minor,t_swegle,tcrit_infinite,l_hat_sawtooth,k_infinite_over_pi,mode_k_over_pi,"
       "mode_k_sign_changes,k_rcond,status,reason\n";
  for (const auto& s : sweep)
    row(f, kernel_name(s.kernel), s.h, s.r.load, s.r.load_eigen, s.r.load_bisection, s.r.relative_difference,
        s.est.first_minor, s.est.first_minor / s.r.load, s.est.second_minor, s.est.nearest_neighbour,
        s.est.nearest_neighbour_minor, s.est.swegle, s.inf.tcrit, s.inf.l_hat_sawtooth, s.inf.k_over_pi,
        s.r.mode_wavenumber.k_projection, s.r.mode_wavenumber.k_sign_changes, s.r.a0_rcond, status_name(s.r.status),
        s.r.reason);
}

inline void write_forms(const std::string& out_dir, const std::vector<SweepRow>& sweep) {
  std::ofstream f(out_dir + "/forms.csv");
  f << "kernel,h_over_dx,tcrit_uncorrected,tcrit_plus,tcrit_conservative,ratio_uncorrected,ratio_plus\n";
  for (const auto& s : sweep)
    row(f, kernel_name(s.kernel), s.h, s.t_uncorrected, s.t_plus, s.r.load, s.t_uncorrected / s.r.load,
        s.t_plus / s.r.load);
}

inline void write_versus_n(const std::string& out_dir, const std::vector<NRow>& nrows, int n_cons) {
  std::ofstream f(out_dir + "/versus_n.csv");
  f << "kernel,h_over_dx,N,tcrit,tcrit_eig,tcrit_bisect,rel_diff,tcrit_infinite,mode_k_over_pi,backend,k_rcond,"
       "seconds,status,reason\n";
  for (const auto& r : nrows)
    row(f, kernel_name(r.kernel), r.h, r.n, r.r.load, r.r.load_eigen, r.r.load_bisection, r.r.relative_difference,
        critical_tension_infinite_1d(Kernel<1>(r.kernel), r.h, 1.0, n_cons).tcrit, r.r.mode_wavenumber.k_projection,
        r.r.eigen_backend, r.r.a0_rcond, r.seconds, status_name(r.r.status), r.r.reason);
}

inline void write_exponents(const std::string& out_dir, const std::vector<ExponentFit>& fits) {
  std::ofstream g(out_dir + "/exponents.csv");
  g << "kernel,h_over_dx,tcrit_infinite,l_hat_sawtooth,p_tcrit,p_excess,fit_n_min,fit_n_max\n";
  for (const auto& e : fits)
    row(g, kernel_name(e.kernel), e.h, e.inf.tcrit, e.inf.l_hat_sawtooth, e.p, e.pe, e.n_lo, e.n_hi);
}

inline void write_growth(const std::string& out_dir, const std::vector<GrowthRow>& growth) {
  std::ofstream gr(out_dir + "/growth.csv");
  gr << "kernel,h_over_dx,tcrit,T,growth_rate,unstable_modes,mode_k_over_pi,mode_k_sign_changes\n";
  for (const auto& r : growth) {
    const bool none = r.g.unstable.empty();
    row(gr, kernel_name(r.kernel), r.h, r.tcrit, r.t, r.g.growth_rate, r.g.unstable.size(),
        none ? "nan" : num(r.g.unstable[0].wavenumber.k_projection),
        none ? "nan" : num(r.g.unstable[0].wavenumber.k_sign_changes));
  }
}

inline void write_timing(const std::string& out_dir, const std::map<std::string, double>& timing,
                         double versus_n_seconds) {
  std::ofstream f(out_dir + "/timing.csv");
  f << "what,seconds\n";
  for (auto& [k, v] : timing) row(f, "n30_sweep_" + k, v);
  row(f, "versus_n_all", versus_n_seconds);
}

}  // namespace tcrit
