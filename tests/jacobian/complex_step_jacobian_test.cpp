#include "sphstab/jacobian/complex_step_jacobian.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/numerics/random_vector.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace complex_step_jacobian_test {

/// A toy force with a known Jacobian, independent of SPH: a nonlinear spring chain with fixed ends,
/// a_i = (u_{i+1} - 2 u_i + u_{i-1}) + c (u_{i+1} - u_i)^3 - c (u_i - u_{i-1})^3 + load * u_i.
class SpringChain final : public ForceFunction {
 public:
  SpringChain(int n, double c, double load, bool poison = false) : m_n(n), m_c(c), m_load(load), m_poison(poison) {}
  int dofs() const override { return m_n; }
  int dim() const override { return 1; }
  std::string name() const override { return "spring-chain"; }
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const override { eval(u, a); }
  void acceleration(const Eigen::VectorXcd& u, Eigen::VectorXcd& a) const override { eval(u, a); }
  double load() const override { return m_load; }
  std::unique_ptr<ForceFunction> with_load(double load) const override {
    return std::make_unique<SpringChain>(m_n, m_c, load, m_poison);
  }
  SparsityPattern dof_pattern() const override {
    SparsityPattern p;
    p.rows = p.cols = m_n;
    p.offsets.assign(1, 0);
    for (int i = 0; i < m_n; ++i) {
      for (int j = std::max(0, i - 1); j <= std::min(m_n - 1, i + 1); ++j) p.indices.push_back(j);
      p.offsets.push_back(static_cast<long>(p.indices.size()));
    }
    return p;
  }
  bool conservative() const override { return true; }
  double strain_energy(const Eigen::VectorXd&) const override { return 0; }
  std::complex<double> strain_energy(const Eigen::VectorXcd&) const override { return 0; }
  Eigen::VectorXd dof_mass() const override { return Eigen::VectorXd::Ones(m_n); }

  Eigen::MatrixXd exact_minus_jacobian(const Eigen::VectorXd& u) const {
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m_n, m_n);
    auto at = [&](int i) { return (i < 0 || i >= m_n) ? 0.0 : u[i]; };
    for (int i = 0; i < m_n; ++i) {
      const double dr = at(i + 1) - u[i], dl = u[i] - at(i - 1);
      J(i, i) = -2 - 3 * m_c * dr * dr - 3 * m_c * dl * dl + m_load;
      if (i + 1 < m_n) J(i, i + 1) = 1 + 3 * m_c * dr * dr;
      if (i > 0) J(i, i - 1) = 1 + 3 * m_c * dl * dl;
    }
    return -J;
  }

 private:
  template <class S>
  void eval(const Eigen::Matrix<S, Eigen::Dynamic, 1>& u, Eigen::Matrix<S, Eigen::Dynamic, 1>& a) const {
    a.resize(m_n);
    auto at = [&](int i) { return (i < 0 || i >= m_n) ? S(0) : u[i]; };
    for (int i = 0; i < m_n; ++i) {
      const S dr = at(i + 1) - u[i], dl = u[i] - at(i - 1);
      a[i] = dr - dl + m_c * dr * dr * dr - m_c * dl * dl * dl + m_load * u[i];
    }
    if (m_poison) a[m_n / 2] = S(std::nan(""));
  }
  int m_n;
  double m_c, m_load;
  bool m_poison;
};

