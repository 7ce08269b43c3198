// The first-order view y' = F(y) of the second-order forms: its Jacobian has the block structure [[0, I], [-A, 0]]
// and its rightmost eigenvalue reproduces the growth rate max Re sqrt(-mu) of u'' = -A u, by the dense and the
// Spectra routes.
#include "sphstab/growth/system_spectrum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace system_spectrum_test {

std::shared_ptr<const WaveForm1D> wave(int n, MomentumForm form, double tension) {
  Kernel<1> k(KernelType::CubicSpline);
  auto set = make_lattice<1>(LatticeType::Line, n, {.spacing = 1.0, .support_radius = k.support_radius(1.3)});
  return std::make_shared<WaveForm1D>(make_discretisation(set, k, 1.3), form, tension);
}

TEST(SystemSpectrum, SecondOrderFormJacobianIsTheBlockMatrix) {
  auto force = wave(15, MomentumForm::Plus, 0.01);
  SecondOrderForm system(force);
  const int n = force->dofs();
  ASSERT_EQ(system.size(), 2 * n);
  const Eigen::VectorXd y = 1e-3 * Eigen::VectorXd::LinSpaced(2 * n, -1.0, 1.0);
  const Eigen::MatrixXd j(jacobian(system, y));
  const Eigen::MatrixXd a(jacobian(*force, y.head(n)));  // A = -da/du
  EXPECT_EQ(j.topLeftCorner(n, n), Eigen::MatrixXd::Zero(n, n));
  EXPECT_EQ(j.topRightCorner(n, n), Eigen::MatrixXd::Identity(n, n));
  EXPECT_EQ(j.bottomLeftCorner(n, n), -a);  // the same complex-step arithmetic: bitwise
  EXPECT_EQ(j.bottomRightCorner(n, n), Eigen::MatrixXd::Zero(n, n));
  Eigen::VectorXd f;
  system.rate(y, f);
  Eigen::VectorXd acc;
  force->acceleration(Eigen::VectorXd(y.head(n)), acc);
  EXPECT_EQ(f.head(n), y.tail(n));
  EXPECT_EQ(f.tail(n), acc);
}

TEST(SystemSpectrum, GrowthRateEqualsTheSecondOrderGrowth) {
  // Plus form beyond its critical tension: unstable; conservative at small tension: stable (growth 0).
  for (auto [form, tension, unstable] :
       {std::tuple{MomentumForm::Plus, 0.02, true}, std::tuple{MomentumForm::Conservative, 1e-5, false}}) {
    auto force = wave(21, form, tension);
    const LinearGrowth ref = linear_growth(*force, Eigen::VectorXd::Zero(force->dofs()));
    SecondOrderForm system(force);
    const SystemSpectrum s = system_spectrum(system, Eigen::VectorXd::Zero(system.size()), {.want_mode = true});
    ASSERT_EQ(s.info(), Status::Successful);
    EXPECT_EQ(s.backend, "dense");
    if (unstable) {
      EXPECT_GT(ref.gamma, 0.1);
      EXPECT_NEAR(s.growth_rate, ref.gamma, 1e-10 * ref.gamma);
      EXPECT_NEAR(std::abs(s.lambda.imag()), 0.0, 1e-8 * ref.gamma);  // a real exponential mode
      EXPECT_NEAR(s.mode.norm(), 1.0, 1e-14);
    } else {
      // Purely oscillatory: Re lambda = 0 up to the round-off of the eigensolver.
      EXPECT_LT(std::abs(s.growth_rate), 1e-6 * std::sqrt(ref.lambda_max));
    }
  }
}

TEST(SystemSpectrum, SpectraAgreesWithDense) {
  auto force = wave(150, MomentumForm::Plus, 0.02);
  SecondOrderForm system(force);
  const Eigen::VectorXd y = Eigen::VectorXd::Zero(system.size());
  const SystemSpectrum dense = system_spectrum(system, y);
  const SystemSpectrum sparse = system_spectrum(system, y, {.dense_max = 100, .nev = 4});
  ASSERT_EQ(dense.backend, "dense");
  ASSERT_EQ(sparse.backend, "spectra");
  ASSERT_EQ(sparse.info(), Status::Successful);
  EXPECT_GT(dense.growth_rate, 0.1);
  EXPECT_NEAR(sparse.growth_rate, dense.growth_rate, 1e-8 * dense.growth_rate);
}

TEST(SystemSpectrum, RejectsBadInput) {
  EXPECT_THROW(system_spectrum(SparseMatrix<>(0, 0)), std::invalid_argument);
  EXPECT_THROW(system_spectrum(SparseMatrix<>(2, 3)), std::invalid_argument);
  SparseMatrix<> nan_j(2, 2);
  nan_j.insert(0, 1) = std::nan("");
  EXPECT_THROW(system_spectrum(nan_j), std::invalid_argument);
  EXPECT_THROW(SecondOrderForm(nullptr), std::invalid_argument);
  SecondOrderForm system(wave(5, MomentumForm::Plus, 0.0));
  EXPECT_THROW(system_spectrum(system, Eigen::VectorXd::Zero(3)), std::invalid_argument);
  SparseMatrix<> one(1, 1);
  one.insert(0, 0) = 2.5;
  EXPECT_EQ(system_spectrum(one).growth_rate, 2.5);  // y' = 2.5 y
}

}  // namespace
}  // namespace sphstab
