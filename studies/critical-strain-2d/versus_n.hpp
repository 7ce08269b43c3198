#pragma once
// e_crit against the block size n of the critical-strain-2d study (versus_n.csv): the conservative form under
// isotropic pre-strain, cubic spline, h = 1.3 dx, square and hexagonal blocks of n x n free particles, with the
// periodic value at the same n (exact symbol) and the infinite-lattice limit.
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "strain_setup.hpp"

namespace cstrain {

struct NRow {
  LatticeType lt;
  KernelType kt;
  double h;
  LoadDirection sign;
  int n;
  CriticalLoad r;
  SymbolCriticalStrain periodic, inf;
  double seconds;
  std::string method;
};

/// e_crit for every lattice of kLattices and block size of `sizes`, writing out_dir/versus_n.csv row by row.
inline std::vector<NRow> versus_n(const std::vector<int>& sizes, const std::string& out_dir) {
  std::vector<NRow> nrows;
  const auto t0 = Clock::now();
  std::ofstream csv(out_dir + "/versus_n.csv");
  csv << "lattice,kernel,h_over_dx,form,prestrain,direction,n,method,ecrit,ecrit_eig,ecrit_bisect,rel_diff,"
         "mode_kx_over_pi,mode_ky_over_pi,ecrit_periodic,periodic_kx_over_pi,periodic_ky_over_pi,ecrit_infinite,"
         "status,reason,seconds\n";
  for (LatticeType lt : kLattices)
    for (KernelType kt : {KernelType::CubicSpline})
      for (double h : {1.3}) {
        const Kernel<2> kernel(kt);
        const ElasticSymbol2D symbol(lt, kernel, h, 1.0, kMaterial, MomentumForm::Conservative,
                                     PreStrainKind::Isotropic);
        for (int n : sizes) {
          auto disc = make_discretisation(strain_lattice_2d(lt, kernel, h, n), kernel, h);
          const Linearisation jac =
              analytic_jacobian_2d(*disc, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
          for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
            const auto tc = Clock::now();
            CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
            // Bisection (~40 factorisations) up to n = 20; the eigen route alone above (benchmark.md: timing).
            opt.method = n <= 20 ? CriticalLoadMethod::Both : CriticalLoadMethod::Eigen;
            NRow row{lt, kt, h, sign, n, critical_load(jac, sign, opt), {}, {}, 0, n <= 20 ? "both" : "eig"};
            row.periodic = critical_strain_periodic_symbol_2d(symbol, n, sign);
            row.inf = critical_strain_infinite_2d(symbol, sign);
            row.seconds = seconds_since(tc);
            csv << lattice_name(lt) << "," << kernel_name(kt) << "," << num(h) << ",conservative,isotropic,"
                << load_direction_name(sign) << "," << n << "," << row.method << "," << num(row.r.load) << ","
                << num(row.r.load_eigen) << "," << num(row.r.load_bisection) << "," << num(row.r.relative_difference)
                << "," << num(row.r.mode_wavevector.kx_over_pi) << "," << num(row.r.mode_wavevector.ky_over_pi) << ","
                << num(row.periodic.e) << "," << num(row.periodic.kx_over_pi) << "," << num(row.periodic.ky_over_pi)
                << "," << num(row.inf.e) << "," << status_name(row.r.status) << "," << csv_quote(row.r.reason) << ","
                << sig(row.seconds, 4) << "\n";
            nrows.push_back(std::move(row));
          }
        }
        std::cout << "critical-strain-2d: versus n " << lattice_name(lt) << " " << kernel_name(kt) << " h " << h << " ("
                  << sig(seconds_since(t0), 3) << " s)" << std::endl;
      }
  return nrows;
}

}  // namespace cstrain
