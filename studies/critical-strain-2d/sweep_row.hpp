#pragma once
// One case of the finite-lattice sweeps of the critical-strain-2d study (sweep.csv and nonsymmetric.csv share it):
// the case, e_crit of its n x n block with the critical mode, the infinite-lattice limit, and its CSV line.
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "strain_setup.hpp"

namespace cstrain {

struct SweepRow {
  LatticeType lattice;
  KernelType kernel;
  double h;
  MomentumForm form;
  PreStrainKind kind;
  LoadDirection sign;
  int n;
  CriticalLoad r;
  SymbolCriticalStrain inf;
  double seconds;
};

/// The case `row` (lattice .. n) with e_crit of `jac` in its direction by `opt`, the infinite-lattice limit of
/// `symbol` (128 x 128 grid) and the seconds both took.
inline SweepRow critical_row(SweepRow row, const Linearisation& jac, const ElasticSymbol2D& symbol,
                             const CriticalLoadOptions& opt) {
  const auto tc = Clock::now();
  row.r = critical_load(jac, row.sign, opt);
  row.inf = critical_strain_infinite_2d(symbol, row.sign, 128);
  row.seconds = seconds_since(tc);
  return row;
}

/// The row of `rows` with these parameters, or nullptr.
inline const SweepRow* find_row(const std::vector<SweepRow>& rows, LatticeType lt, KernelType kt, double h,
                                MomentumForm f, PreStrainKind kind, LoadDirection s) {
  for (const auto& r : rows)
    if (r.lattice == lt && r.kernel == kt && std::abs(r.h - h) < 1e-9 && r.form == f && r.kind == kind && r.sign == s)
      return &r;
  return nullptr;
}

inline std::string sweep_header() {
  return "lattice,kernel,h_over_dx,form,prestrain,direction,n,criterion,ecrit,ecrit_eig,ecrit_bisect,rel_diff,"
         "mechanism,mode_kx_over_pi,mode_ky_over_pi,mode_peak_fraction,ecrit_infinite,infinite_kx_over_pi,"
         "infinite_ky_over_pi,infinite_mechanism,status,reason,seconds\n";
}

inline std::string sweep_line(const SweepRow& s) {
  std::ostringstream o;
  o << lattice_name(s.lattice) << "," << kernel_name(s.kernel) << "," << num(s.h) << "," << momentum_form_name(s.form)
    << "," << kind_name(s.kind) << "," << load_direction_name(s.sign) << "," << s.n << ","
    << criterion_name(s.r.criterion) << "," << num(s.r.load) << "," << num(s.r.load_eigen) << ","
    << num(s.r.load_bisection) << "," << num(s.r.relative_difference) << "," << mechanism_name(s.r.mechanism) << ","
    << num(s.r.mode_wavevector.kx_over_pi) << "," << num(s.r.mode_wavevector.ky_over_pi) << ","
    << num(s.r.mode_wavevector.peak_fraction) << "," << num(s.inf.e) << "," << num(s.inf.kx_over_pi) << ","
    << num(s.inf.ky_over_pi) << "," << mechanism_name(s.inf.mechanism) << "," << status_name(s.r.status) << ","
    << csv_quote(s.r.reason) << "," << sig(s.seconds, 4) << "\n";
  return o.str();
}

/// "critical-strain-2d: <what> done/total (seconds since t0)" on stdout, every 8 cases and at the last.
inline void progress(const std::string& what, int done, int total, Clock::time_point t0) {
  if (done % 8 == 0 || done == total)
    std::cout << "critical-strain-2d: " << what << " " << done << "/" << total << " (" << sig(seconds_since(t0), 3)
              << " s)" << std::endl;
}

}  // namespace cstrain
