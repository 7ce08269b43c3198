#pragma once
/// \file artificial_stress.hpp
/// Artificial stress of Gray, Monaghan & Swift (2001) [GMS] for 2D symmetric stress tensors.
///
/// Per particle, the stress sigma (tension positive, sigma = -P I + S) is rotated to its principal axes,
/// each TENSILE principal component gets Rbar = -epsilon sigmabar / rho^2 (compressive ones 0), and Rbar is
/// rotated back (GMS 6.1-6.7). The pair term (R_i + R_j) f_ij^n, f_ij = W(r_ij)/W(dp), is added to the
/// sigma_i/rho_i^2 + sigma_j/rho_j^2 bracket of the momentum equation (GMS 3.1 + 3.12, 6.9):
///   a_i^a += sum_j m_j (R_i^ab + R_j^ab) f_ij^n dW_ij/dx_i^b.
///
/// \note Rotation (GMS 6.1-6.3) with e1 = (c, s), e2 = (-s, c), tan 2 theta = 2 sxy / (sxx - syy):
///       sigmabar^xx = c^2 sxx + 2sc sxy + s^2 syy, sigmabar^yy = s^2 sxx - 2sc sxy + c^2 syy. The printed (6.3)
///       has +2sc sxy, a typo (it does not preserve the trace of [GMS2001, (6.2)-(6.3)]; recomputed here).
/// \note Complex-step safety: the rotation is evaluated from double-angle quantities that are analytic in the
///       stress entries, cos 2theta = (sxx - syy)/(2 r), sin 2theta = sxy / r, r = sqrt(((sxx-syy)/2)^2 + sxy^2),
///       c^2 = (1 + cos 2theta)/2, s^2 = (1 - cos 2theta)/2, sc = sin 2theta / 2 -- no atan2, no angle. Branches
///       (which principal stresses are tensile) use real parts only. When both principal stresses are tensile
///       the back-rotation of (6.5-6.7) is the identity map and R = -epsilon sigma/rho^2 is returned in that
///       closed form; when both are compressive R = 0. The rotation is only needed in the mixed case, where
///       r > 0 strictly, so there is no division by zero and no special case at sxx = syy (GMS 6.10 is not
///       needed). R is a smooth function of sigma except where a principal stress crosses 0.
/// \note Units are the caller's; GMS use rho0 = c0 = 1 (stress in rho0 c0^2).
#include <Eigen/Core>
#include <complex>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// Symmetric 2x2 tensor (stress or artificial stress) by its three independent components.
template <class Scalar = double>
struct SymmetricTensor2 {
  Scalar xx{0}, yy{0}, xy{0};
};

/// Principal frame of a symmetric 2x2 tensor (GMS 6.1-6.3). major >= minor (real parts) are the principal
/// values, major along e1 = (c, s), minor along e2 = (-s, c).
template <class Scalar = double>
struct PrincipalFrame {
  Scalar major{0};   ///< sigmabar^xx = c^2 sxx + 2sc sxy + s^2 syy (GMS 6.2) = mean + radius
  Scalar minor{0};   ///< sigmabar^yy = s^2 sxx - 2sc sxy + c^2 syy (GMS 6.3, sign corrected) = mean - radius
  Scalar cc{1};      ///< c^2 = cos^2 theta
  Scalar ss{0};      ///< s^2 = sin^2 theta
  Scalar sc{0};      ///< s c = sin theta cos theta
  double theta = 0;  ///< 0.5 atan2(2 sxy, sxx - syy) of the real parts, in (-pi/2, pi/2]; 0 for an isotropic tensor
};

/// GMS artificial-stress parameters: R = -epsilon sigmabar/rho^2 on tensile principal components, pair factor
/// f^n. GMS use epsilon = 0.3 ("~0.3") and n = 4 throughout.
struct ArtificialStressParameters {
  double epsilon = 0.3;  ///< >= 0
  double exponent = 4;   ///< n >= 0 (integer values use exact repeated multiplication)
};

/// Principal values and rotation of a symmetric tensor (GMS 6.1-6.3), analytic in the entries (see file note).
/// An isotropic tensor (sxx = syy, sxy = 0) gets theta = 0.
template <class Scalar>
PrincipalFrame<Scalar> principal_frame(const SymmetricTensor2<Scalar>& sigma);

