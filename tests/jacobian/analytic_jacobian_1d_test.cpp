// The closed form A(T) = K - n T L (Powell (3.40)) against complex-step differentiation of the force functions
// themselves, written here independently from the definitions of docs/conventions.md §4.
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"

#include <gtest/gtest.h>

#include <complex>
#include <random>

#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace analytic_jacobian_1d_test {

using C = std::complex<double>;
using VecC = Eigen::VectorXcd;

struct Lattice1D {
  ParticleSet<1> p;
  Kernel<1> kernel;
  double h;
  NeighbourList nl;
  Lattice1D(KernelType type, double h_, int nfree, bool periodic = false)
      : p(make_lattice<1>(LatticeType::Line, nfree, {.spacing = 1.0, .support_radius = 2 * h_, .periodic = periodic})),
        kernel(type),
        h(h_),
        nl(find_neighbours(p, kernel.support_radius(h_))) {}

  Operators<1, C> ops_at(const VecC& u) const {
    Positions<1, C> x = p.x.cast<C>();
    x.col(0) += u;
    return assemble_operators<1, C>(p, nl, kernel, h, {.kernel = false, .gradient = true, .hessian = true}, &x);
  }
  /// s_i = sum_j (u_j - u_i) G_ij(x + u) + T for every particle.
  VecC stress(const Operators<1, C>& o, const VecC& u, double t) const {
    const SparseMatrix<C>& g = o.G[0];
    VecC s = VecC::Constant(p.size(), C(t));
    for (int i = 0; i < p.size(); ++i)
      for (SparseMatrix<C>::InnerIterator it(g, i); it; ++it) s[i] += (u[it.col()] - u[i]) * it.value();
    return s;
  }
  /// f_i = sum_j (s_j + alpha s_i) G_ij (uncorrected alpha = 0, plus 1, minus -1).
  VecC force_alpha(const VecC& u, double t, double alpha) const {
    auto o = ops_at(u);
    VecC s = stress(o, u, t), f = VecC::Zero(p.size());
    for (int i = 0; i < p.size(); ++i)
      for (SparseMatrix<C>::InnerIterator it(o.G[0], i); it; ++it) f[i] += (s[it.col()] + alpha * s[i]) * it.value();
    return f;
  }
  /// Powell (3.27): f_k = sum_i (s_k + s_i) (G_ki + (u_k - u_i) H_ki).
  VecC force_conservative(const VecC& u, double t) const {
    auto o = ops_at(u);
    VecC s = stress(o, u, t), f = VecC::Zero(p.size());
    for (int k = 0; k < p.size(); ++k)
      for (SparseMatrix<C>::InnerIterator it(o.G[0], k); it; ++it) {
        const int i = it.col();
        f[k] += (s[k] + s[i]) * (it.value() + (u[k] - u[i]) * o.H[0][0].coeff(k, i));
      }
    return f;
  }
  /// U = 1/2 sum over ALL particles of s_i^2 (Powell (3.22) with c = 1).
  C energy(const VecC& u, double t) const {
    VecC s = stress(ops_at(u), u, t);
    return 0.5 * (s.array() * s.array()).sum();
  }
};

/// A = -df/du on the free block by complex step (exact to rounding).
template <class F>
Eigen::MatrixXd jacobian_by_complex_step(const Lattice1D& s, F force) {
  const std::vector<int> free = s.p.indices(Role::Free);
  const int nf = static_cast<int>(free.size());
  const double eps = 1e-30;
  Eigen::MatrixXd a(nf, nf);
  for (int c = 0; c < nf; ++c) {
    VecC u = VecC::Zero(s.p.size());
    u[free[c]] = C(0, eps);
    VecC f = force(u);
    for (int r = 0; r < nf; ++r) a(r, c) = -f[free[r]].imag() / eps;
  }
  return a;
}

