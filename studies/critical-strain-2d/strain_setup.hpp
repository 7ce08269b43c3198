#pragma once
// The set-up of the critical-strain-2d study (GitHub issue 3, [GMS2001, §5]): the plane-strain material, the kernels
// and lattices of the sweeps, the h/dx grid, and the cell formats of its CSV files and summary tables.
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace cstrain {

using namespace sphstab;
using study::Clock;
using study::seconds_since;

// Plane strain, E = 2.1, nu = 0.3, rho = 7.8 (Powell's Swegle test); e_crit depends on nu only.
inline const double kE = 2.1, kNu = 0.3, kRho = 7.8;
inline const ElasticMaterial kMaterial =
    ElasticMaterial::from_lame(kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), kE / (2 * (1 + kNu)), kRho);
inline const std::vector<KernelType> kKernels{KernelType::CubicSpline, KernelType::QuinticSpline,
                                              KernelType::WendlandC2, KernelType::WendlandC4};
inline const std::vector<LatticeType> kLattices{LatticeType::Square, LatticeType::Hexagonal};

/// A CSV number: 12 significant digits.
inline std::string num(double v) { return format_number(v, 12); }
/// Not study::sig: NaN is printed "nan" here (gms.csv infinite_k_* columns, and the GMS table of the summary).
inline std::string sig(double v, int digits = 3) { return format_number(v, digits); }
inline std::string kind_name(PreStrainKind k) { return k == PreStrainKind::Isotropic ? "isotropic" : "uniaxial"; }

/// h/dx = 1.0, 1.0 + step/10, ... <= 2.5, computed exactly in decimal.
inline std::vector<double> h_grid(double step_tenths) {
  std::vector<double> hs;
  for (int i = 10; i <= 25; i += static_cast<int>(step_tenths)) hs.push_back(i / 10.0);
  return hs;
}

}  // namespace cstrain
