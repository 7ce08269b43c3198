// Threads (core/threads.hpp): the threaded loops give the same bits as one thread. Each case evaluates (or steps) with
// 1 and with 2 (the pair loop: up to 4) threads and compares every entry exactly; the lattices are large enough
// (> 2 * kMinRowsPerThread rows) that the second run really is split between two threads (asserted through
// threads_for). The pair loop (rate_form/pair_loop.hpp) is also called directly, cut into any number of chunks.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "../../src/forms/rate_form/dispatch.hpp"
#include "../../src/forms/rate_form/pair_loop.hpp"
#include "forms_fixture.hpp"
#include "sphstab/core/simd_dispatch.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/forms/linear_elastic.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/integrate/scene_run.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/gms_scenes.hpp"

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

/// The particles of d in a random order (positions, volumes, roles, depths permuted): neighbours are far apart in
/// the numbering, so that a pair-loop chunk's halo reaches back over most rows.
std::shared_ptr<const Discretisation<2>> shuffled(const Discretisation<2>& d, unsigned seed) {
  const ParticleSet<2>& p = d.particles;
  std::vector<int> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  ParticleSet<2> q = p;
  for (int i = 0; i < p.size(); ++i) {
    q.x.row(i) = p.x.row(order[i]);
    q.volume[i] = p.volume[order[i]];
    q.role[i] = p.role[order[i]];
    if (!p.depth.empty()) q.depth[i] = p.depth[order[i]];
  }
  return make_discretisation(q, d.kernel, d.h);
}

/// The pair loop's inputs (rate_form/pair_loop.hpp) on a discretisation: perturbed positions, random velocities,
/// densities, masses, sigma / rho^2, R and XSPH flags.
struct PairLoopCase {
  std::string name;
  std::shared_ptr<const Discretisation<2>> disc;
  ViscositySwitch viscosity = ViscositySwitch::Off;
  bool stress = false, xsph = false, summation = false;
};
struct PairLoopInputs {
  std::vector<long> upper;
  std::vector<Eigen::Vector2d> x, v;
  std::vector<double> rho, vol, mass;
  std::vector<Eigen::Matrix2d> sigma_rho2, R;
  std::vector<char> moves;
};
PairLoopInputs pair_loop_inputs(const Discretisation<2>& d, unsigned seed) {
  const int n = d.size();
  const NeighbourList& nl = d.neighbours;
  const Eigen::VectorXd u = test::random_vector(16 * n, 1.0, seed);  // uniform in [-1, 1]
  PairLoopInputs in;
  for (int i = 0; i < n; ++i) {
    const double* r = u.data() + 16 * i;
    in.upper.push_back(std::upper_bound(nl.indices.begin() + nl.offsets[i], nl.indices.begin() + nl.offsets[i + 1], i) -
                       nl.indices.begin());
    in.x.push_back(d.particles.x.row(i).transpose() + 0.05 * d.h * Eigen::Vector2d(r[0], r[1]));
    in.v.emplace_back(0.1 * r[2], 0.1 * r[3]);
    in.rho.push_back(1 + 0.1 * r[4]);
    in.mass.push_back(d.particles.volume[i] * (1 + 0.1 * r[5]));
    in.vol.push_back(in.mass[i] / in.rho[i]);
    in.sigma_rho2.push_back((Eigen::Matrix2d() << r[6], r[7], r[7], r[8]).finished());
    in.R.push_back((Eigen::Matrix2d() << 0.3 * r[9], 0.3 * r[10], 0.3 * r[10], 0.3 * r[11]).finished());
    in.moves.push_back(r[12] > -0.8);
  }
  return in;
}

/// Every output of the pair loop (vhat, acc, L, drho) on `threads` threads over `chunks` chunks, as one vector.
Eigen::VectorXd pair_loop_outputs(const PairLoopCase& c, const PairLoopInputs& in, int threads, int chunks) {
  namespace rd = rate_form_detail;
  const Discretisation<2>& d = *c.disc;
  const int n = d.size();
  std::vector<Eigen::Vector2d> vhat(n), acc(n);
  std::vector<Eigen::Matrix2d> L(n);
  std::vector<double> drho(n);
  const double support = d.kernel.support_radius(d.h);
  rd::PairLoopArrays<2> A{.n = n,
                          .offsets = d.neighbours.offsets.data(),
                          .upper = in.upper.data(),
                          .indices = d.neighbours.indices.data(),
                          .x = in.x.data(),
                          .v = in.v.data(),
                          .rho = in.rho.data(),
                          .vol = in.vol.data(),
                          .mass = in.mass.data(),
                          .sigma_rho2 = in.sigma_rho2.data(),
                          .R = in.R.data(),
                          .xsph_moves = in.moves.data(),
                          .support2 = support * support,
                          .h = d.h,
                          .eta2 = 0.01 * d.h * d.h,
                          .alpha_c0 = -1.0,
                          .beta = 2.0,
                          .xsph = 0.5,
                          .summation = c.summation,
                          .vhat = vhat.data(),
                          .acc = acc.data(),
                          .L = L.data(),
                          .drho = drho.data()};
  for (int a = 0; a < 2; ++a) {
    A.box[a] = d.particles.box_hi[a] - d.particles.box_lo[a];
    A.half_box[a] = d.particles.periodic[a] ? 0.5 * A.box[a] : std::numeric_limits<double>::infinity();
  }
  rd::PairLoopScratch<2> scratch;
  const rd::PairFactor pair_factor(d.kernel.value(d.particles.spacing, d.h), 4);
  rd::with_kernel_functions(d.kernel, d.h, [&](const auto& kf) {
    rd::with_term_tags(c.viscosity, c.stress, [&](auto viscosity_tag, auto stress_tag) {
      constexpr ViscositySwitch kV = decltype(viscosity_tag)::value;
      constexpr bool kS = decltype(stress_tag)::value;
      if (c.xsph)
        rd::pair_loop<2, kV, kS, true>(A, kf, pair_factor, scratch, threads, chunks);
      else
        rd::pair_loop<2, kV, kS, false>(A, kf, pair_factor, scratch, threads, chunks);
    });
  });
  Eigen::VectorXd out(9 * n);
  for (int i = 0; i < n; ++i) out.segment<9>(9 * i) << vhat[i], acc[i], L[i].reshaped(), drho[i];
  return out;
}

