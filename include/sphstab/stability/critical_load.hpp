#pragma once
/// \file critical_load.hpp
/// The critical-load engine: the smallest |load| at which the linearisation A(load) = A0 + load A1
/// (jacobian/linearisation.hpp) leaves the stable set, in the direction asked (tension: load > 0, compression:
/// load < 0). One engine for every producer — the 1D critical tension [Powell2012, (3.40)], the 2D critical
/// pre-strain, the corrected forms through the complex-step Jacobian — so a new scheme plugs in by producing a
/// Linearisation. With tau = |load| and sgn = +1 (tension) or -1 (compression):
///
/// Criterion::Definiteness (symmetric A): A(load) = K - tau L with K = A0, L = -sgn A1; stable iff positive
///   definite ([Powell2012, Thm 3.1] necessary; sufficient for a conservative form by Lyapunov). Two independent
///   routes, which must agree (relative 1e-8; NumericalIssue beyond 1e-6):
///   1. bisection with CHOLMOD LL^T [Powell2012, footnote g]: bracket from `start` in steps of `step` (inf beyond
///      `max`), then geometric bisection to hi/lo - 1 <= rtol (load_bracket.hpp);
///   2. the generalised symmetric eigenproblem L x = lambda K x: tau_crit = 1/lambda_max (inf when lambda_max <= 0);
///      dense LAPACK dsygv up to dense_max unknowns, else Spectra's SymGEigsSolver in Cholesky mode over CHOLMOD,
///      optionally shifted to B = K - lo L with the bisection's stable end lo (shift_spectra: nu = lambda / (1 - lo
///      lambda), tau = lo + 1/nu_max, which makes the wanted end dominant). The eigenvector is the critical mode.
///   On a periodic 1D lattice the translation (and, for even N, the sawtooth, G s = 0) are projected out first
///   (deflate_periodic); a sawtooth destabilised by the load gives load 0.
/// Criterion::Spectrum (any A; the criterion of [Powell2012, Thm 3.1] for u'' = -A u): every eigenvalue of A real
///   and positive (|Im mu| <= imag_tol x scale, Re mu > 0). Dense, one dgeev per tested load; with
///   spectrum_real_crossing the first real crossing det A = 0 is found first from the eigenvalues nu of A0^-1 (sgn A1)
///   (tau = -1/nu for the most negative real nu; the "eigen" route) and the scan tests fractions of it; a complex
///   pair (flutter) found earlier is bisected and reported as mechanism ComplexPair. An unstable window narrower
///   than the sampling is missed (sampling, not proof).
/// Criterion::SymmetricPart: definiteness of (A + A^T)/2 by the two routes above. For non-symmetric A this is NOT a
///   stability criterion (an energy-like sufficient condition only); always labelled as such.
/// Criterion::Auto: Definiteness for symmetric A, else Spectrum up to spectrum_dense_max unknowns, else
///   SymmetricPart.
///
/// load = +-inf: the criterion holds for every load of that sign up to `max`; load = 0: it fails already at zero
/// load. A load-independent A (A1 negligible, e.g. the minus form) gives +-inf or 0 from A(0) alone.
///
/// \code{.cpp}
/// auto lin = sphstab::analytic_jacobian_2d(*disc, material, sphstab::MomentumForm::Conservative,
///                                          sphstab::PreStrainKind::Isotropic);
/// sphstab::CriticalLoad r = sphstab::critical_load(lin, sphstab::LoadDirection::Tension,
///                                                  sphstab::CriticalLoadOptions::strain_2d());
/// if (r.info() == sphstab::Status::Successful) std::cout << r.load << " " << r.mode_wavevector.kx_over_pi;
/// \endcode
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/core/status.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/jacobian/linearisation.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/linalg/cholmod_factor.hpp"
#include "sphstab/particles/particle_set.hpp"
#include "sphstab/spectral/dominant_wavenumber.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

enum class Criterion {
  Auto,           ///< Definiteness if symmetric; else Spectrum (up to spectrum_dense_max dofs) or SymmetricPart
  Definiteness,   ///< positive definiteness of A (A must be symmetric)
  Spectrum,       ///< every eigenvalue of A real and > 0 (dense)
  SymmetricPart,  ///< positive definiteness of (A + A^T)/2
};
/// Parses "auto", "definiteness", "spectrum", "symmetric-part" (old spellings "pd", "real-positive-spectrum",
/// "symmetric-part-pd" accepted); throws std::invalid_argument otherwise.
Criterion parse_criterion(const std::string& name);
/// "auto", "definiteness", "spectrum", "symmetric-part".
std::string criterion_name(Criterion criterion);

enum class CriticalLoadMethod { Eigen, Bisection, Both };
enum class EigenBackend { Auto, Dense, Spectra };
/// Parses "eig", "bisect", "both"; throws std::invalid_argument otherwise.
CriticalLoadMethod parse_critical_load_method(const std::string& name);
/// Parses "auto", "dense", "spectra"; throws std::invalid_argument otherwise.
EigenBackend parse_eigen_backend(const std::string& name);

