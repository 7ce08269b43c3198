#include "sphstab/integrate/linear_step_map.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../forms/forms_fixture.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace sphstab {
namespace linear_step_map_test {

using test::kGms;

/// Every integrator configuration the closed forms cover.
std::vector<RateFormRunOptions> integrators(double dt) {
  std::vector<RateFormRunOptions> out;
  for (PositionUpdate p : {PositionUpdate::Gms, PositionUpdate::Trapezoid})
    for (bool reuse : {false, true}) out.push_back({.dt = dt, .positions = p, .reuse_corrector_rate = reuse});
  out.push_back({.dt = dt, .integrator = RateFormIntegrator::Leapfrog});
  return out;
}

/// Two independent routes to the one-step map at a rest state: the closed form from the complex-step J
/// (linear_step_map.hpp) and central differences of the stepper's own code (rate_form_step_matrix). Central
/// differences with increments 1e-7 max(1, |z|) on states of size ~10 carry rounding ~1e-16 * 10 / 1e-7 = 1e-8 and
/// a truncation error O(1e-14) (the step is smooth): 1e-6 of the map's scale leaves a margin of 100.
template <int Dim>
void expect_routes_agree(const RateFormScheme<Dim>& scheme, const std::string& what) {
  const Eigen::VectorXd y = scheme.uniform_state();
  Eigen::VectorXd f;
  scheme.rate(y, f);
  ASSERT_LT(f.cwiseAbs().maxCoeff(), 1e-12) << what << ": not a rest state";
  const Eigen::MatrixXd J(jacobian(scheme, y));
  const StateLayout layout = state_layout(scheme);
  for (const RateFormRunOptions& o : integrators(0.3)) {
    const Eigen::MatrixXd closed = linear_step_map(J, layout, o);
    const Eigen::MatrixXd stepper = rate_form_step_matrix(scheme, y, o.dt, o);
    ASSERT_EQ(closed.rows(), stepper.rows()) << what << " " << rate_form_integrator_name(o);
    const double scale = std::max(1.0, stepper.cwiseAbs().maxCoeff());
    const double diff = (closed - stepper).cwiseAbs().maxCoeff();
    EXPECT_LT(diff, 1e-6 * scale) << what << " " << rate_form_integrator_name(o);
    std::printf("%s %s: size %ld, max |closed - stepper| %.2e of %.2e\n", what.c_str(),
                rate_form_integrator_name(o).c_str(), static_cast<long>(closed.rows()), diff, scale);
    // The map is not the identity: the comparison tests something.
    EXPECT_GT((stepper - Eigen::MatrixXd::Identity(stepper.rows(), stepper.cols())).cwiseAbs().maxCoeff(), 1e-2);
  }
}

TEST(LinearStepMap, ClosedFormEqualsTheSteppersCentralDifferences1D) {
  const auto disc = test::lattice_discretisation<1>({.n = 6, .h = 1.3});
  for (double xi : {0.95, 1.0, 1.05}) {
    expect_routes_agree(RateFormScheme<1>(disc, kGms, {}, 1.0 / xi), "1D plain xi " + std::to_string(xi));
    // XSPH (position rows of J are no longer the velocity selection) and a linear viscosity (Jvv != 0).
    expect_routes_agree(
        RateFormScheme<1>(disc, kGms, {.xsph = 0.5, .viscosity = ViscositySwitch::Always, .viscosity_alpha = 0.5},
                          1.0 / xi),
        "1D xsph+viscosity xi " + std::to_string(xi));
  }
}

TEST(LinearStepMap, ClosedFormEqualsTheSteppersCentralDifferences2D) {
  const auto disc = test::lattice_discretisation<2>({.n = 3, .h = 1.3});
  Eigen::VectorXd dev(3);
  dev << 0.004, -0.002, 0.001;
  expect_routes_agree(RateFormScheme<2>(disc, kGms, {.xsph = 0.5, .artificial_stress = 0.3}, 1.0 / 1.03, dev),
                      "2D xsph+artificial stress xi 1.03");
}

/// The selection matrices of the layout, built here independently of the library's.
struct Slots {
  Eigen::MatrixXd P, S;
  explicit Slots(const StateLayout& s)
      : P(Eigen::MatrixXd::Zero(s.size, s.size)), S(Eigen::MatrixXd::Zero(s.size, s.size)) {
    for (std::size_t k = 0; k < s.position.size(); ++k) {
      P(s.position[k], s.position[k]) = 1;
      S(s.position[k], s.velocity[k]) = 1;
    }
  }
};

// Without XSPH the position rows of J are the velocity selection, and the GMS map is Heun's polynomial R(dt J) =
// I + dt J + dt^2/2 J^2 plus the uncorrected positions' dt^3/4 Q J S J, which vanishes without pre-stress (Jvx = 0).
TEST(LinearStepMap, PredictorCorrectorIsHeunPlusTheUncorrectedPositionsTerm) {
  const auto disc = test::lattice_discretisation<1>({.n = 6, .h = 1.3});
  const double dt = 0.3;
  for (double xi : {1.0, 1.05}) {
    const RateFormScheme<1> scheme(disc, kGms, {}, 1.0 / xi);
    const Eigen::VectorXd y = scheme.uniform_state();
    const Eigen::MatrixXd J(jacobian(scheme, y));
    const StateLayout layout = state_layout(scheme);
    const Slots m(layout);
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(J.rows(), J.cols());
    const Eigen::MatrixXd heun = I + dt * J + 0.5 * dt * dt * J * J;
    const Eigen::MatrixXd extra = 0.25 * dt * dt * dt * (I - m.P) * J * m.S * J;
    const Eigen::MatrixXd M = predictor_corrector_map(J, layout, dt);
    EXPECT_LT((M - heun - extra).cwiseAbs().maxCoeff(), 1e-13 * M.cwiseAbs().maxCoeff()) << "xi " << xi;
    if (xi == 1.0)
      EXPECT_LT(extra.cwiseAbs().maxCoeff(), 1e-15 * M.cwiseAbs().maxCoeff());
    else  // pre-stress: the term is there (so the identity above is not trivially Heun's)
      EXPECT_GT(extra.cwiseAbs().maxCoeff(), 1e-5);
  }
}

// x'' = -x as x' = v, v' = -x. The staggered leap-frog's eigenvalues are exp(+-i phi), cos(phi) = 1 - dt^2/2. The PC
// with GMS's uncorrected positions is velocity Verlet here (x_p = x + dt v + dt^2/2 a is the final x, and the corrector
// averages a(x) and a(x_p)): the same neutral eigenvalues. Without a position slot (the same J as a generic
// first-order system) the PC is Heun: R(+-i dt) = 1 +- i dt - dt^2/2, |R| > 1.
// u'' = -A u with velocity Verlet (kick, drift, kick: run_leapfrog's, the TL-SPH runs of the impact studies) has the
// staggered leap-frog's spectrum: both produce u^{n+1} = u^n + dt v^{n+1/2}, v^{n+1/2} = v^{n-1/2} - dt A u^n, only the
// carried velocity differs by half a kick. So the staggered map on y = (u, v), J = [0 I; -A 0] gives the verdict of a
// velocity-Verlet run. A has a negative eigenvalue (semi-discrete growth, sqrt(0.3)) and one beyond the step limit
// (omega dt = sqrt(20) 0.5 > 2: integrator growth); every eigenvalue of the Verlet map is one of the staggered map's.
TEST(LinearStepMap, StaggeredLeapfrogHasVelocityVerletsSpectrum) {
  const int n = 5;
  const double dt = 0.5;
  Eigen::VectorXd mu(n);
  mu << -0.3, 0.5, 2, 9, 20;
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Random(n, n)).householderQ();
  const Eigen::MatrixXd A = Q * mu.asDiagonal() * Q.transpose();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  J.topRightCorner(n, n).setIdentity();
  J.bottomLeftCorner(n, n) = -A;
  StateLayout layout{.size = 2 * n};
  for (int k = 0; k < n; ++k) layout.position.push_back(k), layout.velocity.push_back(n + k);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd kick = Eigen::MatrixXd::Identity(2 * n, 2 * n), drift = kick;
  kick.bottomLeftCorner(n, n) = -0.5 * dt * A;
  drift.topRightCorner(n, n) = dt * I;
  const Eigen::VectorXcd verlet = (kick * drift * kick).eigenvalues();
  const Eigen::VectorXcd staggered = staggered_leapfrog_map(J, layout, dt).eigenvalues();
  for (auto z : verlet) {
    double best = 1e300;
    for (auto w : staggered) best = std::min(best, std::abs(z - w));
    EXPECT_LT(best, 1e-9 * std::abs(z)) << z;
  }
  const double rho = verlet.cwiseAbs().maxCoeff();
  EXPECT_NEAR(staggered.cwiseAbs().maxCoeff(), rho, 1e-10 * rho);
  // The growth is the step limit's, not the negative eigenvalue's: |z| + 1/|z| = |2 - omega^2 dt^2| for omega^2 = 20.
  const double b = 20 * dt * dt - 2;
  EXPECT_NEAR(rho, 0.5 * (b + std::sqrt(b * b - 4)), 1e-10 * rho);
}