/// The pair loop cut into 1 to 40 chunks on 1 to 4 threads gives the bits of one chunk on one thread (the serial
/// loop), for every kind of sweep: no terms, viscosity and artificial stress, XSPH (two sweeps), summation continuity
/// with and without XSPH, a periodic box, another kernel, and the particles in a random order (halos over most rows).
/// The threads are asked for directly (the loop's own count, not threads_for), so the small lattices split too.
TEST(Threads, PairLoopIsTheSameBitsForAnyChunksAndThreads) {
  const auto block = test::lattice_discretisation<2>({.n = 20, .h = 1.5, .perturbation = 0.2});
  const auto torus = test::lattice_discretisation<2>({.n = 20, .h = 1.5, .periodic = true, .perturbation = 0.2});
  const auto wendland = test::lattice_discretisation<2>({.n = 16, .kernel = KernelType::WendlandC2, .h = 1.3});
  const auto mixed = shuffled(*block, 11), mixed_torus = shuffled(*torus, 12);
  const std::vector<PairLoopCase> cases = {
      {"plain", block},
      {"viscosity+stress", block, ViscositySwitch::Always, true},
      {"xsph (gms)", block, ViscositySwitch::Compression, true, true},
      {"summation", block, ViscositySwitch::Compression, false, false, true},
      {"summation+xsph", block, ViscositySwitch::Off, true, true, true},
      {"periodic", torus, ViscositySwitch::Compression, true, true},
      {"wendland", wendland, ViscositySwitch::Always, true, true, true},
      {"shuffled", mixed, ViscositySwitch::Compression, true, true},
      {"shuffled summation", mixed, ViscositySwitch::Always, true, false, true},
      {"shuffled periodic", mixed_torus, ViscositySwitch::Compression, true, true, true},
  };
  for (const PairLoopCase& c : cases) {
    const PairLoopInputs in = pair_loop_inputs(*c.disc, 5);
    const Eigen::VectorXd serial = pair_loop_outputs(c, in, 1, 1);
    EXPECT_GT(serial.cwiseAbs().maxCoeff(), 1e-3) << c.name;
    EXPECT_TRUE(serial.allFinite()) << c.name;
    for (int threads : {1, 2, 3, 4})
      for (int chunks : {0, 1, 2, 3, 5, 8, 13, 40})
        EXPECT_EQ(test::differing_bits(serial, pair_loop_outputs(c, in, threads, chunks)), 0)
            << c.name << ": " << threads << " threads, " << chunks << " chunks";
  }
}

/// The pair loop's row scalars by the AVX2 lanes (rate_form/pair_lanes.hpp, 4 pairs per vector) give the bits of the
/// baseline's 2 lanes, on one thread and on three threads over 7 chunks (halo rows: a row's pairs in part), for the
/// sweeps above; the Wendland kernel takes the kernel's own functions (no lanes) and is the same either way.
TEST(Threads, PairLoopAvx2LanesAreTheBaselineBits) {
  if (!avx2_enabled()) GTEST_SKIP() << "no AVX2 on this CPU (or SPHSTAB_SIMD=baseline): only the baseline build runs";
  const auto block = test::lattice_discretisation<2>({.n = 20, .h = 1.5, .perturbation = 0.2});
  const auto torus = test::lattice_discretisation<2>({.n = 20, .h = 1.5, .periodic = true, .perturbation = 0.2});
  const auto mixed = shuffled(*block, 11);
  const std::vector<PairLoopCase> cases = {
      {"plain", block},
      {"viscosity+stress", block, ViscositySwitch::Always, true},
      {"xsph (gms)", block, ViscositySwitch::Compression, true, true},
      {"summation", block, ViscositySwitch::Compression, false, false, true},
      {"periodic", torus, ViscositySwitch::Compression, true, true},
      {"shuffled summation+xsph", mixed, ViscositySwitch::Always, true, true, true},
  };
  for (const PairLoopCase& c : cases) {
    const PairLoopInputs in = pair_loop_inputs(*c.disc, 6);
    for (const auto& [threads, chunks] : {std::pair{1, 1}, std::pair{3, 7}}) {
      Eigen::VectorXd baseline;
      {
        const PortableSimdGuard portable;
        baseline = pair_loop_outputs(c, in, threads, chunks);
      }
      const Eigen::VectorXd avx2 = pair_loop_outputs(c, in, threads, chunks);
      EXPECT_GT(baseline.cwiseAbs().maxCoeff(), 1e-3) << c.name;
      EXPECT_EQ(test::differing_bits(baseline, avx2), 0) << c.name << ": " << threads << " threads";
    }
  }
}