/// Back-rotation (GMS 6.5-6.7): R^xx = c^2 Rbar^xx + s^2 Rbar^yy, R^yy = s^2 Rbar^xx + c^2 Rbar^yy,
/// R^xy = sc (Rbar^xx - Rbar^yy).
template <class Scalar>
SymmetricTensor2<Scalar> rotate_from_frame(const PrincipalFrame<Scalar>& frame, const Scalar& rbar_xx,
                                           const Scalar& rbar_yy);

/// Artificial stress R of one particle (GMS 6.4-6.7; 5.31 with the particle's own density):
/// Rbar = -epsilon sigmabar / rho^2 for each tensile (real part > 0) principal stress, 0 otherwise.
/// Throws std::invalid_argument for epsilon < 0 or non-finite, or density with real part <= 0.
template <class Scalar>
SymmetricTensor2<Scalar> artificial_stress(const SymmetricTensor2<Scalar>& sigma, const Scalar& density,
                                           double epsilon);

/// Stress fields: N x 3, row i = (sigma_i^xx, sigma_i^yy, sigma_i^xy).
template <class Scalar = double>
using TensorField2 = Eigen::Matrix<Scalar, Eigen::Dynamic, 3>;

/// Per-particle artificial stress R_i (N x 3, columns xx, yy, xy) from sigma_i (N x 3) and density rho_i (N).
template <class Scalar>
TensorField2<Scalar> artificial_stress(const TensorField2<Scalar>& sigma,
                                       const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& density, double epsilon);

/// W(dp, h): the reference kernel value of f = W(r)/W(dp) (GMS 3.13). Throws std::invalid_argument for h <= 0,
/// dp <= 0 (or non-finite) and for dp beyond the kernel support (W(dp) = 0).
double artificial_stress_reference_kernel(const Kernel<2>& kernel, double h, double dp);

/// x^n for real n >= 0: exact repeated multiplication for integer n, exp(n log x) otherwise (0 where the
/// real part of x is <= 0 and n > 0). Analytic in x for x with positive real part (complex-step safe).
template <class Scalar>
Scalar artificial_stress_power(const Scalar& x, double n);

/// Pair factor f_ij^n with f_ij = W(r_ij)/W(dp) (GMS 3.13): `w_ij` = W(r_ij) (no volume), `w_dp` = W(dp) > 0.
template <class Scalar>
Scalar artificial_stress_pair_factor(const Scalar& w_ij, double w_dp, double n) {
  return artificial_stress_power(Scalar(w_ij / w_dp), n);
}

/// Artificial-stress acceleration (GMS 3.1 + 3.12, 6.9), to be added to a 2D momentum equation:
///   a_i^a = sum_{j != i} m_j (R_i^ab + R_j^ab) f_ij^n dW_ij/dx_i^b,   f_ij = W(r_ij)/W(dp),
/// evaluated from operator matrices assembled with volumes V_j: W(r_ij) = W_ij / V_j and
/// m_j dW_ij/dx_i = (m_j / V_j) G_ij (so positions may be displaced or complex, as in assemble_operators).
/// @param[in] ops     operators with W and G assembled (same neighbour pattern), N x N
/// @param[in] mass    m_j, N entries
/// @param[in] volume  V_j > 0 the operators were assembled with, N entries
/// @param[in] R       per-particle artificial stress, N x 3 (xx, yy, xy), e.g. from artificial_stress()
/// @param[in] w_dp    W(dp) > 0 (artificial_stress_reference_kernel)
/// @param[in] n       exponent n >= 0
/// @return N x 2 accelerations (interleave as dof i*2+a if needed).
/// \note With R < 0 (tension) the term is repulsive, like a positive pressure (GMS §3).
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 2> artificial_stress_acceleration(const Operators<2, Scalar>& ops,
                                                                        const Eigen::VectorXd& mass,
                                                                        const Eigen::VectorXd& volume,
                                                                        const TensorField2<Scalar>& R, double w_dp,
                                                                        double n);

}  // namespace sphstab
