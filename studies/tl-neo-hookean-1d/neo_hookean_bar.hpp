#pragma once
// The bar of the tl-neo-hookean-1d study, Ismail (2009) §4.6.3, §5.3: a 1D compressible Neo-Hookean bar
// (models/neo_hookean.hpp, 1D strain: P = mu (F - 1/F) + lambda ln F / F, algorithm 5.1) discretised with the
// finite-strain total-Lagrangian SPH form (forms/finite_strain_total_lagrangian.hpp), its fixed layers carrying the
// imposed stretch; the homogeneous stretch, T11 of the SPH form and of the model, and the linearised Jacobian
// A = -da/du (complex step) at a stretched equilibrium.
#include <Eigen/Core>
#include <cmath>
#include <memory>

#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/particles/lattice.hpp"

namespace nh1d {

using namespace sphstab;

// SI units. Ismail's bar (§4.6.3, §5.3): steel-like E = 200 GPa, rho = 8000; the quasi-static bar is 15 mm long.
constexpr double kE = 200e9, kRho = 8000, kLength = 0.015, kStretch = 6;
// Ismail's h = 5.5 dx with the mollifier's native support h: sphstab's support-2h convention gives h = 2.75 dx.
constexpr double kHOverDx = 2.75;

/// The bar: n free particles on [0, L], fixed layers two kernel supports deep at both ends (every particle within a
/// support of a free one has a complete neighbourhood, so the homogeneous stretch is an exact equilibrium).
struct Bar {
  std::shared_ptr<const Discretisation<1>> disc;
  std::shared_ptr<NeoHookean<1>> material;
  std::shared_ptr<FiniteStrainTotalLagrangian<1>> tl;
  Eigen::VectorXd x_free, x_fixed;
  double dx = 0, m1 = 0;
  int centre = 0;  // free slot of the centre particle

  Bar(int n, double nu) {
    dx = kLength / n;
    const Kernel<1> kernel(KernelType::ModifiedMollifier);
    const double h = kHOverDx * dx;
    ParticleSet<1> set =
        make_lattice<1>(LatticeType::Line, n, {.spacing = dx, .support_radius = 2 * kernel.support_radius(h)});
    disc = make_discretisation(set, kernel, h);
    material = std::make_shared<NeoHookean<1>>(ElasticMaterial::from_young_poisson(kE, nu, kRho));
    // the variational pair (plain reference gradient, difference strain, plus divergence): symmetric Jacobian
    tl = std::make_shared<FiniteStrainTotalLagrangian<1>>(disc, material, kRho);
    x_free = disc->free_positions().col(0);
    x_fixed.resize(disc->size() - disc->free_count());
    for (int i = 0, k = 0; i < disc->size(); ++i)
      if (disc->free_slot[i] < 0) x_fixed[k++] = disc->particles.x(i, 0);
    centre = n / 2;
    // discrete first moment: F - 1 = m1 (lambda - 1) for the plain gradient
    set_stretch(2.0);
    m1 = tl->deformation_gradients(Eigen::VectorXd(x_free))(disc->free[centre], 0) - 1;
    set_stretch(1.0);
  }
  void set_stretch(double lambda) { tl->set_fixed_displacement((lambda - 1) * x_fixed); }
  Eigen::VectorXd homogeneous(double lambda) const { return (lambda - 1) * x_free; }
  double c_l() const { return std::sqrt(material->material().uniaxial_modulus(UniaxialState::Strain) / kRho); }
  double mu() const { return material->material().mu(); }
  /// P = T11 (1D strain: J = F) of free particle f.
  double t11(const Eigen::VectorXd& u, int f) const { return tl->stresses(u)(disc->free[f], 0); }
  double F(const Eigen::VectorXd& u, int f) const { return tl->deformation_gradients(u)(disc->free[f], 0); }
  double analytic_t11(double lambda) const {
    return material->stress(Deformation<double, 1>(Deformation<double, 1>::Constant(lambda)))(0, 0);
  }
  double tangent(double f) const {
    return material->tangent(Deformation<double, 1>(Deformation<double, 1>::Constant(f)))(0, 0);
  }
  /// A = -da/du at the homogeneous stretch (an equilibrium), symmetrised (complex step is symmetric to ~1e-16).
  Eigen::MatrixXd jacobian_at(double lambda) {
    set_stretch(lambda);
    const Eigen::MatrixXd A(jacobian(*tl, homogeneous(lambda)));
    set_stretch(1.0);
    return 0.5 * (A + A.transpose());
  }
  /// T11 / mu at the homogeneous stretch lambda of the free particle farthest from the analytic value.
  double static_t11(double lambda) {
    const double analytic = analytic_t11(lambda) / mu();
    set_stretch(lambda);
    const Eigen::VectorXd u = homogeneous(lambda);
    double static_sph = std::nan("");  // the worst free particle
    for (int f = 0; f < disc->free_count(); ++f) {
      const double t = t11(u, f) / mu();
      if (std::isnan(static_sph) || std::abs(t - analytic) > std::abs(static_sph - analytic)) static_sph = t;
    }
    set_stretch(1.0);
    return static_sph;
  }
  /// F of the centre particle at the homogeneous stretch lambda.
  double centre_F(double lambda) {
    set_stretch(lambda);
    const double f = F(homogeneous(lambda), centre);
    set_stretch(1.0);
    return f;
  }
};

}  // namespace nh1d