TEST(AnalyticJacobian1D, MatchesComplexStepOfEveryForm) {
  const double t = 0.37;
  for (auto [type, h] : {std::pair{KernelType::QuinticSpline, 1.3}, std::pair{KernelType::CubicSpline, 1.7},
                         std::pair{KernelType::WendlandC4, 2.2}}) {
    Lattice1D s(type, h, 12);
    const Linearisation jac = analytic_jacobian_1d(s.p, s.kernel, h);  // uncorrected: A0 = K, A1 = -L
    ASSERT_EQ(jac.dofs(), 12);
    ASSERT_TRUE(jac.symmetric);
    const double scale = Eigen::MatrixXd(jac.A0).norm() + t * Eigen::MatrixXd(jac.A1).norm();
    for (const auto& form_alpha : {std::pair{MomentumForm::Uncorrected, 0.0}, std::pair{MomentumForm::Plus, 1.0},
                                   std::pair{MomentumForm::Minus, -1.0}}) {
      const MomentumForm form = form_alpha.first;  // named variables: the lambda captures alpha (clang 14 cannot
      const double alpha = form_alpha.second;      // capture a structured binding)
      Eigen::MatrixXd cs = jacobian_by_complex_step(s, [&](const VecC& u) { return s.force_alpha(u, t, alpha); });
      Eigen::MatrixXd closed = Eigen::MatrixXd(analytic_jacobian_1d(s.p, s.kernel, h, form).at(t));
      EXPECT_LT((cs - closed).norm(), 1e-13 * scale) << kernel_name(type) << " " << momentum_form_name(form);
    }
    Eigen::MatrixXd cs = jacobian_by_complex_step(s, [&](const VecC& u) { return s.force_conservative(u, t); });
    const Linearisation cons = analytic_jacobian_1d(s.p, s.kernel, h, MomentumForm::Conservative);
    EXPECT_LT((cs - Eigen::MatrixXd(cons.at(t))).norm(), 1e-13 * scale) << kernel_name(type) << " conservative";
    // A1 = -n L exactly (n = 4 is a power of two).
    EXPECT_EQ(Eigen::MatrixXd(cons.A1), -4.0 * Eigen::MatrixXd(-jac.A1)) << kernel_name(type);
  }
}

TEST(AnalyticJacobian1D, ConservativeForceIsMinusEnergyGradient) {
  // Powell (3.27) = -dU/du with U summed over free AND fixed particles, at a random displaced state.
  Lattice1D s(KernelType::CubicSpline, 1.4, 10);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> dist(-0.05, 0.05);
  VecC u = VecC::Zero(s.p.size());
  for (int i : s.p.indices(Role::Free)) u[i] = dist(rng);
  const double t = 0.2, eps = 1e-30;
  VecC f = s.force_conservative(u, t);
  for (int k : s.p.indices(Role::Free)) {
    VecC up = u;
    up[k] += C(0, eps);
    const double dudk = s.energy(up, t).imag() / eps;
    EXPECT_NEAR(f[k].real(), -dudk, 1e-13 * (1 + std::abs(dudk)));
  }
}

TEST(AnalyticJacobian1D, StructureOfKAndL) {
  Lattice1D s(KernelType::Gaussian, 1.6, 20);
  const Linearisation jac = analytic_jacobian_1d(s.p, s.kernel, s.h);
  Eigen::MatrixXd k = jac.A0, l = -Eigen::MatrixXd(jac.A1);
  EXPECT_LT((k - k.transpose()).norm(), 1e-14 * k.norm());
  EXPECT_LT((l - l.transpose()).norm(), 1e-14 * l.norm());
  // Diagonal of K = sum over ALL j of G_ij^2 (free and fixed neighbours): the same for every free particle.
  for (int i = 1; i < 20; ++i) EXPECT_NEAR(k(i, i), k(0, 0), 1e-13 * k(0, 0));
  // Periodic lattice: translation is a null vector of both.
  Lattice1D per(KernelType::Gaussian, 1.6, 21, true);
  const Linearisation pj = analytic_jacobian_1d(per.p, per.kernel, per.h);
  EXPECT_TRUE(pj.periodic);
  Eigen::VectorXd one = Eigen::VectorXd::Ones(21);
  EXPECT_LT((pj.A0 * one).norm(), 1e-13);
  EXPECT_LT((pj.A1 * one).norm(), 1e-13);
}

TEST(AnalyticJacobian1D, RejectsIrregularSetsAndMissingOperators) {
  Kernel<1> k(KernelType::CubicSpline);
  auto p = make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .support_radius = 2.6, .perturbation = 0.1});
  EXPECT_THROW(analytic_jacobian_1d(p, k, 1.3), std::invalid_argument);
  auto q = make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .fixed_layers = 1});  // incomplete layers
  EXPECT_THROW(analytic_jacobian_1d(q, k, 1.3), std::invalid_argument);
  auto r = make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .support_radius = 2.6});
  auto nl = find_neighbours(r, 2.6);
  auto ops = assemble_operators(r, nl, k, 1.3, {.kernel = false, .gradient = true, .hessian = false});
  EXPECT_THROW(analytic_jacobian_1d(r, ops), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
