#pragma once
/// \file lattice_dispersion.hpp
/// SPH dispersion relation on a uniform, prestressed 2D lattice (Gray, Monaghan & Swift 2001 [GMS] §4-5).
///
/// A plane wave x_a = xbar_a + X exp(i(k.xbar_a - omega t)) on an infinite lattice of equal particles
/// (m = rho V_cell; V_cell = dp^2 on the square and face-centred lattices) in a uniform state with density rho,
/// pressure P, diagonal deviatoric stress S (lattice axes = principal axes), shear modulus mu, sound speed c0,
/// XSPH (eps = 1/2) motion, continuity (3.8), the velocity gradient (3.10), the Jaumann stress rate (2.3) and
/// the artificial stress R f^n (3.12) gives (GMS 5.8, 5.9 with 5.13), with K_a = 2(P - S^aa), zeta = (Sxx - Syy)/2:
///   rho omega^2 Vx/(1-beta) = -(K_x - rho c0^2) A_x (A.V) + K_x (B_x Vx + C Vy) + (2mu/3)(2 Vx A_x - Vy A_y) A_x
///                             + mu (Vx A_y + Vy A_x) A_y - zeta (Vx A_y - Vy A_x) A_y - 2 rho^2 R^xx (f_xx Vx + f_xy
///                             Vy)
///   rho omega^2 Vy/(1-beta) = -(K_y - rho c0^2) A_y (A.V) + K_y (B_y Vy + C Vx) + (2mu/3)(2 Vy A_y - Vx A_x) A_y
///                             + mu (Vx A_y + Vy A_x) A_x - zeta (Vx A_y - Vy A_x) A_x - 2 rho^2 R^yy (f_yy Vy + f_xy
///                             Vx)
/// with the lattice sums over b != a, r_ab = r_a - r_b (GMS 5.5, 5.14, 5.15):
///   A = V_cell sum sin(k.r_ab) grad_a W_ab,   (B_x, B_y, C) = V_cell sum (1 - cos k.r_ab)(W_xx, W_yy, W_xy),
///   beta = V_cell/2 sum (1 - cos k.r_ab) W_ab, (f_xx, f_yy, f_xy) = Z sum (1 - cos k.r_ab) d^2(W^{n+1}),
///   Z = V_cell / ((n+1) W(dp)^n).
/// The formulas were re-derived (notes in lattice_dispersion.cpp) and are checked in the tests against a
/// complex-step linearisation of the SPH equations on a periodic lattice.
///
/// \note The A_x^2 coefficient of the face-centred longitudinal mode follows (5.8): rho c0^2 + 4mu/3 - 2(P - Sxx).
///       GMS (5.25) prints "- P + Sxx" (a factor 2 lost); the linearisation test confirms (5.8).
/// \note By default, as in GMS (5.13), R is frozen at its uniform value: the perturbation dR of the artificial
///       stress through the perturbed stress and density is neglected. With
///       LatticeSumOptions::perturbed_artificial_stress it is included: particle b's dR_b enters as
///       a = -i rho A^f . dR, A^f = V_cell sum sin(k.r_ab) f_ab^n grad_a W_ab, and dR = (dR/dsigma) dsigma +
///       (dR/drho) drho is the complex-step derivative of artificial_stress() at the uniform state (one-sided where a
///       principal stress is exactly 0). The term vanishes when sin(k.r_ab) = 0 for every neighbour (square
///       lattice, k = (pi/dp, 0)), but not in general (face-centred, k = (pi/dp, 0): 2-12 % of omega^2 for
///       isotropic tension 0.01-0.1 and h/dp = 1-1.2).
/// \note Long waves: A -> -k, (B_x, B_y, C) -> (kx^2, ky^2, kx ky), beta -> 0 recover the continuum (4.9)/(4.10)
///       (P cancels) up to the lattice's discrete moment errors (Sum V x dW/dx = -1 + O(aliasing)).
/// \note Units are the caller's; GMS use rho0 = c0 = 1. Sums scale as 1/dp (A) and 1/dp^2 (B, C, f).
#include <Eigen/Core>
#include <array>
#include <complex>
#include <limits>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {

