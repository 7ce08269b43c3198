#pragma once
// The cases of the dispersion-rate-form study: its formulations, the material, the periodic box and the Bloch symbol
// of the scheme on it.
#include <cmath>
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/lattice_dispersion.hpp"
#include "sphstab/spectral/rate_form_symbol.hpp"

namespace dispersion_study {

using namespace sphstab;

struct Formulation {
  std::string name;
  RateFormOptions options;
};

// The formulations of the critical-stress and Swegle rate-form studies, GMS's combination added; `quick`: gms and
// ncsph only (the study's test case).
inline std::vector<Formulation> formulations(bool quick = false) {
  if (quick)
    return {{"gms", {.xsph = 0.5, .artificial_stress = 0.3}},
            {"ncsph", {.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph}}};
  return {{"sph", {}},
          {"sph-xsph", {.xsph = 0.5}},
          {"sph-as", {.artificial_stress = 0.3}},
          {"gms", {.xsph = 0.5, .artificial_stress = 0.3}},
          {"ncsph", {.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph}},
          {"ncsph-anti",
           {.continuity = ContinuityForm::Divergence,
            .gradient = RateFormGradient::Ncsph,
            .momentum = RateFormMomentum::Antisymmetric}},
          {"cij", {.momentum = RateFormMomentum::Cij}},
          {"ssph", {.momentum = RateFormMomentum::StabilisedSph}}};
}

// MCM-like steel in units of dx (the spectrum scales with c_P / dx).
inline const ElasticMaterial kSteel = ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8);

template <int Dim>
inline RateFormSymbol<Dim> symbol_of(const RateFormOptions& o, double h, double xi, int n) {
  const Kernel<Dim> kernel(KernelType::CubicSpline);
  const ParticleSet<Dim> set =
      make_lattice<Dim>(Dim == 1 ? LatticeType::Line : LatticeType::Square, n,
                        {.spacing = 1.0, .support_radius = kernel.support_radius(h), .periodic = true});
  const RateFormScheme<Dim> scheme(make_discretisation(set, kernel, h), kSteel, o, kSteel.density() / xi);
  return rate_form_symbol(scheme, scheme.uniform_state());
}

// Periodic box holding three supports each way (the widest stencil: S-SPH, antisymmetrised NCSPH).
inline int box_for(double h) { return 2 * static_cast<int>(std::ceil(3 * 2 * h)) + 2; }

inline UniformState gms_state(double xi) {
  const double rho = kSteel.density() / xi;
  return {.density = rho,
          .sound_speed = kSteel.sound_speed(),
          .shear_modulus = kSteel.mu(),
          .pressure = kSteel.bulk_modulus() * (rho / kSteel.density() - 1)};
}

}  // namespace dispersion_study
