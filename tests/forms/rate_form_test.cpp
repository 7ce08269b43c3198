#include "sphstab/forms/rate_form.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "../spectral/gms_linearisation.hpp"
#include "forms_fixture.hpp"
#include "sphstab/growth/system_spectrum.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"
#include "sphstab/spectral/lattice_dispersion.hpp"

namespace sphstab {
namespace rate_form_test {

using Complex = std::complex<double>;

RateFormOptions all_terms() {
  return {.xsph = 0.5, .viscosity = ViscositySwitch::Compression, .artificial_stress = 0.3};
}

/// rho0 = c0 = 1 (K = 1), mu = 0.3: the GMS units.
using test::kGms;

TEST(RateForm, UniformLatticeIsAnEquilibriumToRounding) {
  for (bool periodic : {false, true})
    for (double xi : {0.98, 1.0, 1.02}) {
      const auto disc = test::lattice_discretisation<2>({.n = 8, .h = 1.3, .periodic = periodic});
      Eigen::VectorXd dev(3);
      dev << 0.01, -0.004, 0.0;
      const RateFormScheme<2> scheme(disc, kGms, all_terms(), 1.0 / xi, dev);
      const Eigen::VectorXd y = scheme.uniform_state();
      Eigen::VectorXd f;
      scheme.rate(y, f);
      EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-14) << "periodic " << periodic << " xi " << xi;
      const auto line = test::lattice_discretisation<1>({.n = 12, .h = 1.3, .periodic = periodic});
      const RateFormScheme<1> bar(line, kGms, all_terms(), 1.0 / xi, Eigen::VectorXd::Constant(1, 0.01));
      bar.rate(bar.uniform_state(), f);
      EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-14) << "1D periodic " << periodic << " xi " << xi;
    }
}

TEST(RateForm, StateLayoutAndBadInput) {
  const auto disc = test::lattice_discretisation<2>({.n = 4, .h = 1.3});  // 4 x 4 free + 2 layers: 64 particles
  const RateFormScheme<2> scheme(disc, kGms);
  EXPECT_EQ(scheme.size(), 16 * 8 + 48 * 4);
  const RateFormScheme<2> frozen(disc, kGms, {.evolve_fixed = false});
  EXPECT_EQ(frozen.size(), 16 * 8);
  EXPECT_THROW(RateFormScheme<2>(nullptr, kGms), std::invalid_argument);
  EXPECT_THROW(RateFormScheme<2>(disc, ElasticMaterial::from_bulk_shear(0, 0.0, 1)), std::invalid_argument);
  EXPECT_THROW(RateFormScheme<2>(disc, kGms, {.xsph = -0.1}), std::invalid_argument);
  EXPECT_THROW(RateFormScheme<2>(disc, kGms, {}, 0.0), std::invalid_argument);
  EXPECT_THROW(RateFormScheme<2>(disc, kGms, {}, 1.0, Eigen::VectorXd::Zero(2)), std::invalid_argument);
  EXPECT_THROW(ElasticMaterial::from_young_poisson(2.1, 0.5, 7.8), std::invalid_argument);
  EXPECT_THROW(ElasticMaterial::from_young_poisson(-1, 0.3, 7.8), std::invalid_argument);
  EXPECT_THROW(parse_viscosity_switch("on"), std::invalid_argument);
  EXPECT_THROW(parse_continuity_form("sum"), std::invalid_argument);
  Eigen::VectorXd f, y = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(scheme.rate(y, f), std::invalid_argument);
  const ElasticMaterial steel = ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8);
  EXPECT_NEAR(steel.bulk_modulus(), 1.75, 1e-14);
  EXPECT_NEAR(steel.mu(), 2.1 / 2.6, 1e-14);
}

TEST(RateForm, ComplexStepJacobianMatchesFiniteDifferences) {
  // A perturbed, moving, stressed state exercises every term (viscosity on approaching pairs, tensile R, XSPH).
  for (ContinuityForm c : {ContinuityForm::Summation, ContinuityForm::Divergence}) {
    const auto disc = test::lattice_discretisation<2>({.n = 6, .h = 1.3, .periodic = true});
    RateFormOptions o = all_terms();
    o.continuity = c;
    const RateFormScheme<2> scheme(disc, kGms, o, 1.0 / 1.03);
    Eigen::VectorXd y = scheme.uniform_state() + random_vector(scheme.size(), 1e-2, 11);
    const SparseMatrix<> J = jacobian(scheme, y);
    Eigen::MatrixXd fd(scheme.size(), scheme.size());
    Eigen::VectorXd fp, fm;
    for (int k = 0; k < scheme.size(); ++k) {
      const double step = 1e-6;
      Eigen::VectorXd yp = y, ym = y;
      yp[k] += step;
      ym[k] -= step;
      scheme.rate(yp, fp);
      scheme.rate(ym, fm);
      fd.col(k) = (fp - fm) / (2 * step);
    }
    const Eigen::MatrixXd Jd(J);
    EXPECT_LT((Jd - fd).cwiseAbs().maxCoeff(), 1e-6 * Jd.cwiseAbs().maxCoeff());
    // The pattern is a superset: no finite-difference entry falls outside it.
    EXPECT_LT((fd - fd.cwiseProduct(Eigen::MatrixXd(Jd.cwiseAbs().cwiseSign()))).cwiseAbs().maxCoeff(), 1e-7);
  }
}

