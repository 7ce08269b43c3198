#pragma once
/// \file affine_critical_tension.hpp
/// Critical load of ANY force function whose Jacobian is affine in the load, A(T) = A0 + T A1 (affine_jacobian in
/// complex_step_jacobian.hpp; A = -da/du at the lattice equilibrium, T = 1D tension), symmetric or not.
///
/// Criteria (StabilityCriterion):
///  - PositiveDefinite ("pd"), for symmetric A (conservative forms, and every plain form at a 1D lattice
///    equilibrium, Powell 3.40): T_crit = the smallest T > 0 at which A(T) stops being positive definite. Computed
///    by critical_tension() with K = A0 and L = -A1 (n = 1): the CHOLMOD bisection (Powell footnote g) and the
///    generalised eigenproblem -A1 x = lambda A0 x, T_crit = 1 / lambda_max, cross-checked against each other.
///    For a conservative form A positive definite proves stability (Lyapunov); for the others it is necessary.
///  - RealPositiveSpectrum ("real-positive-spectrum"), for nonsymmetric A (non-conservative forms with a corrected
///    kernel, or at a displaced state): the NECESSARY condition of Powell Theorem 3.1 for u'' = -A u. With
///    u = v e^{lambda t}, lambda^2 = -mu for each eigenvalue mu of A; the equilibrium is unstable unless every mu is
///    real and positive (then lambda is imaginary). T_crit = the smallest T > 0 at which an eigenvalue of A(T) leaves
///    the positive real axis: Re mu <= 0 or |Im mu| > imag_tol max|mu|. Dense LAPACK dgeev per T; bracket by
///    doubling from t_start, then geometric bisection to hi/lo - 1 <= rtol. The growth rate
///    gamma = max Re sqrt(-mu) (growth_rate.hpp) is reported at growth_factor * T_crit.
///    \note The spectrum may leave and re-enter the positive real axis; the bracket search samples |T| at
///          t_start * 2^k (and t = 0), so an excursion narrower than a doubling between two samples can be missed.
///  - SymmetricPartPositiveDefinite ("symmetric-part-pd"): positive definiteness of (A + A^T)/2, by the pd route.
///    For nonsymmetric A it is neither necessary nor sufficient for stability of u'' = -A u; it is the energy-like
///    test v^T A v > 0 for all v (the "A positive definite" reading of Theorem 3.1 that Powell applies, 3.38).
///
/// LoadDirection::Compression looks for the largest T < 0 (the critical compression T_crit^-): the same searches on
/// A0 + |T| (-A1); tcrit is then reported negative. tcrit = +-inf: the criterion holds for every T of that sign
/// (within the search limits, see `reason`); tcrit = 0: it fails already at T = 0 (A0 itself).
///
/// \code{.cpp}
/// sphstab::WaveForm1D force(disc, sphstab::MomentumForm::Plus, 0.0, sphstab::make_gradient_provider<1>(c));
/// auto split = sphstab::affine_jacobian(force, Eigen::VectorXd::Zero(force.dofs()));
/// for (const auto& r : sphstab::affine_critical_tension(split, sphstab::LoadDirection::Tension, x_free))
///   std::cout << sphstab::criterion_name(r.criterion) << " " << r.tcrit << " " << sphstab::status_name(r.status);
/// \endcode
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/stability/critical_tension.hpp"

