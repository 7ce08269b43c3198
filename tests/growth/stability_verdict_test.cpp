#include "sphstab/growth/stability_verdict.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include "../forms/forms_fixture.hpp"
#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/problems/swegle.hpp"
#include "sphstab/spectral/rate_form_symbol.hpp"

namespace sphstab {
namespace stability_verdict_test {

using test::kGms;

RateFormRunOptions pc(double dt) { return {.dt = dt}; }
RateFormRunOptions pc1(double dt) { return {.dt = dt, .reuse_corrector_rate = true}; }
RateFormRunOptions leapfrog(double dt) { return {.dt = dt, .integrator = RateFormIntegrator::Leapfrog}; }

/// The Swegle block of n x n free particles (problems/swegle.hpp, steel) and the mirror symmetry about its centre.
struct SwegleBlock {
  SwegleScene scene;
  ElasticMaterial steel = ElasticMaterial::from_bulk_shear(1.0, 0.0, 1.0);
  MirrorSymmetry mirror;
};

SwegleBlock swegle_block(int n) {
  SwegleOptions so;
  so.n = n;
  SwegleScene scene = make_swegle_scene(so);
  const ElasticMaterial steel = ElasticMaterial::from_young_poisson(so.youngs_modulus, so.poisson_ratio, so.density);
  const MirrorSymmetry mirror = mirror_symmetry(
      scene.free_positions(), scene.discretisation->particles.x.row(scene.centre).transpose(), 1e-9 * so.spacing);
  return {std::move(scene), steel, mirror};
}

TEST(StabilityVerdict, DecisionRules) {
  const double f = 0.05;
  EXPECT_EQ(classify_verdict(0.0, 0.0, f), VerdictClass::Stable);
  EXPECT_EQ(classify_verdict(0.05, 0.05, f), VerdictClass::Stable);  // equal to the floor: not detected
  EXPECT_EQ(classify_verdict(0.0, 0.0501, f), VerdictClass::Integrator);
  EXPECT_EQ(classify_verdict(0.04, 0.0501, f), VerdictClass::Integrator);  // J below the floor
  EXPECT_EQ(classify_verdict(1.0, 0.999, f), VerdictClass::SemiDiscrete);  // map reproduces J
  EXPECT_EQ(classify_verdict(1.0, 1.04, f), VerdictClass::SemiDiscrete);   // excess 0.04: not above the floor
  EXPECT_EQ(classify_verdict(1.0, 1.0501, f), VerdictClass::Both);
  EXPECT_EQ(classify_verdict(-1.0, 0.06, f), VerdictClass::Integrator);   // decaying J, growing map
  EXPECT_EQ(classify_verdict(1.0, 0.01, f), VerdictClass::SemiDiscrete);  // damped by the integrator: still U
  EXPECT_EQ(verdict_letter(VerdictClass::Both), "B");
  EXPECT_EQ(verdict_name(VerdictClass::Integrator), "integrator");
  EXPECT_DOUBLE_EQ(detection_floor(100.0, 1e4), std::log(1e4) / 200.0);
  EXPECT_THROW(detection_floor(0.0, 10.0), std::invalid_argument);
  EXPECT_THROW(detection_floor(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(classify_verdict(NAN, 0.0, f), std::invalid_argument);
  EXPECT_THROW(classify_verdict(0.0, 0.0, 0.0), std::invalid_argument);
}

/// ln|R(i theta)| / dt of Heun's R(z) = 1 + z + z^2/2: ln(1 + theta^4/4) / (2 dt).
double heun_growth(double omega, double dt) {
  const double t = omega * dt;
  return std::log1p(t * t * t * t / 4) / (2 * dt);
}

// (a) A neutral J (1D periodic rate-form lattice at xi = 1: an undamped spectrum +-i omega) under the GMS
// predictor-corrector at two dt. The map is Heun's polynomial there (linear_step_map_test), so its growth is
// ln(1 + (omega_max dt)^4 / 4) / (2 dt) exactly, ~ omega^4 dt^3 / 8; the exponent from the two dt is
// 3 + ln((1 - t2^4/8) / (1 - t1^4/8)) / ln 2 = 3 - 0.0003 at omega dt = 0.1, 0.2, so |p - 3| < 0.002 can only fail
// if the law is wrong. Class I: J is neutral within the floor, the map grows above it.
TEST(StabilityVerdict, NeutralSpectrumUnderThePredictorCorrectorIsIntegratorOnly) {
  const auto disc = test::lattice_discretisation<1>({.n = 12, .h = 1.3, .periodic = true});
  const RateFormScheme<1> scheme(disc, kGms);
  const Eigen::VectorXd y = scheme.uniform_state();
  const RateFormSpectrum s = rate_form_spectrum(scheme, y);
  ASSERT_EQ(s.status, Status::Successful);
  const double omega = s.eigenvalues.cwiseAbs().maxCoeff();
  // Neutral: the periodic lattice's translations give B a zero eigenvalue, whose rounding (~1e-17) becomes
  // lambda = sqrt(mu) ~ 1e-8 omega (measured 7e-9 omega); the verdict's resolution 1e-7 max(omega, 1/dt) covers it.
  ASSERT_LT(s.growth_rate, 1e-7 * omega);
  double g[2];
  const double dts[2] = {0.1 / omega, 0.2 / omega};
  for (int k = 0; k < 2; ++k) {
    const double floor = heun_growth(omega, dts[k]) / 10;
    const StabilityVerdict v = stability_verdict(scheme, y, pc(dts[k]), {.floor = floor});
    ASSERT_EQ(v.status, Status::Successful) << v.reason;
    EXPECT_EQ(v.verdict, VerdictClass::Integrator) << v.letter();
    EXPECT_EQ(v.map_route, "reduced");  // at rest, two rates per step
    EXPECT_LE(v.map_size, 2 * disc->dofs());
    EXPECT_NEAR(v.map_growth, heun_growth(omega, dts[k]), 1e-6 * heun_growth(omega, dts[k]));
    EXPECT_NEAR(v.lambda_max, omega, 1e-12 * omega);
    EXPECT_LE(v.semi_discrete_growth, v.resolution);
    EXPECT_GT(v.map_mode.particle, -1);  // the growing mode is located
    EXPECT_GT(v.map_mode.kx_over_pi, 0.0);
    g[k] = v.map_growth;
    std::printf("pc dt omega %.2f: map growth %.6e, omega^4 dt^3 / 8 = %.6e\n", omega * dts[k], g[k],
                std::pow(omega, 4) * std::pow(dts[k], 3) / 8);
  }
  const double p = std::log(g[1] / g[0]) / std::log(2.0);
  std::printf("pc exponent %.6f\n", p);
  EXPECT_NEAR(p, 3.0, 2e-3);
  // The same from central differences of the stepper itself (a second route to rho(M)).
  const StabilityVerdict w = stability_verdict(scheme, y, pc(dts[1]), {.floor = g[1] / 10, .stepper_map = true});
  EXPECT_EQ(w.map_route, "stepper");
  EXPECT_NEAR(w.map_growth, g[1], 1e-4 * g[1]);
}

// The reduced route (the map on (v, p) of rate_form_spectrum.hpp, no dense J or M) against the closed-form dense map
// of the whole J (linear_step_map.hpp, through the J overload): a 5 x 5 Swegle block (one fixed layer) in tension and
// in compression, with every term that enters J at rest (XSPH, the viscosity's linear part, artificial stress,
// summation continuity), both position updates. Then the four mirror classes of the block: the largest class rate is
// the whole block's rate, for both J and M (the classes partition the motion).
TEST(StabilityVerdict, ReducedRouteEqualsTheDenseMapOfTheWholeJacobian) {
  const SwegleBlock b = swegle_block(5);
  const SwegleOptions& so = b.scene.options;
  const ElasticMaterial& steel = b.steel;
  const SwegleScene& scene = b.scene;
  const auto& d = scene.discretisation;
  const MirrorSymmetry& mirror = b.mirror;
  const double dt = 0.3 * scene.h / steel.p_wave_speed();
  int compared = 0;
  for (double xi : {1.03, 0.97})
    for (const RateFormOptions& o :
         {RateFormOptions{}, RateFormOptions{.xsph = 0.5, .viscosity = ViscositySwitch::Always, .artificial_stress = 0.3},
          RateFormOptions{.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph}})
      for (int integrator = 0; integrator < 3; ++integrator) {  // PC with Gms and trapezoid positions, leap-frog
        const PositionUpdate positions = integrator == 1 ? PositionUpdate::Trapezoid : PositionUpdate::Gms;
        const RateFormScheme<2> scheme(d, steel, o, so.density / xi);
        const Eigen::VectorXd y = scheme.uniform_state();
        const RateFormRunOptions run{
            .dt = dt,
            .positions = positions,
            .integrator = integrator == 2 ? RateFormIntegrator::Leapfrog : RateFormIntegrator::PredictorCorrector};
        if (integrator == 2 && o.viscosity == ViscositySwitch::Always) {  // Jvv != 0: the dense map, no class
          EXPECT_EQ(stability_verdict(scheme, y, run, {.floor = 1e-5 / dt}).map_route, "closed-form");
          EXPECT_THROW(stability_verdict(scheme, y, run, {.floor = 1, .basis = symmetry_basis(mirror, -1, 1)}),
                       std::invalid_argument);
          continue;
        }
        const double floor = 1e-5 / dt;
        const StabilityVerdict red = stability_verdict(scheme, y, run, {.floor = floor});
        ASSERT_EQ(red.status, Status::Successful) << red.reason;
        EXPECT_EQ(red.map_route, "reduced");
        ComplexStepJacobian jac(scheme);
        const Eigen::MatrixXd J(jac.compute(y));
        const StabilityVerdict dense = stability_verdict(J, state_layout(scheme), run, floor);
        ASSERT_EQ(dense.status, Status::Successful) << dense.reason;
        const std::string what = "xi " + std::to_string(xi) + " xsph " + std::to_string(o.xsph) + " " +
                                 rate_form_integrator_name(run) +
                                 (positions == PositionUpdate::Gms ? " gms" : " trapezoid");
        EXPECT_LT(red.map_size, scheme.size()) << what;
        // Rates from different eigenproblems: rounding ~1e-13 in rho, i.e. ~1e-13 / dt in the growth.
        EXPECT_NEAR(red.map_growth, dense.map_growth, 1e-10 / dt + 1e-8 * std::abs(dense.map_growth)) << what;
        // The reduction's gamma_J is max Re over the non-zero spectrum (rate_form_spectrum.hpp), the dense one's also
        // sees the slaved density and stress's zero eigenvalues: equal where either grows, both <= 0 otherwise
        // (the viscosity damps every non-zero mode: -0.31 against +3e-14).
        EXPECT_NEAR(std::max(red.semi_discrete_growth, 0.0), std::max(dense.semi_discrete_growth, 0.0),
                    1e-7 * dense.lambda_max)
            << what;
        EXPECT_EQ(red.verdict, dense.verdict) << what << ": " << red.letter() << " vs " << dense.letter();
        double class_map = -1e300, class_semi = -1e300;
        for (int px : {-1, 1})
          for (int py : {-1, 1}) {
            const StabilityVerdict c =
                stability_verdict(scheme, y, run, {.floor = floor, .basis = symmetry_basis(mirror, px, py)});
            ASSERT_EQ(c.status, Status::Successful) << c.reason;
            class_map = std::max(class_map, c.map_growth);
            class_semi = std::max(class_semi, c.semi_discrete_growth);
          }
        EXPECT_NEAR(class_map, red.map_growth, 1e-10 / dt + 1e-8 * std::abs(red.map_growth)) << what;
        EXPECT_NEAR(std::max(class_semi, 0.0), std::max(red.semi_discrete_growth, 0.0), 1e-7 * red.lambda_max) << what;
        std::printf("%s: map growth reduced %.9e dense %.9e classes %.9e; J %.4e; %s\n", what.c_str(), red.map_growth,
                    dense.map_growth, class_map, red.semi_discrete_growth, red.letter().c_str());
        ++compared;
      }
  EXPECT_EQ(compared, 16);
  // A basis off the reduced route is refused (PC1 carries the rate: its map is not reduced).
  const RateFormScheme<2> scheme(d, steel, {}, so.density);
  EXPECT_THROW(stability_verdict(scheme, scheme.uniform_state(), pc1(dt),
                                 {.floor = 1, .basis = symmetry_basis(mirror, -1, 1)}),
               std::invalid_argument);
}

// Powell's XSPH (2.71) on the leap-frog's v^{n+1/2} acts outside F; at rest its map is reduced exactly
// (rate_form_spectrum.hpp: the companion of w_{n+1} = (I + P + dt^2 B P) w_n - P w_{n-1}). Against the stepper's own
// map by central differences (rate_form_step_matrix), whole and per mirror class, in tension.
TEST(StabilityVerdict, PowellXsphLeapfrogMapIsReducedExactly) {
  const SwegleBlock b = swegle_block(7);
  const SwegleOptions& so = b.scene.options;
  const ElasticMaterial& steel = b.steel;
  const SwegleScene& scene = b.scene;
  const auto& d = scene.discretisation;
  const MirrorSymmetry& mirror = b.mirror;
  const double dt = 0.8 * scene.h / steel.p_wave_speed();
  int compared = 0;
  // Tension with eps 0.1 and 0.3 (the stepper's dense map is the test's cost: ~8 s each under ASan).
  for (double xi : {1.05})
    for (double eps : {0.1, 0.3}) {
      const RateFormScheme<2> scheme(d, steel, {}, so.density / xi);
      const Eigen::VectorXd y = scheme.uniform_state();
      const RateFormRunOptions run{.dt = dt, .integrator = RateFormIntegrator::Leapfrog, .leapfrog_xsph = eps};
      const double floor = 1e-5 / dt;
      const StabilityVerdict red = stability_verdict(scheme, y, run, {.floor = floor});
      ASSERT_EQ(red.status, Status::Successful) << red.reason;
      EXPECT_EQ(red.map_route, "reduced");
      const StabilityVerdict step = stability_verdict(scheme, y, run, {.floor = floor, .stepper_map = true});
      ASSERT_EQ(step.status, Status::Successful) << step.reason;
      EXPECT_EQ(step.map_route, "stepper");
      const std::string what = "xi " + std::to_string(xi) + " eps " + std::to_string(eps);
      // Central differences (delta 1e-7) of a linear step: rounding ~1e-9 in rho.
      EXPECT_NEAR(red.map_growth, step.map_growth, 1e-8 / dt + 1e-6 * std::abs(step.map_growth)) << what;
      EXPECT_EQ(red.verdict, step.verdict) << what;
      double class_map = -1e300;
      for (int px : {-1, 1})
        for (int py : {-1, 1})
          class_map = std::max(
              class_map,
              stability_verdict(scheme, y, run, {.floor = floor, .basis = symmetry_basis(mirror, px, py)}).map_growth);
      EXPECT_NEAR(class_map, red.map_growth, 1e-10 / dt + 1e-8 * std::abs(red.map_growth)) << what;
      // The smoothing only damps: never faster than the plain leap-frog's map.
      RateFormRunOptions plain = run;
      plain.leapfrog_xsph = 0;
      const StabilityVerdict p = stability_verdict(scheme, y, plain, {.floor = floor});
      EXPECT_LE(red.map_growth, p.map_growth + 1e-10 / dt) << what;
      std::printf("%s: map growth reduced %.9e stepper %.9e classes %.9e, without XSPH %.9e; J %.4e; %s\n",
                  what.c_str(), red.map_growth, step.map_growth, class_map, p.map_growth, red.semi_discrete_growth,
                  red.letter().c_str());
      ++compared;
    }
  EXPECT_EQ(compared, 2);
}

// PC1 carries the rate: the map on (y, F^0) is twice as large and, on an undamped first-order oscillation, its root
// mu = 1 + z + z^2/2 - z^3/4 - z^4/8 + ... (mu^2 - (1 + 3z/2) mu + z/2 = 0) gives |mu|^2 = 1 + theta^4/2 + O(theta^6):
// omega^4 dt^3 / 4, twice the PC's, although it is velocity Verlet for x'' = a(x).
TEST(StabilityVerdict, OneRatePerStepGrowsTwiceAsFastOnANeutralSpectrum) {
  const auto disc = test::lattice_discretisation<1>({.n = 12, .h = 1.3, .periodic = true});
  const RateFormScheme<1> scheme(disc, kGms);
  const Eigen::VectorXd y = scheme.uniform_state();
  const StabilityVerdict probe = stability_verdict(scheme, y, pc(0.01), {.floor = 1});
  const double omega = probe.lambda_max;
  double g[2];
  const double dts[2] = {0.05 / omega, 0.1 / omega};
  for (int k = 0; k < 2; ++k) {
    const double law = std::pow(omega, 4) * std::pow(dts[k], 3) / 4;
    const StabilityVerdict v = stability_verdict(scheme, y, pc1(dts[k]), {.floor = law / 10});
    ASSERT_EQ(v.status, Status::Successful) << v.reason;
    EXPECT_EQ(v.verdict, VerdictClass::Integrator);
    EXPECT_EQ(v.map_size, 2 * scheme.size());
    EXPECT_NEAR(v.map_growth, law, 0.03 * law);  // O(theta^2) relative: 2 % at theta = 0.1
    g[k] = v.map_growth;
    std::printf("pc1 dt omega %.2f: map growth %.6e, omega^4 dt^3 / 4 = %.6e\n", omega * dts[k], g[k], law);
  }
  const double p = std::log(g[1] / g[0]) / std::log(2.0);
  std::printf("pc1 exponent %.6f\n", p);
  EXPECT_NEAR(p, 3.0, 0.05);
}

// The staggered leap-frog below its limit (dt max|Im lambda| < 2) is neutral on the same spectrum: S, with the map's
// growth within the rounding resolution (the check that the resolution is not optimistic).
TEST(StabilityVerdict, LeapfrogBelowItsLimitIsStable) {
  const auto disc = test::lattice_discretisation<1>({.n = 12, .h = 1.3, .periodic = true});
  const RateFormScheme<1> scheme(disc, kGms);
  const Eigen::VectorXd y = scheme.uniform_state();
  const double omega = stability_verdict(scheme, y, pc(0.01), {.floor = 1}).lambda_max;
  const double dt = 1.5 / omega;
  const StabilityVerdict v = stability_verdict(scheme, y, leapfrog(dt), {.floor = 1e-3});
  ASSERT_EQ(v.status, Status::Successful) << v.reason;
  EXPECT_EQ(v.verdict, VerdictClass::Stable) << v.letter();
  EXPECT_LE(std::abs(v.map_growth), v.resolution);
  std::printf("leapfrog neutral: map growth %.3e, resolution %.3e\n", v.map_growth, v.resolution);
  // Beyond the limit the map itself grows: I.
  const StabilityVerdict w = stability_verdict(scheme, y, leapfrog(2.2 / omega), {.floor = 1e-3});
  EXPECT_EQ(w.verdict, VerdictClass::Integrator) << w.letter();
}

// (b) An unstable J under the leap-frog: a 1D periodic rate-form lattice in tension. The semi-discrete rate equals
// the one of the Bloch symbol (spectral/rate_form_symbol.hpp: a separate route through the symbol's 4 x 4 blocks)
// at the box's wavevectors; the map reproduces it to O(dt^2) below it ((2/dt) asinh(gamma dt / 2) for a real
// lambda), so the class is U.
TEST(StabilityVerdict, TensionUnderTheLeapfrogIsSemiDiscrete) {
  const int n = 16;
  const auto disc = test::lattice_discretisation<1>({.n = n, .h = 1.3, .periodic = true});
  const double xi = 1.2;
  const RateFormScheme<1> scheme(disc, kGms, {}, 1.0 / xi);
  const Eigen::VectorXd y = scheme.uniform_state();
  const RateFormSymbol<1> symbol = rate_form_symbol(scheme, y);
  double analytic = 0;
  for (int m = 0; m <= n / 2; ++m) {
    Eigen::Matrix<double, 1, 1> k;
    k << 2 * M_PI * m / n;  // box length n dx, dx = 1
    const Eigen::VectorXcd l = Eigen::MatrixXcd(symbol.at(k)).eigenvalues();
    for (auto z : l) analytic = std::max(analytic, z.real());
  }
  ASSERT_GT(analytic, 1e-3) << "choose a tension that is unstable";
  const double omega = stability_verdict(scheme, y, pc(0.01), {.floor = analytic / 10}).lambda_max;
  const double dt = 0.5 / omega;
  const StabilityVerdict v = stability_verdict(scheme, y, leapfrog(dt), {.floor = analytic / 10});
  ASSERT_EQ(v.status, Status::Successful) << v.reason;
  EXPECT_EQ(v.verdict, VerdictClass::SemiDiscrete) << v.letter();
  EXPECT_NEAR(v.semi_discrete_growth, analytic, 1e-8 * omega);
  EXPECT_LT(std::abs(v.integrator_excess), v.floor);
  EXPECT_GT(v.semi_discrete_mode.kx_over_pi, 0.0);
  EXPECT_GE(v.semi_discrete_mode.particle, 0);
  EXPECT_DOUBLE_EQ(v.semi_discrete_mode.x_share, 1.0);  // 1D
  std::printf("tension xi %.2f: semi-discrete %.6e, symbol %.6e, map %.6e, mode k dx/pi %.3f\n", xi,
              v.semi_discrete_growth, analytic, v.map_growth, v.semi_discrete_mode.kx_over_pi);
}

// 2D: basic SPH on a periodic 8 x 8 square lattice at xi = 1.02 grows at 0.1868 (the GMS lattice dispersion value of
// tests/cli/spectrum_command_test.cpp and rate_form_test); under the leap-frog below its limit: U, the mode located
// on the lattice.
TEST(StabilityVerdict, TensionOnASquareLatticeUnderTheLeapfrog) {
  const auto disc = test::lattice_discretisation<2>({.n = 8, .h = 1.3, .periodic = true});
  const RateFormScheme<2> scheme(disc, kGms, {}, 1.0 / 1.02);
  const Eigen::VectorXd y = scheme.uniform_state();
  const BravaisLattice2D lattice = bravais_lattice_2d(LatticeType::Square, 1.0);
  const double omega = stability_verdict(scheme, y, pc(0.01), {.floor = 0.01}).lambda_max;
  const StabilityVerdict v = stability_verdict(scheme, y, leapfrog(0.5 / omega), {.floor = 0.01, .lattice = lattice});
  ASSERT_EQ(v.status, Status::Successful) << v.reason;
  EXPECT_EQ(v.verdict, VerdictClass::SemiDiscrete) << v.letter();
  EXPECT_NEAR(v.semi_discrete_growth, 0.1868, 2e-4);
  EXPECT_EQ(v.map_route, "reduced");  // at rest, no viscosity: from the eigenvalues of B
  EXPECT_EQ(v.map_size, disc->dofs());
  // The stepper's own map by central differences (size + 2 dofs): the same growth.
  const StabilityVerdict w =
      stability_verdict(scheme, y, leapfrog(0.5 / omega), {.floor = 0.01, .stepper_map = true});
  EXPECT_EQ(w.map_size, scheme.size() + 2 * disc->dofs());
  EXPECT_NEAR(w.map_growth, v.map_growth, 1e-6 * v.map_growth);
  for (const VerdictMode* m : {&v.semi_discrete_mode, &v.map_mode}) {
    EXPECT_EQ(m->shape.size(), disc->dofs());
    EXPECT_GE(m->kx_over_pi, 0.0);
    EXPECT_LE(m->kx_over_pi, 1.0 + 1e-9);
    EXPECT_GE(m->ky_over_pi, 0.0);
    EXPECT_LE(m->ky_over_pi, 1.0 + 1e-9);
    EXPECT_GE(m->x_share, 0.0);
    EXPECT_LE(m->x_share, 1.0);
    EXPECT_GE(m->particle, 0);
  }
  std::printf("2D tension: semi-discrete %.6e at k dx/pi (%.3f, %.3f) x share %.3f; map %.6e at (%.3f, %.3f)\n",
              v.semi_discrete_growth, v.semi_discrete_mode.kx_over_pi, v.semi_discrete_mode.ky_over_pi,
              v.semi_discrete_mode.x_share, v.map_growth, v.map_mode.kx_over_pi, v.map_mode.ky_over_pi);
}

// x' = v, v' = k x: gamma_J = sqrt(k); the staggered leap-frog's map has mu + 1/mu = 2 + k dt^2, so gamma_M =
// (2/dt) asinh(sqrt(k) dt / 2) exactly.
TEST(StabilityVerdict, ExactRatesOfAnExponentialModeUnderTheLeapfrog) {
  const double k = 4, dt = 0.1;
  Eigen::MatrixXd J(2, 2);
  J << 0, 1, k, 0;
  const StateLayout layout{.size = 2, .position = {0}, .velocity = {1}};
  const StabilityVerdict v = stability_verdict(J, layout, leapfrog(dt), 0.1);
  ASSERT_EQ(v.status, Status::Successful) << v.reason;
  EXPECT_NEAR(v.semi_discrete_growth, 2.0, 1e-14);
  EXPECT_NEAR(v.map_growth, 2 / dt * std::asinh(std::sqrt(k) * dt / 2), 1e-12);
  EXPECT_EQ(v.verdict, VerdictClass::SemiDiscrete);
  EXPECT_EQ(v.map_size, 4);
}

// (c) Just above and just below the floor: the class flips S <-> U (semi-discrete rate) and S <-> I (map rate).
TEST(StabilityVerdict, FloorFlipsTheClass) {
  Eigen::MatrixXd J(2, 2);
  J << 0, 1, 1, 0;  // x' = v, v' = x: gamma_J = 1, gamma_M = (2/dt) asinh(dt/2) = 0.99958 at dt = 0.1
  const StateLayout layout{.size = 2, .position = {0}, .velocity = {1}};
  const double dt = 0.1;
  const StabilityVerdict below = stability_verdict(J, layout, leapfrog(dt), 1.001);
  const StabilityVerdict above = stability_verdict(J, layout, leapfrog(dt), 0.999);
  EXPECT_EQ(below.verdict, VerdictClass::Stable) << below.letter();
  EXPECT_EQ(above.verdict, VerdictClass::SemiDiscrete) << above.letter();
  // A neutral first-order oscillation as in the rate form at rest without pre-stress: x' = v, v' = q, q' = -v
  // (omega = 1, the restoring force through q, not x, so Jvx = 0 and the PC map is Heun's: gamma_M =
  // ln(1 + dt^4/4) / (2 dt)). (For v' = -x the GMS positions make the PC velocity Verlet: neutral.)
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3, 3);
  K(0, 1) = 1, K(1, 2) = 1, K(2, 1) = -1;
  const StateLayout with_q{.size = 3, .position = {0}, .velocity = {1}};
  const double g = heun_growth(1.0, dt);
  const StabilityVerdict s = stability_verdict(K, with_q, pc(dt), g * 1.001);
  const StabilityVerdict i = stability_verdict(K, with_q, pc(dt), g * 0.999);
  EXPECT_EQ(s.verdict, VerdictClass::Stable) << s.letter();
  EXPECT_EQ(i.verdict, VerdictClass::Integrator) << i.letter();
  EXPECT_NEAR(i.map_growth, g, 1e-6 * g);
}

// B: a slow exponential mode next to a fast first-order oscillation under the PC. State (x0, x1, v0, v1, q1):
// x0' = v0, v0' = 1e-4 x0 (gamma = 0.01); x1' = v1, v1' = 10 q1, q1' = -10 v1 (omega = 10, x1 passive). At dt = 0.05
// the oscillation's ln(1 + (omega dt)^4 / 4) / (2 dt) = 0.155 exceeds the semi-discrete 0.01 by more than the floor
// 0.005: both; at dt = 0.005 the integrator's part is 1.6e-4: U.
TEST(StabilityVerdict, SlowInstabilityAndAFastOscillationUnderThePredictorCorrectorIsBoth) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(5, 5);
  J(0, 2) = 1, J(2, 0) = 1e-4;
  J(1, 3) = 1, J(3, 4) = 10, J(4, 3) = -10;
  const StateLayout layout{.size = 5, .position = {0, 1}, .velocity = {2, 3}};
  const StabilityVerdict b = stability_verdict(J, layout, pc(0.05), 0.005);
  ASSERT_EQ(b.status, Status::Successful) << b.reason;
  EXPECT_EQ(b.verdict, VerdictClass::Both) << b.letter();
  EXPECT_NEAR(b.semi_discrete_growth, 0.01, 1e-12);
  EXPECT_NEAR(b.map_growth, heun_growth(10, 0.05), 1e-6 * heun_growth(10, 0.05));
  EXPECT_EQ(b.map_mode.particle, 1);  // the oscillation's velocity DOF
  EXPECT_EQ(b.semi_discrete_mode.particle, 0);
  const StabilityVerdict u = stability_verdict(J, layout, pc(0.005), 0.005);
  EXPECT_EQ(u.verdict, VerdictClass::SemiDiscrete) << u.letter();
}

TEST(StabilityVerdict, FailureIsAStatusAndBadInputThrows) {
  const auto disc = test::lattice_discretisation<1>({.n = 6, .h = 1.3});
  const RateFormScheme<1> scheme(disc, kGms);
  Eigen::VectorXd y = scheme.uniform_state();
  // A floor below the rounding resolution cannot be resolved.
  const StabilityVerdict tiny = stability_verdict(scheme, y, pc(0.1), {.floor = 1e-12});
  EXPECT_EQ(tiny.status, Status::NumericalIssue);
  EXPECT_NE(tiny.reason.find("resolution"), std::string::npos) << tiny.reason;
  // A non-finite state: J is not finite.
  y[scheme.density_offset(disc->free[0])] = NAN;
  const StabilityVerdict nan = stability_verdict(scheme, y, pc(0.1), {.floor = 1});
  EXPECT_EQ(nan.status, Status::NumericalIssue);
  EXPECT_FALSE(nan.reason.empty());
  const Eigen::VectorXd y0 = scheme.uniform_state();
  const auto throws_with = [](auto f) {
    try {
      f();
      ADD_FAILURE() << "no throw";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("stability_verdict: ", 0), 0u) << e.what();
    }
  };
  throws_with([&] { stability_verdict(scheme, y0, pc(0.1), {}); });  // no floor
  throws_with([&] { stability_verdict(scheme, y0, pc(0.0), {.floor = 1}); });
  throws_with([&] { stability_verdict(scheme, Eigen::VectorXd(y0.head(3)), pc(0.1), {.floor = 1}); });
  throws_with([&] {
    RateFormRunOptions o = pc(0.1);
    o.yield_stress = 1;
    stability_verdict(scheme, y0, o, {.floor = 1});
  });
  throws_with([&] {
    stability_verdict(Eigen::MatrixXd::Zero(2, 2), {.size = 2, .position = {0}, .velocity = {1}}, pc(0.1), -1.0);
  });
}

}  // namespace
}  // namespace sphstab
