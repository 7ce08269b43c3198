// The matrix-free rate-form Jacobian product (complex_step_product.hpp) against the assembled coloured complex-step
// J (complex_step_jacobian.hpp) and a central finite difference of the rate; and the leading eigenvalue of J by
// Spectra on the product against the dense spectrum of the assembled J.
#include "sphstab/jacobian/complex_step_product.hpp"

#include <Spectra/GenEigsSolver.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "../forms/forms_fixture.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace sphstab {
namespace complex_step_product_test {

using test::kGms;

TEST(ComplexStepProduct, IsTheAssembledJacobianTimesTheVector) {
  // Stretched (xi = 1.02) block with a deviator, viscosity, XSPH and the artificial stress: every term of F.
  const auto disc = test::lattice_discretisation<2>({.n = 6, .h = 1.3, .periodic = false});
  Eigen::VectorXd dev(3);
  dev << 0.004, -0.002, 0.001;
  const RateFormScheme<2> scheme(
      disc, kGms, {.xsph = 0.5, .viscosity = ViscositySwitch::Always, .artificial_stress = 0.3}, 1.0 / 1.02, dev);
  Eigen::VectorXd y0 = scheme.uniform_state();
  y0 += 1e-3 * random_vector(static_cast<int>(y0.size()), 1.0, 3).cwiseProduct(y0.cwiseAbs());  // off the uniform state
  const SparseMatrix<> J = jacobian(scheme, y0);
  const ComplexStepProduct jv(scheme, y0);
  for (unsigned seed : {1u, 2u}) {
    const Eigen::VectorXd x = random_vector(static_cast<int>(y0.size()), 1.0, seed);
    Eigen::VectorXd y(y0.size());
    jv.apply(x, y);
    const Eigen::VectorXd ref = J * x;
    EXPECT_LT((y - ref).cwiseAbs().maxCoeff(), 1e-13 * ref.cwiseAbs().maxCoeff()) << "seed " << seed;
    // Independent of complex arithmetic: central difference, error O(eps^2) + round-off / eps.
    const double eps = 1e-6;
    Eigen::VectorXd fp, fm;
    scheme.rate(Eigen::VectorXd(y0 + eps * x), fp);
    scheme.rate(Eigen::VectorXd(y0 - eps * x), fm);
    const Eigen::VectorXd fd = (fp - fm) / (2 * eps);
    EXPECT_LT((y - fd).cwiseAbs().maxCoeff(), 1e-6 * ref.cwiseAbs().maxCoeff()) << "seed " << seed;
  }
  EXPECT_EQ(jv.products(), 2);
  Eigen::VectorXd zero = Eigen::VectorXd::Zero(y0.size()), y(y0.size());
  jv.apply(zero, y);
  EXPECT_EQ(y.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ComplexStepProduct, ExactAtLengthsFarFromOne) {
  // Issue 36: a step of 1e-30 / max|x| is not small against positions at dx = 1e-40 (nor exact against velocities at
  // 1e58). The product must equal the assembled J x (per-column steps) at every supported length, and rescale exactly:
  // with lengths times L and the material fixed (velocities unchanged, times times L), x = r o variable_scale() keeps
  // its velocity, density and stress entries, and J x (in the units of F = dy/dt) has its position rows unchanged and
  // its velocity, density and stress rows times 1/L.
  Eigen::VectorXd at_one;
  for (double L : {1.0, 1e-40, 1e40}) {
    const auto disc = test::lattice_discretisation<2>({.n = 5, .h = 1.3, .periodic = false, .spacing = L});
    Eigen::VectorXd dev(3);
    dev << 0.004, -0.002, 0.001;
    const RateFormScheme<2> scheme(disc, kGms, {.xsph = 0.5, .viscosity = ViscositySwitch::Always}, 1.0 / 1.02, dev);
    Eigen::VectorXd y0 = scheme.uniform_state();
    const Eigen::VectorXd s = scheme.variable_scale();
    const Eigen::VectorXd x = random_vector(static_cast<int>(y0.size()), 1.0, 7).cwiseProduct(s);
    const SparseMatrix<> J = jacobian(scheme, y0);
    Eigen::VectorXd y(y0.size());
    ComplexStepProduct(scheme, y0).apply(x, y);
    const Eigen::VectorXd ref = J * x;
    Eigen::VectorXd rescaled = y;
    for (int i = 0; i < scheme.discretisation().size(); ++i) {
      if (scheme.velocity_offset(i) >= 0) rescaled.segment(scheme.velocity_offset(i), 2) *= L;
      if (scheme.density_offset(i) >= 0) rescaled.segment(scheme.density_offset(i), 4) *= L;
    }
    EXPECT_LT((y - ref).cwiseAbs().maxCoeff(), 1e-12 * ref.cwiseAbs().maxCoeff()) << "L = " << L;
    // A vector of unit entries, as an eigensolver starts from: its position entries are 1e40 times the positions at
    // L = 1e-40, so only a step scaled by the variables keeps h x small against them.
    const Eigen::VectorXd u = random_vector(static_cast<int>(y0.size()), 1.0, 8);
    Eigen::VectorXd yu(y0.size());
    ComplexStepProduct(scheme, y0).apply(u, yu);
    const Eigen::VectorXd ref_u = J * u;
    EXPECT_LT((yu - ref_u).cwiseAbs().maxCoeff(), 1e-12 * ref_u.cwiseAbs().maxCoeff()) << "unit vector, L = " << L;
    if (L == 1.0)
      at_one = rescaled;
    else
      EXPECT_LT((rescaled - at_one).cwiseAbs().maxCoeff(), 1e-12 * at_one.cwiseAbs().maxCoeff()) << "L = " << L;
  }
}

TEST(ComplexStepProduct, SpectraFindsTheLeadingEigenvalueMatrixFree) {
  // Tension without artificial stress: J has growing modes; the largest real part from Spectra on the product must
  // be that of the dense spectrum of the assembled J.
  const auto disc = test::lattice_discretisation<2>({.n = 6, .h = 1.3, .periodic = false});
  const RateFormScheme<2> scheme(disc, kGms, {}, 1.0 / 1.05);
  const Eigen::VectorXd y0 = scheme.uniform_state();
  const Eigen::MatrixXd J = Eigen::MatrixXd(jacobian(scheme, y0));
  const Eigen::EigenSolver<Eigen::MatrixXd> dense(J, false);
  ASSERT_EQ(dense.info(), Eigen::Success);
  const double top = dense.eigenvalues().real().maxCoeff();
  ASSERT_GT(top, 0);  // the stretched block is unstable
  ComplexStepProduct jv(scheme, y0);
  Spectra::GenEigsSolver<ComplexStepProduct> eigs(jv, 2, 40);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestReal, 5000, 1e-12);
  ASSERT_EQ(eigs.info(), Spectra::CompInfo::Successful);
  EXPECT_NEAR(eigs.eigenvalues()[0].real(), top, 1e-9 * top);
  EXPECT_GT(jv.products(), 0);
}

TEST(ComplexStepProduct, RejectsBadInput) {
  const auto disc = test::lattice_discretisation<2>({.n = 4, .h = 1.3, .periodic = false});
  const RateFormScheme<2> scheme(disc, kGms);
  const Eigen::VectorXd y0 = scheme.uniform_state();
  EXPECT_THROW(ComplexStepProduct(scheme, Eigen::VectorXd::Zero(3)), std::invalid_argument);
  Eigen::VectorXd bad = y0;
  bad[0] = NAN;
  EXPECT_THROW(ComplexStepProduct(scheme, bad), std::invalid_argument);
  EXPECT_THROW(ComplexStepProduct(scheme, y0, 0.0), std::invalid_argument);
  const ComplexStepProduct jv(scheme, y0);
  Eigen::VectorXd x(3), y(3);
  EXPECT_THROW(jv.apply(x, y), std::invalid_argument);
}

}  // namespace complex_step_product_test
}  // namespace sphstab