/// Lattice sums of GMS (5.5) and (5.14)-(5.15).
struct LatticeSums {
  Eigen::Vector2d A = Eigen::Vector2d::Zero();   ///< (A_x, A_y), 1/length
  Eigen::Vector2d Af = Eigen::Vector2d::Zero();  ///< A with f^n: V_cell sum sin(k.r_ab) f_ab^n grad_a W_ab
  double Bx = 0, By = 0, C = 0;                  ///< 1/length^2
  double beta = 0;                               ///< XSPH factor: Vhat = (1 - beta) V (GMS 5.3)
  double fxx = 0, fyy = 0, fxy = 0;              ///< artificial-stress sums, 1/length^2
  double cell_volume = 0;                        ///< V_cell = m / rho
  int neighbours = 0;                            ///< lattice points b != a with W_ab > 0 that were summed
};

struct LatticeSumOptions {
  double spacing = 1.0;  ///< dp > 0: nearest-neighbour distance (also the dp of f = W/W(dp))
  double exponent = 4;   ///< n >= 0 of the artificial stress
  /// Sum only over |r_ab| <= max_distance (analysis of nearest-neighbour contributions); default: whole support.
  double max_distance = std::numeric_limits<double>::infinity();
  /// Dispersion only: include the perturbation of R through the stress (needs UniformState::epsilon).
  bool perturbed_artificial_stress = false;
};

/// Uniform prestressed state of GMS §4 (lattice axes = principal axes). sigma^aa = -P + S^aa (tension > 0).
struct UniformState {
  double density = 1;        ///< rho > 0
  double sound_speed = 1;    ///< c0 >= 0 (bulk modulus K = rho c0^2, EOS 2.7)
  double shear_modulus = 0;  ///< mu >= 0
  double pressure = 0;       ///< P
  double sxx = 0, syy = 0;   ///< deviatoric S^xx, S^yy
  double rxx = 0, ryy = 0;   ///< artificial stress R^xx, R^yy (uniform, R^xy = 0)
  double epsilon = 0;        ///< the GMS coefficient behind (rxx, ryy); used only for the perturbation of R
  double sigma_xx() const { return -pressure + sxx; }
  double sigma_yy() const { return -pressure + syy; }
};

/// The state with R from the GMS rule (6.4): R^aa = -epsilon sigma^aa / rho^2 where sigma^aa > 0, else 0;
/// records epsilon.
UniformState with_artificial_stress(UniformState state, double epsilon);

/// omega^2 and modes of the 2x2 dispersion problem.
struct DispersionRelation {
  LatticeSums sums;                             ///< the lattice sums used (continuum: A = -k, B = k k, beta = 0)
  Eigen::Matrix2d M = Eigen::Matrix2d::Zero();  ///< rho omega^2 V / (1 - beta) = M V
  /// omega^2 = (1 - beta) eig(M) / rho; [0] is the quasi-longitudinal mode (eigenvector closest to k; for k = 0
  /// the x mode). Negative (or complex) omega^2: growth rate sqrt(-omega^2).
  std::array<std::complex<double>, 2> omega2{};
  Eigen::Matrix2cd modes = Eigen::Matrix2cd::Identity();  ///< columns: unit V of omega2[0], omega2[1]
};

/// Lattice sums for the Square, FaceCentred (rows dp apart, odd rows shifted dp/2) or Hexagonal lattice,
/// smoothing length h, wavevector k (1/length). Throws std::invalid_argument for another lattice type, h <= 0,
/// dp <= 0, n < 0, non-finite k, or dp outside the kernel support (W(dp) = 0).
LatticeSums lattice_sums(LatticeType type, const Kernel<2>& kernel, double h, const Eigen::Vector2d& k,
                         const LatticeSumOptions& options = {});

/// The matrix M of GMS (5.8)/(5.9) with the artificial stress (5.13) from given sums; see the file comment.
/// `perturbed_artificial_stress` adds the dR term (uses sums.Af and state.epsilon).
Eigen::Matrix2d dispersion_matrix(const LatticeSums& sums, const UniformState& state,
                                  bool perturbed_artificial_stress = false);

/// Lattice dispersion relation (GMS 5.8/5.9 + 5.13). Throws as lattice_sums, and for density <= 0, mu < 0.
DispersionRelation lattice_dispersion(LatticeType type, const Kernel<2>& kernel, double h, const Eigen::Vector2d& k,
                                      const UniformState& state, const LatticeSumOptions& options = {});

/// Continuum dispersion relation (GMS 4.9/4.10): rho omega^2 V = M V (R is ignored: no artificial stress).
DispersionRelation continuum_dispersion(const Eigen::Vector2d& k, const UniformState& state);

}  // namespace sphstab
