#pragma once
// The infinite-lattice limit of the critical-strain-2d study (infinite.csv): e_crit from the 2 x 2 Fourier symbols,
// minimised over the Brillouin zone, for square, hexagonal and face-centred lattices, every kernel and h/dx, the
// conservative and plus forms, isotropic and uniaxial pre-strain, tension and compression.
#include <fstream>
#include <string>
#include <vector>

#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "strain_setup.hpp"

namespace cstrain {

struct InfRow {
  LatticeType lt;
  KernelType kt;
  double h;
  MomentumForm form;
  PreStrainKind kind;
  LoadDirection sign;
  SymbolCriticalStrain s;
};

/// Every case on the h/dx grid of step 0.1 (128 x 128 grid), writing out_dir/infinite.csv row by row.
inline std::vector<InfRow> infinite_lattice(const std::string& out_dir) {
  std::vector<InfRow> infrows;
  std::ofstream csv(out_dir + "/infinite.csv");
  csv << "lattice,kernel,h_over_dx,form,prestrain,direction,ecrit_infinite,kx_over_pi,ky_over_pi,mechanism,"
         "neutral_points,reason\n";
  for (LatticeType lt : {LatticeType::Square, LatticeType::Hexagonal, LatticeType::FaceCentred})
    for (KernelType kt : kKernels)
      for (double h : h_grid(1))
        for (MomentumForm form : {MomentumForm::Conservative, MomentumForm::Plus})
          for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
            const ElasticSymbol2D symbol(lt, Kernel<2>(kt), h, 1.0, kMaterial, form, kind);
            for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
              InfRow row{lt, kt, h, form, kind, sign, critical_strain_infinite_2d(symbol, sign, 128)};
              csv << lattice_name(lt) << "," << kernel_name(kt) << "," << num(h) << "," << momentum_form_name(form)
                  << "," << kind_name(kind) << "," << load_direction_name(sign) << "," << num(row.s.e) << ","
                  << num(row.s.kx_over_pi) << "," << num(row.s.ky_over_pi) << "," << mechanism_name(row.s.mechanism)
                  << "," << row.s.neutral_points << "," << csv_quote(row.s.reason) << "\n";
              infrows.push_back(row);
            }
          }
  return infrows;
}

}  // namespace cstrain
