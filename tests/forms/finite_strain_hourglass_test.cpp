// Hourglass control of the finite-strain total-Lagrangian form (FiniteStrainOptions::hourglass, the pair term of
// [Ganzenmueller2015] in forms/finite_strain_total_lagrangian.hpp, bond-projected and full): zero for affine fields
// (finite rotation and stretch), linear and (bond-projected) angular momentum to round-off, the complex-step Jacobian
// against central differences of the force, the exact lift of the 1D sawtooth on a periodic lattice, the pair force
// of TrixiParticles.jl's independent statement of the paper, coefficient 0 = the form without it, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "forms_fixture.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"

namespace sphstab {
namespace finite_strain_hourglass_test {

using test::random_vector;
using test::kLame;
using test::kRho;

using test::max_abs;

/// u = (A - I) X + b on every particle; the fixed particles' part goes to `fixed`.
template <int Dim>
Eigen::VectorXd affine_field(const Discretisation<Dim>& d, const Eigen::Matrix<double, Dim, Dim>& A,
                             const Eigen::Matrix<double, Dim, 1>& b, Eigen::VectorXd& fixed) {
  Eigen::VectorXd u(d.dofs());
  fixed.resize(Dim * (d.size() - d.free_count()));
  long next = 0;
  for (int i = 0; i < d.size(); ++i) {
    const Eigen::Matrix<double, Dim, 1> X = d.particles.x.row(i).transpose();
    const Eigen::Matrix<double, Dim, 1> ui = (A - Eigen::Matrix<double, Dim, Dim>::Identity()) * X + b;
    if (d.free_slot[i] >= 0)
      u.template segment<Dim>(Dim * d.free_slot[i]) = ui;
    else
      fixed.template segment<Dim>(Dim * next++) = ui;
  }
  return u;
}

/// The hourglass part of the acceleration: a(c_HG) - a(0).
template <int Dim>
Eigen::VectorXd hourglass_part(std::shared_ptr<const Discretisation<Dim>> d,
                               std::shared_ptr<const HyperelasticModel<Dim>> m, FiniteStrainOptions<Dim> o,
                               const Eigen::VectorXd& u, const Eigen::VectorXd& fixed) {
  FiniteStrainTotalLagrangian<Dim> off(d, m, kRho, o);
  o.hourglass = 1.0;
  FiniteStrainTotalLagrangian<Dim> on(d, m, kRho, o);
  off.set_fixed_displacement(fixed);
  on.set_fixed_displacement(fixed);
  Eigen::VectorXd a0, a1;
  off.acceleration(u, a0);
  on.acceleration(u, a1);
  return a1 - a0;
}

TEST(FiniteStrainHourglass, VanishesForAFiniteRotationAndStretchWithTheCorrectedGradient) {
  // Perturbed lattice: NCSPH reproduces the affine field at every active particle (F_i = A), so every pair error
  // F_i X_ij - x_ij is zero. Scale: the hourglass part of a random field of displacement 0.05 dx.
  auto d = test::lattice_discretisation<2>({.n = 6, .perturbation = 0.15});
  auto nh = std::make_shared<NeoHookean<2>>(kLame);
  const FiniteStrainOptions<2> o{.gradient = make_gradient_provider<2>(Correction::Ncsph)};
  const double t = 0.7;
  Eigen::Matrix2d R, S;
  R << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  S << 1.4, 0.25, 0.25, 0.8;
  Eigen::VectorXd fixed;
  const Eigen::VectorXd u = affine_field<2>(*d, R * S, Eigen::Vector2d(0.3, -1.1), fixed);
  const Eigen::VectorXd ahg = hourglass_part<2>(d, nh, o, u, fixed);
  Eigen::VectorXd fixed0 = Eigen::VectorXd::Zero(fixed.size());
  const double scale = max_abs(hourglass_part<2>(d, nh, o, random_vector(d->dofs(), 0.05, 5), fixed0));
  EXPECT_GT(scale, 1e-3);
  EXPECT_LT(max_abs(ahg), 1e-12 * scale / 0.05);  // round-off of O(1) displacements against 0.05
  FiniteStrainOptions<2> full = o;
  full.hourglass_projection = HourglassProjection::Full;
  const double scale_full = max_abs(hourglass_part<2>(d, nh, full, random_vector(d->dofs(), 0.05, 5), fixed0));
  EXPECT_GT(scale_full, 1e-3);
  EXPECT_LT(max_abs(hourglass_part<2>(d, nh, full, u, fixed)), 1e-12 * scale_full / 0.05);
  // 1D: a stretch by 1.7 and a translation
  auto d1 = test::lattice_discretisation<1>({.n = 20, .perturbation = 0.15});
  const FiniteStrainOptions<1> o1{.gradient = make_gradient_provider<1>(Correction::Ncsph)};
  auto nh1 = std::make_shared<NeoHookean<1>>(kLame);
  Eigen::VectorXd fixed1;
  const Eigen::VectorXd u1 =
      affine_field<1>(*d1, Eigen::Matrix<double, 1, 1>(1.7), Eigen::Matrix<double, 1, 1>(2.0), fixed1);
  Eigen::VectorXd fixed10 = Eigen::VectorXd::Zero(fixed1.size());
  const double scale1 = max_abs(hourglass_part<1>(d1, nh1, o1, random_vector(d1->dofs(), 0.05, 6), fixed10));
  EXPECT_LT(max_abs(hourglass_part<1>(d1, nh1, o1, u1, fixed1)), 1e-12 * scale1 / 0.05);
}

TEST(FiniteStrainHourglass, PlainGradientVanishesOnARegularLatticeOnlyBySymmetry) {
  // Plain gradient: F_i = I + m1 (A - I) != A, so every pair error is (F_i - A) X_ij. On a regular lattice with fixed
  // layers two supports deep every active F_i is the same and the bonds +X and -X cancel: zero at the free particles.
  // On a perturbed lattice they do not: the term is not exact for affine fields without a corrected gradient.
  Eigen::Matrix2d A;
  A << 1.3, 0.2, -0.1, 0.9;
  auto nh = std::make_shared<NeoHookean<2>>(kLame);
  auto regular = test::lattice_discretisation<2>({.n = 6, .support_scale = 2.0});
  Eigen::VectorXd fixed;
  Eigen::VectorXd u = affine_field<2>(*regular, A, Eigen::Vector2d::Zero(), fixed);
  Eigen::VectorXd fixed0 = Eigen::VectorXd::Zero(fixed.size());
  const double scale = max_abs(hourglass_part<2>(regular, nh, {}, random_vector(regular->dofs(), 0.05, 5), fixed0));
  EXPECT_LT(max_abs(hourglass_part<2>(regular, nh, {}, u, fixed)), 1e-12 * scale / 0.05);
  auto perturbed = test::lattice_discretisation<2>({.n = 6, .perturbation = 0.15, .support_scale = 2.0});
  u = affine_field<2>(*perturbed, A, Eigen::Vector2d::Zero(), fixed);
  EXPECT_GT(max_abs(hourglass_part<2>(perturbed, nh, {}, u, fixed)), 1e-4 * scale / 0.05);
}

TEST(FiniteStrainHourglass, ConservesLinearAndAngularMomentumToRoundOff) {
  // No fixed particles, perturbed lattice, unequal volumes and densities, large deformation: the pair force is
  // antisymmetric and central, so sum_i m_i a_i^HG = 0 and sum_i m_i x_i x a_i^HG = 0 (x current).
  auto base = test::lattice_discretisation<2>({.n = 6, .perturbation = 0.2, .fixed_layers = 0});
  ParticleSet<2> set = base->particles;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(0.7, 1.3);
  Eigen::VectorXd rho(set.size());
  for (int i = 0; i < set.size(); ++i) {
    set.volume[i] *= U(rng);
    rho[i] = kRho * U(rng);
  }
  auto d = make_discretisation(set, base->kernel, base->h);
  auto nh = std::make_shared<NeoHookean<2>>(kLame);
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.15, 4);
  FiniteStrainTotalLagrangian<2> off(d, nh, rho, {.divergence = StressDivergence::Plain});
  for (HourglassProjection proj : {HourglassProjection::Bond, HourglassProjection::Full}) {
    FiniteStrainTotalLagrangian<2> on(
        d, nh, rho, {.divergence = StressDivergence::Plain, .hourglass = 0.5, .hourglass_projection = proj});
    Eigen::VectorXd a0, a1;
    off.acceleration(u, a0);
    on.acceleration(u, a1);
    const Eigen::VectorXd ma = on.dof_mass().cwiseProduct(a1 - a0);
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    double L = 0, scale = 0, lscale = 0;
    for (int i = 0; i < d->size(); ++i) {
      const Eigen::Vector2d x = d->particles.x.row(i).transpose() + u.segment<2>(2 * i);
      const Eigen::Vector2d f = ma.segment<2>(2 * i);
      p += f;
      L += x[0] * f[1] - x[1] * f[0];
      scale += f.norm();
      lscale += x.norm() * f.norm();
    }
    EXPECT_GT(scale, 1e-2);
    EXPECT_LT(p.norm(), 1e-14 * scale);
    if (proj == HourglassProjection::Bond)
      EXPECT_LT(std::abs(L), 1e-14 * lscale);  // central pair forces
    else
      EXPECT_GT(std::abs(L), 1e-4 * lscale);  // the full error vector is not along the bond
  }
}

TEST(FiniteStrainHourglass, ComplexStepJacobianIsTheCentralDifferenceOfTheForce) {
  // At a deformed state (displacement 0.05 dx, NCSPH and plain gradients): A = -da/du by complex step against
  // -(a(u + s e_k) - a(u - s e_k)) / (2 s), s = 1e-6: truncation O(s^2) and round-off O(1e-16 / s) both < 1e-8.
  auto d = test::lattice_discretisation<2>({.n = 5, .perturbation = 0.1});
  auto nh = std::make_shared<NeoHookean<2>>(kLame);
  for (auto grad : {std::shared_ptr<const GradientProvider<2>>(), make_gradient_provider<2>(Correction::Ncsph)})
    for (HourglassProjection proj : {HourglassProjection::Bond, HourglassProjection::Full}) {
      FiniteStrainTotalLagrangian<2> tl(d, nh, kRho,
                                        {.gradient = grad, .hourglass = 0.3, .hourglass_projection = proj});
      const Eigen::VectorXd u = random_vector(tl.dofs(), 0.05, 8);
      const Eigen::MatrixXd A(jacobian(tl, u));
      Eigen::MatrixXd Afd(tl.dofs(), tl.dofs());
      const double s = 1e-6;
      for (int k = 0; k < tl.dofs(); ++k) {
        Eigen::VectorXd up = u, um = u, ap, am;
        up[k] += s;
        um[k] -= s;
        tl.acceleration(up, ap);
        tl.acceleration(um, am);
        Afd.col(k) = -(ap - am) / (2 * s);
      }
      EXPECT_LT(max_abs(A - Afd), 1e-8 * max_abs(A)) << tl.name();
      // and the hourglass part is really there (its Jacobian is not the one without it)
      FiniteStrainTotalLagrangian<2> off(d, nh, kRho, {.gradient = grad});
      EXPECT_GT(max_abs(A - Eigen::MatrixXd(jacobian(off, u))), 1e-3 * max_abs(A)) << tl.name();
    }
}

TEST(FiniteStrainHourglass, LiftsThePeriodicSawtoothByTheClosedForm) {
  // Periodic 1D lattice (dx = 1, V = 1), plain gradient: G kills the sawtooth (-1)^i, so A saw = mu_HG saw with
  // (linearising the term at rest: delta_ij = -(u_j - u_i) sgn(X_ij), zero for even m, 2 (-1)^i for odd m)
  //   mu_HG = 4 c_HG (E / rho) sum_{m odd >= 1} W(m dx) V / (m dx)^2.
  auto d =
      test::lattice_discretisation<1>({.n = 24, .kernel = KernelType::ModifiedMollifier, .h = 2.5, .periodic = true});
  auto hooke = std::make_shared<Hooke<1>>(kLame, UniaxialState::Stress);
  const double c = 0.3, E = kLame.young();
  FiniteStrainTotalLagrangian<1> tl(d, hooke, kRho, {.hourglass = c});
  double sum = 0;
  for (int m = 1; m < 12; m += 2) sum += d->kernel.value(double(m), d->h) / (m * m);
  const double mu = 4 * c * (E / kRho) * sum;
  Eigen::VectorXd saw(tl.dofs());
  for (int i = 0; i < tl.dofs(); ++i) saw[i] = i % 2 ? -1.0 : 1.0;
  const Eigen::MatrixXd A(jacobian(tl, Eigen::VectorXd::Zero(tl.dofs())));
  EXPECT_GT(mu, 1e-3);
  EXPECT_LT(max_abs(A * saw - mu * saw), 1e-12 * mu);
  FiniteStrainTotalLagrangian<1> off(d, hooke, kRho);  // without control the sawtooth is a zero-energy mode
  EXPECT_LT(max_abs(Eigen::MatrixXd(jacobian(off, Eigen::VectorXd::Zero(tl.dofs()))) * saw), 1e-12 * mu);
}

TEST(FiniteStrainHourglass, IsThePenaltyForceOfTrixiParticlesAndTwiceLammpsSmd) {
  // Independent pair loop in TrixiParticles.jl's convention (PenaltyForceGanzenmueller, its statement of
  // [Ganzenmueller2015]): X_ab = X_a - X_b, x_ab = x_a - x_b, eps^a = F_a X_ab - x_ab, and
  //   dv_a = (alpha / 2) V_a V_b W_ab (E eps^a . x_ab + E eps^b . x_ab) / (|X_ab|^2 |x_ab|^2 m_a) x_ab.
  // With alpha = c_HG it must equal the form's term on a perturbed, unequal-volume block at a large deformation, for
  // the plain and the NCSPH gradient. (LAMMPS SMD's pair_smd_tlsph elastic branch has one more factor 1/2 in its
  // delta, besides its 0.1 h / 0.01 h^2 regularisations: its amplitude is 2 c_HG for the same force.)
  auto base = test::lattice_discretisation<2>({.n = 6, .perturbation = 0.2, .fixed_layers = 0});
  ParticleSet<2> set = base->particles;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0.7, 1.3);
  for (int i = 0; i < set.size(); ++i) set.volume[i] *= U(rng);
  auto d = make_discretisation(set, base->kernel, base->h);
  auto nh = std::make_shared<NeoHookean<2>>(kLame);
  const double alpha = 0.37, E = kLame.young();
  const Eigen::VectorXd u = random_vector(d->dofs(), 0.12, 8);
  for (auto grad : {std::shared_ptr<const GradientProvider<2>>(), make_gradient_provider<2>(Correction::Ncsph)}) {
    FiniteStrainOptions<2> o{.gradient = grad, .divergence = StressDivergence::Plain};
    FiniteStrainTotalLagrangian<2> off(d, nh, kRho, o);
    o.hourglass = alpha;
    FiniteStrainTotalLagrangian<2> on(d, nh, kRho, o);
    Eigen::VectorXd a0, a1;
    off.acceleration(u, a0);
    on.acceleration(u, a1);
    const Eigen::MatrixXd F = on.deformation_gradients(u);  // row i: F_ab at column 2 a + b
    auto Fof = [&](int i) {
      Eigen::Matrix2d m;
      m << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
      return m;
    };
    Eigen::VectorXd ref = Eigen::VectorXd::Zero(d->dofs());
    for (int a = 0; a < d->size(); ++a) {
      const Eigen::Matrix2d Fa = Fof(a);
      for (int b = 0; b < d->size(); ++b) {
        const Eigen::Vector2d Xab = (d->particles.x.row(a) - d->particles.x.row(b)).transpose();
        const double W = d->kernel.value(Xab.norm(), d->h);
        if (b == a || W == 0) continue;
        const Eigen::Matrix2d Fb = Fof(b);
        const Eigen::Vector2d xab = Xab + u.segment<2>(2 * a) - u.segment<2>(2 * b);
        const double Va = d->particles.volume[a], Vb = d->particles.volume[b];
        const double delta_sum = E * (Fa * Xab - xab).dot(xab) + E * (Fb * Xab - xab).dot(xab);
        ref.segment<2>(2 * a) +=
            (alpha / 2) * Va * Vb * W * delta_sum / (Xab.squaredNorm() * xab.squaredNorm() * kRho * Va) * xab;
      }
    }
    EXPECT_GT(max_abs(ref), 1e-3);
    EXPECT_LT(max_abs(a1 - a0 - ref), 1e-12 * max_abs(ref));
  }
}

