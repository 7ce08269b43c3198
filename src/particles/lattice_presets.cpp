#include "sphstab/particles/lattice_presets.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

ParticleSet<1> tension_lattice_1d(const Kernel<1>& kernel, double h, int free, bool periodic, int layer_supports) {
  if (layer_supports < 1)
    throw std::invalid_argument("tension_lattice_1d: layer_supports must be >= 1 (got " +
                                std::to_string(layer_supports) + ")");
  if (free < 1)
    throw std::invalid_argument("tension_lattice_1d: need at least one free particle (got " + std::to_string(free) +
                                ")");
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("tension_lattice_1d: h must be finite and > 0 (got " + format_number(h) + ")");
  return make_lattice<1>(
      LatticeType::Line, free,
      {.spacing = 1.0, .support_radius = layer_supports * kernel.support_radius(h), .periodic = periodic});
}

ParticleSet<2> strain_lattice_2d(LatticeType type, const Kernel<2>& kernel, double h, int n, bool periodic) {
  if (n < 1)
    throw std::invalid_argument("strain_lattice_2d: need at least one free particle per side (got " +
                                std::to_string(n) + ")");
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("strain_lattice_2d: h must be finite and > 0 (got " + format_number(h) + ")");
  if (type != LatticeType::Square && type != LatticeType::Hexagonal && type != LatticeType::FaceCentred)
    throw std::invalid_argument("strain_lattice_2d: lattice '" + lattice_name(type) +
                                "' is not two-dimensional (valid: square, hex, face-centred)");
  return make_lattice<2>(type, n, {.spacing = 1.0, .support_radius = kernel.support_radius(h), .periodic = periodic});
}

}  // namespace sphstab
