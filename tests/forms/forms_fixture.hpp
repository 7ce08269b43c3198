#pragma once
// Shared set-up of the forms tests: a lattice at dx = 1 (or `spacing`) with fixed layers for the kernel's support (or
// periodic, or perturbed), its discretisation, and reproducible random vectors.
#include <Eigen/Core>
#include <bit>
#include <complex>
#include <cstdint>
#include <memory>
#include <random>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/models/elastic_material.hpp"
#include "sphstab/numerics/random_vector.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/system/force_function.hpp"

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

/// The elastic-form tests' constants: lambda = 1.2, mu = 0.8, rho = 7.8.
inline constexpr double kRho = 7.8;
inline const ElasticMaterial kLame = ElasticMaterial::from_lame(1.2, 0.8, kRho);

/// max |m_ij| (0 for an empty matrix).
inline double max_abs(const Eigen::MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; }

/// dU/du by the complex step of the strain energy (h = 1e-30: exact to rounding), one DOF at a time; a variational
/// form has M a = -dU/du.
inline Eigen::VectorXd energy_gradient(const ForceFunction& f, const Eigen::VectorXd& u) {
  Eigen::VectorXd g(u.size());
  Eigen::VectorXcd uc = u.cast<std::complex<double>>();
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    uc[k] += std::complex<double>(0, 1e-30);
    g[k] = f.strain_energy(uc).imag() / 1e-30;
    uc[k] = u[k];
  }
  return g;
}

/// GMS's units (K = 1, mu = 0.3 K, rho = 1), the rate-form tests' material.
inline const ElasticMaterial kGms = ElasticMaterial::from_bulk_shear(1.0, 0.3, 1.0);

/// Number of entries where a and b differ in any bit (NaN included); -1 for different sizes.
inline long differing_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return -1;
  long count = 0;
  for (long k = 0; k < a.size(); ++k)
    if (std::bit_cast<std::uint64_t>(a[k]) != std::bit_cast<std::uint64_t>(b[k])) ++count;
  return count;
}

/// A free nx x ny block of spacing dx (particle (i, j) at ((i + 1/2) dx, (j + 1/2) dx), index j nx + i).
inline ParticleSet<2> free_block(int nx, int ny, double dx) {
  ParticleSet<2> p = ParticleSet<2>::free_grid(nx * ny, dx);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) p.x.row(j * nx + i) << (i + 0.5) * dx, (j + 0.5) * dx;
  return p;
}

}  // namespace sphstab::test
