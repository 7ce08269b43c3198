// Threads (core/threads.hpp): the threaded loops give the same bits as one thread. Each case evaluates (or steps) with
// 1 and with 2 threads and compares every entry exactly; the lattices are large enough (> 2 * kMinRowsPerThread rows)
// that the second run really is split between two threads (asserted through threads_for).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <bit>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "forms_fixture.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/forms/linear_elastic.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace threads_determinism_test {

using test::kGms;

/// A state off equilibrium: the uniform state with random velocities, densities and stresses.
Eigen::VectorXd perturbed_state(const RateFormScheme<2>& scheme, unsigned seed) {
  Eigen::VectorXd y = scheme.uniform_state();
  return y + test::random_vector(static_cast<int>(y.size()), 1e-3, seed);
}

TEST(Threads, CountIsSetAndBadCountRejected) {
  const ThreadCountGuard guard;
  EXPECT_THROW(set_threads(0), std::invalid_argument);
  try {
    set_threads(-3);
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("-3"), std::string::npos);
  }
  set_threads(1);
  EXPECT_EQ(max_threads(), 1);
  EXPECT_EQ(threads_for(1'000'000), 1);
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  set_threads(2);
  EXPECT_EQ(max_threads(), 2);
  EXPECT_EQ(threads_for(2 * kMinRowsPerThread), 2);
  EXPECT_EQ(threads_for(2 * kMinRowsPerThread - 1), 1);
}

/// rate() with 1 and 2 threads on a 36 x 36 block (1296 free particles plus fixed layers), for the option sets of
/// every code path: plain gradient without / with XSPH (two passes instead of the ring), viscosity and artificial
/// stress; the NCSPH gradient; the plain gradient with the C_ij and S-SPH momentum (local means).
TEST(Threads, RateFormRateIsTheSameBitsWithTwoThreads) {
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  const auto disc = test::lattice_discretisation<2>({.n = 36, .h = 1.5});
  ASSERT_GE(disc->particles.size(), 2 * kMinRowsPerThread);
  const std::vector<std::pair<std::string, RateFormOptions>> cases = {
      {"plain", {}},
      {"plain+viscosity", {.viscosity = ViscositySwitch::Always}},
      {"gms", {.xsph = 0.5, .viscosity = ViscositySwitch::Compression, .artificial_stress = 0.3}},
      {"ncsph", {.gradient = RateFormGradient::Ncsph}},
      {"ncsph+xsph", {.xsph = 0.5, .viscosity = ViscositySwitch::Compression, .gradient = RateFormGradient::Ncsph}},
      {"cij", {.momentum = RateFormMomentum::Cij}},
      {"s-sph", {.momentum = RateFormMomentum::StabilisedSph}},
  };
  for (const auto& [name, options] : cases) {
    const RateFormScheme<2> scheme(disc, kGms, options, 1.02);
    const Eigen::VectorXd y = perturbed_state(scheme, 7);
    Eigen::VectorXd one, two;
    {
      const ThreadCountGuard guard(1);
      scheme.rate(y, one);
    }
    {
      const ThreadCountGuard guard(2);
      ASSERT_EQ(threads_for(disc->particles.size()), 2);
      scheme.rate(y, two);
    }
    EXPECT_GT(one.cwiseAbs().maxCoeff(), 1e-6) << name;  // a real, non-zero rate
    EXPECT_EQ(test::differing_bits(one, two), 0) << name;
  }
}

/// 100 predictor-corrector steps of the GMS scheme (XSPH, viscosity, artificial stress) with 1 and 2 threads end in
/// the same state, bit for bit.
TEST(Threads, RateFormRunIsTheSameBitsAfter100Steps) {
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  const auto disc = test::lattice_discretisation<2>({.n = 36, .h = 1.5});
  const RateFormScheme<2> scheme(disc, kGms,
                                 {.xsph = 0.5, .viscosity = ViscositySwitch::Compression, .artificial_stress = 0.3});
  Eigen::VectorXd y0 = scheme.uniform_state();
  for (int i = 0; i < disc->particles.size(); i += 7)
    if (scheme.velocity_offset(i) >= 0) y0[scheme.velocity_offset(i)] = 0.01;
  RateFormRunResult one, two;
  {
    const ThreadCountGuard guard(1);
    one = run_rate_form(scheme, y0, {.dt = 0.05, .t_end = 5.0});
  }
  {
    const ThreadCountGuard guard(2);
    two = run_rate_form(scheme, y0, {.dt = 0.05, .t_end = 5.0});
  }
  ASSERT_TRUE(one.completed()) << one.message;
  ASSERT_EQ(one.steps, 100);
  EXPECT_GT((one.y - y0).cwiseAbs().maxCoeff(), 1e-4);  // the state moved
  EXPECT_EQ(test::differing_bits(one.y, two.y), 0);
}

/// The reported failure is the same with two threads: the lowest particle with a singular NCSPH moment matrix.
TEST(Threads, RateFormErrorNamesTheSameParticle) {
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  const auto disc = test::lattice_discretisation<2>({.n = 36, .h = 1.5});
  const RateFormScheme<2> scheme(disc, kGms, {.gradient = RateFormGradient::Ncsph});
  Eigen::VectorXd y = scheme.uniform_state();
  // Non-finite positions of two particles, one in each thread's half.
  y[scheme.position_offset(900)] = std::numeric_limits<double>::quiet_NaN();
  y[scheme.position_offset(100)] = std::numeric_limits<double>::quiet_NaN();
  std::string messages[2];
  for (int t : {1, 2}) {
    const ThreadCountGuard guard(t);
    Eigen::VectorXd f;
    try {
      scheme.rate(y, f);
    } catch (const std::domain_error& e) {
      messages[t - 1] = e.what();
    }
  }
  EXPECT_FALSE(messages[0].empty());
  EXPECT_EQ(messages[0], messages[1]);
}

/// LinearElasticSph with 1 and 2 threads: TL SpMV passes, UL reassembly (minus gradient) and passes, both pair loops.
TEST(Threads, LinearElasticAccelerationIsTheSameBitsWithTwoThreads) {
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  const Kernel<2> kernel(KernelType::CubicSpline);
  const ParticleSet<2> set = make_lattice<2>(LatticeType::Square, 40, {.spacing = 1.0, .periodic = true});
  for (LagrangianFrame frame : {LagrangianFrame::Total, LagrangianFrame::Updated}) {
    const LinearElasticSph<2> form(set, kernel, 1.3,
                                   {.material = ElasticMaterial::from_lame(1.2, 0.8, 7.8), .frame = frame});
    const Eigen::VectorXd u = test::random_vector(2 * form.free_count(), 1e-3, 3);
    Eigen::VectorXd a[2], b[2];
    for (int t : {1, 2}) {
      const ThreadCountGuard guard(t);
      form.acceleration(u, a[t - 1]);
      form.acceleration_pair_loop(u, b[t - 1]);
    }
    EXPECT_GT(a[0].cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_EQ(test::differing_bits(a[0], a[1]), 0);
    EXPECT_EQ(test::differing_bits(b[0], b[1]), 0);
  }
}

}  // namespace
}  // namespace sphstab
