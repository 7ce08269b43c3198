// The dispersion relation (GMS 5.8/5.9 + 5.13) against an independent route: the Bloch-reduced Jacobian of the
// SPH equations written particle by particle on a periodic lattice (gms_linearisation.hpp), by complex step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gms_linearisation.hpp"
#include "sphstab/spectral/lattice_dispersion.hpp"

namespace sphstab {
namespace lattice_dispersion_linearisation_test {

using test::Complex;

/// Largest distance from each predicted omega^2 to its nearest two Bloch values among the four wave values.
double mismatch(const std::vector<Complex>& bloch, const std::array<Complex, 2>& predicted) {
  double worst = 0;
  for (const Complex& p : predicted) {
    std::vector<double> d;
    for (int m = 0; m < 4; ++m) d.push_back(std::abs(bloch[m] - p));
    std::sort(d.begin(), d.end());
    worst = std::max(worst, d[1]);  // each mode is a +-lambda pair: two equal omega^2
  }
  return worst;
}

UniformState elastic_state(double P, double sxx, double syy) {
  return {.density = 1, .sound_speed = 1, .shear_modulus = 0.22, .pressure = P, .sxx = sxx, .syy = syy};
}

struct Case {
  LatticeType type;
  double h;
  Eigen::Vector2d k;
  UniformState state;
};

TEST(LatticeDispersionLinearisation, MatchesFrozenRDispersionRelation) {
  const double pi = M_PI, L = 8.0;  // 8 x 8 periodic lattice, dp = 1: k must be a multiple of 2 pi / 8
  Kernel<2> w(KernelType::CubicSpline);
  std::vector<Case> cases = {
      // GMS §5.3: k = (pi/dp, 0), tension in x, artificial stress from epsilon = 0.3
      {LatticeType::Square, 1.0, {pi, 0}, with_artificial_stress(elastic_state(-0.03, 0.01, -0.005), 0.3)},
      {LatticeType::FaceCentred, 1.0, {pi, 0}, with_artificial_stress(elastic_state(-0.03, 0.01, -0.005), 0.3)},
      {LatticeType::FaceCentred, 1.5, {pi, 0}, with_artificial_stress(elastic_state(0.02, 0.01, -0.01), 0.3)},
      // oblique k: exercises A_y, C, f_xy and the zeta (spin) terms
      {LatticeType::Square,
       1.3,
       {2 * pi * 3 / L, 2 * pi * 1 / L},
       with_artificial_stress(elastic_state(-0.02, 0.04, -0.02), 0.3)},
      {LatticeType::FaceCentred,
       1.2,
       {2 * pi * 1 / L, 2 * pi * 2 / L},
       with_artificial_stress(elastic_state(0.01, -0.05, 0.03), 0.3)},
      {LatticeType::FaceCentred,
       1.0,
       {2 * pi * 3 / L, 2 * pi * 3 / L},
       with_artificial_stress(elastic_state(-0.05, 0.0, 0.02), 0.3)},
  };
  for (const auto& c : cases) {
    auto g = test::make_gms_lattice(c.type, 8, c.h, c.state, 0.3, /*live_r=*/false);
    auto bloch = test::gms_bloch_omega2(g, c.k);
    auto d = lattice_dispersion(c.type, w, c.h, c.k, c.state);
    const double scale = std::max(std::abs(d.omega2[0]), std::abs(d.omega2[1]));
    SCOPED_TRACE(lattice_name(c.type) + " h = " + std::to_string(c.h) + " k = (" + std::to_string(c.k[0]) + ", " +
                 std::to_string(c.k[1]) + ")");
    // Complex step is exact to rounding; the eigenvalues of the 8x8 Bloch matrix carry ~1e-13 relative error.
    EXPECT_LT(mismatch(bloch, d.omega2), 1e-10 * scale);
    // The remaining four eigenvalues are the steady modes (lambda = 0; a defective eigenvalue can scatter them
    // by ~sqrt(rounding) in lambda, i.e. ~1e-16 in omega^2).
    for (int m = 4; m < 8; ++m) EXPECT_LT(std::abs(bloch[m]), 1e-12 * scale);
  }
}

TEST(LatticeDispersionLinearisation, ConfirmsFactorTwoInFaceCentredLongitudinalMode) {
  // GMS (5.25) prints A_x^2 (rho c0^2 + 4mu/3 - P + Sxx); (5.8) gives -2(P - Sxx). Only (5.8) matches.
  const UniformState st = elastic_state(-0.3, 0.1, -0.05);  // strong tension so that the difference is visible
  const Eigen::Vector2d k(M_PI, 0);
  Kernel<2> w(KernelType::CubicSpline);
  auto g = test::make_gms_lattice(LatticeType::FaceCentred, 8, 1.0, st, 0.0, false);
  auto bloch = test::gms_bloch_omega2(g, k);
  auto d = lattice_dispersion(LatticeType::FaceCentred, w, 1.0, k, st);
  const auto& s = d.sums;
  const double ps = st.pressure - st.sxx, ax2 = s.A[0] * s.A[0];
  const double printed = (1 - s.beta) * (2 * s.Bx * ps + ax2 * (1 + 4 * st.shear_modulus / 3 - ps));
  const double derived = (1 - s.beta) * (2 * s.Bx * ps + ax2 * (1 + 4 * st.shear_modulus / 3 - 2 * ps));
  EXPECT_NEAR(d.omega2[0].real(), derived, 1e-13);
  double best_printed = 1e9, best_derived = 1e9;
  for (int m = 0; m < 4; ++m) {
    best_printed = std::min(best_printed, std::abs(bloch[m] - printed));
    best_derived = std::min(best_derived, std::abs(bloch[m] - derived));
  }
  EXPECT_LT(best_derived, 1e-12);
  EXPECT_GT(best_printed, 1e-2);  // |A_x^2 (P - Sxx)| (1 - beta) = 0.185 * 0.4 * 0.615 = 0.046
}

TEST(LatticeDispersionLinearisation, PerturbedArtificialStress) {
  // GMS (5.13) freezes R. With R = R(sigma, rho) its perturbation enters through sum sin(k.r) f^n grad W, which
  // vanishes on the square lattice for k = (pi/dp, 0) (all sin(k.r_ab) = 0) but not on the face-centred one.
  Kernel<2> w(KernelType::CubicSpline);
  const double pi = M_PI, L = 8.0;
  std::vector<Case> cases = {
      {LatticeType::Square, 1.0, {pi, 0}, with_artificial_stress(elastic_state(-0.03, 0.01, -0.005), 0.3)},
      {LatticeType::FaceCentred, 1.0, {pi, 0}, with_artificial_stress(elastic_state(-0.03, 0.01, -0.005), 0.3)},
      // mixed principal stresses (sigma_xx > 0 > sigma_yy): the rotation's derivative enters dR^xy
      {LatticeType::FaceCentred, 1.2, {pi, 0}, with_artificial_stress(elastic_state(0.0, 0.05, -0.05), 0.3)},
      {LatticeType::FaceCentred,
       1.3,
       {2 * pi * 3 / L, 2 * pi * 1 / L},
       with_artificial_stress(elastic_state(-0.02, 0.04, -0.06), 0.3)},
      {LatticeType::Square,
       1.2,
       {2 * pi * 1 / L, 2 * pi * 2 / L},
       with_artificial_stress(elastic_state(-0.05, 0.01, 0.02), 0.3)},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(lattice_name(c.type) + " h = " + std::to_string(c.h));
    auto g = test::make_gms_lattice(c.type, 8, c.h, c.state, 0.3, /*live_r=*/true);
    auto bloch = test::gms_bloch_omega2(g, c.k);
    auto live = lattice_dispersion(c.type, w, c.h, c.k, c.state, {.perturbed_artificial_stress = true});
    auto frozen = lattice_dispersion(c.type, w, c.h, c.k, c.state);
    const double scale = std::max(std::abs(live.omega2[0]), std::abs(live.omega2[1]));
    EXPECT_LT(mismatch(bloch, live.omega2), 1e-10 * scale);
    const double frozen_gap = mismatch(bloch, frozen.omega2);
    if (c.type == LatticeType::Square && c.k[1] == 0)
      EXPECT_LT(frozen_gap, 1e-10 * scale);  // sin(k.r_ab) = 0: frozen R is exact
    else
      EXPECT_GT(frozen_gap, 1e-4 * scale);  // the perturbation of R matters
  }
}

}  // namespace
}  // namespace sphstab
