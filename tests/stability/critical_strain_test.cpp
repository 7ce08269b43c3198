// Critical pre-strain of finite 2D lattices: bisection (CHOLMOD) against the generalised eigenproblem (dense and
// Spectra), the dense spectrum criterion against definiteness where both apply, exact form ratios, brackets checked
// with independent dense eigenvalues, and the dominant wavevector on synthetic modes.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace sphstab {
namespace critical_strain_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

Linearisation jacobian(LatticeType type, int n, KernelType kernel, double h, MomentumForm form, PreStrainKind kind,
                       bool periodic = false) {
  Kernel<2> k(kernel);
  auto d = make_discretisation(strain_lattice_2d(type, k, h, n, periodic), k, h);
  return analytic_jacobian_2d(*d, kMaterial, form, kind);
}

/// The defaults of the old critical_strain.
CriticalLoadOptions strain_options() { return CriticalLoadOptions::strain_2d(); }

/// critical_load with the 2D defaults (the old critical_strain).
CriticalLoad critical_strain(const Linearisation& lin, LoadDirection sign,
                             const CriticalLoadOptions& options = strain_options()) {
  return critical_load(lin, sign, options);
}

double smallest_symmetric_eigenvalue(const SparseMatrix<>& a) {
  const Eigen::MatrixXd d(a);
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (d + d.transpose()), Eigen::EigenvaluesOnly)
      .eigenvalues()[0];
}

TEST(CriticalStrain, BisectionAgreesWithEigenOnSquareAndHex) {
  struct Case {
    LatticeType type;
    KernelType kernel;
    double h;
  };
  for (const Case& c :
       {Case{LatticeType::Square, KernelType::CubicSpline, 1.3}, Case{LatticeType::Square, KernelType::WendlandC4, 1.8},
        Case{LatticeType::Hexagonal, KernelType::QuinticSpline, 1.2},
        Case{LatticeType::Hexagonal, KernelType::WendlandC2, 1.5}})
    for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX})
      for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
        const Linearisation jac = jacobian(c.type, 8, c.kernel, c.h, MomentumForm::Conservative, kind);
        const CriticalLoad r = critical_strain(jac, sign);
        const std::string what = lattice_name(c.type) + " " + kernel_name(c.kernel) + " " + load_direction_name(sign);
        ASSERT_EQ(r.status, Status::Successful) << what << ": " << r.reason;
        EXPECT_EQ(r.criterion, Criterion::Definiteness);
        EXPECT_EQ(r.eigen_backend, "dense");
        if (std::isinf(r.load)) {
          EXPECT_TRUE(std::isinf(r.load_bisection)) << what;
          continue;
        }
        EXPECT_EQ(r.load > 0, sign == LoadDirection::Tension) << what;
        EXPECT_LE(r.relative_difference, 1e-8) << what;  // the brief's agreement requirement
        // Independent check of the bracket by dense eigenvalues.
        EXPECT_GT(smallest_symmetric_eigenvalue(jac.at(r.load * (1 - 1e-7))), 0.0) << what;
        EXPECT_LT(smallest_symmetric_eigenvalue(jac.at(r.load * (1 + 1e-7))), 0.0) << what;
        // Spectra (Cholesky mode over CHOLMOD) gives the same eigenvalue as dense dsygv.
        CriticalLoadOptions sp = strain_options();
        sp.backend = EigenBackend::Spectra;
        sp.method = CriticalLoadMethod::Eigen;
        const CriticalLoad s = critical_strain(jac, sign, sp);
        EXPECT_EQ(s.eigen_backend, "spectra");
        EXPECT_NEAR(s.load, r.load, 1e-10 * std::abs(r.load)) << what;
      }
}

