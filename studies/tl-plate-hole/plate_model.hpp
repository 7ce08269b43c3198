#pragma once
// The discretised quarter plate of a run and its total-Lagrangian body [Ismail2009, §5.4.4]: the one model the static
// solution (static_solution.hpp) and the suddenly applied load (dynamic_load.hpp) both solve. Cubic spline at
// h = 1.3 dx, ghosts two supports deep, NCSPH-corrected gradient, the plus divergence and the hourglass control c_hg;
// rho = 1 (the static solution does not depend on it; the dynamic history in transit times W / c_s neither).
#include <memory>

#include "plate_cases.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/problems/plate_with_hole.hpp"

namespace plate_hole {

struct PlateModel {
  double dx = 0, h = 0, W = 0;
  sphstab::PlateWithHole plate;
  std::shared_ptr<const sphstab::Discretisation<2>> disc;
  std::shared_ptr<const sphstab::HyperelasticModel<2>> material;  ///< Hooke or Neo-Hookean by Run::model
  std::unique_ptr<sphstab::FiniteStrainTotalLagrangian<2>> tl;
  sphstab::SparseMatrix<> T;  ///< u_all = T u_real (mirror_map)
  int nr = 0;                 ///< real unknowns, 2 x real particles
};

inline PlateModel plate_model(const Run& run, double c_hg) {
  using namespace sphstab;
  PlateModel m;
  const Kernel<2> kernel(KernelType::CubicSpline);
  m.dx = kA / run.a_over_dx, m.h = kHOverDx * m.dx, m.W = run.w_over_a * kA;
  m.plate = make_plate_with_hole(
      {.radius = kA, .width = m.W, .spacing = m.dx, .ghost_depth = 2 * kernel.support_radius(m.h) + 0.5 * m.dx});
  m.disc = make_discretisation(m.plate.particles, kernel, m.h);
  const auto lame = ElasticMaterial::from_young_poisson(run.youngs, run.nu, 1.0);
  if (run.model == "hooke")
    m.material = std::make_shared<Hooke<2>>(lame);
  else
    m.material = std::make_shared<NeoHookean<2>>(lame);
  m.tl = std::make_unique<FiniteStrainTotalLagrangian<2>>(
      m.disc, m.material, 1.0,
      FiniteStrainOptions<2>{.gradient = make_gradient_provider<2>(Correction::Ncsph),
                             .divergence = StressDivergence::Plus,
                             .hourglass = c_hg});
  m.nr = 2 * m.plate.real_count;
  m.T = mirror_map(m.plate);
  return m;
}

}  // namespace plate_hole
