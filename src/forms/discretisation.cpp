#include "sphstab/forms/discretisation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/numerics/instantiation.hpp"

namespace sphstab {

template <int Dim>
std::shared_ptr<const Discretisation<Dim>> make_discretisation(ParticleSet<Dim> particles, const Kernel<Dim>& kernel,
                                                               double h, double neighbour_radius) {
  particles.validate("make_discretisation");
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("make_discretisation: smoothing length h must be finite and > 0 (got " +
                                format_number(h) + ")");
  const double support = kernel.support_radius(h);
  if (neighbour_radius <= 0) neighbour_radius = support;
  if (neighbour_radius < support * (1 - 1e-12))
    throw std::invalid_argument("make_discretisation: neighbour radius " + format_number(neighbour_radius) +
                                " is smaller than the kernel support " + format_number(support));
  auto d = std::make_shared<Discretisation<Dim>>(Discretisation<Dim>{std::move(particles), kernel, h, {}, {}, {}});
  d->neighbours = find_neighbours(d->particles, neighbour_radius);
  d->free = d->particles.indices(Role::Free);
  if (d->free.empty()) throw std::invalid_argument("make_discretisation: the particle set has no free particles");
  d->free_slot.assign(d->particles.size(), -1);
  for (int f = 0; f < static_cast<int>(d->free.size()); ++f) d->free_slot[d->free[f]] = f;
  return d;
}

#define SPHSTAB_INSTANTIATE(D)                                                                                       \
  template std::shared_ptr<const Discretisation<D>> make_discretisation<D>(ParticleSet<D>, const Kernel<D>&, double, \
                                                                           double);
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
