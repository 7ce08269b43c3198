#include "sphstab/forms/elastic_bar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/problems/bar_wave_exact.hpp"

namespace sphstab {
namespace elastic_bar_test {

ElasticBarOptions bar_options(int n, StrainGradient g, StressDivergence d, BarBoundary b,
                              LagrangianFrame f = LagrangianFrame::Total, double h_over_dx = 1.3) {
  ElasticBarOptions o;
  o.particles = n;
  o.gradient = g;
  o.divergence = d;
  o.boundary = b;
  o.frame = f;
  o.h_over_dx = h_over_dx;
  return o;
}

double max_abs(const SparseMatrix<>& m) {
  double x = 0;
  for (int k = 0; k < m.outerSize(); ++k)
    for (SparseMatrix<>::InnerIterator it(m, k); it; ++it) x = std::max(x, std::abs(it.value()));
  return x;
}

TEST(ElasticBar, MirrorGhostsMakeAllFormsEqualAndSymmetric) {
  // With mirror ghosts every free particle has a full symmetric neighbourhood on the lattice, so G 1 = 0 on free
  // rows and plain = minus = plus; plain/plain is then exactly the variational (adjoint) pair.
  for (double hr : {1.0, 1.3, 2.0}) {
    ElasticBar1D ref(bar_options(40, StrainGradient::Plain, StressDivergence::Plain, BarBoundary::Mirror,
                                 LagrangianFrame::Total, hr));
    const SparseMatrix<> A = ref.stiffness_matrix();
    const double scale = max_abs(A);
    for (auto [g, d] :
         std::vector<std::pair<StrainGradient, StressDivergence>>{{StrainGradient::Minus, StressDivergence::Minus},
                                                                  {StrainGradient::Minus, StressDivergence::Plus},
                                                                  {StrainGradient::Minus, StressDivergence::Adjoint},
                                                                  {StrainGradient::Plain, StressDivergence::Adjoint}}) {
      ElasticBar1D other(bar_options(40, g, d, BarBoundary::Mirror, LagrangianFrame::Total, hr));
      EXPECT_LT(max_abs(other.stiffness_matrix() - A), 1e-12 * scale)
          << strain_gradient_name(g) << "/" << stress_divergence_name(d) << " h/dx " << hr;
    }
    EXPECT_LT(max_abs(A - SparseMatrix<>(A.transpose())), 1e-12 * scale) << "h/dx " << hr;
    // Rigid translation: no strain, no force.
    Eigen::VectorXd one = Eigen::VectorXd::Ones(40);
    EXPECT_LT((ref.strain_matrix() * one).cwiseAbs().maxCoeff(), 1e-12 * max_abs(ref.strain_matrix()));
  }
}

TEST(ElasticBar, DeficientEndsBreakPlainConsistencyButNotMinus) {
  ElasticBar1D plain(bar_options(40, StrainGradient::Plain, StressDivergence::Plain, BarBoundary::None));
  ElasticBar1D minus(bar_options(40, StrainGradient::Minus, StressDivergence::Plus, BarBoundary::None));
  Eigen::VectorXd one = Eigen::VectorXd::Ones(40);
  const Eigen::VectorXd e_plain = plain.strain_matrix() * one, e_minus = minus.strain_matrix() * one;
  EXPECT_GT(std::abs(e_plain[0]), 10.0);  // gradient of a constant ~ 1/(2 dx) at the end (dx = 0.025)
  EXPECT_NEAR(e_plain[20], 0.0, 1e-10);   // interior: full support
  EXPECT_LT(e_minus.cwiseAbs().maxCoeff(), 1e-10);
  // Minus gradient + plus divergence is the adjoint pair: V-symmetric (uniform V: symmetric) stiffness.
  const SparseMatrix<> A = minus.stiffness_matrix();
  EXPECT_LT(max_abs(A - SparseMatrix<>(A.transpose())), 1e-12 * max_abs(A));
  ElasticBar1D adj(bar_options(40, StrainGradient::Minus, StressDivergence::Adjoint, BarBoundary::None));
  EXPECT_LT(max_abs(adj.stiffness_matrix() - A), 1e-12 * max_abs(A));
}

TEST(ElasticBar, StandingWaveAccelerationConvergesToTheDiscreteMomentLimit) {
  // Free-free fundamental mode u = cos(pi X / L): ü = -c² (pi/L)² u. At fixed h/dx, plain SPH gives
  // G G u = m1² u'' + O(h²) with the discrete first moment m1 = Σ_j (x_j - x_i) G_ij (interior rows), so the error
  // tends to |m1² - 1| (the SPH wave speed is m1 c), while the deviation from m1² x exact converges at O(h²).
  // The first-order corrected gradient with its adjoint divergence divides by m1 and converges to the exact value.
  for (KernelType k : {KernelType::CubicSpline, KernelType::WendlandC2}) {
    std::vector<double> err_plain, err_corr;
    double m1 = 0;
    for (int n : {50, 100, 200}) {
      auto o = bar_options(n, StrainGradient::Plain, StressDivergence::Plain, BarBoundary::Mirror);
      o.kernel = k;
      ElasticBar1D bar(o);
      o.gradient = StrainGradient::Corrected;
      o.divergence = StressDivergence::Adjoint;
      ElasticBar1D corr(o);
      m1 = (bar.strain_matrix() * bar.positions())[n / 2];
      const double c = bar.wave_speed(), kk = M_PI / o.length;
      Eigen::VectorXd u = (kk * bar.positions().array()).cos().matrix(), a(n), exact = -c * c * kk * kk * u;
      bar.acceleration(u, a);
      err_plain.push_back((a - m1 * m1 * exact).norm() / exact.norm());
      corr.acceleration(u, a);
      err_corr.push_back((a - exact).norm() / exact.norm());
    }
    for (std::size_t i = 1; i < err_plain.size(); ++i) {
      EXPECT_NEAR(std::log2(err_plain[i - 1] / err_plain[i]), 2.0, 0.05) << kernel_name(k) << " " << err_plain[i];
      EXPECT_NEAR(std::log2(err_corr[i - 1] / err_corr[i]), 2.0, 0.05) << kernel_name(k) << " " << err_corr[i];
    }
    // Cubic B-spline at h = 1.3 dx: m1 = 1.0224 (2.2 % fast waves); Wendland C2: 1.0100.
    EXPECT_NEAR(m1, k == KernelType::CubicSpline ? 1.022373 : 1.009984, 1e-6);
  }
}

TEST(ElasticBar, UpdatedLagrangianAgreesWithTotalLagrangianAtSmallAmplitude) {
  const int n = 100;
  for (auto [b, g, d] : std::vector<std::tuple<BarBoundary, StrainGradient, StressDivergence>>{
           {BarBoundary::Mirror, StrainGradient::Minus, StressDivergence::Minus},
           {BarBoundary::None, StrainGradient::Minus, StressDivergence::Minus},
           {BarBoundary::None, StrainGradient::Corrected, StressDivergence::Adjoint},
           {BarBoundary::None, StrainGradient::Plain, StressDivergence::Plus}}) {
    SCOPED_TRACE(bar_boundary_name(b) + " " + strain_gradient_name(g) + "/" + stress_divergence_name(d));
    ElasticBar1D tl(bar_options(n, g, d, b));
    ElasticBar1D ul(bar_options(n, g, d, b, LagrangianFrame::Updated));
    // Same operator at u -> 0: a_UL(u) - a_TL(u) = O(|u|²).
    Eigen::VectorXd u = (3.0 * tl.positions().array()).sin().matrix() * 1e-9, a1(n), a2(n);
    tl.acceleration(u, a1);
    ul.acceleration(u, a2);
    EXPECT_LT((a1 - a2).norm(), 1e-6 * a1.norm()) << bar_boundary_name(b);
    // Rigid translation by 7.3 dx: zero acceleration in UL too, and the neighbour list is rebuilt.
    Eigen::VectorXd shift = Eigen::VectorXd::Constant(n, 7.3 * tl.spacing());
    const long builds = ul.neighbour_builds();
    ul.acceleration(shift, a2);
    EXPECT_EQ(ul.neighbour_builds(), builds + 1);
    if (g != StrainGradient::Plain || b == BarBoundary::Mirror)  // plain + deficient ends strains a translation
      EXPECT_LT(a2.cwiseAbs().maxCoeff(), 1e-9);                 // |G| ~ 1/dx² = 1e4: round-off
    // Velocity-jump runs: TL and UL differ by O(amplitude) (geometric change of the operators), so the relative
    // difference must scale linearly with the amplitude. Plain gradients with deficient ends strain a translation
    // (ε ~ u/dx at the ends), which gives the largest constant (1.4e-3 at amplitude 1e-6).
    std::vector<double> rel;
    for (double amp : {1e-6, 1e-7}) {
      BarJumpProblem p;
      p.velocity_left = amp;
      p.velocity_right = -amp;
      BarJumpExact ex(p);
      Eigen::VectorXd v0(n);
      for (int i = 0; i < n; ++i) v0[i] = ex.initial_velocity(tl.positions()[i]);
      LeapfrogOptions opt;
      opt.dt = cfl_time_step(kDefaultCourant, tl.h(), tl.wave_speed());
      opt.t_end = 1.5;
      auto rt = run_leapfrog(tl.system(), Eigen::VectorXd::Zero(n), v0, opt);
      auto ru = run_leapfrog(ul.system(), Eigen::VectorXd::Zero(n), v0, opt);
      ASSERT_TRUE(rt.completed() && ru.completed());
      rel.push_back((rt.v - ru.v).norm() / rt.v.norm());
    }
    EXPECT_LT(rel[0], 2e-3);
    EXPECT_NEAR(rel[0] / rel[1], 10.0, 0.1);       // linear in amplitude; quadratic remainder ~ 1e-3 relative
    EXPECT_EQ(ul.neighbour_builds(), builds + 2);  // one rebuild back from the shifted state, none while running
  }
}

TEST(ElasticBar, SymmetricFormConservesEnergyWithSecondOrderOscillation) {
  // TL, mirror ghosts, plain/plain = adjoint pair: ü = -A u with A symmetric (uniform masses). Velocity-jump data
  // excite every mode. 10^4 steps at dt = f x dt_limit; the max relative energy deviation must scale as dt².
  ElasticBar1D bar(bar_options(100, StrainGradient::Minus, StressDivergence::Adjoint, BarBoundary::Mirror));
  auto sys = bar.system();
  auto est = estimate_stability_limit(sys.acceleration, bar.size(), {.symmetric = true});
  BarJumpExact ex(BarJumpProblem{});
  Eigen::VectorXd v0(bar.size());
  for (int i = 0; i < bar.size(); ++i) v0[i] = ex.initial_velocity(bar.positions()[i]);
  std::vector<double> fr = {0.2, 0.1, 0.05}, dev;
  for (double f : fr) {
    LeapfrogOptions opt;
    opt.dt = f * est.dt_limit;
    opt.max_steps = 10000;
    opt.record_every = 10;
    auto r = run_leapfrog(sys, Eigen::VectorXd::Zero(bar.size()), v0, opt);
    ASSERT_TRUE(r.completed());
    const double e0 = r.history.front().total;
    double d = 0, first = 0, last = 0;
    const std::size_t m = r.history.size(), tenth = m / 10;
    for (std::size_t k = 0; k < m; ++k) {
      d = std::max(d, std::abs(r.history[k].total - e0) / e0);
      if (k < tenth) first += r.history[k].total / tenth;
      if (k >= m - tenth) last += r.history[k].total / tenth;
    }
    dev.push_back(d);
    EXPECT_LT(std::abs(last - first) / e0, 0.1 * d) << "no secular drift, f = " << f;
    // Momentum is conserved by the symmetric form with mirror ghosts only approximately (ghost stresses act
    // as end tractions); just report it here: the study checks it against the exact solution.
  }
  for (std::size_t k = 1; k < fr.size(); ++k)
    EXPECT_NEAR(std::log2(dev[k - 1] / dev[k]), 2.0, 0.15) << dev[k];  // sampled maximum of an oscillation
}

TEST(ElasticBar, StabilityLimitPredictsBlowUp) {
  ElasticBar1D bar(bar_options(120, StrainGradient::Plain, StressDivergence::Plain, BarBoundary::Mirror));
  auto sys = bar.system();
  auto dense = estimate_stability_limit(sys.acceleration, bar.size());
  auto krylov = estimate_stability_limit(sys.acceleration, bar.size(), {.dense_limit = 0});
  ASSERT_TRUE(dense.converged && krylov.converged);
  EXPECT_EQ(krylov.method, "spectra-gen");
  EXPECT_NEAR(krylov.lambda_max, dense.lambda_max, 1e-8 * dense.lambda_max);
  EXPECT_TRUE(dense.dominant_real_positive);
  EXPECT_GT(dense.min_real, -1e-9 * dense.lambda_max);  // no exponentially growing semi-discrete mode
  const double dt_cfl = cfl_time_step(kDefaultCourant, bar.h(), bar.wave_speed());
  EXPECT_LT(dt_cfl, dense.dt_limit);
  Eigen::VectorXd u0 = Eigen::VectorXd::Zero(bar.size()), v0(bar.size());
  for (int i = 0; i < bar.size(); ++i) v0[i] = (i % 2 ? 1e-3 : -1e-3);  // sawtooth: the highest mode
  LeapfrogOptions opt;
  opt.max_steps = 3000;
  opt.limits.energy_growth = 100;
  opt.dt = 0.98 * dense.dt_limit;
  EXPECT_EQ(run_leapfrog(sys, u0, v0, opt).status, RunStatus::Completed);
  opt.dt = 1.02 * dense.dt_limit;
  auto r = run_leapfrog(sys, u0, v0, opt);
  EXPECT_EQ(r.status, RunStatus::EnergyGrowth) << r.message;
}

TEST(ElasticBar, XsphHookPreservesUniformVelocityAndRejectsBadInput) {
  ElasticBar1D bar(bar_options(30, StrainGradient::Plain, StressDivergence::Plain, BarBoundary::Mirror));
  auto hook = bar.xsph_hook(0.1);
  Eigen::VectorXd v = Eigen::VectorXd::Constant(30, -0.01), w;
  hook(Eigen::VectorXd::Zero(30), v, w);
  EXPECT_LT((w - v).cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_THROW(ElasticBar1D(bar_options(1, StrainGradient::Plain, StressDivergence::Plain, BarBoundary::Mirror)),
               std::invalid_argument);
  EXPECT_THROW(bar.xsph_hook(-1.0), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