TEST(RateForm, AgreesWithTheTestOnlyGmsEquations) {
  // tests/spectral/gms_linearisation.hpp writes GMS (3.1, 3.6, 3.8, 3.10, 2.3, 6.x) particle by particle (no
  // viscosity): the same rate at a random state.
  for (double eps : {0.0, 0.3}) {
    UniformState st{.density = 1.0 / 1.02, .sound_speed = 1.0, .shear_modulus = 0.3, .pressure = 1.0 / 1.02 - 1.0};
    auto g = test::make_gms_lattice(LatticeType::Square, 8, 1.3, st, eps, /*live_r=*/true);
    const auto disc = make_discretisation(g.set, g.kernel, g.h);
    const RateFormScheme<2> scheme(disc, kGms, {.xsph = 0.5, .artificial_stress = eps}, st.density);
    const int n = g.set.size();
    Eigen::VectorXd y = scheme.uniform_state() + random_vector(scheme.size(), 1e-3, 5);
    Eigen::Matrix<Complex, Eigen::Dynamic, 8> u(n, 8);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 8; ++c) u(i, c) = y[8 * i + c];
    const auto du = test::gms_rhs(g, u);
    Eigen::VectorXd f;
    scheme.rate(y, f);
    double worst = 0, scale = 0;
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 8; ++c) {
        worst = std::max(worst, std::abs(du(i, c).real() - f[8 * i + c]));
        scale = std::max(scale, std::abs(f[8 * i + c]));
      }
    EXPECT_LT(worst, 1e-13 * scale) << "eps " << eps;
  }
}

TEST(RateForm, JaumannRateRotatesTheStressWithTheSpin) {
  // Rigid counter-clockwise rotation v = w (-y, x) on a block (no fixed layers needed: the interior L is a multiple
  // of the exact skew gradient, whatever the lattice moment): dS/dt = Omega S - S Omega, so for S = diag(a, d):
  // dS_xy/dt = w' (a - d) > 0, dS_xx/dt = -dS_yy/dt = 0, and tr dS/dt = 0 (D = 0).
  const auto disc = test::lattice_discretisation<2>({.n = 9, .h = 1.3, .fixed_layers = 0});
  Eigen::VectorXd dev(3);
  dev << 0.02, -0.01, 0.0;
  const RateFormScheme<2> scheme(disc, kGms, {}, 1.0, dev);
  Eigen::VectorXd y = scheme.uniform_state();
  const double w = 1e-3;
  const Eigen::Vector2d c(4.5, 4.5);  // block centre
  for (int i = 0; i < disc->size(); ++i)
    scheme.set_velocity(y, i, w * Eigen::Vector2d(-(disc->particles.x(i, 1) - c[1]), disc->particles.x(i, 0) - c[0]));
  Eigen::VectorXd f;
  scheme.rate(y, f);
  const int centre = 4 * 9 + 4, s = scheme.stress_offset(centre);
  EXPECT_GT(f[s + 2], 0.9 * w * (dev[0] - dev[1]));  // the lattice moment of the cubic spline is ~1.02
  EXPECT_LT(f[s + 2], 1.1 * w * (dev[0] - dev[1]));
  EXPECT_LT(std::abs(f[s]), 1e-12 * std::abs(f[s + 2]) + 1e-18);
  EXPECT_LT(std::abs(f[s + 1]), 1e-12 * std::abs(f[s + 2]) + 1e-18);
  EXPECT_LT(std::abs(f[scheme.density_offset(centre)]), 1e-15);  // tr L = 0
}