TEST(CriticalStrain, FormRatiosAreExact) {
  // Complete lattice: one A0 for every form; A1 isotropic cons = 2 plus = 4 uncorrected -> e ratios 1 : 2 : 4.
  for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
    const auto cons = critical_strain(jacobian(LatticeType::Square, 7, KernelType::CubicSpline, 1.3,
                                               MomentumForm::Conservative, PreStrainKind::Isotropic),
                                      sign);
    const auto plus = critical_strain(
        jacobian(LatticeType::Square, 7, KernelType::CubicSpline, 1.3, MomentumForm::Plus, PreStrainKind::Isotropic),
        sign);
    const auto unc = critical_strain(jacobian(LatticeType::Square, 7, KernelType::CubicSpline, 1.3,
                                              MomentumForm::Uncorrected, PreStrainKind::Isotropic),
                                     sign);
    ASSERT_TRUE(std::isfinite(cons.load));
    EXPECT_NEAR(plus.load / cons.load, 2.0, 1e-12);
    EXPECT_NEAR(unc.load / cons.load, 4.0, 1e-12);
    const auto minus = critical_strain(
        jacobian(LatticeType::Square, 7, KernelType::CubicSpline, 1.3, MomentumForm::Minus, PreStrainKind::UniaxialX),
        sign);
    EXPECT_TRUE(std::isinf(minus.load));
    EXPECT_EQ(minus.load > 0, sign == LoadDirection::Tension);  // signed: +inf in tension, -inf in compression
    EXPECT_EQ(minus.status, Status::Successful);
  }
}

TEST(CriticalStrain, SpectrumCriterionEqualsDefinitenessForSymmetricA) {
  // For symmetric A, "all eigenvalues real and > 0" is positive definiteness: the dense dgeev route must reproduce
  // the CHOLMOD / dsygv value.
  const Linearisation jac = jacobian(LatticeType::Hexagonal, 6, KernelType::CubicSpline, 1.3,
                                     MomentumForm::Conservative, PreStrainKind::UniaxialX);
  for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
    const CriticalLoad def = critical_strain(jac, sign);
    CriticalLoadOptions o = strain_options();
    o.criterion = Criterion::Spectrum;
    const CriticalLoad spec = critical_strain(jac, sign, o);
    ASSERT_EQ(spec.status, Status::Successful) << spec.reason;
    EXPECT_EQ(spec.criterion, Criterion::Spectrum);
    EXPECT_EQ(spec.mechanism, InstabilityMechanism::RealCrossing);
    EXPECT_NEAR(spec.load_eigen, def.load, 1e-9 * std::abs(def.load));
    EXPECT_NEAR(spec.load_bisection, def.load, 1e-9 * std::abs(def.load));  // spectrum_rtol 1e-10 bracket
  }
}

TEST(CriticalStrain, NonSymmetricUniaxialPlusUsesTheSpectrum) {
  const Linearisation plus =
      jacobian(LatticeType::Square, 6, KernelType::CubicSpline, 1.3, MomentumForm::Plus, PreStrainKind::UniaxialX);
  const Linearisation unc = jacobian(LatticeType::Square, 6, KernelType::CubicSpline, 1.3, MomentumForm::Uncorrected,
                                     PreStrainKind::UniaxialX);
  ASSERT_FALSE(plus.symmetric);
  for (LoadDirection sign : {LoadDirection::Tension, LoadDirection::Compression}) {
    const CriticalLoad r = critical_strain(plus, sign);
    ASSERT_EQ(r.status, Status::Successful) << r.reason;
    EXPECT_EQ(r.criterion, Criterion::Spectrum);
    ASSERT_TRUE(std::isfinite(r.load));
    // The bracket, by an independent criterion evaluation: all eigenvalues real positive below, not above.
    auto stable = [&](double e) {
      const Eigen::MatrixXd a(plus.at(e));
      const DenseGeneralEigen ev = general_eigen(a);
      for (Eigen::Index t = 0; t < ev.values.size(); ++t)
        if (std::abs(ev.values[t].imag()) > 1e-9 * a.norm() || !(ev.values[t].real() > 0)) return false;
      return true;
    };
    EXPECT_TRUE(stable(r.load * (1 - 1e-6)));
    EXPECT_FALSE(stable(r.load * (1 + 1e-6)));
    // uncorrected A1 = plus A1 / 2: exactly twice the critical strain, whatever the mechanism
    const CriticalLoad u = critical_strain(unc, sign);
    EXPECT_NEAR(u.load / r.load, 2.0, 1e-8);  // spectrum bisection to rtol 1e-10 on both
    EXPECT_EQ(u.mechanism, r.mechanism);
    // The symmetric-part criterion is labelled as such.
    CriticalLoadOptions o = strain_options();
    o.criterion = Criterion::SymmetricPart;
    const CriticalLoad sp = critical_strain(plus, sign, o);
    EXPECT_EQ(sp.criterion, Criterion::SymmetricPart);
    EXPECT_NE(sp.reason.find("symmetric-part"), std::string::npos);
    EXPECT_LE(sp.relative_difference, 1e-8);
  }
  CriticalLoadOptions bad = strain_options();
  bad.criterion = Criterion::Definiteness;
  EXPECT_THROW(critical_strain(plus, LoadDirection::Tension, bad), std::invalid_argument);
}

