// The rate-form scheme's pair loop (PairLoop::Pairs: each pair once, src/forms/rate_form/pair_loop.hpp) against
// its row loop (PairLoop::Rows, every pair from both sides): the same rates to rounding for every combination of the
// terms, in 1D and 2D, with fixed layers or periodic, with a list longer than the support, driven particles, other
// kernels; and what it refuses.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "forms_fixture.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/forms/rate_form.hpp"

namespace sphstab {
namespace rate_form_pair_loop_test {

using test::kGms;

/// A busy state: positions, velocities, densities and stresses perturbed, so that every pair term acts (approaching
/// and receding pairs, tensile and compressive principal stresses).
template <int Dim>
Eigen::VectorXd busy_state(const RateFormScheme<Dim>& s, std::uint64_t seed) {
  Eigen::VectorXd y = s.uniform_state() + random_vector(s.size(), 0.05, seed);
  const Eigen::VectorXd dev = random_vector(s.discretisation().size() * RateFormScheme<Dim>::kStress, 0.02, seed + 1);
  for (int i = 0; i < s.discretisation().size(); ++i)
    if (s.stress_offset(i) >= 0)
      for (int c = 0; c < RateFormScheme<Dim>::kStress; ++c)
        y[s.stress_offset(i) + c] += dev[RateFormScheme<Dim>::kStress * i + c];
  return y;
}

/// max |Pairs - Rows| over max |Rows| of the two loops' rates at y.
template <int Dim>
double loops_disagree(std::shared_ptr<const Discretisation<Dim>> disc, RateFormOptions o, const Eigen::VectorXd& dev,
                      std::uint64_t seed, const std::vector<int>& driven = {}) {
  o.pair_loop = PairLoop::Rows;
  RateFormScheme<Dim> rows(disc, kGms, o, 1.0 / 1.02, dev);
  o.pair_loop = PairLoop::Pairs;
  RateFormScheme<Dim> pairs(disc, kGms, o, 1.0 / 1.02, dev);
  if (!driven.empty()) {
    const std::vector<Eigen::Matrix<double, Dim, 1>> acc(driven.size(), Eigen::Matrix<double, Dim, 1>::Constant(0.01));
    rows.set_driven(driven, acc);
    pairs.set_driven(driven, acc);
  }
  const Eigen::VectorXd y = busy_state(rows, seed);
  Eigen::VectorXd f, g;
  rows.rate(y, f);
  pairs.rate(y, g);
  EXPECT_EQ(f.size(), g.size());
  return (g - f).cwiseAbs().maxCoeff() / f.cwiseAbs().maxCoeff();
}

std::vector<RateFormOptions> every_term_combination() {
  std::vector<RateFormOptions> all;
  for (ContinuityForm c : {ContinuityForm::Summation, ContinuityForm::Divergence})
    for (double xsph : {0.0, 0.5})
      for (ViscositySwitch v : {ViscositySwitch::Off, ViscositySwitch::Compression, ViscositySwitch::Always})
        for (double eps : {0.0, 0.3})
          for (bool evolve : {true, false})
            all.push_back({.continuity = c,
                           .xsph = xsph,
                           .viscosity = v,
                           .viscosity_alpha = 1,
                           .viscosity_beta = 2,
                           .artificial_stress = eps,
                           .evolve_fixed = evolve});
  return all;
}

std::string describe(const RateFormOptions& o) {
  return "continuity " + std::to_string(static_cast<int>(o.continuity)) + " xsph " + std::to_string(o.xsph) +
         " viscosity " + std::to_string(static_cast<int>(o.viscosity)) + " eps " + std::to_string(o.artificial_stress) +
         " evolve_fixed " + std::to_string(o.evolve_fixed);
}

TEST(RateFormPairLoop, AgreesWithTheRowLoopForEveryTermIn2D) {
  // Fixed layers (with a list radius 1.4 x the support: the pairs beyond the support are skipped) and periodic.
  const auto layered = test::lattice_discretisation<2>({.n = 7, .h = 1.3, .perturbation = 0.1});
  const auto wide = make_discretisation(layered->particles, layered->kernel, 1.3, 1.4 * 2.6);
  const auto periodic = test::lattice_discretisation<2>({.n = 8, .h = 1.3, .periodic = true, .perturbation = 0.1});
  const Eigen::Vector3d dev(0.01, -0.02, 0.005);
  double worst = 0;
  for (const RateFormOptions& o : every_term_combination())
    for (const auto& disc : {layered, wide, periodic}) {
      const double e = loops_disagree<2>(disc, o, dev, 3);
      EXPECT_LT(e, 1e-13) << describe(o);
      worst = std::max(worst, e);
    }
  EXPECT_GT(worst, 0.0);  // the loops sum in different orders: not bitwise equal, so the test can tell them apart
}

TEST(RateFormPairLoop, AgreesWithTheRowLoopIn1DAndWithDrivenParticlesAndOtherKernels) {
  const auto line = test::lattice_discretisation<1>({.n = 16, .h = 1.3, .perturbation = 0.1});
  const auto ring = test::lattice_discretisation<1>({.n = 16, .h = 1.3, .periodic = true, .perturbation = 0.1});
  for (const RateFormOptions& o : every_term_combination()) {
    EXPECT_LT(loops_disagree<1>(line, o, Eigen::VectorXd::Constant(1, 0.01), 5), 1e-13) << "1D " << describe(o);
    EXPECT_LT(loops_disagree<1>(ring, o, Eigen::VectorXd::Constant(1, -0.01), 5), 1e-13) << "1D " << describe(o);
  }
  const RateFormOptions gms{.continuity = ContinuityForm::Divergence,
                            .xsph = 0.5,
                            .viscosity = ViscositySwitch::Compression,
                            .viscosity_alpha = 1,
                            .viscosity_beta = 2,
                            .artificial_stress = 0.3};
  const auto block = test::lattice_discretisation<2>({.n = 6, .h = 1.3, .perturbation = 0.1});
  EXPECT_LT(loops_disagree<2>(block, gms, Eigen::Vector3d(0.01, 0.0, 0.002), 9, {7, 20}), 1e-13) << "driven";
  for (KernelType k : {KernelType::QuinticSpline, KernelType::WendlandC2, KernelType::Gaussian}) {
    const auto disc = test::lattice_discretisation<2>({.n = 6, .kernel = k, .h = 1.2, .perturbation = 0.1});
    EXPECT_LT(loops_disagree<2>(disc, gms, Eigen::Vector3d(0.01, 0.0, 0.002), 9), 1e-13)
        << "kernel " << static_cast<int>(k);
  }
}

TEST(RateFormPairLoop, RebuiltKeepsTheLoopAndComplexStatesUseTheRowLoop) {
  const auto disc = test::lattice_discretisation<2>({.n = 6, .h = 1.3, .perturbation = 0.1});
  const RateFormOptions o{.xsph = 0.5, .viscosity = ViscositySwitch::Always, .pair_loop = PairLoop::Pairs};
  const RateFormScheme<2> pairs(disc, kGms, o);
  const RateFormScheme<2> re = pairs.rebuilt(pairs.uniform_state(), 1.2 * 2.6);
  EXPECT_EQ(re.options().pair_loop, PairLoop::Pairs);
  const Eigen::VectorXd y = busy_state(pairs, 4);
  Eigen::VectorXd f, g;
  pairs.rate(y, f);
  re.rate(y, g);
  EXPECT_LT((f - g).cwiseAbs().maxCoeff(), 1e-13 * f.cwiseAbs().maxCoeff());
  // The complex rate is the row loop's, so its real part at a real state is the row loop's rate bit for bit.
  RateFormOptions r = o;
  r.pair_loop = PairLoop::Rows;
  const RateFormScheme<2> rows(disc, kGms, r);
  Eigen::VectorXcd fc, gc;
  pairs.rate(Eigen::VectorXcd(y.cast<std::complex<double>>()), fc);
  rows.rate(Eigen::VectorXcd(y.cast<std::complex<double>>()), gc);
  EXPECT_EQ(Eigen::VectorXd(fc.real()), Eigen::VectorXd(gc.real()));
}

TEST(RateFormPairLoop, TakenScratchGivesTheSameBits) {
  // A run's Verlet rebuilds hand the old scheme's scratch arrays to the new one (RunBook::build): the rates must be the
  // bits of a scheme with its own, whether the taken arrays are larger (longer list) or smaller, for both loops and the
  // complex (row-loop) evaluation.
  const auto disc = test::lattice_discretisation<2>({.n = 6, .h = 1.3, .perturbation = 0.1});
  for (PairLoop loop : {PairLoop::Rows, PairLoop::Pairs})
    for (double donor_radius : {1.5 * 2.6, 2.6}) {
      const RateFormOptions o{
          .xsph = 0.5, .viscosity = ViscositySwitch::Always, .artificial_stress = 0.3, .pair_loop = loop};
      const RateFormScheme<2> base(disc, kGms, o);
      const Eigen::VectorXd y0 = busy_state(base, 6), y = busy_state(base, 7);
      RateFormScheme<2> donor = base.rebuilt(y0, donor_radius);
      Eigen::VectorXd f;
      donor.rate(y0, f);
      Eigen::VectorXcd fc;
      donor.rate(Eigen::VectorXcd(y0.cast<std::complex<double>>()), fc);
      const RateFormScheme<2> own = base.rebuilt(y, 1.2 * 2.6);
      RateFormScheme<2> taker = base.rebuilt(y, 1.2 * 2.6);
      taker.take_scratch(donor);
      Eigen::VectorXd g, h;
      own.rate(y, g);
      taker.rate(y, h);
      EXPECT_EQ(g, h) << "loop " << static_cast<int>(loop) << ", donor list radius " << donor_radius;
      Eigen::VectorXcd gc, hc;
      own.rate(Eigen::VectorXcd(y.cast<std::complex<double>>()), gc);
      taker.rate(Eigen::VectorXcd(y.cast<std::complex<double>>()), hc);
      EXPECT_EQ(gc, hc);
      donor.rate(y0, f);  // the donor, left without scratch, grows its own again
      EXPECT_EQ(f.size(), base.size());
    }
}

TEST(RateFormPairLoop, SameBitsOnOneAndTwoThreads) {
  // The pair loop is serial; the per-particle passes around it (unpack, stresses, rates) are threaded row by row. A
  // 40 x 40 block (about 1900 particles with the layers: above the 512 rows per thread that turn threading on) with
  // every GMS term.
  if (!threads_available()) GTEST_SKIP() << "built without OpenMP";
  const auto disc = test::lattice_discretisation<2>({.n = 40, .h = 1.3, .perturbation = 0.1});
  const RateFormScheme<2> s(disc, kGms,
                            {.continuity = ContinuityForm::Divergence,
                             .xsph = 0.5,
                             .viscosity = ViscositySwitch::Compression,
                             .artificial_stress = 0.3,
                             .pair_loop = PairLoop::Pairs});
  const Eigen::VectorXd y = busy_state(s, 6);
  Eigen::VectorXd f1, f2;
  {
    const ThreadCountGuard one(1);
    s.rate(y, f1);
  }
  {
    const ThreadCountGuard two(2);
    s.rate(y, f2);
  }
  ASSERT_EQ(f1.size(), f2.size());
  EXPECT_EQ(f1, f2);
}

TEST(RateFormPairLoop, RefusesTheFormsItDoesNotCover) {
  const auto disc = test::lattice_discretisation<2>({.n = 4, .h = 1.3});
  for (RateFormOptions o :
       {RateFormOptions{.gradient = RateFormGradient::Ncsph}, RateFormOptions{.momentum = RateFormMomentum::Cij},
        RateFormOptions{.momentum = RateFormMomentum::StabilisedSph}}) {
    o.pair_loop = PairLoop::Pairs;
    EXPECT_THROW(RateFormScheme<2>(disc, kGms, o), std::invalid_argument);
  }
  EXPECT_NO_THROW(
      RateFormScheme<2>(disc, kGms, {.momentum = RateFormMomentum::Antisymmetric, .pair_loop = PairLoop::Pairs}));
  EXPECT_EQ(parse_pair_loop("pairs"), PairLoop::Pairs);
  EXPECT_EQ(parse_pair_loop("rows"), PairLoop::Rows);
  EXPECT_THROW(parse_pair_loop("half"), std::invalid_argument);
}

}  // namespace rate_form_pair_loop_test
}  // namespace sphstab
