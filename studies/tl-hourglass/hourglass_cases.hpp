#pragma once
// The cases of the tl-hourglass study (zero-energy modes of the finite-strain TL form and the [Ganzenmueller2015]
// hourglass control term, FiniteStrainOptions::hourglass): lattice units (dx = 1, E = 1, rho = 1, nu = 0.3), the
// coefficients c_HG, the zigzag threshold, the lattices (1D lines and 2D square blocks, periodic or with fixed layers
// two supports deep) and the variants of the form (plain / NCSPH reference gradient x difference / direct strain sum,
// and the term's full-vector projection), with the construction of a case's lattice and form.
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/particles/lattice.hpp"

namespace hourglass {

using namespace sphstab;

// Lattice units for (a), (b) and the noise runs: dx = 1, E = 1, rho = 1 (eigenvalues in E / (rho dx^2)).
constexpr double kNu = 0.3;
inline const std::vector<double> kCoefficients{0, 0.01, 0.03, 0.1, 0.3, 1};
constexpr double kZigzag =
    0.5;  // a mode is "zigzag" when its hourglass_fraction (spectral/zigzag_modes.hpp) exceeds this

struct Config {
  std::string name;
  int dim;
  bool periodic;
  KernelType kernel;
  double h;  // h / dx
  int n;     // free particles per side
};
struct Variant {
  std::string name;
  bool ncsph;
  StrainSum sum;
  HourglassProjection projection = HourglassProjection::Bond;
};
inline const std::vector<Config> kConfigs{
    {"1d-periodic-cubic", 1, true, KernelType::CubicSpline, 1.3, 40},
    {"1d-clamped-cubic", 1, false, KernelType::CubicSpline, 1.3, 40},
    {"1d-clamped-mollifier", 1, false, KernelType::ModifiedMollifier, 2.75, 40},
    {"2d-periodic-cubic", 2, true, KernelType::CubicSpline, 1.3, 12},
    {"2d-block-cubic", 2, false, KernelType::CubicSpline, 1.3, 12},
};
inline const std::vector<Variant> kVariants{
    {"plain-difference", false, StrainSum::Difference},
    {"plain-direct", false, StrainSum::Direct},
    {"ncsph-difference", true, StrainSum::Difference},
    {"ncsph-direct", true, StrainSum::Direct},
    // the term's full-vector variant (not the paper's); at c_HG = 0 plain-difference
    {"plain-difference-full", false, StrainSum::Difference, HourglassProjection::Full}};

template <int Dim>
std::shared_ptr<const Discretisation<Dim>> lattice(const Config& c) {
  const Kernel<Dim> k(c.kernel);
  const ParticleSet<Dim> set = make_lattice<Dim>(Dim == 1 ? LatticeType::Line : LatticeType::Square, c.n,
                                                 {.spacing = 1.0,
                                                  .fixed_layers = c.periodic ? 0 : -1,
                                                  .support_radius = c.periodic ? 0.0 : 2 * k.support_radius(c.h),
                                                  .periodic = c.periodic});
  return make_discretisation(set, k, c.h);
}

template <int Dim>
FiniteStrainTotalLagrangian<Dim> form(std::shared_ptr<const Discretisation<Dim>> d, const Variant& v, double chg,
                                      double E = 1.0, double rho = 1.0) {
  auto m = std::make_shared<NeoHookean<Dim>>(ElasticMaterial::from_young_poisson(E, kNu, 1.0));
  FiniteStrainOptions<Dim> o{.strain_sum = v.sum, .hourglass = chg, .hourglass_projection = v.projection};
  if (v.ncsph) o.gradient = make_gradient_provider<Dim>(Correction::Ncsph);
  return FiniteStrainTotalLagrangian<Dim>(d, m, rho, o);
}

}  // namespace hourglass