TEST(CriticalStrain, PeriodicSetIsReportedNotCrashed) {
  const Linearisation jac = jacobian(LatticeType::Square, 8, KernelType::CubicSpline, 1.3, MomentumForm::Conservative,
                                     PreStrainKind::Isotropic, true);
  const CriticalLoad r = critical_strain(jac, LoadDirection::Tension);
  EXPECT_EQ(r.status, Status::NumericalIssue);
  EXPECT_NE(r.reason.find("symbol"), std::string::npos);
  CriticalLoadOptions bad = strain_options();
  bad.rtol = 0;
  EXPECT_THROW(critical_strain(jac, LoadDirection::Tension, bad), std::invalid_argument);
}

TEST(CriticalStrain, NoNeighboursInsideTheSupportIsReportedNotStable) {
  // h = 0.3 dx: support 0.6 dx < dx, so A0 = A1 = 0. That is not "stable for every e" but undefined.
  const Linearisation jac = jacobian(LatticeType::Square, 6, KernelType::CubicSpline, 0.3, MomentumForm::Conservative,
                                     PreStrainKind::Isotropic);
  const CriticalLoad r = critical_strain(jac, LoadDirection::Tension);
  EXPECT_EQ(r.status, Status::NumericalIssue);
  EXPECT_TRUE(std::isnan(r.load));
  EXPECT_NE(r.reason.find("no particle has a neighbour"), std::string::npos) << r.reason;
  const ElasticSymbol2D symbol(LatticeType::Square, Kernel<2>(KernelType::CubicSpline), 0.3, 1.0, kMaterial,
                               MomentumForm::Conservative, PreStrainKind::Isotropic);
  EXPECT_TRUE(std::isnan(critical_strain_infinite_2d(symbol, LoadDirection::Tension).e));
  EXPECT_TRUE(std::isnan(critical_strain_periodic_symbol_2d(symbol, 8, LoadDirection::Tension).e));
  // the minus form has a genuine A0 but A1 = 0: stable for every pre-strain
  const CriticalLoad m = critical_strain(
      jacobian(LatticeType::Square, 6, KernelType::CubicSpline, 1.3, MomentumForm::Minus, PreStrainKind::Isotropic),
      LoadDirection::Tension);
  EXPECT_EQ(m.status, Status::Successful);
  EXPECT_TRUE(std::isinf(m.load) && m.load > 0);
}

TEST(CriticalStrain, CriticalModeWavevectorApproachesTheZoneBoundaryZero) {
  // Square lattice, cubic h = 1.3, isotropic tension: the infinite lattice is unstable at the zone-boundary zero
  // k = (pi, 0) (l^xx(pi, 0) > 0, A0^ = 0). At n = 48 the critical mode is that sawtooth in x with the lowest
  // envelope in y (ky dx / pi ~ 2/(n + 1)); e_crit ~ n^-2.
  const Linearisation jac = jacobian(LatticeType::Square, 40, KernelType::CubicSpline, 1.3, MomentumForm::Conservative,
                                     PreStrainKind::Isotropic);
  CriticalLoadOptions o = strain_options();
  o.method = CriticalLoadMethod::Eigen;
  const CriticalLoad r = critical_strain(jac, LoadDirection::Tension, o);
  ASSERT_EQ(r.status, Status::Successful) << r.reason;
  const double kmax = std::max(r.mode_wavevector.kx_over_pi, r.mode_wavevector.ky_over_pi),
               kmin = std::min(r.mode_wavevector.kx_over_pi, r.mode_wavevector.ky_over_pi);
  EXPECT_NEAR(kmax, 1.0, 0.03);  // peak resolution ~ 1/n
  EXPECT_LE(kmin, 3.0 / 41);     // lowest envelope(s)
}

