// 2D Fourier symbols against the assembled periodic Jacobian (Bloch vectors and whole spectra), the exact 2 x 2
// critical strain on hand-made matrices, and the lattice sums of Gray, Monaghan & Swift (2001) §5.
#include "sphstab/spectral/fourier_symbol_2d.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <complex>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"

namespace sphstab {
namespace fourier_symbol_2d_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

std::shared_ptr<const Discretisation<2>> periodic(LatticeType type, int n, KernelType kernel, double h) {
  Kernel<2> k(kernel);
  return make_discretisation(make_lattice<2>(type, n, {.spacing = 1.0, .periodic = true}), k, h);
}

TEST(CriticalStrain2x2, HandMadeCases) {
  using M = Eigen::Matrix2d;
  // Symmetric: det root at e = 2.
  auto r = critical_strain_2x2(M{{2, 0}, {0, 3}}, M{{-1, 0}, {0, -1}}, LoadDirection::Tension);
  EXPECT_DOUBLE_EQ(r.e, 2.0);
  EXPECT_EQ(r.mechanism, InstabilityMechanism::RealCrossing);
  r = critical_strain_2x2(M{{2, 0}, {0, 3}}, M{{-1, 0}, {0, -1}}, LoadDirection::Compression);
  EXPECT_TRUE(std::isinf(r.e) && r.e < 0);
  // Skew perturbation: eigenvalues 1.5 +- sqrt(0.25 - e^2) merge at |e| = 0.5 (det = 2 + e^2 stays positive).
  r = critical_strain_2x2(M{{1, 0}, {0, 2}}, M{{0, 1}, {-1, 0}}, LoadDirection::Tension);
  EXPECT_NEAR(r.e, 0.5, 1e-15);
  EXPECT_EQ(r.mechanism, InstabilityMechanism::ComplexPair);
  r = critical_strain_2x2(M{{1, 0}, {0, 2}}, M{{0, 1}, {-1, 0}}, LoadDirection::Compression);
  EXPECT_NEAR(r.e, -0.5, 1e-15);
  // Zero symbol: A = e a1.
  EXPECT_EQ(critical_strain_2x2(M::Zero(), M{{-1, 0}, {0, 2}}, LoadDirection::Tension).mechanism,
            InstabilityMechanism::ZeroSymbol);
  EXPECT_EQ(critical_strain_2x2(M::Zero(), M{{1, 0}, {0, 2}}, LoadDirection::Tension).mechanism,
            InstabilityMechanism::None);
  EXPECT_EQ(critical_strain_2x2(M::Zero(), M{{1, 0}, {0, 2}}, LoadDirection::Compression).mechanism,
            InstabilityMechanism::ZeroSymbol);
  EXPECT_EQ(critical_strain_2x2(M::Zero(), M{{0, 0}, {0, 2}}, LoadDirection::Tension, 1e-14).mechanism,
            InstabilityMechanism::Neutral);
}

TEST(FourierSymbol2D, BlochVectorsOfThePeriodicJacobian) {
  struct Case {
    LatticeType type;
    int n;
    KernelType kernel;
    double h;
  };
  for (const Case& c : {Case{LatticeType::Square, 8, KernelType::CubicSpline, 1.3},
                        Case{LatticeType::Hexagonal, 10, KernelType::WendlandC4, 1.6},
                        Case{LatticeType::FaceCentred, 8, KernelType::QuinticSpline, 1.2}})
    for (MomentumForm form : {MomentumForm::Conservative, MomentumForm::Plus, MomentumForm::Uncorrected})
      for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
        auto d = periodic(c.type, c.n, c.kernel, c.h);
        const Linearisation jac = analytic_jacobian_2d(*d, kMaterial, form, kind);
        const ElasticSymbol2D sym(c.type, d->kernel, c.h, 1.0, kMaterial, form, kind);
        const auto ks = periodic_wavevectors(sym.lattice(), c.n);
        const Eigen::MatrixXd a0(jac.A0), a1(jac.A1);
        const double scale0 = a0.cwiseAbs().maxCoeff(), scale1 = a1.cwiseAbs().maxCoeff();
        for (size_t m = 0; m < ks.size(); m += 7) {
          const Eigen::Vector2d k = ks[m];
          const ElasticSymbol2D::Value v = sym(k);
          for (int comp = 0; comp < 2; ++comp) {
            Eigen::VectorXcd u(jac.dofs());
            for (int f = 0; f < d->free_count(); ++f) {
              const std::complex<double> phase = std::polar(1.0, k.dot(jac.x.row(f).transpose()));
              u[2 * f] = comp == 0 ? phase : 0.0;
              u[2 * f + 1] = comp == 1 ? phase : 0.0;
            }
            const Eigen::VectorXcd r0 = a0.cast<std::complex<double>>() * u, r1 = a1.cast<std::complex<double>>() * u;
            for (int f = 0; f < d->free_count(); ++f)
              for (int a = 0; a < 2; ++a) {
                // A (v e^{ik.x}) = (A^ v) e^{ik.x}: sums of ~50 terms of size max|A|, round-off only
                EXPECT_LE(std::abs(r0[2 * f + a] - v.a0(a, comp) * u[2 * f + comp]), 1e-12 * scale0)
                    << lattice_name(c.type) << " m " << m;
                EXPECT_LE(std::abs(r1[2 * f + a] - v.a1(a, comp) * u[2 * f + comp]), 1e-12 * scale1)
                    << lattice_name(c.type) << " m " << m;
              }
          }
        }
      }
}

