#pragma once
/// \file rate_form_critical_stress.hpp
/// Critical stress of the rate-form scheme (forms/rate_form.hpp): the smallest uniform mean stress sigma0 (tension
/// positive, sigma = sigma0 I, deviator 0) at which the full-state linearisation J = dF/dy at rest has an eigenvalue
/// with a positive real part (growth/rate_form_spectrum.hpp). The block is held at its lattice positions with the
/// density of the equation of state, rho = rho0 / xi, sigma0 = K (1 - 1/xi), i.e. xi = 1 / (1 - sigma0 / K).
///
/// J depends on sigma0 through rho (not affinely, unlike the A0 + load A1 of critical_load.hpp), so the route is the
/// geometric bracket and bisection of load_bracket.hpp on tau = |sigma0| / M, M = K + 4 mu / 3 (the P-wave modulus),
/// with "stable" meaning growth_rate <= growth_tolerance x max |lambda|. tau is directly comparable with the 1D
/// pre-tension T of the §3.3 model (T = sigma0 / M there).
///
/// \note For the 1D bar with plain SPH the at-rest linearisation is exactly (docs/conventions.md §7)
///       rho u'' = -((M + sigma0) K_plus - 2 sigma0 L) u: the stiffness of the "plus" form of the §3.3 model with the
///       modulus raised by the density coupling (p = K rho / rho0 - K gives K / xi = K - sigma0, and 1/rho^2 adds
///       2 sigma0). Hence sigma0_crit / M = T_plus / (1 - T_plus), checked in tests/stability.
///
/// \code{.cpp}
/// auto r = sphstab::rate_form_critical_stress<1>(disc, material, {}, {.direction = sphstab::LoadDirection::Tension});
/// if (r.info() == sphstab::Status::Successful) std::cout << r.stress_over_modulus << " at xi = " << r.xi;
/// \endcode
#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/stability/load_bracket.hpp"

namespace sphstab {

struct RateFormCriticalOptions {
  LoadDirection direction = LoadDirection::Tension;
  double growth_tolerance = 1e-7;  ///< unstable when max Re lambda > growth_tolerance x max |lambda|
  double start = 1e-3;             ///< first tau tested
  double max = 0.5;                ///< largest tau tested (tension: also < K / M, where xi -> inf)
  double min = 1e-9;               ///< below: unstable at (almost) zero load
  double step = 2;                 ///< bracket growth factor
  double rtol = 1e-8;              ///< hi / lo - 1 at the end of the bisection
  Eigen::MatrixXd basis;           ///< optional invariant subspace (rate_form_spectrum's basis)
};

struct RateFormCriticalStress {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double stress_over_modulus = nan;  ///< sigma0_crit / M, signed; +-inf when stable up to max, 0 if unstable at 0
  double stress = nan;               ///< sigma0_crit
  double xi = nan;                   ///< volume strain V / V0 at sigma0_crit
  double growth_above = nan;         ///< growth rate at the unstable end of the bracket
  LoadBracket bracket;               ///< in tau
  int evaluations = 0;               ///< spectra computed
  Status status = Status::NotComputed;
  std::string reason;
  Status info() const { return status; }
};

/// Throws std::invalid_argument for a null discretisation, a bad material or options (tolerances <= 0, step <= 1,
/// min >= max); a failed spectrum is a NumericalIssue result with its reason.
template <int Dim>
RateFormCriticalStress rate_form_critical_stress(std::shared_ptr<const Discretisation<Dim>> disc,
                                                 const ElasticMaterial& material, const RateFormOptions& options,
                                                 const RateFormCriticalOptions& critical = {});

}  // namespace sphstab
