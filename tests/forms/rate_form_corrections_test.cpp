// Kernel corrections on the rate-form scheme: NCSPH (Powell 1.19) in the velocity gradient and momentum, the C_ij
// momentum form (4.10) and S-SPH (algorithm 4.2), each against an independent evaluation from the operator
// matrices (operators/ncsph.hpp, operators/local_polish.hpp) and against the properties that define it.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "forms_fixture.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/operators/local_polish.hpp"
#include "sphstab/operators/ncsph.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {
namespace rate_form_corrections_test {

using test::kGms;

/// The state's fields, unpacked independently of the scheme's evaluation (fixed particles: reference positions,
/// v = 0).
struct Fields {
  ParticleSet<2> current;  // positions x, volumes m / rho
  Eigen::MatrixX2d v;
  Eigen::VectorXd rho;
  std::vector<Eigen::Matrix2d> sigma;
};

Fields unpack(const RateFormScheme<2>& s, const Eigen::VectorXd& y) {
  const ParticleSet<2>& p = s.discretisation().particles;
  Fields f{p, Eigen::MatrixX2d::Zero(p.size(), 2), Eigen::VectorXd(p.size()), {}};
  for (int i = 0; i < p.size(); ++i) {
    if (s.position_offset(i) >= 0) {
      f.current.x.row(i) = y.segment<2>(s.position_offset(i)).transpose();
      f.v.row(i) = y.segment<2>(s.velocity_offset(i)).transpose();
    }
    const int r = s.density_offset(i);
    f.rho[i] = y[r];
    f.current.volume[i] = s.mass()[i] / f.rho[i];
    Eigen::Matrix2d sig;
    sig << y[r + 1], y[r + 3], y[r + 3], y[r + 2];
    f.sigma.push_back(sig - s.material().bulk_modulus() * (f.rho[i] / s.material().density() - 1) *
                                Eigen::Matrix2d::Identity());
  }
  return f;
}

Eigen::VectorXd acceleration(const RateFormScheme<2>& s, const Eigen::VectorXd& f, int i) {
  return f.segment<2>(s.velocity_offset(i));
}

/// A perturbed, moving, stressed state with non-uniform density.
Eigen::VectorXd random_state(const RateFormScheme<2>& s, double density_spread, std::uint64_t seed) {
  Eigen::VectorXd y = s.uniform_state() + random_vector(s.size(), 0.05, seed);
  for (int i = 0; i < s.discretisation().size(); ++i)
    y[s.density_offset(i)] = s.initial_density() * (1 + density_spread * random_vector(1, 1.0, seed + 1 + i)[0]);
  return y;
}

TEST(RateFormCorrections, NcsphVelocityGradientIsExactForLinearFieldsUpToTheBoundary) {
  // v = A x + b on a block without fixed layers: with NCSPH, drho/dt = -rho tr A and dS/dt = 2 mu dev sym A at every
  // particle (boundary and corners included); the plain gradient is wrong at the boundary.
  const auto disc = test::lattice_discretisation<2>({.n = 9, .h = 1.3, .perturbation = 0.2, .fixed_layers = 0});
  Eigen::Matrix2d A;
  A << 0.3, -0.2, 0.5, 0.1;
  const Eigen::Vector2d b(0.7, -0.4);
  const Eigen::Matrix2d D = 0.5 * (A + A.transpose());
  for (RateFormGradient g : {RateFormGradient::Ncsph, RateFormGradient::Plain}) {
    const RateFormScheme<2> s(disc, kGms, {.continuity = ContinuityForm::Divergence, .gradient = g}, 1.1);
    Eigen::VectorXd y = s.uniform_state(), f;
    for (int i = 0; i < disc->size(); ++i) {
      const Eigen::Vector2d x = disc->particles.x.row(i).transpose();
      y.segment<2>(s.velocity_offset(i)) = A * x + b;
    }
    s.rate(y, f);
    double err = 0;
    for (int i = 0; i < disc->size(); ++i) {
      const int r = s.density_offset(i);
      const Eigen::Matrix2d dev = 2 * kGms.mu() * (D - D.trace() / 3 * Eigen::Matrix2d::Identity());
      err = std::max({err, std::abs(f[r] + 1.1 * A.trace()), std::abs(f[r + 1] - dev(0, 0)),
                      std::abs(f[r + 2] - dev(1, 1)), std::abs(f[r + 3] - dev(0, 1))});
    }
    if (g == RateFormGradient::Ncsph)
      EXPECT_LT(err, 1e-13);
    else
      EXPECT_GT(err, 1e-2);  // the test can tell
  }
}

TEST(RateFormCorrections, NcsphMatchesTheOperatorMatrixRoute) {
  // Powell (1.19) from operators/ncsph.hpp at the current positions and volumes m / rho; then L, the divergence
  // continuity and the row momentum (1.36) (self term included) written from the matrices.
  const auto disc = test::lattice_discretisation<2>({.n = 7, .h = 1.3, .fixed_layers = 1});
  for (RateFormMomentum m : {RateFormMomentum::Symmetric, RateFormMomentum::Antisymmetric}) {
    const RateFormScheme<2> s(
        disc, kGms, {.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph, .momentum = m},
        1.0 / 1.03);
    const Eigen::VectorXd y = random_state(s, 0.05, 3);
    Eigen::VectorXd f;
    s.rate(y, f);
    const Fields fl = unpack(s, y);
    const NeighbourList& nl = disc->neighbours;
    const auto ops = assemble_operators(fl.current, nl, disc->kernel, disc->h);
    const auto G = ncsph_gradient<2, double>(fl.current, ops.W, ops.G);
    auto entry = [&](int i, long k) { return Eigen::Vector2d(G[0].valuePtr()[k], G[1].valuePtr()[k]); };
    double worst = 0, scale = 0;
    for (int i = 0; i < disc->size(); ++i) {
      Eigen::Matrix2d L = Eigen::Matrix2d::Zero();
      Eigen::Vector2d a = Eigen::Vector2d::Zero();
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        L += (fl.v.row(j) - fl.v.row(i)).transpose() * entry(i, k).transpose();
        const Eigen::Matrix2d bracket = fl.sigma[i] / (fl.rho[i] * fl.rho[i]) + fl.sigma[j] / (fl.rho[j] * fl.rho[j]);
        if (m == RateFormMomentum::Symmetric) {
          a += fl.rho[j] * bracket * entry(i, k);
        } else if (j != i) {
          const long kt =
              std::lower_bound(nl.indices.begin() + nl.offsets[j], nl.indices.begin() + nl.offsets[j + 1], i) -
              nl.indices.begin();
          a += s.mass()[j] * bracket *
               (0.5 * (entry(i, k) / fl.current.volume[j] - entry(j, kt) / fl.current.volume[i]));
        }
      }
      const int r = s.density_offset(i);
      worst = std::max(worst, std::abs(f[r] + fl.rho[i] * L.trace()));
      scale = std::max(scale, std::abs(f[r]));
      if (s.velocity_offset(i) >= 0) {
        worst = std::max(worst, (acceleration(s, f, i) - a).cwiseAbs().maxCoeff());
        scale = std::max(scale, a.cwiseAbs().maxCoeff());
      }
    }
    EXPECT_LT(worst, 1e-12 * scale) << static_cast<int>(m);
  }
}