/// Sorts complex numbers by real part, then imaginary part.
std::vector<std::complex<double>> sorted(std::vector<std::complex<double>> v) {
  std::sort(v.begin(), v.end(),
            [](auto a, auto b) { return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag(); });
  return v;
}

TEST(FourierSymbol2D, SpectrumOfThePeriodicJacobianIsTheUnionOfSymbolSpectra) {
  // Uniaxial plus: non-symmetric A; e large enough that some eigenvalues are complex or negative.
  for (double e : {0.02, -0.3, 0.4})
    for (MomentumForm form : {MomentumForm::Conservative, MomentumForm::Plus}) {
      const int n = 8;
      auto d = periodic(LatticeType::Square, n, KernelType::WendlandC2, 1.2);
      const Linearisation jac = analytic_jacobian_2d(*d, kMaterial, form, PreStrainKind::UniaxialX);
      const ElasticSymbol2D sym(LatticeType::Square, d->kernel, 1.2, 1.0, kMaterial, form, PreStrainKind::UniaxialX);
      const Eigen::MatrixXd a(jac.at(e));
      const DenseGeneralEigen ev = general_eigen(a);
      ASSERT_EQ(ev.status, Status::Successful);
      std::vector<std::complex<double>> dense(ev.values.data(), ev.values.data() + ev.values.size()), symbol;
      for (const Eigen::Vector2d& k : periodic_wavevectors(sym.lattice(), n)) {
        const ElasticSymbol2D::Value v = sym(k);
        const Eigen::Vector2cd s = Eigen::Matrix2d(v.a0 + e * v.a1).eigenvalues();
        symbol.push_back(s[0]);
        symbol.push_back(s[1]);
      }
      dense = sorted(dense);
      symbol = sorted(symbol);
      const double scale = a.cwiseAbs().maxCoeff();
      double worst = 0;
      for (size_t t = 0; t < dense.size(); ++t) worst = std::max(worst, std::abs(dense[t] - symbol[t]));
      // dgeev backward error ~ eps ||A||; degenerate (repeated) eigenvalues move by sqrt(eps) at most
      EXPECT_LE(worst, 1e-7 * scale) << momentum_form_name(form) << " e " << e;
    }
}

TEST(FourierSymbol2D, PeriodicCriticalStrainBracketsTheDenseSpectrum) {
  // Odd n: no zone-boundary zero is admissible, so the periodic critical strain is positive.
  const int n = 9;
  for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
    auto d = periodic(LatticeType::Square, n, KernelType::CubicSpline, 1.3);
    const Linearisation jac = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
    const ElasticSymbol2D sym(LatticeType::Square, d->kernel, 1.3, 1.0, kMaterial, MomentumForm::Conservative,
                              PreStrainKind::Isotropic);
    const SymbolCriticalStrain r = critical_strain_periodic_symbol_2d(sym, n, sign);
    ASSERT_TRUE(std::isfinite(r.e)) << r.reason;
    EXPECT_EQ(r.e > 0, sign == LoadDirection::Tension);
    auto third_smallest = [&](double e) {  // two translation zeros, then the critical eigenvalue
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(jac.at(e)));
      return es.eigenvalues()[2];
    };
    const double scale = Eigen::MatrixXd(jac.A0).cwiseAbs().maxCoeff();
    EXPECT_GT(third_smallest(r.e * (1 - 1e-6)), 0.0);
    EXPECT_LT(third_smallest(r.e * (1 + 1e-6)), 0.0);
    EXPECT_LE(std::abs(third_smallest(r.e)), 1e-12 * scale);
  }
}

