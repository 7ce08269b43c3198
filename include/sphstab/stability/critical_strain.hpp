#pragma once
/// \file critical_strain.hpp
/// Critical pre-strain of a finite 2D lattice: the smallest |e| (e > 0 tension, e < 0 compression) at which the
/// linearisation A(e) = A0 + e A1 (analytic_jacobian_2d.hpp) leaves the stable set, the 2D analogue of the 1D critical
/// tension (critical_tension.hpp). With tau = |e| and sgn = +1 (tension) or -1 (compression):
///
/// Criterion "definiteness" (A(e) symmetric: conservative always; plus, uncorrected for isotropic pre-strain; minus):
///   A(e) = K - tau L with K = A0, L = -sgn A1. Two independent routes must agree (relative 1e-8):
///   1. bisection with CHOLMOD LL^T (A positive definite iff the factorisation succeeds): bracket from e_start in
///      steps of a factor 8 (inf beyond e_max), then geometric bisection to hi/lo - 1 <= rtol, one symbolic analysis;
///   2. the generalised symmetric eigenproblem L x = lambda K x (K = A0 positive definite): tau_crit = 1/lambda_max
///      (inf when lambda_max <= 0); dense LAPACK dsygv up to dense_max unknowns, else Spectra's SymGEigsSolver in
///      Cholesky mode over a CHOLMOD factor of the SHIFTED B = K - lo L (lo: the positive definite end of the bracket
///      of route 1, a spectral transformation only: nu = lambda / (1 - lo lambda), tau = lo + 1/nu_max; it makes the
///      wanted end of the spectrum dominant, 3-5 Lanczos restarts instead of tens). The eigenvector is the mode.
/// Criterion "spectrum" (any A, the stability criterion for u'' = -A u, Powell Theorem 3.1: every eigenvalue real and
///   positive), dense, for non-symmetric A (uniaxial plus/uncorrected):
///   1. eigen route: real crossings det A(e) = 0 from the eigenvalues nu of M = A0^{-1} (sgn A1) (dgeev):
///      A0 + tau sgn A1 singular iff nu = -1/tau, so tau_real = -1/nu for the most negative real nu;
///   2. bisection on "all eigenvalues of A(e) (dgeev) have |Im| <= imag_tol ||A||_F and Re > 0": the criterion is
///      tested at tau_real x {1/16, 1/8, 1/4, 1/2, 3/4, 0.9, 1 - d} and tau_real (1 + d), d = spectrum_rtol / 4; the
///      first failure is bisected to spectrum_rtol (without tau_real: bracket from e_start in factors of 8). An
///      unstable window that opens and closes between two tested points is missed (sampling, not a proof). When the
///      first instability is a real crossing the routes agree; when a complex pair (flutter) comes first the bisection
///      value is the result, mechanism = complex-pair, and the eigen route only bounds it from above.
/// Criterion "symmetric-part": definiteness of (A + A^T)/2, with both routes as above. For non-symmetric A this is
///   NOT the stability criterion (sufficient for a decaying energy-like norm only); offered because it is sparse and
///   cheap, and always labelled in the result.
///
/// Dominant wavevector of the critical mode: dominant_wavevector.hpp (peak of the structure factor).
///
/// A0 must be positive definite (fixed layers). On a periodic lattice A0 is singular (translations and the
/// zone-boundary zeros, fourier_symbol_2d.hpp): the result is then NumericalIssue with a reason; use
/// critical_strain_periodic_symbol_2d (exact there).
///
/// \code{.cpp}
/// auto jac = sphstab::analytic_jacobian_2d(*disc, material, sphstab::MomentumForm::Conservative,
///                                          sphstab::PreStrainKind::Isotropic);
/// sphstab::CriticalStrain r = sphstab::critical_strain(jac, sphstab::LoadSign::Tension);
/// if (r.status == sphstab::Status::Successful) { double e = r.e; double kx = r.mode_k.kx_over_pi; }
/// \endcode
#include <limits>
#include <string>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/linalg/cholmod_factor.hpp"
#include "sphstab/linalg/status.hpp"
#include "sphstab/stability/critical_tension.hpp"
#include "sphstab/stability/dominant_wavevector.hpp"
#include "sphstab/stability/fourier_symbol_2d.hpp"