TEST(DominantWavevector, RecoversSyntheticModes) {
  // Plane wave on a periodic hex lattice at an admissible k; standing wave on a square block; perturbed positions.
  {
    const auto set = make_lattice<2>(LatticeType::Hexagonal, 12, {.spacing = 1.0, .periodic = true});
    const BravaisLattice2D lat = bravais_lattice_2d(LatticeType::Hexagonal);
    const Eigen::Vector2d k = periodic_wavevectors(lat, 12)[3 + 12 * 5];
    Eigen::VectorXd mode(2 * set.size());
    for (int i = 0; i < set.size(); ++i) {
      const double ph = k.dot(set.x.row(i).transpose());
      mode[2 * i] = std::cos(ph);
      mode[2 * i + 1] = 0.3 * std::cos(ph);
    }
    const WavevectorEstimate w = dominant_wavevector(mode, set.x, lat);
    const Eigen::Vector2d expect = lat.fold(k) / M_PI;
    EXPECT_NEAR(w.kx_over_pi, expect[0], 1e-6);
    EXPECT_NEAR(w.ky_over_pi, expect[1], 1e-6);
    EXPECT_NEAR(w.peak_fraction, 0.5, 1e-9);  // cos = two plane waves of equal power, exact on a periodic box
  }
  {
    const int n = 17;
    const auto set = make_lattice<2>(LatticeType::Square, n, {.spacing = 1.0, .fixed_layers = 0});
    const double kx = 0.8 * M_PI, ky = 0.25 * M_PI;
    Eigen::VectorXd mode(2 * set.size());
    for (int i = 0; i < set.size(); ++i) {
      mode[2 * i] = std::sin(kx * set.x(i, 0)) * std::sin(ky * set.x(i, 1));
      mode[2 * i + 1] = 0;
    }
    const WavevectorEstimate w = dominant_wavevector(mode, set.x, bravais_lattice_2d(LatticeType::Square));
    // finite box: leakage between +-k shifts the peak by O(1/n^2) of the zone
    EXPECT_NEAR(w.kx_over_pi, 0.8, 0.02);
    EXPECT_NEAR(w.ky_over_pi, 0.25, 0.02);
  }
  {
    const auto set =
        make_lattice<2>(LatticeType::Square, 16, {.spacing = 1.0, .fixed_layers = 0, .perturbation = 0.05, .seed = 4});
    const Eigen::Vector2d k(0.5 * M_PI, 0.9 * M_PI);
    Eigen::VectorXcd mode(2 * set.size());
    for (int i = 0; i < set.size(); ++i) {
      mode[2 * i] = std::polar(1.0, k.dot(set.x.row(i).transpose()));
      mode[2 * i + 1] = 0;
    }
    const WavevectorEstimate w = dominant_wavevector(mode, set.x, bravais_lattice_2d(LatticeType::Square));
    EXPECT_NEAR(w.kx_over_pi, 0.5, 1e-6);  // a complex plane wave is exactly maximal at k, positions irrelevant
    EXPECT_NEAR(w.ky_over_pi, 0.9, 1e-6);
    EXPECT_NEAR(w.peak_fraction, 1.0, 1e-9);
  }
  EXPECT_THROW(dominant_wavevector(Eigen::VectorXd(3), Eigen::MatrixX2d(2, 2), bravais_lattice_2d(LatticeType::Square)),
               std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