/// RateFormScheme::rate with the pair loop (PairLoop::Pairs) on 1 to 4 threads: the same bits as on one. A 48 x 48
/// block (2916 particles with the fixed layers, so that threads_for gives 4), in order and shuffled.
TEST(Threads, RateFormPairLoopIsTheSameBitsOnOneToFourThreads) {
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  const auto block = test::lattice_discretisation<2>({.n = 48, .h = 1.5, .perturbation = 0.2});
  const auto torus = test::lattice_discretisation<2>({.n = 48, .h = 1.5, .periodic = true, .perturbation = 0.2});
  const auto mixed = shuffled(*block, 11);
  ASSERT_GE(block->particles.size(), 4 * kMinRowsPerThread);
  const RateFormOptions gms{.continuity = ContinuityForm::Divergence,
                            .xsph = 0.5,
                            .viscosity = ViscositySwitch::Compression,
                            .artificial_stress = 0.3,
                            .pair_loop = PairLoop::Pairs};
  const std::vector<std::tuple<std::string, std::shared_ptr<const Discretisation<2>>, RateFormOptions>> cases = {
      {"plain", block, {.continuity = ContinuityForm::Divergence, .pair_loop = PairLoop::Pairs}},
      {"viscosity+stress",
       block,
       {.continuity = ContinuityForm::Divergence,
        .viscosity = ViscositySwitch::Always,
        .artificial_stress = 0.3,
        .pair_loop = PairLoop::Pairs}},
      {"gms", block, gms},
      {"summation",
       block,
       {.continuity = ContinuityForm::Summation, .viscosity = ViscositySwitch::Always, .pair_loop = PairLoop::Pairs}},
      {"summation+xsph",
       block,
       {.continuity = ContinuityForm::Summation, .xsph = 0.5, .artificial_stress = 0.3, .pair_loop = PairLoop::Pairs}},
      {"periodic gms", torus, gms},
      {"shuffled gms", mixed, gms},
      {"shuffled summation",
       mixed,
       {.continuity = ContinuityForm::Summation, .artificial_stress = 0.3, .pair_loop = PairLoop::Pairs}},
  };
  for (const auto& [name, disc, options] : cases) {
    const RateFormScheme<2> scheme(disc, kGms, options, 1.02);
    const Eigen::VectorXd y = perturbed_state(scheme, 7);
    Eigen::VectorXd one;
    {
      const ThreadCountGuard guard(1);
      scheme.rate(y, one);
    }
    EXPECT_GT(one.cwiseAbs().maxCoeff(), 1e-6) << name;
    for (int t : {2, 3, 4}) {
      const ThreadCountGuard guard(t);
      ASSERT_EQ(threads_for(disc->particles.size()), t);
      Eigen::VectorXd f;
      scheme.rate(y, f);
      EXPECT_EQ(test::differing_bits(one, f), 0) << name << ", " << t << " threads";
    }
  }
}

/// 300 steps of GMS's rings (§7.2, dp = 0.1: 4400 particles, the pair loop with XSPH, the one-evaluation
/// predictor-corrector and neighbour rebuilds) with 1 and 2 threads end in the same state, bit for bit.
TEST(Threads, RingsRunIsTheSameBitsAfter300StepsOnTwoThreads) {
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  const Scene<2> s = gms_rings_scene({.spacing = 0.1});
  ASSERT_EQ(s.scheme->options().pair_loop, PairLoop::Pairs);
  RateFormRunOptions o = scene_run_options(s);
  o.t_end = 300 * o.dt;
  RateFormRunResult one, two;
  {
    const ThreadCountGuard guard(1);
    one = run_rate_form(*s.scheme, s.y0, o);
  }
  {
    const ThreadCountGuard guard(2);
    ASSERT_EQ(threads_for(s.scheme->discretisation().size()), 2);
    two = run_rate_form(*s.scheme, s.y0, o);
  }
  ASSERT_TRUE(one.completed()) << one.message;
  ASSERT_GE(one.steps, 300);
  EXPECT_GT(one.neighbour_builds, 1);  // the rings moved far enough for the list to be rebuilt
  EXPECT_EQ(test::differing_bits(one.y, two.y), 0);
}

}  // namespace threads_determinism_test
}  // namespace sphstab