TEST(LinearStepMap, ScalarOscillatorEigenvalues) {
  const double dt = 0.5, phi = std::acos(1 - dt * dt / 2);
  Eigen::MatrixXd J(2, 2);
  J << 0, 1, -1, 0;
  const StateLayout layout{.size = 2, .position = {0}, .velocity = {1}};
  const StateLayout none{.size = 2, .position = {}, .velocity = {}};
  const auto nearest = [](const Eigen::VectorXcd& values, std::complex<double> target) {
    double best = 1e300;
    for (auto mu : values) best = std::min(best, std::abs(mu - target));
    return best;
  };
  const Eigen::VectorXcd lf = staggered_leapfrog_map(J, layout, dt).eigenvalues();
  EXPECT_NEAR(lf.cwiseAbs().maxCoeff(), 1.0, 1e-12);
  EXPECT_LT(nearest(lf, std::polar(1.0, phi)), 1e-10);
  const Eigen::VectorXcd verlet = predictor_corrector_map(J, layout, dt).eigenvalues();
  EXPECT_NEAR(verlet.cwiseAbs().maxCoeff(), 1.0, 1e-12);
  EXPECT_LT(nearest(verlet, std::polar(1.0, phi)), 1e-10);
  const Eigen::VectorXcd heun = predictor_corrector_map(J, none, dt).eigenvalues();
  const std::complex<double> z(0, dt), R = 1.0 + z + 0.5 * z * z;
  EXPECT_LT(nearest(heun, R), 1e-14);
  EXPECT_GT(std::abs(R), 1.0 + 1e-3);
}