TEST(FourierSymbol2D, GrayMonaghanSwiftLatticeSums) {
  // GMS (2001) §5 at h = dp, k = (pi/dp, 0), 2D cubic spline: B_x = l^xx, B_y = l^yy, A_x = -s_x (their r_ab = -r).
  const Kernel<2> cubic(KernelType::CubicSpline);
  const ElasticSymbol2D square(LatticeType::Square, cubic, 1.0, 1.0, kMaterial, MomentumForm::Plus,
                               PreStrainKind::Isotropic);
  const auto sq = square({M_PI, 0});
  EXPECT_NEAR(sq.l(0, 0), 150 * (2 - std::sqrt(2.0)) / (7 * M_PI), 1e-12);  // 3.996, closed form of GMS (5.20)
  EXPECT_NEAR(sq.l(1, 1), -0.0969, 5e-5);                                   // printed -0.096 ([RC] -0.0969)
  EXPECT_LE(sq.s.norm(), 1e-15);
  const ElasticSymbol2D fcc(LatticeType::FaceCentred, cubic, 1.0, 1.0, kMaterial, MomentumForm::Plus,
                            PreStrainKind::Isotropic);
  const auto fc = fcc({M_PI, 0});
  EXPECT_NEAR(std::abs(fc.s[0]), 0.430, 5e-4);  // printed to 2 figures (0.43), [RC] 0.430
  EXPECT_NEAR(fc.l(0, 0), 2.814, 5e-4);
  EXPECT_NEAR(fc.l(1, 1), 0.516, 5e-4);
  EXPECT_NEAR(fc.s[1], 0.0, 1e-15);
}

TEST(FourierSymbol2D, InfiniteLatticeZoneBoundaryZero) {
  // Square, cubic, h = dp: l^xx(pi, 0) > 0 destabilises tension, l^yy(pi, 0) < 0 compression (GMS): e_inf = 0 both.
  const Kernel<2> cubic(KernelType::CubicSpline);
  const ElasticSymbol2D sym(LatticeType::Square, cubic, 1.0, 1.0, kMaterial, MomentumForm::Conservative,
                            PreStrainKind::Isotropic);
  for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
    const SymbolCriticalStrain r = critical_strain_infinite_2d(sym, sign, 32);
    EXPECT_EQ(r.e, 0.0);
    EXPECT_EQ(r.mechanism, InstabilityMechanism::ZeroSymbol);
    EXPECT_TRUE((r.kx_over_pi == 1 && r.ky_over_pi == 0) || (r.kx_over_pi == 0 && r.ky_over_pi == 1)) << r.kx_over_pi;
  }
  EXPECT_THROW(critical_strain_infinite_2d(sym, LoadDirection::Tension, 8), std::invalid_argument);
  EXPECT_THROW(
      ElasticSymbol2D(LatticeType::Line, cubic, 1.0, 1.0, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic),
      std::invalid_argument);
  EXPECT_THROW(periodic_wavevectors(sym.lattice(), 1), std::invalid_argument);
}

TEST(FourierSymbol2D, LongWaveLimitIsTheContinuum) {
  // k -> 0: A0^ -> acoustic tensor k k, A1^ -> -c s0 k k^T / rho (l(k) -> k k^T).
  const Kernel<2> k5(KernelType::QuinticSpline);
  const ElasticSymbol2D sym(LatticeType::Hexagonal, k5, 1.5, 1.0, kMaterial, MomentumForm::Plus,
                            PreStrainKind::UniaxialX);
  const Eigen::Vector2d k(1e-3, 0.5e-3);
  const auto v = sym(k);
  const Eigen::Matrix2d kk = k * k.transpose();
  // second-order moments of a smooth kernel on a lattice: relative error O(k^2) + lattice aliasing ~1e-4 at h = 1.5
  EXPECT_LE((v.l - kk).norm() / kk.norm(), 1e-3);
  EXPECT_LE((v.s - k).norm() / k.norm(), 1e-3);
}

}  // namespace
}  // namespace sphstab
