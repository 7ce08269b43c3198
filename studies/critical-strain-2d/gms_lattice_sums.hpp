#pragma once
// The check of Gray, Monaghan & Swift [GMS2001, §5] in the critical-strain-2d study (gms.csv): their lattice sums
// B_x = l^xx, B_y = l^yy, A_x = -s_x of the plus form's 2 x 2 Fourier symbol at k = (pi/dp, 0), cubic spline, on
// square and face-centred lattices, h/dp = 1.0 .. 1.7 (0.05); e_crit of that single mode, of the whole Brillouin
// zone, and of an n = 20 block (h/dp = 1.0, 1.1, ..., 1.7).
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "strain_setup.hpp"

namespace cstrain {

struct GmsRow {
  LatticeType lt;
  double h, bx, by, ax, ek_t, ek_c, einf_t, einf_c, en_t, en_c;
  std::string kinf_t, kinf_c;
};

/// Every GMS case, writing out_dir/gms.csv row by row; the n = 20 blocks only with `with_blocks` (else NaN).
inline std::vector<GmsRow> gms_lattice_sums(bool with_blocks, const std::string& out_dir) {
  std::vector<GmsRow> gms;
  std::ofstream csv(out_dir + "/gms.csv");
  csv << "lattice,h_over_dp,B_x,B_y,A_x,ecrit_k_pi0_tension,ecrit_k_pi0_compression,ecrit_infinite_tension,"
         "ecrit_infinite_compression,infinite_k_tension,infinite_k_compression,ecrit_n20_tension,"
         "ecrit_n20_compression\n";
  const Kernel<2> cubic(KernelType::CubicSpline);
  for (LatticeType lt : {LatticeType::Square, LatticeType::FaceCentred})
    for (int i = 0; i <= 14; ++i) {
      const double h = 1.0 + 0.05 * i;
      const bool finite_n = i % 2 == 0;  // n = 20 lattice at h/dp = 1.0, 1.1, ..., 1.7
      // GMS's momentum equation sum_b m_b (sigma_a/rho_a^2 + sigma_b/rho_b^2) grad W is the plus form;
      // a uniform pressure is the isotropic pre-stress (tension = -P).
      const ElasticSymbol2D sym(lt, cubic, h, 1.0, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic);
      const auto v = sym({M_PI, 0});
      GmsRow g{lt, h, v.l(0, 0), v.l(1, 1), -v.s[0], 0, 0, 0, 0, std::nan(""), std::nan(""), "", ""};
      g.ek_t = critical_strain_2x2(v.a0, v.a1, LoadDirection::Tension, 1e-12 * v.a1.cwiseAbs().maxCoeff()).e;
      g.ek_c = critical_strain_2x2(v.a0, v.a1, LoadDirection::Compression, 1e-12 * v.a1.cwiseAbs().maxCoeff()).e;
      const auto it = critical_strain_infinite_2d(sym, LoadDirection::Tension);
      const auto ic = critical_strain_infinite_2d(sym, LoadDirection::Compression);
      g.einf_t = it.e;
      g.einf_c = ic.e;
      g.kinf_t = "(" + sig(it.kx_over_pi) + " " + sig(it.ky_over_pi) + ")";
      g.kinf_c = "(" + sig(ic.kx_over_pi) + " " + sig(ic.ky_over_pi) + ")";
      if (with_blocks && finite_n) {
        auto disc = make_discretisation(strain_lattice_2d(lt, cubic, h, 20), cubic, h);
        const auto jac = analytic_jacobian_2d(*disc, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic);
        CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
        opt.method = CriticalLoadMethod::Eigen;
        opt.want_mode = false;
        g.en_t = critical_load(jac, LoadDirection::Tension, opt).load;
        g.en_c = critical_load(jac, LoadDirection::Compression, opt).load;
      }
      csv << lattice_name(lt) << "," << num(h) << "," << num(g.bx) << "," << num(g.by) << "," << num(g.ax) << ","
          << num(g.ek_t) << "," << num(g.ek_c) << "," << num(g.einf_t) << "," << num(g.einf_c) << "," << g.kinf_t << ","
          << g.kinf_c << "," << num(g.en_t) << "," << num(g.en_c) << "\n";
      gms.push_back(g);
    }
  return gms;
}

/// The GMS row at (lt, h), or nullptr.
inline const GmsRow* gms_at(const std::vector<GmsRow>& gms, LatticeType lt, double h) {
  for (const auto& g : gms)
    if (g.lt == lt && std::abs(g.h - h) < 1e-9) return &g;
  return nullptr;
}

}  // namespace cstrain