TEST(RateFormCorrections, CijAndSsphMatchTheLiteralAlgorithms) {
  // (4.10) with C = local_polish(P, counts) of P = V_j grad W_ij at the current state, and algorithm 4.2 written as
  // printed: for every particle i and j in N(i), a_i += (f_ij + g_ij)/2, a_j -= (f_ij + g_ij)/2.
  const auto disc = test::lattice_discretisation<2>({.n = 7, .h = 1.3, .fixed_layers = 2});
  const NeighbourList& nl = disc->neighbours;
  for (SwitchRule rule : {SwitchRule::Tension, SwitchRule::AsPrinted, SwitchRule::Always}) {
    for (RateFormMomentum m : {RateFormMomentum::Cij, RateFormMomentum::StabilisedSph}) {
      if (m == RateFormMomentum::Cij && rule != SwitchRule::Tension) continue;
      const RateFormScheme<2> s(disc, kGms, {.momentum = m, .switch_rule = rule}, 1.0 / 1.03);
      const Eigen::VectorXd y = random_state(s, 0.05, 9);
      Eigen::VectorXd f;
      s.rate(y, f);
      const Fields fl = unpack(s, y);
      const int n = disc->size();
      const auto ops = assemble_operators(fl.current, nl, disc->kernel, disc->h);
      const Eigen::VectorXd counts = neighbour_counts(disc->particles, nl, NeighbourCounting::Actual);
      std::array<LocalMeans<double>, 2> means{local_means(ops.G[0], counts), local_means(ops.G[1], counts)};
      Eigen::MatrixX2d a = Eigen::MatrixX2d::Zero(n, 2);
      for (int i = 0; i < n; ++i) {
        std::array<bool, 2> on{};
        for (int al = 0; al < 2; ++al) {
          double sum = 0;
          for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) sum += fl.sigma[nl.indices[k]](al, al);
          on[al] = rule == SwitchRule::Always || (rule == SwitchRule::Tension ? sum > 0 : sum <= 0);
          if (disc->particles.depth[i] == 0) on[al] = false;  // BP
        }
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
          const int j = nl.indices[k];
          const Eigen::Vector2d P(ops.G[0].valuePtr()[k], ops.G[1].valuePtr()[k]);
          Eigen::Vector2d rcm;  // r_i + c_j - m_i
          for (int al = 0; al < 2; ++al)
            rcm[al] = means[al].row[i] + means[al].column[j] - means[al].mean_of_columns[i];
          if (m == RateFormMomentum::Cij) {
            a.row(i) += (fl.sigma[j] / fl.rho[j] * (P - rcm)).transpose();
            continue;
          }
          const Eigen::Matrix2d Sij = fl.sigma[i] / fl.rho[i] + fl.sigma[j] / fl.rho[j];
          const Eigen::Vector2d fij = Sij * P;
          Eigen::Vector2d gij = -Sij * rcm;
          for (int al = 0; al < 2; ++al)
            if (!on[al]) gij[al] = 0;
          a.row(i) += 0.5 * (fij + gij).transpose();
          a.row(j) -= 0.5 * (fij + gij).transpose();
        }
      }
      double worst = 0, scale = 0;
      for (int i = 0; i < n; ++i)
        if (s.velocity_offset(i) >= 0) {
          worst = std::max(worst, (acceleration(s, f, i) - a.row(i).transpose()).cwiseAbs().maxCoeff());
          scale = std::max(scale, a.row(i).cwiseAbs().maxCoeff());
        }
      EXPECT_LT(worst, 1e-12 * scale) << s.name();
    }
  }
}

