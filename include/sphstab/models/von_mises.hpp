#pragma once
/// \file von_mises.hpp
/// Von Mises (J2) perfect plasticity by radial return, for the stored deviators of the rate-form scheme
/// (forms/rate_form.hpp): 1D S = (S_xx) in uniaxial strain, 2D S = (S_xx, S_yy, S_xy) in plane strain.
///
/// The 3 x 3 deviator s is completed from the stored entries:
///   plane strain      s = [[S_xx, S_xy, 0], [S_xy, S_yy, 0], [0, 0, S_zz]],  S_zz = -(S_xx + S_yy)
///   uniaxial strain   s = diag(S_xx, -S_xx/2, -S_xx/2)  (isotropic response to a strain along x only)
/// J2 = s:s / 2, and the von Mises stress is sigma_eq = sqrt(3 J2). Perfect plasticity with yield stress Y keeps
/// sigma_eq <= Y. A trial deviator with sigma_eq > Y is scaled back along its own direction (radial return,
/// Wilkins 1964; the usual reading of the criterion [GMS2001, §7.3], which names it but gives no formula):
///   s <- (Y / sigma_eq) s.
/// The scaling preserves S_zz = -(S_xx + S_yy) and the uniaxial form, so it acts on the stored entries directly.
/// It is the exact closest-point projection onto the yield cylinder for an isotropic elastic law with constant shear
/// modulus (the scheme's dS/dt = 2 mu dev D), so no modulus enters. The pressure is untouched (J2 plasticity is
/// volume preserving).
///
/// \note Uniaxial strain: s:s = S_xx^2 (1 + 1/4 + 1/4) = 3/2 S_xx^2, so sigma_eq = (3/2)|S_xx| and the bar yields at
///       |S_xx| = 2Y/3: the elastic-perfectly-plastic deviator of a bar under monotonic uniaxial strain is
///       S_xx = +-2Y/3 once yielded (tests/models/von_mises_test.cpp checks it in a run).
///
/// \code{.cpp}
/// const sphstab::VonMises steel(0.03);                          // Y = 0.03 (GMS §7.3, units rho0 c0^2)
/// Eigen::Vector3d s(0.05, -0.01, 0.02);                          // (S_xx, S_yy, S_xy), plane strain
/// const auto r = sphstab::radial_return<2>(steel, s);
/// if (r.yielded) s = r.deviator;                                 // von_mises_stress<2>(s) == 0.03
/// \endcode
#include <Eigen/Core>

namespace sphstab {

/// Stored deviator entries per particle: 1 (1D: S_xx), 3 (2D: S_xx, S_yy, S_xy), as RateFormScheme::kStress.
template <int Dim>
inline constexpr int kDeviatorEntries = Dim == 1 ? 1 : 3;

template <int Dim>
using StoredDeviator = Eigen::Matrix<double, kDeviatorEntries<Dim>, 1>;

/// Perfectly plastic von Mises material: the yield stress Y.
class VonMises {
 public:
  /// @param yield_stress Y > 0; +infinity is allowed (never yields). Throws std::invalid_argument otherwise (NaN,
  ///                     <= 0).
  explicit VonMises(double yield_stress);
  double yield_stress() const { return m_yield; }

 private:
  double m_yield;
};

/// sigma_eq = sqrt(3 J2) of the completed deviator (see the file comment). Dim 1 or 2.
template <int Dim>
double von_mises_stress(const StoredDeviator<Dim>& s);

template <int Dim>
struct RadialReturn {
  StoredDeviator<Dim> deviator;  ///< the returned deviator; bitwise the input when not yielded
  bool yielded = false;          ///< the trial state lay outside the yield surface (sigma_eq > Y)
  double trial_stress = 0;       ///< sigma_eq of the trial deviator
};

/// Radial return of a trial deviator: unchanged if sigma_eq <= Y, else scaled by Y / sigma_eq (then sigma_eq = Y to
/// rounding, a few ulps). A non-finite trial is returned unchanged and not yielded (the run reports it).
template <int Dim>
RadialReturn<Dim> radial_return(const VonMises& model, const StoredDeviator<Dim>& trial);

}  // namespace sphstab