TEST(LinearStepMap, BadInputIsOneLineNamingTheFunction) {
  const StateLayout layout{.size = 2, .position = {0}, .velocity = {1}};
  const Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2, 2);
  const auto throws_with = [](auto f, const std::string& prefix) {
    try {
      f();
      ADD_FAILURE() << "no throw, expected " << prefix;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  throws_with([&] { predictor_corrector_map(Eigen::MatrixXd::Zero(3, 3), layout, 0.1); }, "predictor_corrector_map: ");
  throws_with([&] { predictor_corrector_reuse_map(J, layout, 0.0); }, "predictor_corrector_reuse_map: ");
  throws_with([&] { staggered_leapfrog_map(J, {.size = 2, .position = {0}, .velocity = {0}}, 0.1); },
              "staggered_leapfrog_map: ");
  throws_with(
      [&] {
        linear_step_map(J, layout, {.dt = 0.1, .integrator = RateFormIntegrator::Leapfrog, .leapfrog_xsph = 0.1});
      },
      "linear_step_map: ");
  Eigen::MatrixXd bad = J;
  bad(0, 1) = NAN;
  throws_with([&] { predictor_corrector_map(bad, layout, 0.1); }, "predictor_corrector_map: ");
}

}  // namespace
}  // namespace sphstab