TEST(FiniteStrainHourglass, CoefficientZeroIsTheFormWithoutIt) {
  auto d = test::lattice_discretisation<2>({.n = 5, .perturbation = 0.1});
  auto nh = std::make_shared<NeoHookean<2>>(kLame);
  FiniteStrainTotalLagrangian<2> plain(d, nh, kRho);
  FiniteStrainTotalLagrangian<2> zero(d, nh, kRho, {.hourglass = 0.0});
  FiniteStrainTotalLagrangian<2> tiny(d, nh, kRho, {.hourglass = 1e-9});
  const Eigen::VectorXd u = random_vector(plain.dofs(), 0.1, 2);
  Eigen::VectorXd a, a0, at;
  plain.acceleration(u, a);
  zero.acceleration(u, a0);
  tiny.acceleration(u, at);
  EXPECT_TRUE(a == a0);  // bit-identical
  EXPECT_FALSE(a == at);
  EXPECT_EQ(plain.name(), zero.name());
  EXPECT_TRUE(zero.conservative());
  EXPECT_FALSE(tiny.conservative());  // the term has no potential
  EXPECT_NE(tiny.name().find("hourglass"), std::string::npos);
}

TEST(FiniteStrainHourglass, BadCoefficientIsOneLineInvalidArgument) {
  auto d = test::lattice_discretisation<1>({.n = 10});
  auto nh = std::make_shared<NeoHookean<1>>(kLame);
  for (double c : {-0.1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    try {
      FiniteStrainTotalLagrangian<1> tl(d, nh, kRho, {.hourglass = c});
      ADD_FAILURE() << "accepted " << c;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("hourglass"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace sphstab
