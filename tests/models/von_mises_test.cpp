// Von Mises radial return (models/von_mises.hpp): the returned deviator lies on the yield surface, elastic states are
// untouched bitwise, the return is radial; and in a run (integrate/rate_form_run.hpp) a 1D bar under uniform
// uniaxial strain ends on the elastic-perfectly-plastic answer S_xx = +-2Y/3.
#include "sphstab/models/von_mises.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace von_mises_test {

template <int Dim>
StoredDeviator<Dim> random_deviator(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  StoredDeviator<Dim> s;
  for (int k = 0; k < kDeviatorEntries<Dim>; ++k) s[k] = u(rng);
  return s;
}

template <int Dim>
bool same_bits(const StoredDeviator<Dim>& a, const StoredDeviator<Dim>& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * kDeviatorEntries<Dim>) == 0;
}

/// sqrt(3 J2) from the full 3 x 3 deviator, written out independently of von_mises_stress.
double j2_stress(const Eigen::Matrix3d& s) { return std::sqrt(1.5 * (s.array() * s.array()).sum()); }

TEST(VonMises, EquivalentStressOfTheCompletedDeviator) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 100; ++k) {
    const StoredDeviator<2> s = random_deviator<2>(rng, 1.0);
    Eigen::Matrix3d full = Eigen::Matrix3d::Zero();
    full << s[0], s[2], 0, s[2], s[1], 0, 0, 0, -(s[0] + s[1]);  // plane strain: S_zz = -(S_xx + S_yy)
    EXPECT_NEAR(von_mises_stress<2>(s), j2_stress(full), 1e-14);
    const StoredDeviator<1> s1(s[0]);
    const Eigen::Matrix3d uni = Eigen::Vector3d(s[0], -s[0] / 2, -s[0] / 2).asDiagonal();  // uniaxial strain
    EXPECT_NEAR(von_mises_stress<1>(s1), j2_stress(uni), 1e-14);
    EXPECT_NEAR(von_mises_stress<1>(s1), 1.5 * std::abs(s[0]), 1e-15);
  }
  // Pure shear S_xy = tau: sigma_eq = sqrt(3) tau.
  EXPECT_NEAR(von_mises_stress<2>(StoredDeviator<2>(0, 0, 0.5)), std::sqrt(3.0) * 0.5, 1e-15);
}

template <int Dim>
void expect_return_properties(unsigned seed) {
  std::mt19937_64 rng(seed);
  const VonMises model(0.03);
  int yielded = 0, elastic = 0;
  std::uniform_real_distribution<double> log_scale(std::log(0.002), std::log(0.1));
  for (int k = 0; k < 2000; ++k) {
    const StoredDeviator<Dim> trial = random_deviator<Dim>(rng, std::exp(log_scale(rng)));
    const RadialReturn<Dim> r = radial_return<Dim>(model, trial);
    EXPECT_EQ(r.trial_stress, von_mises_stress<Dim>(trial));
    if (von_mises_stress<Dim>(trial) <= 0.03) {
      ++elastic;
      EXPECT_FALSE(r.yielded);
      EXPECT_TRUE(same_bits<Dim>(r.deviator, trial));  // untouched, bit for bit
      continue;
    }
    ++yielded;
    ASSERT_TRUE(r.yielded);
    // On the yield surface to rounding (a few ulps of Y).
    EXPECT_NEAR(von_mises_stress<Dim>(r.deviator) / 0.03, 1.0, 1e-14);
    // Radial: the same direction, scaled down (S_zz = -(S_xx + S_yy) therefore still holds).
    const double scale = r.deviator.norm() / trial.norm();
    EXPECT_LT(scale, 1.0);
    EXPECT_LT((r.deviator / r.deviator.norm() - trial / trial.norm()).norm(), 1e-15);
    EXPECT_NEAR(scale, 0.03 / von_mises_stress<Dim>(trial), 1e-15);
  }
  EXPECT_GT(yielded, 100);  // both branches exercised
  EXPECT_GT(elastic, 100);
}

TEST(VonMises, ReturnLiesOnTheSurfaceIsRadialAndLeavesElasticStatesAlone) {
  expect_return_properties<1>(5);
  expect_return_properties<2>(6);
}

TEST(VonMises, UniaxialStrainYieldsAtTwoThirdsY) {
  // 1D: sigma_eq = 3/2 |S_xx|, so S_xx = +-2Y/3 is the surface.
  const VonMises model(0.3);
  const double on = 2 * 0.3 / 3;
  EXPECT_FALSE(radial_return<1>(model, StoredDeviator<1>(on * (1 - 1e-12))).yielded);
  EXPECT_FALSE(radial_return<1>(model, StoredDeviator<1>(-on * (1 - 1e-12))).yielded);
  for (double sign : {1.0, -1.0}) {
    const RadialReturn<1> r = radial_return<1>(model, StoredDeviator<1>(sign * 0.5));
    EXPECT_TRUE(r.yielded);
    EXPECT_NEAR(r.deviator[0], sign * on, 1e-16);
  }
}

