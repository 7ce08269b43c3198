#include "sphstab/problems/swegle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sphstab/particles/lattice.hpp"

namespace sphstab {

double SwegleScene::initial_kinetic_energy() const {
  const Discretisation<2>& d = *discretisation;
  double ke = 0;
  for (int f = 0; f < d.free_count(); ++f)
    ke += 0.5 * material.density() * d.particles.volume[d.free[f]] *
          (v0[2 * f] * v0[2 * f] + v0[2 * f + 1] * v0[2 * f + 1]);
  return ke;
}

Eigen::VectorXd SwegleScene::free_positions() const {
  const Discretisation<2>& d = *discretisation;
  Eigen::VectorXd x(d.dofs());
  for (int f = 0; f < d.free_count(); ++f)
    for (int a = 0; a < 2; ++a) x[2 * f + a] = d.particles.x(d.free[f], a);
  return x;
}

SwegleScene make_swegle_scene(const SwegleOptions& o) {
  const char* who = "make_swegle_scene";
  if (o.n < 3) throw std::invalid_argument(std::string(who) + ": need n >= 3 (got " + std::to_string(o.n) + ")");
  if (!(o.spacing > 0) || !(o.h_over_dx > 0) || !std::isfinite(o.spacing) || !std::isfinite(o.h_over_dx))
    throw std::invalid_argument(std::string(who) + ": spacing and h/dx must be finite and > 0");
  if (!(o.velocity > 0) || !std::isfinite(o.velocity) || !std::isfinite(o.direction_angle))
    throw std::invalid_argument(std::string(who) + ": velocity must be finite and > 0 (got " +
                                std::to_string(o.velocity) + ")");
  if (o.layer_supports < 1)
    throw std::invalid_argument(std::string(who) + ": layer_supports must be >= 1 (got " +
                                std::to_string(o.layer_supports) + ")");
  SwegleScene s;
  s.options = o;
  s.material = ElasticMaterial::from_young_poisson(o.youngs_modulus, o.poisson_ratio, o.density);
  s.prestrain = PreStrain::from_area_ratio(o.area_ratio);
  s.h = o.h_over_dx * o.spacing;
  Kernel<2> kernel(o.kernel);
  LatticeOptions lo;
  lo.spacing = o.spacing;
  lo.support_radius = o.layer_supports * kernel.support_radius(s.h);
  ParticleSet<2> set = make_lattice<2>(LatticeType::Square, o.n, lo);
  s.discretisation = make_discretisation(std::move(set), kernel, s.h);
  const Discretisation<2>& d = *s.discretisation;
  // The free particle nearest to the centre of the free block.
  const double c = 0.5 * o.n * o.spacing;
  double best = 1e300;
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    const double r = std::hypot(d.particles.x(i, 0) - c, d.particles.x(i, 1) - c);
    if (r < best - 1e-12 * o.spacing) {
      best = r;
      s.centre = i;
    }
  }
  s.v0 = Eigen::VectorXd::Zero(d.dofs());
  const int f = d.free_slot[s.centre];
  s.v0[2 * f] = o.velocity * std::cos(o.direction_angle);
  s.v0[2 * f + 1] = o.velocity * std::sin(o.direction_angle);
  s.wave_speed = std::sqrt((s.material.lambda() + 2 * s.material.mu()) / s.material.density());
  return s;
}

}  // namespace sphstab