/// The scale of the spectrum criterion's imaginary-part tolerance.
enum class ImagScale {
  SpectralRadius,  ///< imag_tol x max |mu|
  FrobeniusNorm    ///< imag_tol x ||A||_F
};

struct CriticalLoadOptions {
  Criterion criterion = Criterion::Auto;
  CriticalLoadMethod method = CriticalLoadMethod::Both;  ///< definiteness routes
  EigenBackend backend = EigenBackend::Auto;
  int dense_max = 200;  ///< Auto backend: dense dsygv up to this many unknowns, Spectra above
  CholmodVariant variant = CholmodVariant::Simplicial;
  double start = 1e-3;         ///< first |load| of the bracket search
  double max = 1e8;            ///< |load| beyond which the result is +-inf
  double min = 1e-200;         ///< the search gives up below (definiteness: NumericalIssue; spectrum: load 0)
  double step = 2;             ///< bracket growth factor (> 1)
  double rtol = 1e-13;         ///< definiteness bisection: hi/lo - 1 <= rtol
  bool shift_spectra = false;  ///< Spectra route: shift by the bracket's stable end (see the file comment)
  double spectra_tol = 1e-13;
  int spectra_maxit = 3000;
  int spectra_ncv = 0;           ///< 0: 40 (doubled twice on non-convergence)
  bool deflate_periodic = true;  ///< 1D periodic: project out translation (+ sawtooth for even N)
  /// Definiteness of a symmetric A: use (A + A^T)/2, which removes round-off asymmetry (a complex-step Jacobian is
  /// symmetric to ~1e-16 only); false: the upper triangle as stored (the setting of the 2D studies, whose analytic
  /// A0 is symmetric to round-off too; the two differ in the last digits, ~1e-11 relative in e_crit).
  bool symmetrize = true;
  int spectrum_dense_max = 1200;  ///< Auto criterion: largest non-symmetric A for the dense spectrum
  double spectrum_rtol = 1e-10;   ///< spectrum bisection (one dgeev per step): hi/lo - 1 <= spectrum_rtol
  double imag_tol = 1e-10;        ///< spectrum: |Im mu| <= imag_tol x scale counts as real
  ImagScale imag_scale = ImagScale::SpectralRadius;
  bool spectrum_real_crossing = false;  ///< spectrum: eigen route (first real crossing) and the scan seeded by it
  double zero_tol = 1e-12;              ///< A1 negligible when ||A1||_F <= zero_tol (||A0||_F + ||A0 + A1||_F)
  bool want_mode = true;                ///< keep the critical mode and its dominant wavenumber / wavevector
  /// A(0) failing the criterion (A0 not positive definite; a spectrum failing at zero load; unstable down to `min`)
  /// gives load 0 (unstable already without load) instead of NumericalIssue (A0 singular: the load is undefined).
  bool a0_failure_is_zero_load = false;
  double growth_factor = 0;  ///< > 1: growth rate gamma of A(growth_factor x load) (dense; 0: not computed)

  /// The defaults of the 1D critical tension [Powell2012, ch. 3]: factor-2 bracket from 1e-3 to 1e8, simplicial
  /// CHOLMOD, unshifted Spectra above 200 unknowns, no mode (critical_tension_1d reads the bracket in units of
  /// n T). \note want_mode changes LAPACK's path (eigenvectors or not), hence the last bits of the eigen route.
  static CriticalLoadOptions tension_1d();
  /// The defaults of the 2D critical pre-strain: factor-8 bracket from 1e-3 to 1e3, supernodal CHOLMOD, shifted
  /// Spectra, dense spectrum criterion seeded by the real crossing, imag_tol 1e-9 ||A||_F.
  static CriticalLoadOptions strain_2d();
  /// The defaults for any force function's complex-step linearisation (corrected forms): the 1D definiteness
  /// routes, the spectrum bisected from 1e-3 to 1e8 with imag_tol 1e-10 max|mu|, and the growth rate at 2 load.
  static CriticalLoadOptions force_function();
};

