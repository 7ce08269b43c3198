#pragma once
// The non-symmetric sweep of the critical-strain-2d study (nonsymmetric.csv): the uniaxial plus form, whose Jacobian
// is not symmetric, with the stability criterion proper (every eigenvalue real and positive, dense dgeev) on n x n
// blocks of every lattice and kernel, with the infinite-lattice limit.
#include <fstream>
#include <string>
#include <vector>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sweep_row.hpp"

namespace cstrain {

/// Runs the sweep over kLattices x kKernels x hs with n free particles per side, writing out_dir/nonsymmetric.csv
/// row by row.
inline std::vector<SweepRow> nonsymmetric_sweep(const std::vector<double>& hs, int n, const std::string& out_dir) {
  std::vector<SweepRow> rows;
  const auto t0 = Clock::now();
  std::ofstream csv(out_dir + "/nonsymmetric.csv");
  csv << sweep_header();
  const int total = static_cast<int>(kLattices.size() * kKernels.size() * hs.size());
  int done = 0;
  for (LatticeType lt : kLattices)
    for (KernelType kt : kKernels)
      for (double h : hs) {
        const Kernel<2> kernel(kt);
        auto disc = make_discretisation(strain_lattice_2d(lt, kernel, h, n), kernel, h);
        const Linearisation jac = analytic_jacobian_2d(*disc, kMaterial, MomentumForm::Plus, PreStrainKind::UniaxialX);
        const ElasticSymbol2D symbol(lt, kernel, h, 1.0, kMaterial, MomentumForm::Plus, PreStrainKind::UniaxialX);
        for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
          CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
          opt.criterion = Criterion::Spectrum;
          rows.push_back(critical_row({lt, kt, h, MomentumForm::Plus, PreStrainKind::UniaxialX, sign, n, {}, {}, 0},
                                      jac, symbol, opt));
          csv << sweep_line(rows.back());
        }
        progress("non-symmetric", ++done, total, t0);
      }
  return rows;
}

}  // namespace cstrain