namespace sphstab {

enum class StrainCriterion {
  Auto,          ///< definiteness if jac.symmetric; else spectrum up to spectrum_dense_max dofs, else symmetric-part
  Definiteness,  ///< positive definiteness of A(e) (A must be symmetric)
  Spectrum,      ///< every eigenvalue of A(e) real and > 0 (dense)
  SymmetricPart  ///< positive definiteness of (A + A^T)/2
};
/// "auto", "definiteness", "spectrum", "symmetric-part".
StrainCriterion parse_strain_criterion(const std::string& name);
std::string strain_criterion_name(StrainCriterion c);

struct CriticalStrainOptions {
  TcritMethod method = TcritMethod::Both;
  EigenBackend backend = EigenBackend::Auto;
  int dense_max = 400;  ///< definiteness, Auto backend: dense dsygv up to this many dofs, Spectra above
  CholmodVariant variant = CholmodVariant::Supernodal;
  StrainCriterion criterion = StrainCriterion::Auto;
  int spectrum_dense_max = 1200;  ///< Auto criterion: largest non-symmetric A for the dense spectrum criterion
  double e_start = 1e-3;          ///< first |e| tried by the bisection bracket search
  double e_max = 1e3;             ///< |e| beyond which the result is +-inf
  double e_min = 1e-14;           ///< bisection gives up below (status NumericalIssue)
  double rtol = 1e-12;            ///< definiteness bisection: hi/lo - 1 <= rtol
  double spectrum_rtol = 1e-10;   ///< spectrum bisection (one dgeev per step): hi/lo - 1 <= spectrum_rtol
  double imag_tol = 1e-9;         ///< spectrum criterion: |Im mu| <= imag_tol ||A||_F counts as real
  double spectra_tol = 1e-12;
  int spectra_maxit = 3000;
  int spectra_ncv = 0;  ///< 0: min(size, 40)
  bool want_mode = true;
};

struct CriticalStrain {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double e = nan;             ///< result, signed (tension > 0, compression < 0): eigen route, else bisection; +-inf
  double e_eigen = nan;       ///< eigen route (spectrum criterion: first real crossing)
  double e_bisection = nan;   ///< geometric mean of the final bracket
  double bisection_lo = nan;  ///< largest |e| found stable (signed)
  double bisection_hi = nan;  ///< smallest |e| found unstable (signed)
  double relative_difference = nan;  ///< |eigen - bisection| / max (0 if both infinite)
  double a0_rcond = nan;             ///< CHOLMOD rcond estimate of A0 (definiteness criteria)
  int factorizations = 0;            ///< Cholesky factorisations (or dgeev calls) in the bisection
  int size = 0;                      ///< degrees of freedom
  LoadSign sign = LoadSign::Tension;
  StrainCriterion criterion = StrainCriterion::Definiteness;  ///< the criterion actually used
  InstabilityMechanism mechanism = InstabilityMechanism::None;
  std::string eigen_backend;  ///< "dense", "spectra" or "dgeev" (empty if not run)
  Status status = Status::NotComputed;
  std::string reason;     ///< how the value arose; semicolon-separated, no commas (CSV-safe)
  Eigen::VectorXcd mode;  ///< critical mode (2 per free particle), unit norm (want_mode)
  WavevectorEstimate mode_k;
};

/// Critical pre-strain of A(e) = jac.A0 + e jac.A1 in the direction `sign`. Throws std::invalid_argument for invalid
/// options, an empty Jacobian, or criterion Definiteness on a non-symmetric Jacobian.
CriticalStrain critical_strain(const ElasticJacobian2d& jac, LoadSign sign, const CriticalStrainOptions& options = {});

/// The lattice of critical-strain studies: n x n free particles at spacing dx = 1 with fixed layers completing every
/// neighbourhood (support 2h), or periodic. Throws std::invalid_argument for n < 1, h <= 0, a non-2D lattice.
ParticleSet<2> strain_lattice_2d(LatticeType type, const Kernel<2>& kernel, double h, int n, bool periodic = false);

}  // namespace sphstab