TEST(VonMises, BadYieldStressAndNonFiniteTrials) {
  EXPECT_THROW(VonMises(0.0), std::invalid_argument);
  EXPECT_THROW(VonMises(-1.0), std::invalid_argument);
  EXPECT_THROW(VonMises(std::nan("")), std::invalid_argument);
  const VonMises never(std::numeric_limits<double>::infinity());
  EXPECT_FALSE(radial_return<2>(never, StoredDeviator<2>(1e300, -1e300, 1e300)).yielded);
  const double inf = std::numeric_limits<double>::infinity();
  const RadialReturn<2> r = radial_return<2>(VonMises(1.0), StoredDeviator<2>(inf, 0, 0));
  EXPECT_FALSE(r.yielded);  // left for the run's non-finite check, not turned into NaN
  EXPECT_EQ(r.deviator[0], inf);
  RateFormRunOptions o{.dt = 0.1, .t_end = 1};
  o.yield_stress = -1;
  const Kernel<1> k(KernelType::CubicSpline);
  const auto d =
      make_discretisation(make_lattice<1>(LatticeType::Line, 8,
                                          {.spacing = 1.0, .support_radius = k.support_radius(1.3), .periodic = true}),
                          k, 1.3);
  const RateFormScheme<1> scheme(d, ElasticMaterial::from_bulk_shear(1, 0.3, 1));
  EXPECT_THROW(run_rate_form(scheme, scheme.uniform_state(), o), std::invalid_argument);
}

// --- In a run -------------------------------------------------------------------------------------------------------

const ElasticMaterial kGms = ElasticMaterial::from_bulk_shear(1.0, 0.3, 1.0);

/// A periodic bar of 200 particles (dx = 1, cubic spline, h = 1.3) with the triangle-wave velocity v = rate X' for
/// |X'| <= L/4 (X' measured from the middle), continued with slope -rate to the seam: the middle half is stretched
/// and the outer half compressed at the uniform rate `rate`, with no velocity jump anywhere (a uniform gradient on
/// a periodic box is impossible). Far from the kinks at X' = +-L/4 the stretch is homogeneous, x = X (1 + rate t),
/// until the kinks' waves arrive (c_p = 1.18: 50 dx away, t ~ 40).
struct LoadedBar {
  std::shared_ptr<const Discretisation<1>> disc;
  RateFormScheme<1> scheme;
  Eigen::VectorXd y0;
  double length = 0;
  explicit LoadedBar(double rate)
      : disc(make_discretisation(
            make_lattice<1>(LatticeType::Line, 200,
                            {.spacing = 1.0,
                             .support_radius = Kernel<1>(KernelType::CubicSpline).support_radius(1.3),
                             .periodic = true}),
            Kernel<1>(KernelType::CubicSpline), 1.3)),
        scheme(disc, kGms) {
    const ParticleSet<1>& p = disc->particles;
    length = p.box_hi[0] - p.box_lo[0];
    y0 = scheme.uniform_state();
    for (int i = 0; i < p.size(); ++i) {
      const double x = offset(i);
      const double v = std::abs(x) <= length / 4 ? rate * x : rate * ((x > 0 ? 1 : -1) * length / 2 - x);
      scheme.set_velocity(y0, i, Eigen::Matrix<double, 1, 1>(v));
    }
  }
  double offset(int i) const { return disc->particles.x(i, 0) - disc->particles.box_lo[0] - length / 2; }
  double stress(const Eigen::VectorXd& y, int i) const { return y[scheme.stress_offset(i)]; }
};

