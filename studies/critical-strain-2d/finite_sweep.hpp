#pragma once
// The main sweep of the critical-strain-2d study (sweep.csv): n x n blocks of every lattice, kernel and h/dx; e_crit
// in tension and compression for isotropic and uniaxial pre-strain and every momentum form, with the infinite-lattice
// limit. The symmetric forms by positive definiteness; the non-symmetric ones (uniaxial plus and uncorrected) by the
// symmetric-part criterion, labelled (the stability criterion proper is nonsymmetric_sweep.hpp).
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sweep_row.hpp"

namespace cstrain {

/// Runs the sweep over kLattices x kKernels x hs with n free particles per side, writing out_dir/sweep.csv row by row.
inline std::vector<SweepRow> finite_sweep(const std::vector<double>& hs, int n, const std::string& out_dir) {
  std::vector<SweepRow> sweep;
  std::ofstream csv(out_dir + "/sweep.csv");
  csv << sweep_header();
  const auto t0 = Clock::now();
  int done = 0;
  const int total = static_cast<int>(kLattices.size() * kKernels.size() * hs.size());
  for (LatticeType lt : kLattices)
    for (KernelType kt : kKernels) {
      const Kernel<2> kernel(kt);
      for (double h : hs) {
        auto disc = make_discretisation(strain_lattice_2d(lt, kernel, h, n), kernel, h);
        const Operators<2> ops = assemble_operators<2>(disc->particles, disc->neighbours, kernel, h,
                                                       {.kernel = false, .gradient = true, .hessian = true});
        // The shared 2-core machine limits the budget: every h with the eigen route (conservative,
        // isotropic); on the subset h in {1.0, 1.6, 2.2} also the bisection route, uniaxial pre-strain and the
        // other forms (eigen route).
        const bool subset = std::abs(std::round((h - 1.0) / 0.6) * 0.6 - (h - 1.0)) < 1e-9;
        for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX})
          for (MomentumForm form : all_momentum_forms()) {
            if (!subset && (form != MomentumForm::Conservative || kind != PreStrainKind::Isotropic)) continue;
            const Linearisation jac = analytic_jacobian_2d(*disc, ops, kMaterial, form, kind);
            const ElasticSymbol2D symbol(lt, kernel, h, 1.0, kMaterial, form, kind);
            for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
              CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
              if (!jac.symmetric) opt.criterion = Criterion::SymmetricPart;  // dense spectrum: nonsymmetric.csv
              opt.method =
                  subset && form == MomentumForm::Conservative ? CriticalLoadMethod::Both : CriticalLoadMethod::Eigen;
              sweep.push_back(critical_row({lt, kt, h, form, kind, sign, n, {}, {}, 0}, jac, symbol, opt));
              csv << sweep_line(sweep.back());
            }
          }
        progress("sweep", ++done, total, t0);
      }
    }
  return sweep;
}

}  // namespace cstrain