struct CriticalLoad {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double load = nan;                 ///< the result, signed: eigen route when computed, else bisection; +-inf; 0
  double load_eigen = nan;           ///< definiteness: 1/lambda_max; spectrum: first real crossing (signed)
  double load_bisection = nan;       ///< geometric mean of the final bracket (signed)
  double lo = nan;                   ///< largest |load| found stable (signed)
  double hi = nan;                   ///< smallest |load| found unstable (signed)
  double lambda_max = nan;           ///< definiteness: largest eigenvalue of L x = lambda K x (deflated space)
  double relative_difference = nan;  ///< |eigen - bisection| / max (0 if both infinite)
  double a0_rcond = nan;             ///< CHOLMOD rcond estimate of K = A0 (definiteness criteria)
  int evaluations = 0;               ///< Cholesky factorisations or dgeev calls in the bisection
  int size = 0;                      ///< unknowns (after deflation)
  LoadDirection direction = LoadDirection::Tension;
  Criterion criterion = Criterion::Definiteness;  ///< the criterion actually used
  InstabilityMechanism mechanism = InstabilityMechanism::None;
  std::string eigen_backend;  ///< "dense", "spectra" or "dgeev" (empty if not run)
  Status status = Status::NotComputed;
  std::string reason;  ///< how the value arose; semicolon-separated, no commas (CSV-safe)
  /// Critical mode on the free dofs, unit norm (want_mode): the eigenvector at the critical load (for an infinite
  /// load the eigenvector of lambda_max, the direction closest to instability), empty when load = 0.
  Eigen::VectorXcd mode;
  WavenumberEstimate mode_wavenumber;    ///< 1D: dominant k dx / pi of the mode
  WavevectorEstimate mode_wavevector;    ///< 2D: dominant wavevector of the mode (finite load only)
  double growth_load = nan;              ///< load at which growth_rate was evaluated (growth_factor x load)
  double growth_rate = nan;              ///< gamma = max Re sqrt(-mu) of A(growth_load)
  WavenumberEstimate growth_wavenumber;  ///< 1D: fastest-growing mode at growth_load
  int unstable_modes = 0;                ///< modes (real mu or conjugate pairs) growing at growth_load
  double asymmetry0 = nan;               ///< relative_asymmetry(A0)
  double asymmetry1 = nan;               ///< relative_asymmetry(A0 + A1)
  double a1_relative = nan;              ///< ||A1||_F / ||A0||_F

  Status info() const { return status; }
  /// The wavenumber that characterises the instability (1D, NaN when load is 0 or infinite): the fastest-growing
  /// mode at growth_load when the growth rate was computed and a mode grows, else the critical mode of the
  /// definiteness criteria (the spectrum criterion's mode at the bracket's unstable end is not used).
  WavenumberEstimate reported_wavenumber() const {
    if (!std::isfinite(load) || load == 0) return {};
    if (unstable_modes > 0) return growth_wavenumber;
    return criterion == Criterion::Spectrum ? WavenumberEstimate{} : mode_wavenumber;
  }
};

/// Critical load of `lin` in `direction` by options.criterion. Throws std::invalid_argument for invalid options,
/// empty or mismatched matrices, non-finite entries, positions of the wrong size, or Definiteness on a
/// non-symmetric linearisation.
CriticalLoad critical_load(const Linearisation& lin, LoadDirection direction, const CriticalLoadOptions& options = {});

/// The criteria that apply to `lin`: {Definiteness} when symmetric, else {Spectrum, SymmetricPart}; one result each.
std::vector<CriticalLoad> critical_loads(const Linearisation& lin, LoadDirection direction,
                                         const CriticalLoadOptions& options = CriticalLoadOptions::force_function());

/// The critical tension of a 1D momentum form [Powell2012, ch. 3] on a particle set: analytic_jacobian_1d (Powell
/// 3.40) and the Definiteness criterion. The bracket options (start, max, min) are in units of the initial-stress
/// load n T, as in Powell, so every form tests the same matrices (n = initial_stress_multiplier(form); the minus
/// form, n = 0, has no load dependence). Throws as analytic_jacobian_1d and critical_load.
CriticalLoad critical_tension_1d(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h, MomentumForm form,
                                 const CriticalLoadOptions& options = CriticalLoadOptions::tension_1d(),
                                 LoadDirection direction = LoadDirection::Tension);

/// Critical loads of any force function at u = 0: its affine linearisation (complex step), the equilibrium residual,
/// and critical_loads() of the linearisation.
struct ForceCriticalLoad {
  Linearisation jacobian;             ///< A0, A1 at u = 0 (x as given)
  double equilibrium_residual = 0;    ///< max_i |a_i(u = 0)| over the loads 0 and 1 (0 iff u = 0 is an equilibrium)
  double residual_relative = 0;       ///< equilibrium_residual / max |A0_ij|
  std::vector<CriticalLoad> results;  ///< one per applicable criterion
};

/// @param[in] force  any force function affine in its load; evaluated at u = 0 with loads 0 and 1
/// @param[in] x      free-particle positions (free_count x dim; wavenumbers of critical modes), may be empty
/// \note A non-zero residual means u = 0 is not an equilibrium: A is then the Jacobian at a non-equilibrium point and
///       the criteria lose their meaning; callers should report it (sphstab tcrit does, in `reason`).
ForceCriticalLoad force_critical_loads(const ForceFunction& force, LoadDirection direction, const Eigen::MatrixXd& x,
                                       const CriticalLoadOptions& options = CriticalLoadOptions::force_function());

}  // namespace sphstab