TEST(VonMisesRun, UniaxialStrainBarEndsOnPlusMinusTwoThirdsY) {
  // Uniaxial strain at rate e: the hypoelastic deviator is S_xx = (4 mu / 3) ln(1 + e t) (D = e / (1 + e t)) until
  // sigma_eq = 3/2 |S_xx| reaches Y, then S_xx = +Y * 2/3 in the stretched half and -2Y/3 in the compressed half
  // (perfect plasticity: further loading is returned radially onto the surface). The plain SPH gradient of a linear
  // field on this lattice is 1 + delta, delta = sum_k -2 k W'(k) - 1 = 2.24e-2 (cubic spline, h = 1.3 dx), so the
  // discrete elastic stress is (1 + delta) times the continuum one.
  const double rate = 5e-4, Y = 0.003;
  const LoadedBar bar(rate);
  const Kernel<1> k(KernelType::CubicSpline);
  double delta = -1;
  for (int j = 1; j <= 2; ++j) delta += -2 * j * k.d1(static_cast<double>(j), 1.3);
  EXPECT_NEAR(delta, 2.237e-2, 1e-5);
  const double t_yield = (std::exp(2 * Y / 3 / (4 * kGms.mu() / 3 * (1 + delta))) - 1) / rate;  // ~9.8
  for (RateFormIntegrator integrator : {RateFormIntegrator::PredictorCorrector, RateFormIntegrator::Leapfrog}) {
    SCOPED_TRACE(static_cast<int>(integrator));
    const RateFormRunOptions elastic{.dt = 0.3, .t_end = 25.0, .integrator = integrator};
    RateFormRunOptions plastic = elastic;
    plastic.yield_stress = Y;
    // Before yield (t = 0.5 t_yield) nothing yields anywhere: the plastic run is the elastic run, bit for bit.
    RateFormRunOptions early = elastic, early_plastic = plastic;
    early.t_end = early_plastic.t_end = 0.5 * t_yield;
    const Eigen::VectorXd e0 = run_rate_form(bar.scheme, bar.y0, early).y;
    const Eigen::VectorXd p0 = run_rate_form(bar.scheme, bar.y0, early_plastic).y;
    EXPECT_EQ(std::memcmp(e0.data(), p0.data(), sizeof(double) * e0.size()), 0);
    const RateFormRunResult e = run_rate_form(bar.scheme, bar.y0, elastic);
    const RateFormRunResult p = run_rate_form(bar.scheme, bar.y0, plastic);
    ASSERT_TRUE(p.completed()) << p.message;
    int checked = 0;
    for (int i = 0; i < bar.disc->size(); ++i) {
      const double x = bar.offset(i);
      const double sign = std::abs(x) <= bar.length / 4 ? 1 : -1;
      if (std::abs(std::abs(x) - bar.length / 4) < 40) continue;  // the kinks' waves reach ~35 dx by t = 25
      ++checked;
      // Elastic: the analytic hypoelastic stress at 0.5 t_yield and at t = 25 (2.5 t_yield), to the discrete
      // gradient's drift with the stretch (delta moves by ~1e-3 relative over 1 % strain).
      const double s_half = 4 * kGms.mu() / 3 * (1 + delta) * std::log(1 + sign * rate * 0.5 * t_yield);
      EXPECT_NEAR(bar.stress(e0, i) / s_half, 1.0, 1e-3) << "particle " << i;
      const double s_end = 4 * kGms.mu() / 3 * (1 + delta) * std::log(1 + sign * rate * 25.0);
      EXPECT_NEAR(bar.stress(e.y, i) / s_end, 1.0, 2e-3) << "particle " << i;
      // Plastic: exactly on the surface, with the sign of the loading.
      EXPECT_NEAR(bar.stress(p.y, i) / (sign * 2 * Y / 3), 1.0, 1e-14) << "particle " << i;
    }
    EXPECT_EQ(checked, 40);
    // The return does not touch the pressure's equation: densities are those of the elastic run to the (tiny)
    // feedback of the deviator on the motion.
    const int mid = 100;
    EXPECT_NEAR(p.y[bar.scheme.density_offset(mid)], e.y[bar.scheme.density_offset(mid)], 1e-6);
  }
}

TEST(VonMisesRun, PlaneStrainDeviatorAboveYieldIsReturnedAfterOneStep) {
  // A uniform 2D state at rest with a deviator beyond the surface: F = 0 there (a uniform stress exerts no force on
  // a periodic lattice), so after one step every particle carries exactly the returned initial deviator.
  const Kernel<2> k(KernelType::CubicSpline);
  const auto d =
      make_discretisation(make_lattice<2>(LatticeType::Square, 6,
                                          {.spacing = 1.0, .support_radius = k.support_radius(1.3), .periodic = true}),
                          k, 1.3);
  const StoredDeviator<2> dev(0.04, -0.01, 0.02);
  const RateFormScheme<2> scheme(d, kGms, {}, std::nan(""), dev);
  const double Y = 0.03;
  const RadialReturn<2> expected = radial_return<2>(VonMises(Y), dev);
  ASSERT_TRUE(expected.yielded);
  for (RateFormIntegrator integrator : {RateFormIntegrator::PredictorCorrector, RateFormIntegrator::Leapfrog}) {
    const RateFormRunResult r = run_rate_form(scheme, scheme.uniform_state(),
                                              {.dt = 0.1, .t_end = 0.1, .integrator = integrator, .yield_stress = Y});
    ASSERT_TRUE(r.completed());
    for (int i = 0; i < d->size(); ++i) {
      const StoredDeviator<2> s = r.y.segment<3>(scheme.stress_offset(i));
      EXPECT_NEAR(von_mises_stress<2>(s) / Y, 1.0, 1e-14);
      EXPECT_LT((s - expected.deviator).norm(), 1e-15);
    }
  }
}

}  // namespace
}  // namespace sphstab