/// Powell (4.18), written out: the first-step Shepard gradient Gt^a_ik = (G^a_ik S0_i - Wv_ik G0^a_i) / S0_i^2 at the
/// state of `fl` (G = V_k grad W_ik, Wv = V_k W_ik at the current positions and volumes), with the sums S0_i = sum_k
/// V0_k W0_ik and G0_i = sum_k V0_k grad W0_ik of the discretisation's particles; as sparse matrices on the list.
std::array<SparseMatrix<>, 2> shepard_gradient(const Discretisation<2>& d, const Fields& fl, const Operators<2>& ops) {
  const NeighbourList& nl = d.neighbours;
  const auto W = [&](const Eigen::Vector2d& r) { return d.kernel.value(r.norm(), d.h); };
  const auto gW = [&](const Eigen::Vector2d& r) -> Eigen::Vector2d {
    const double rr = r.norm();
    return rr > 0 ? Eigen::Vector2d(d.kernel.d1(rr, d.h) / rr * r) : Eigen::Vector2d::Zero();
  };
  std::array<SparseMatrix<>, 2> gt{ops.G[0], ops.G[1]};
  for (int i = 0; i < d.size(); ++i) {
    double s0 = 0;
    Eigen::Vector2d g0 = Eigen::Vector2d::Zero();
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      const Eigen::Vector2d r0 = (d.particles.x.row(i) - d.particles.x.row(j)).transpose();
      s0 += d.particles.volume[j] * W(r0);
      g0 += d.particles.volume[j] * gW(r0);
    }
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      const double wv = fl.current.volume[j] * W((fl.current.x.row(i) - fl.current.x.row(j)).transpose());
      for (int a = 0; a < 2; ++a)
        gt[a].valuePtr()[k] = (ops.G[a].valuePtr()[k] * s0 - wv * g0[a]) / (s0 * s0);
    }
  }
  return gt;
}