TEST(RateForm, ViscosityOnlyDissipates) {
  const auto disc = test::lattice_discretisation<2>({.n = 8, .h = 1.3, .periodic = true});
  for (ViscositySwitch sw : {ViscositySwitch::Compression, ViscositySwitch::Always}) {
    const RateFormScheme<2> with(disc, kGms, {.viscosity = sw, .viscosity_alpha = 1.0, .viscosity_beta = 2.0});
    const RateFormScheme<2> without(disc, kGms);
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      Eigen::VectorXd y = with.uniform_state();
      const Eigen::VectorXd r = random_vector(with.size(), 1.0, static_cast<unsigned>(seed));
      for (int i = 0; i < disc->size(); ++i) y.segment<2>(with.velocity_offset(i)) = 0.1 * r.segment<2>(8 * i);
      Eigen::VectorXd fw, fo;
      with.rate(y, fw);
      without.rate(y, fo);
      double power = 0;  // sum_i m_i v_i . a_visc,i
      for (int i = 0; i < disc->size(); ++i)
        power +=
            with.mass()[i] * y.segment<2>(with.velocity_offset(i)).dot((fw - fo).segment<2>(with.velocity_offset(i)));
      EXPECT_LT(power, 0.0) << "seed " << seed;
    }
  }
}

/// The rate-form J on a periodic lattice against the lattice dispersion relation (GMS 5.8/5.9 with the perturbed
/// artificial stress), an independent route through lattice sums: every Bloch omega^2 of every admissible k appears
/// among -lambda^2 of the full-state spectrum.
void expect_spectrum_matches_dispersion(LatticeType type, double h, double xi, double xsph, double eps) {
  const int n = 8;
  const Kernel<2> kernel(KernelType::CubicSpline);
  const auto set = make_lattice<2>(type, n, {.spacing = 1.0, .periodic = true});
  const auto disc = make_discretisation(set, kernel, h);
  const RateFormScheme<2> scheme(disc, kGms, {.xsph = xsph, .artificial_stress = eps}, 1.0 / xi);
  const Eigen::VectorXd y = scheme.uniform_state();
  const SystemSpectrum spec = system_spectrum(scheme, y, {.dense_max = 4000});
  ASSERT_EQ(spec.status, Status::Successful);
  UniformState state{.density = 1.0 / xi, .sound_speed = 1.0, .shear_modulus = 0.3, .pressure = 1.0 / xi - 1.0};
  if (eps > 0) state = with_artificial_stress(state, eps);
  double scale = 0, worst = 0, predicted_growth = 0;
  for (int m2 = 0; m2 < n; ++m2)
    for (int m1 = 0; m1 < n; ++m1) {
      const double dy = type == LatticeType::Hexagonal ? std::sqrt(3.0) / 2 : 1.0;
      const Eigen::Vector2d k(2 * M_PI * m1 / n, 2 * M_PI * m2 / (n * dy));
      const LatticeSums sums = lattice_sums(type, kernel, h, k, {.perturbed_artificial_stress = eps > 0});
      const Eigen::Matrix2d M = dispersion_matrix(sums, state, eps > 0);
      Eigen::EigenSolver<Eigen::Matrix2d> es(M);
      // (1 - beta) of lattice_dispersion is XSPH with eps = 1/2: (1 - 2 eps beta) in general.
      const double xfactor = 1 - 2 * xsph * sums.beta;
      for (int b = 0; b < 2; ++b) {
        const Complex w2 = xfactor * es.eigenvalues()[b] / state.density;
        scale = std::max(scale, std::abs(w2));
        predicted_growth = std::max(predicted_growth, std::sqrt(-w2).real());
        double best = 1e300;
        for (int q = 0; q < spec.eigenvalues.size(); ++q)
          best = std::min(best, std::abs(-spec.eigenvalues[q] * spec.eigenvalues[q] - w2));
        worst = std::max(worst, best);
      }
    }
  EXPECT_LT(worst, 1e-9 * scale) << lattice_name(type) << " h " << h << " xi " << xi;
  EXPECT_NEAR(spec.growth_rate, predicted_growth, 1e-7 * std::sqrt(scale) + 1e-9)
      << lattice_name(type) << " h " << h << " xi " << xi;
}

TEST(RateForm, FullStateSpectrumIsTheLatticeDispersionRelation) {
  expect_spectrum_matches_dispersion(LatticeType::Square, 1.3, 1.02, 0.0, 0.0);
  expect_spectrum_matches_dispersion(LatticeType::Square, 1.3, 0.98, 0.5, 0.0);
  expect_spectrum_matches_dispersion(LatticeType::Square, 1.0, 1.02, 0.5, 0.3);
  expect_spectrum_matches_dispersion(LatticeType::FaceCentred, 1.5, 1.02, 0.0, 0.3);
  expect_spectrum_matches_dispersion(LatticeType::FaceCentred, 1.2, 0.97, 0.25, 0.0);
}

}  // namespace
}  // namespace sphstab
