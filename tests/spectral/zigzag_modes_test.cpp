// Zigzag (hourglass) mode classification (spectral/zigzag_modes.hpp) on the Turek-Hron CSM3 beam, and the
// [Ganzenmueller2015] term's lift of the beam's softest zigzag mode (studies/tl-csm3-hourglass at 3 across):
// grid indices and extents of the beam, the hourglass fraction of alternating and smooth fields, off-grid input;
// A(c_HG) = A0 + c_HG B exactly (the term is linear in c_HG); the first-order perturbation slope phi^T B phi of the
// softest zigzag eigenvalue against the eigen solver at small c_HG (two methods); the lift is monotone, leaves the
// fundamental of the corrected variational form nearly unchanged and shifts that of the plain-gradient form by tens
// of percent (its F is not exact for the beam's bending field at the surfaces, so the term penalises bending).
#include "sphstab/spectral/zigzag_modes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/forms/variational_total_lagrangian.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

namespace sphstab {
namespace zigzag_modes_test {

using C = TurekHronCsm3;
constexpr double kZigzag = 0.5;

std::shared_ptr<const Discretisation<2>> beam_disc(int across, double& dx) {
  const TurekHronBeam beam = turek_hron_beam({.across = across, .clamp_layers = 4});
  dx = beam.dx;
  return make_discretisation(beam.particles, Kernel<2>(KernelType::WendlandC2), 1.5 * beam.dx);
}

std::shared_ptr<const HyperelasticModel<2>> svk() {
  return std::make_shared<StVenantKirchhoff<2>>(
      ElasticMaterial::from_lame(2 * C::shear_modulus * C::poisson / (1 - 2 * C::poisson), C::shear_modulus, 1.0));
}

TEST(ZigzagModes, BeamGridAndFractionsOfAlternatingAndSmoothFields) {
  double dx = 0;
  const auto d = beam_disc(4, dx);
  const GridIndices<2> g = grid_indices<2>(*d, dx);
  EXPECT_EQ(g.extent[0], 70);  // 70 free columns x 4 rows (tests/problems/turek_hron_csm3_test.cpp)
  EXPECT_EQ(g.extent[1], 4);
  Eigen::VectorXd saw(d->dofs()), checker(d->dofs()), bend(d->dofs());
  for (int f = 0; f < d->free_count(); ++f) {
    const auto [ix, iy] = g.index[f];
    saw.segment<2>(2 * f) << 0, (ix % 2 ? -1.0 : 1.0);                       // sawtooth along the beam
    checker.segment<2>(2 * f) << ((ix + iy) % 2 ? -1.0 : 1.0), 0;            // checkerboard
    bend.segment<2>(2 * f) << 0, 1 - std::cos(std::numbers::pi * ix / 140);  // smooth deflection
  }
  EXPECT_NEAR(hourglass_fraction<2>(saw, g), 1.0, 1e-12);
  EXPECT_NEAR(hourglass_fraction<2>(checker, g), 1.0, 1e-12);
  // a smooth field on the box treated as periodic: only the jump of 1 at the wrap-around leaks to |k| > pi/2
  // (0.0101 computed; a 1/k^2 tail), far below the classification threshold 0.5
  EXPECT_LT(hourglass_fraction<2>(bend, g), 0.02);
  EXPECT_THROW(grid_indices<2>(*d, 0.7 * dx), std::invalid_argument);
  EXPECT_THROW(hourglass_fraction<2>(Eigen::VectorXd::Ones(3), g), std::invalid_argument);
}

struct Spectrum {
  double mu_zig = NAN, mu_fund = NAN;
  int zig_below = 0;
  Eigen::VectorXd phi_zig;
};

Spectrum spectrum(const Eigen::MatrixXd& A, const GridIndices<2>& g) {
  const std::vector<ZigzagMode> modes = zigzag_spectrum<2>(A, g);
  Spectrum s;
  for (const ZigzagMode& m : modes)
    if (m.zigzag < kZigzag) {
      s.mu_fund = m.mu;
      break;
    }
  for (const ZigzagMode& m : modes)
    if (m.zigzag >= kZigzag) {
      s.mu_zig = m.mu;
      s.phi_zig = m.phi;
      break;
    }
  for (const ZigzagMode& m : modes) s.zig_below += m.zigzag >= kZigzag && m.mu < s.mu_fund;
  return s;
}

TEST(ZigzagModes, HourglassTermLiftsTheBeamsSoftestZigzagModeLinearly) {
  double dx = 0;
  const auto d = beam_disc(3, dx);
  const GridIndices<2> g = grid_indices<2>(*d, dx);
  const auto ncsph = make_gradient_provider<2>(Correction::Ncsph);
  auto A = [&](double c) {
    return Eigen::MatrixXd(jacobian(VariationalTotalLagrangian<2>(d, svk(), C::density, ncsph, {.coefficient = c}),
                                    Eigen::VectorXd::Zero(d->dofs())));
  };
  const Eigen::MatrixXd A0 = A(0), B = A(1) - A0;
  // the term is linear in c_HG: A(c) = A0 + c B to round-off of the complex-step Jacobian
  EXPECT_LE((A(0.3) - A0 - 0.3 * B).cwiseAbs().maxCoeff(), 1e-10 * B.cwiseAbs().maxCoeff());
  const Spectrum s0 = spectrum(A0, g);
  // the beam's fundamental is far below every zigzag mode (the study: ratio > 100 at 4 and 8 across)
  EXPECT_EQ(s0.zig_below, 0);
  EXPECT_GT(s0.mu_zig / s0.mu_fund, 100);
  // first order: d mu / dc = phi^T B phi (A0 symmetric, phi unit); against the solver at c = delta
  const double slope = s0.phi_zig.dot(B * s0.phi_zig);
  ASSERT_GT(slope, 0);
  const double delta = 1e-3 * s0.mu_zig / slope;  // a 0.1 % lift
  const Spectrum sd = spectrum(A0 + delta * B, g);
  EXPECT_NEAR((sd.mu_zig - s0.mu_zig) / delta, slope, 0.02 * slope);
  // monotone over the study's small coefficients; the fundamental barely moves for the corrected variational form
  double prev = s0.mu_zig;
  for (double c : {0.01, 0.03, 0.1}) {
    const Spectrum sc = spectrum(A0 + c * B, g);
    EXPECT_GT(sc.mu_zig, prev) << "c_HG = " << c;
    EXPECT_EQ(sc.zig_below, 0);
    prev = sc.mu_zig;
    EXPECT_LT(std::abs(sc.mu_fund / s0.mu_fund - 1), 0.03) << "c_HG = " << c;
  }
}

TEST(ZigzagModes, PlainGradientTermStiffensTheBeamsFundamental) {
  double dx = 0;
  const auto d = beam_disc(3, dx);
  const GridIndices<2> g = grid_indices<2>(*d, dx);
  auto A = [&](double c) {
    return Eigen::MatrixXd(jacobian(FiniteStrainTotalLagrangian<2>(d, svk(), C::density, {.hourglass = c}),
                                    Eigen::VectorXd::Zero(d->dofs())));
  };
  const Spectrum s0 = spectrum(A(0), g), s1 = spectrum(A(0.1), g);
  // the plain F is not exact for linear fields at the free surfaces: the term resists bending
  EXPECT_GT(s1.mu_fund / s0.mu_fund - 1, 0.3);
}

}  // namespace
}  // namespace sphstab