// S-SPH with the means of Powell's first-step Shepard gradient (4.18): the scheme against algorithm 4.2 written out
// with local_polish's means of Gt (operators/local_polish.hpp), at a perturbed, moving, stressed state of a block with
// free surfaces; and at the first step (the reference positions and densities) the row mean of Gt vanishes, where the
// raw one is largest, at the surface.
TEST(RateFormCorrections, SsphFirstStepShepardMeans) {
  const auto disc = test::lattice_discretisation<2>({.n = 7, .h = 1.3, .fixed_layers = 0});
  const NeighbourList& nl = disc->neighbours;
  const int n = disc->size();
  const Eigen::VectorXd counts = neighbour_counts(disc->particles, nl, NeighbourCounting::Actual);
  Eigen::VectorXd dev(3);
  dev << 0.02, -0.01, 0.005;
  const RateFormScheme<2> s(disc, kGms,
                            {.momentum = RateFormMomentum::StabilisedSph, .switch_rule = SwitchRule::Always,
                             .excluded_depth = -1, .first_step_shepard = true},
                            1.0, dev);
  {  // first step: r_i = 0 to rounding; the raw r_i is O(1 / dx) at the surface
    const Fields fl = unpack(s, s.uniform_state());
    const auto ops = assemble_operators(fl.current, nl, disc->kernel, disc->h);
    const double raw = local_means(ops.G[0], counts).row.cwiseAbs().maxCoeff();
    EXPECT_GT(raw, 0.02);
    for (const SparseMatrix<>& g : shepard_gradient(*disc, fl, ops))
      EXPECT_LT(local_means(g, counts).row.cwiseAbs().maxCoeff(), 1e-15 * std::max(raw, 1.0));
  }
  const Eigen::VectorXd y = random_state(s, 0.05, 9);
  Eigen::VectorXd f;
  s.rate(y, f);
  const Fields fl = unpack(s, y);
  const auto ops = assemble_operators(fl.current, nl, disc->kernel, disc->h);
  const std::array<SparseMatrix<>, 2> gt = shepard_gradient(*disc, fl, ops);
  const std::array<LocalMeans<double>, 2> means{local_means(gt[0], counts), local_means(gt[1], counts)};
  const std::array<LocalMeans<double>, 2> raw{local_means(ops.G[0], counts), local_means(ops.G[1], counts)};
  double moved = 0;  // how far (4.18) moves the means at this state: the comparison below must be able to tell
  for (int a = 0; a < 2; ++a)
    moved = std::max({moved, (means[a].row - raw[a].row).cwiseAbs().maxCoeff(),
                      (means[a].column - raw[a].column).cwiseAbs().maxCoeff()});
  EXPECT_GT(moved, 1e-2);
  Eigen::MatrixX2d a = Eigen::MatrixX2d::Zero(n, 2);
  for (int i = 0; i < n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      const Eigen::Vector2d P(ops.G[0].valuePtr()[k], ops.G[1].valuePtr()[k]);
      Eigen::Vector2d rcm;
      for (int al = 0; al < 2; ++al)
        rcm[al] = means[al].row[i] + means[al].column[j] - means[al].mean_of_columns[i];
      const Eigen::Matrix2d Sij = fl.sigma[i] / fl.rho[i] + fl.sigma[j] / fl.rho[j];
      const Eigen::Vector2d fg = Sij * P - Sij * rcm;
      a.row(i) += 0.5 * fg.transpose();
      a.row(j) -= 0.5 * fg.transpose();
    }
  double worst = 0, scale = 0;
  for (int i = 0; i < n; ++i) {
    worst = std::max(worst, (acceleration(s, f, i) - a.row(i).transpose()).cwiseAbs().maxCoeff());
    scale = std::max(scale, a.row(i).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-12 * scale);
  // The sums are the first step's: a scheme rebuilt at y (the same pairs: no pair crosses the support at this
  // perturbation) keeps them, so its rates are the same; recomputed at y they would differ by O(perturbation).
  Eigen::VectorXd fr;
  s.rebuilt(y).rate(y, fr);
  EXPECT_LT((fr - f).cwiseAbs().maxCoeff(), 1e-12 * f.cwiseAbs().maxCoeff());
  // Bad input: (4.18) belongs to S-SPH.
  try {
    RateFormScheme<2>(disc, kGms, {.momentum = RateFormMomentum::Cij, .first_step_shepard = true});
    ADD_FAILURE() << "first_step_shepard without S-SPH was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("first_step_shepard"), std::string::npos) << e.what();
  }
}

TEST(RateFormCorrections, UniformStressForceAndMomentumConservation) {
  // Rows of NCSPH and C_ij sum to zero: a uniform stress at uniform density exerts no force at perturbed positions
  // (no initial-stress stiffness), while the plain and antisymmetrised forms do. The antisymmetrised NCSPH and S-SPH
  // (symmetrised pairs) conserve momentum on a periodic lattice; the row form does not.
  const auto disc = test::lattice_discretisation<2>({.n = 8, .h = 1.3, .periodic = true, .perturbation = 0.2});
  Eigen::VectorXd dev(3);
  dev << 0.02, -0.01, 0.005;
  struct Case {
    RateFormOptions o;
    bool zero_force, conserves;
  };
  const std::vector<Case> cases = {
      {{}, false, true},
      {{.gradient = RateFormGradient::Ncsph}, true, false},
      {{.gradient = RateFormGradient::Ncsph, .momentum = RateFormMomentum::Antisymmetric}, false, true},
      {{.momentum = RateFormMomentum::Cij}, true, false},
      {{.momentum = RateFormMomentum::StabilisedSph, .switch_rule = SwitchRule::Always, .excluded_depth = -1},
       false,
       true}};
  for (const Case& c : cases) {
    const RateFormScheme<2> s(disc, kGms, c.o, 1.0 / 1.03, dev);
    Eigen::VectorXd f;
    s.rate(s.uniform_state(), f);  // the perturbed lattice, at rest, uniform state
    double amax = 0;
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    for (int i = 0; i < disc->size(); ++i) {
      amax = std::max(amax, acceleration(s, f, i).cwiseAbs().maxCoeff());
      p += s.mass()[i] * acceleration(s, f, i);
    }
    if (c.zero_force)
      EXPECT_LT(amax, 1e-14) << s.name();
    else
      EXPECT_GT(amax, 1e-4) << s.name();
    // Momentum with a non-uniform state.
    s.rate(random_state(s, 0.0, 21), f);
    p.setZero();
    double scale = 0;
    for (int i = 0; i < disc->size(); ++i) {
      p += s.mass()[i] * acceleration(s, f, i);
      scale += s.mass()[i] * acceleration(s, f, i).norm();
    }
    if (c.conserves)
      EXPECT_LT(p.norm(), 1e-13 * scale) << s.name();
    else
      EXPECT_GT(p.norm(), 1e-6 * scale) << s.name();
  }
}

TEST(RateFormCorrections, ComplexStepJacobianMatchesFiniteDifferences) {
  const auto disc = test::lattice_discretisation<2>({.n = 5, .h = 1.3, .fixed_layers = 2});
  const std::vector<RateFormOptions> variants = {
      {.xsph = 0.5, .gradient = RateFormGradient::Ncsph},
      {.gradient = RateFormGradient::Ncsph, .momentum = RateFormMomentum::Antisymmetric},
      {.continuity = ContinuityForm::Divergence, .momentum = RateFormMomentum::Cij},
      {.xsph = 0.5, .momentum = RateFormMomentum::StabilisedSph}};
  for (const RateFormOptions& o : variants) {
    const RateFormScheme<2> s(disc, kGms, o, 1.0 / 1.03);
    const Eigen::VectorXd y = random_state(s, 0.02, 5);
    const Eigen::MatrixXd J(jacobian(s, y));
    Eigen::MatrixXd fd(s.size(), s.size());
    Eigen::VectorXd fp, fm;
    for (int k = 0; k < s.size(); ++k) {
      Eigen::VectorXd yp = y, ym = y;
      yp[k] += 1e-6;
      ym[k] -= 1e-6;
      s.rate(yp, fp);
      s.rate(ym, fm);
      fd.col(k) = (fp - fm) / 2e-6;
    }
    EXPECT_LT((J - fd).cwiseAbs().maxCoeff(), 1e-6 * J.cwiseAbs().maxCoeff()) << s.name();
  }
}

TEST(RateFormCorrections, SsphNeverIsBasicSphAndBadInput) {
  // At uniform density (4.13) equals (1.36): S-SPH with the switch never on is basic SPH.
  const auto disc = test::lattice_discretisation<2>({.n = 6, .h = 1.3, .perturbation = 0.2});
  const RateFormScheme<2> plain(disc, kGms, {}, 1.0 / 1.02);
  const RateFormScheme<2> never(
      disc, kGms, {.momentum = RateFormMomentum::StabilisedSph, .switch_rule = SwitchRule::Never}, 1.0 / 1.02);
  Eigen::VectorXd y = random_state(plain, 0.0, 4), f1, f2;
  plain.rate(y, f1);
  never.rate(y, f2);
  EXPECT_LT((f1 - f2).cwiseAbs().maxCoeff(), 1e-13 * f1.cwiseAbs().maxCoeff());
  EXPECT_THROW(RateFormScheme<2>(disc, kGms, {.gradient = RateFormGradient::Ncsph, .momentum = RateFormMomentum::Cij}),
               std::invalid_argument);
  EXPECT_THROW(RateFormScheme<2>(disc, kGms, {.momentum = RateFormMomentum::StabilisedSph, .excluded_depth = -2}),
               std::invalid_argument);
  EXPECT_THROW(parse_rate_form_gradient("corrected"), std::invalid_argument);
  EXPECT_THROW(parse_rate_form_momentum("plus"), std::invalid_argument);
  EXPECT_EQ(parse_rate_form_momentum("ssph"), RateFormMomentum::StabilisedSph);
  // A particle whose neighbours lie on a line has a singular NCSPH moment matrix: a clear error, not NaN.
  ParticleSet<2> line;
  line.x = Eigen::MatrixX2d::Zero(6, 2);
  for (int i = 0; i < 6; ++i) line.x(i, 0) = i;
  line.volume = Eigen::VectorXd::Ones(6);
  line.role.assign(6, Role::Free);
  line.depth.assign(6, 0);
  line.spacing = 1;
  const auto flat = make_discretisation(line, disc->kernel, disc->h);
  const RateFormScheme<2> bad(flat, kGms, {.gradient = RateFormGradient::Ncsph});
  EXPECT_THROW(bad.rate(bad.uniform_state(), f1), std::domain_error);
  // A non-finite state: the NCSPH moment matrix is refused before its SVD (which would leave garbage), every time.
  const RateFormScheme<2> ncsph(disc, kGms, {.gradient = RateFormGradient::Ncsph}, 1.0 / 1.02);
  Eigen::VectorXd nan_state = ncsph.uniform_state();
  nan_state[ncsph.position_offset(disc->free[3])] = std::numeric_limits<double>::quiet_NaN();
  for (int repeat = 0; repeat < 3; ++repeat) {
    try {
      ncsph.rate(nan_state, f1);
      ADD_FAILURE() << "no exception for a NaN position";
    } catch (const std::domain_error& e) {
      EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
    }
  }
}

TEST(RateFormCorrections, MinDensityIsTheSmallestCarriedDensity) {
  const auto disc = test::lattice_discretisation<2>({.n = 4, .h = 1.3});
  const RateFormScheme<2> s(disc, kGms, {}, 1.0 / 0.98);  // compressed: every density above rho0
  Eigen::VectorXd y = s.uniform_state();
  EXPECT_EQ(s.min_density(y), 1.0 / 0.98);
  y[s.density_offset(disc->free[2])] = 1.05;
  y[s.density_offset(disc->free[0])] = 1.03;
  for (int i = 0; i < disc->size(); ++i)
    if (s.density_offset(i) >= 0 && i != disc->free[0] && i != disc->free[2]) y[s.density_offset(i)] = 1.2;
  EXPECT_EQ(s.min_density(y), 1.03);
}

}  // namespace
}  // namespace sphstab
