// The predictor-corrector with one rate evaluation per step (RateFormRunOptions::reuse_corrector_rate: a step's F^0
// is the previous step's corrector evaluation) against the two-evaluation predictor-corrector: its first step is the
// same, it converges to the same solution at second order, it evaluates the rate once per step, and it is refused
// where the reuse would be wrong.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>

#include "../forms/forms_fixture.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace sphstab {
namespace rate_form_reuse_rate_test {

using test::kGms;

/// A wave packet on a periodic 8 x 8 lattice in slight compression (xi = 0.99), as the predictor-corrector's order
/// test (tests/growth/rate_form_spectrum_test.cpp).
struct Packet {
  std::shared_ptr<const Discretisation<2>> disc = test::lattice_discretisation<2>({.n = 8, .h = 1.3, .periodic = true});
  RateFormScheme<2> scheme;
  Eigen::VectorXd y0;
  explicit Packet(const RateFormOptions& o) : scheme(disc, kGms, o, 1.0 / 0.99), y0(scheme.uniform_state()) {
    for (int i = 0; i < disc->size(); ++i)
      scheme.set_velocity(y0, i, 1e-3 * Eigen::Vector2d(std::sin(2 * M_PI * disc->particles.x(i, 0) / 8), 0.0));
  }
  RateFormRunResult run(double dt, bool reuse, double t_end = 2.0) const {
    return run_rate_form(scheme, y0, {.dt = dt, .t_end = t_end, .reuse_corrector_rate = reuse});
  }
};

TEST(RateFormReuseRate, FirstStepIsThePredictorCorrectorsAndOneEvaluationPerStep) {
  const Packet p({.viscosity = ViscositySwitch::Always, .artificial_stress = 0.3});
  const RateFormRunResult a = p.run(0.1, false, 0.1), b = p.run(0.1, true, 0.1);
  ASSERT_TRUE(a.completed() && b.completed());
  EXPECT_EQ(a.y, b.y);  // one step: F^0 is F(y0) in both
  const RateFormRunResult c = p.run(0.1, false), d = p.run(0.1, true);
  EXPECT_EQ(c.steps, 20);
  EXPECT_EQ(c.evaluations, 2 * c.steps);
  EXPECT_EQ(d.evaluations, d.steps + 1);
  EXPECT_GT((c.y - d.y).norm(), 0.0);  // later steps differ: the option acts
}

TEST(RateFormReuseRate, ConvergesAtSecondOrderToThePredictorCorrectorsSolution) {
  // Without XSPH both readings are second order (the uncorrected x of GMS (6.15) makes either first order with it).
  // Reference: the two-evaluation predictor-corrector at dt / 8. Measured orders 2.0 (both).
  for (const RateFormOptions& o : {RateFormOptions{.artificial_stress = 0.3},
                                   RateFormOptions{.viscosity = ViscositySwitch::Always, .artificial_stress = 0.3}}) {
    const Packet p(o);
    const Eigen::VectorXd ref = p.run(0.0125, false).y;
    const double e1 = (p.run(0.1, true).y - ref).norm(), e2 = (p.run(0.05, true).y - ref).norm();
    const double order = std::log2(e1 / e2);
    EXPECT_GT(order, 1.8) << "viscosity " << static_cast<int>(o.viscosity);
    EXPECT_LT(order, 2.3) << "viscosity " << static_cast<int>(o.viscosity);
    // And the two readings approach each other at the same order: their difference is of the size of the error.
    const double gap = (p.run(0.05, true).y - p.run(0.05, false).y).norm();
    EXPECT_LT(gap, 4 * e2);
    EXPECT_GT(gap, 0.0);
  }
}

TEST(RateFormReuseRate, RefusedWithTheLeapfrogAndWithAYieldStress) {
  const Packet p({});
  EXPECT_THROW(
      run_rate_form(p.scheme, p.y0,
                    {.dt = 0.1, .t_end = 1, .integrator = RateFormIntegrator::Leapfrog, .reuse_corrector_rate = true}),
      std::invalid_argument);
  EXPECT_THROW(
      run_rate_form(p.scheme, p.y0, {.dt = 0.1, .t_end = 1, .reuse_corrector_rate = true, .yield_stress = 0.1}),
      std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
