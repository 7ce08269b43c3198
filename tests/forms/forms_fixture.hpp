#pragma once
// Shared set-up of the forms tests: a lattice at dx = 1 (or `spacing`) with fixed layers for the kernel's support (or
// periodic, or perturbed), its discretisation, and reproducible random vectors.
#include <Eigen/Core>
#include <memory>
#include <random>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/numerics/random_vector.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab::test {

struct LatticeSpec {
  int n = 10;  ///< free particles per side
  KernelType kernel = KernelType::CubicSpline;
  double h = 1.3;                          ///< h / dx
  LatticeType type = LatticeType::Square;  ///< 2D lattice (1D is always a line)
  bool periodic = false;
  double perturbation = 0;     ///< free particles moved by up to this fraction of dx
  std::uint64_t seed = 7;      ///< of the perturbation
  int fixed_layers = -1;       ///< -1: as many as the support needs
  double support_scale = 1.0;  ///< layers reach support_scale x 2h
  double spacing = 1.0;        ///< dx (h = h/dx times dx)
};

template <int Dim>
std::shared_ptr<const Discretisation<Dim>> lattice_discretisation(const LatticeSpec& s) {
  const Kernel<Dim> k(s.kernel);
  const ParticleSet<Dim> set = make_lattice<Dim>(Dim == 1 ? LatticeType::Line : s.type, s.n,
                                                 {.spacing = s.spacing,
                                                  .fixed_layers = s.fixed_layers,
                                                  .support_radius = s.support_scale * k.support_radius(s.h * s.spacing),
                                                  .periodic = s.periodic,
                                                  .perturbation = s.perturbation,
                                                  .seed = s.seed});
  return make_discretisation(set, k, s.h * s.spacing);
}

using sphstab::random_vector;

}  // namespace sphstab::test