namespace sphstab {

enum class StabilityCriterion { PositiveDefinite, RealPositiveSpectrum, SymmetricPartPositiveDefinite };
enum class LoadDirection { Tension, Compression };

/// "pd", "real-positive-spectrum", "symmetric-part-pd".
std::string criterion_name(StabilityCriterion criterion);
/// "tension", "compression".
std::string load_direction_name(LoadDirection direction);

struct AffineCriticalOptions {
  CriticalTensionOptions symmetric;  ///< pd routes (method, backend, bisection bracket in |T|); want_mode is forced on
  double symmetry_tol = 1e-12;       ///< A0 and A1 count as symmetric when ||A - A^T||_F <= tol ||A||_F
  double zero_tol = 1e-12;           ///< A1 counts as zero when ||A1||_F <= tol (||A0||_F + ||A0 + A1||_F)
  double imag_tol = 1e-10;           ///< spectrum: |Im mu| <= imag_tol max|mu| counts as real
  double t_start = 1e-3;             ///< spectrum bracket: first |T| tried
  double t_max = 1e8;                ///< spectrum: criterion holds up to |T| = t_max => tcrit = +-inf
  double t_min = 1e-12;              ///< spectrum: fails down to |T| = t_min => tcrit = 0
  double rtol = 1e-10;               ///< spectrum bisection: stop when hi/lo - 1 <= rtol
  double growth_factor = 2.0;        ///< gamma is evaluated at growth_factor * T_crit (> 1)
};

/// What affine_critical_tension() decided about the pair (A0, A1).
struct AffineJacobianInfo {
  double asymmetry0 = 0;          ///< relative_asymmetry(A0)
  double asymmetry1 = 0;          ///< relative_asymmetry(A0 + A1) (A at T = 1)
  double a1_relative = 0;         ///< ||A1||_F / ||A0||_F
  bool symmetric = false;         ///< both asymmetries <= symmetry_tol
  bool load_independent = false;  ///< ||A1|| below zero_tol (Powell 3.33: no T dependence)
};

struct AffineCriticalTension {
  static constexpr double nan = CriticalTension::nan;
  StabilityCriterion criterion = StabilityCriterion::PositiveDefinite;
  LoadDirection direction = LoadDirection::Tension;
  double tcrit = nan;         ///< signed critical load (see the file comment)
  double lo = nan, hi = nan;  ///< final bracket in |T| (lo passes, hi fails); pd: bisection bracket
  int evaluations = 0;        ///< dgeev calls (spectrum) or Cholesky factorisations (pd)
  CriticalTension pd;         ///< pd criteria: the critical_tension() result (its T values are |T|)
  double growth_load = nan;   ///< T at which growth_rate was evaluated (growth_factor * tcrit; nan if tcrit is inf)
  double growth_rate = nan;   ///< gamma = max Re sqrt(-mu) of A(growth_load)
  WavenumberEstimate mode_wavenumber;  ///< fastest growing mode at growth_load (k dx / pi)
  AffineJacobianInfo info;
  Status status = Status::NotComputed;
  std::string reason;  ///< how the value arose; semicolon-separated, no commas (CSV-safe)
};

/// Symmetry and load dependence of (A0, A1). Throws std::invalid_argument for mismatched or empty matrices.
AffineJacobianInfo analyse_affine_jacobian(const AffineJacobian& jacobian, const AffineCriticalOptions& options = {});

/// Critical load by one criterion.
/// @param[in] jacobian   A0, A1: n x n (free DOFs), finite
/// @param[in] criterion  PositiveDefinite requires a symmetric pair (else std::invalid_argument)
/// @param[in] x          n positions of the DOFs (wavenumber of the critical mode)
/// Throws std::invalid_argument for bad sizes, non-finite entries or invalid options.
AffineCriticalTension affine_critical_load(const AffineJacobian& jacobian, StabilityCriterion criterion,
                                           LoadDirection direction, const Eigen::VectorXd& x,
                                           const AffineCriticalOptions& options = {});

/// The criteria that apply: {PositiveDefinite} for a symmetric pair, else {RealPositiveSpectrum,
/// SymmetricPartPositiveDefinite}.
std::vector<AffineCriticalTension> affine_critical_tension(const AffineJacobian& jacobian, LoadDirection direction,
                                                           const Eigen::VectorXd& x,
                                                           const AffineCriticalOptions& options = {});

/// Critical loads of a force function at u = 0: its affine Jacobian split (complex step), the equilibrium residual and
/// affine_critical_tension() of the split.
struct ForceCriticalLoad {
  AffineJacobian jacobian;          ///< A0, A1 at u = 0
  double equilibrium_residual = 0;  ///< max_i |a_i(u = 0)| over the loads 0 and 1 (0 iff u = 0 is an equilibrium)
  double residual_relative = 0;     ///< equilibrium_residual / max |A0_ij|
  std::vector<AffineCriticalTension> results;  ///< one per applicable criterion
};

/// @param[in] force      any force function affine in its load (1D: T); evaluated at u = 0 with loads 0 and 1
/// @param[in] x          dofs() positions (wavenumbers of critical modes)
/// \note A non-zero residual means u = 0 is not an equilibrium: A(T) is then the Jacobian at a non-equilibrium point
///       and the criteria lose their meaning; callers should report it (sphstab tcrit does, in `reason`).
ForceCriticalLoad critical_load(const ForceFunction& force, LoadDirection direction, const Eigen::VectorXd& x,
                                const AffineCriticalOptions& options = {});

}  // namespace sphstab