TEST(ComplexStepJacobian, ExactOnAToyForce) {
  SpringChain chain(30, 0.7, 0.2);
  const Eigen::VectorXd u = random_vector(30, 0.5, 1);
  ComplexStepJacobian jac(chain);
  EXPECT_EQ(jac.colours(), 3);  // tridiagonal: columns i, i+3, ... share no row
  Eigen::MatrixXd A = jac.compute(u);
  EXPECT_EQ(jac.info(), Status::Successful);
  EXPECT_LE((A - chain.exact_minus_jacobian(u)).cwiseAbs().maxCoeff(), 1e-14);
  auto split = affine_jacobian(chain, u);
  EXPECT_LE((Eigen::MatrixXd(split.A1) + Eigen::MatrixXd::Identity(30, 30)).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(ComplexStepJacobian, ReportsNonFiniteForces) {
  SpringChain chain(10, 0.1, 0.0, /*poison=*/true);
  ComplexStepJacobian jac(chain);
  EXPECT_EQ(jac.info(), Status::NotComputed);
  jac.compute(Eigen::VectorXd::Zero(10));
  EXPECT_EQ(jac.info(), Status::NumericalIssue);
  EXPECT_THROW(jacobian(chain, Eigen::VectorXd::Zero(10)), std::runtime_error);
  EXPECT_THROW(jac.compute(Eigen::VectorXd::Zero(9)), std::invalid_argument);
  EXPECT_THROW(ComplexStepJacobian(chain, ColouringStrategy::Greedy, 0.0), std::invalid_argument);
}

/// Dense Jacobian, one complex evaluation per column, every row read (no pattern assumed).
Eigen::MatrixXd dense_reference(const ForceFunction& f, const Eigen::VectorXd& u) {
  const int n = f.dofs();
  Eigen::MatrixXd A(n, n);
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXcd uc = u.cast<std::complex<double>>(), a;
    uc[k] += std::complex<double>(0, 1e-30);
    f.acceleration(uc, a);
    A.col(k) = -a.imag() / 1e-30;
  }
  return A;
}

TEST(ComplexStepJacobian, ColouredEqualsDenseOnSphForms) {
  Kernel<1> k1(KernelType::CubicSpline);
  auto line = make_discretisation(
      make_lattice<1>(LatticeType::Line, 25, {.spacing = 1.0, .support_radius = 2.6, .perturbation = 0.1}), k1, 1.3);
  Kernel<2> k2(KernelType::WendlandC4);
  auto square = make_discretisation(
      make_lattice<2>(LatticeType::Square, 5, {.spacing = 1.0, .support_radius = 3.0, .perturbation = 0.1}), k2, 1.5);
  const ElasticMaterial mat = ElasticMaterial::from_lame(2.0, 1.0, 1.0);
  for (MomentumForm form : all_momentum_forms()) {
    WaveForm1D f1(line, form, 0.4);
    ElasticForm2D f2(square, mat, form, PreStrain::uniaxial_x(0.05));
    for (const ForceFunction* f : {static_cast<const ForceFunction*>(&f1), static_cast<const ForceFunction*>(&f2)}) {
      const Eigen::VectorXd u = random_vector(f->dofs(), 0.1, 5);
      Eigen::MatrixXd coloured = ComplexStepJacobian(*f).compute(u);
      Eigen::MatrixXd uncoloured = ComplexStepJacobian(*f, ColouringStrategy::None).compute(u);
      Eigen::MatrixXd reference = dense_reference(*f, u);  // also proves the pattern is a superset
      const double scale = reference.cwiseAbs().maxCoeff();
      EXPECT_LE((coloured - reference).cwiseAbs().maxCoeff(), 1e-14 * scale) << f->name();
      EXPECT_LE((uncoloured - reference).cwiseAbs().maxCoeff(), 1e-14 * scale) << f->name();
    }
  }
}

TEST(ComplexStepJacobian, ColourCountIndependentOfN) {
  // 1D, h = 1.3 dx: neighbours within 2 dx, Jacobian band +-4 -> 9 colours whatever N.
  for (int n : {20, 40, 160}) {
    Kernel<1> k(KernelType::CubicSpline);
    auto d =
        make_discretisation(make_lattice<1>(LatticeType::Line, n, {.spacing = 1.0, .support_radius = 2.6}), k, 1.3);
    ComplexStepJacobian jac(WaveForm1D(d, MomentumForm::Plus, 0.1));
    EXPECT_EQ(jac.colours(), 9) << "N = " << n;
  }
  // 2D square, h = dx (neighbours: the 8 king moves): the Jacobian couples Chebyshev distance <= 2, a row has
  // 2 x 25 = 50 entries, so at least 50 colours; any 5 x 5 block of particles is pairwise conflicting (a clique), so
  // 50 is optimal, and greedy must find the same count for every n.
  std::vector<int> counts;
  for (int n : {20, 28, 36}) {
    Kernel<2> k(KernelType::CubicSpline);
    auto d =
        make_discretisation(make_lattice<2>(LatticeType::Square, n, {.spacing = 1.0, .support_radius = 2.0}), k, 1.0);
    ComplexStepJacobian jac(ElasticForm2D(d, ElasticMaterial::from_lame(1.0, 1.0, 1.0), MomentumForm::Plus));
    EXPECT_TRUE(is_valid_column_colouring(jac.pattern(), jac.colouring()));
    EXPECT_EQ(jac.colours(), 50);
    counts.push_back(jac.colours());
  }
  EXPECT_EQ(counts[0], counts[1]);
  EXPECT_EQ(counts[1], counts[2]);
}

TEST(ComplexStepJacobian, RelativeAsymmetry) {
  Eigen::MatrixXd m(2, 2);
  m << 1, 2, 0, 1;
  EXPECT_NEAR(relative_asymmetry(m.sparseView()), std::sqrt(8.0) / std::sqrt(6.0), 1e-15);
  EXPECT_EQ(relative_asymmetry(SparseMatrix<>(3, 3)), 0.0);
}

}  // namespace
}  // namespace sphstab
