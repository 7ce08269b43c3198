#include "sphstab/stability/critical_strain.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsSolver.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "sphstab/io/format.hpp"
#include "sphstab/linalg/cholmod_cholesky_op.hpp"
#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/linalg/symmetric_pencil.hpp"
#include "sphstab/stability/load_bracket.hpp"

namespace sphstab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Lower triangle (column-major) of a symmetric row-major matrix without transposition: column i of the result holds
/// the entries of row i at columns >= i (equal to the lower triangle by symmetry).
ColSparseMatrix lower_from_symmetric_rows(const SparseMatrix<>& a) {
  const int n = static_cast<int>(a.rows());
  ColSparseMatrix m(n, n);
  std::vector<int> outer(n + 1, 0);
  long nnz = 0;
  for (int i = 0; i < n; ++i) {
    for (SparseMatrix<>::InnerIterator it(a, i); it; ++it)
      if (it.col() >= i) ++nnz;
    outer[i + 1] = static_cast<int>(nnz);
  }
  m.resizeNonZeros(nnz);
  std::copy(outer.begin(), outer.end(), m.outerIndexPtr());
  long k = 0;
  for (int i = 0; i < n; ++i)
    for (SparseMatrix<>::InnerIterator it(a, i); it; ++it)
      if (it.col() >= i) {
        m.innerIndexPtr()[k] = static_cast<int>(it.col());
        m.valuePtr()[k] = it.value();
        ++k;
      }
  return m;
}

/// Lower triangle of (A + A^T)/2.
ColSparseMatrix lower_symmetric_part(const SparseMatrix<>& a) {
  SparseMatrix<> at = a.transpose();
  SparseMatrix<> s = 0.5 * (a + at);
  return lower_from_symmetric_rows(s);
}

void validate(const CriticalStrainOptions& o) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument(std::string("critical_strain: option ") + name + " must be finite and > 0 (got " +
                                  format_number(v) + ")");
  };
  positive(o.e_start, "e_start");
  positive(o.e_max, "e_max");
  positive(o.e_min, "e_min");
  positive(o.rtol, "rtol");
  positive(o.spectrum_rtol, "spectrum_rtol");
  positive(o.imag_tol, "imag_tol");
  positive(o.spectra_tol, "spectra_tol");
  if (o.spectra_maxit <= 0) throw std::invalid_argument("critical_strain: option spectra_maxit must be > 0");
  if (o.dense_max < 0 || o.spectrum_dense_max < 0)
    throw std::invalid_argument("critical_strain: options dense_max and spectrum_dense_max must be >= 0");
}

/// The 2D lattice of the free particles, from the geometry: square (rows dx apart, unshifted), hexagonal (rows
/// dx sqrt(3)/2 apart, alternate rows shifted by dx/2) or face-centred (rows dx apart, shifted).
BravaisLattice2d detect_lattice(const Eigen::MatrixX2d& x, double dx) {
  double dy = kInf;
  bool shifted = false;
  for (Eigen::Index i = 1; i < x.rows(); ++i) {
    const double d = std::abs(x(i, 1) - x(0, 1));
    if (d > 1e-9 * dx) dy = std::min(dy, d);
    const double fx = (x(i, 0) - x(0, 0)) / dx;
    if (std::abs(fx - std::round(fx)) > 0.25) shifted = true;
  }
  if (!shifted) return bravais_lattice_2d(LatticeType::Square, dx);
  if (std::abs(dy - dx * std::sqrt(3.0) / 2) < 1e-6 * dx) return bravais_lattice_2d(LatticeType::Hexagonal, dx);
  return bravais_lattice_2d(LatticeType::FaceCentred, dx);
}

void finish_mode(const ElasticJacobian2d& jac, CriticalStrain& out) {
  if (out.mode.size() == 0) return;
  const double nm = out.mode.norm();
  if (nm > 0) out.mode /= nm;
  const double dx = jac.spacing > 0 ? jac.spacing : 1.0;
  out.mode_k = dominant_wavevector(out.mode, jac.x, detect_lattice(jac.x, dx));
}

/// Definiteness / symmetric-part criterion: A(tau) = K - tau L.
///
/// The bisection's bracket (lo positive definite, hi = 2 lo not) is found first and shared: the bisection refines it,
/// and the Spectra eigen route uses lo as a spectral shift (Cholesky mode with B = K - lo L, positive definite):
/// L x = nu (K - lo L) x has nu = lambda / (1 - lo lambda), so tau = lo + 1/nu_max. Without the shift the wanted end
/// lambda_max = 1/tau_t of L x = lambda K x sits next to a much longer opposite end (-1/|e_compression|) and Lanczos
/// converges slowly; with it nu_max >= 1/(hi - lo) >= 1/lo while nu >= -1/lo on the other side.
void definiteness_routes(const ColSparseMatrix& k, const ColSparseMatrix& l, const CriticalStrainOptions& opt,
                         CriticalStrain& out) {
  const int m = static_cast<int>(k.rows());
  const double sgn = out.sign == LoadSign::Tension ? 1.0 : -1.0;
  const bool eig = opt.method != TcritMethod::Bisection, bis = opt.method != TcritMethod::Eigen;
  const bool dense =
      opt.backend == EigenBackend::Dense || m < 3 || (opt.backend == EigenBackend::Auto && m <= opt.dense_max);

  // A(0) = K must be positive definite for both routes.
  {
    CholmodFactor kf(opt.variant);
    if (!kf.compute(k)) {
      out.status = Status::NumericalIssue;
      append_reason(out.reason,
                    "A0 is not positive definite (Cholesky failed): A(0) singular or indefinite (periodic set? use the "
                    "symbol route)");
      return;
    }
    out.a0_rcond = kf.rcond_estimate();
    if (out.a0_rcond < 1e-14)
      append_reason(out.reason, "A0 near-singular (rcond estimate " + format_number(out.a0_rcond) + ")");
  }

  // Shared bracket (bisection, and the shift of the sparse eigen route).
  SymmetricPencil pencil(k, l);
  CholmodDefiniteness check(opt.variant);
  LoadBracket br;
  const bool need_bracket = bis || (eig && !dense);
  auto pd = [&](double tau) { return check.is_positive_definite(pencil.evaluate(tau)); };
  if (need_bracket) {
    check.analyze_pattern(pencil.pattern());
    br = bracket_critical_load(pd, opt.e_start, opt.e_max, opt.e_min, 8.0);
  }

  Eigen::VectorXd vec;
  if (eig) {
    double tau_eig = CriticalStrain::nan;
    Status st = Status::NotComputed;
    if (dense) {
      out.eigen_backend = "dense";
      const Eigen::MatrixXd kd = Eigen::MatrixXd(k).selfadjointView<Eigen::Lower>();
      const Eigen::MatrixXd ld = Eigen::MatrixXd(l).selfadjointView<Eigen::Lower>();
      DenseSymmetricEigen e = generalized_symmetric_eigen(ld, kd, opt.want_mode);
      st = e.status;
      if (st == Status::Successful) {
        const double lambda_max = e.values[m - 1];
        tau_eig = lambda_max > 0 ? 1.0 / lambda_max : kInf;
        if (opt.want_mode) vec = e.vectors.col(m - 1);
      } else {
        append_reason(out.reason, "dsygv failed (info " + std::to_string(e.lapack_info) + ")");
      }
    } else {
      out.eigen_backend = "spectra";
      // Shift: the positive definite end of the bracket, or e_max when A is positive definite up to e_max (then
      // nu_max <= 0 means stable for every e; without a shift Lanczos crawls towards lambda_max ~ 0-).
      const bool stable_to_max = need_bracket && br.outcome == LoadBracket::Outcome::StableToMax;
      const bool shifted = stable_to_max || (need_bracket && br.outcome == LoadBracket::Outcome::Bracketed);
      const double shift = !shifted ? 0.0 : stable_to_max ? opt.e_max : br.lo;
      CholmodCholeskyOp bop(shifted ? ColSparseMatrix(pencil.evaluate(shift)) : k, opt.variant);
      if (bop.info() != Status::Successful) {
        st = Status::NumericalIssue;
        append_reason(out.reason, "Cholesky of the shifted B = A(lo) failed");
      } else {
        Spectra::SparseSymMatProd<double, Eigen::Lower, Eigen::ColMajor> op(l);
        int ncv = opt.spectra_ncv > 0 ? opt.spectra_ncv : 40;
        st = Status::NotConverging;
        for (int attempt = 0; attempt < 3; ++attempt) {
          ncv = std::min(m, std::max(ncv, 3));
          Spectra::SymGEigsSolver<decltype(op), CholmodCholeskyOp, Spectra::GEigsMode::Cholesky> eigs(op, bop, 1, ncv);
          eigs.init();
          eigs.compute(Spectra::SortRule::LargestAlge, opt.spectra_maxit, opt.spectra_tol,
                       Spectra::SortRule::LargestAlge);
          if (eigs.info() == Spectra::CompInfo::Successful) {
            st = Status::Successful;
            const double nu = eigs.eigenvalues()[0];
            tau_eig = nu > 0 ? shift + 1.0 / nu : kInf;
            if (stable_to_max && std::isfinite(tau_eig)) {
              append_reason(out.reason, "eigen route: first crossing beyond e_max at |e| = " + format_number(tau_eig));
              tau_eig = kInf;
            }
            if (opt.want_mode) vec = eigs.eigenvectors().col(0);
            if (attempt > 0) append_reason(out.reason, "spectra converged with ncv = " + std::to_string(ncv));
            break;
          }
          ncv *= 2;
        }
        if (st != Status::Successful) append_reason(out.reason, "spectra did not converge");
        if (shifted && !stable_to_max && st == Status::Successful &&
            !(tau_eig > shift && tau_eig <= br.hi * (1 + 1e-10)))
          append_reason(out.reason, "shifted eigen route outside the bracket [" + format_number(br.lo) + " " +
                                        format_number(br.hi) + "]");
      }
    }
    if (st == Status::Successful) {
      out.e_eigen = sgn * tau_eig;
      if (std::isinf(tau_eig))
        append_reason(out.reason, "lambda_max <= 0: A(e) positive definite for every e of this sign");
    } else {
      out.status = st;
    }
  }
  if (bis) {
    bisect_critical_load(br, pd, opt.rtol);
    out.factorizations = br.tests;
    if (br.outcome == LoadBracket::Outcome::UnstableToMin) {
      out.status = Status::NumericalIssue;
      append_reason(out.reason, "bisection: unstable down to |e| = " + format_number(opt.e_min));
    } else {
      if (br.outcome == LoadBracket::Outcome::StableToMax)
        append_reason(out.reason, "bisection: stable up to |e| = " + format_number(opt.e_max));
      out.e_bisection = sgn * br.critical();
      out.bisection_lo = sgn * br.lo;
      out.bisection_hi = sgn * br.hi;
    }
  }
  out.mechanism = InstabilityMechanism::RealCrossing;
  if (vec.size() > 0) out.mode = vec.cast<std::complex<double>>();
}

/// Spectrum criterion (dense, any A).
void spectrum_routes(const ElasticJacobian2d& jac, const CriticalStrainOptions& opt, CriticalStrain& out) {
  const double sgn = out.sign == LoadSign::Tension ? 1.0 : -1.0;
  const Eigen::MatrixXd a0(jac.A0);
  const Eigen::MatrixXd a1 = sgn * Eigen::MatrixXd(jac.A1);
  const bool eig = opt.method != TcritMethod::Bisection, bis = opt.method != TcritMethod::Eigen;
  auto spectrum_stable = [&](double tau, DenseGeneralEigen* keep) {
    const Eigen::MatrixXd a = a0 + tau * a1;
    const double tol = opt.imag_tol * a.norm();
    DenseGeneralEigen e = general_eigen(a, keep != nullptr);
    if (e.status != Status::Successful) throw std::runtime_error("dgeev failed");
    bool ok = true;
    for (Eigen::Index t = 0; t < e.values.size(); ++t)
      if (std::abs(e.values[t].imag()) > tol || !(e.values[t].real() > 0)) ok = false;
    if (keep) *keep = std::move(e);
    return ok;
  };
  // A(0) = A0 itself must pass.
  if (!spectrum_stable(0.0, nullptr)) {
    out.status = Status::NumericalIssue;
    append_reason(out.reason,
                  "A0 has an eigenvalue that is not real and positive (periodic set? use the symbol route)");
    return;
  }
  double tau_real = kInf;
  Eigen::VectorXcd real_vec;
  if (eig) {
    out.eigen_backend = "dgeev";
    const Eigen::MatrixXd mm = a0.partialPivLu().solve(a1);
    DenseGeneralEigen e = general_eigen(mm, opt.want_mode);
    if (e.status != Status::Successful) {
      out.status = Status::NumericalIssue;
      append_reason(out.reason, "dgeev of A0^-1 A1 failed");
    } else {
      double nu_min = 0;
      Eigen::Index at = -1;
      for (Eigen::Index t = 0; t < e.values.size(); ++t)
        if (e.values[t].imag() == 0.0 && e.values[t].real() < nu_min) nu_min = e.values[t].real(), at = t;
      if (at >= 0) {
        tau_real = -1.0 / nu_min;
        if (opt.want_mode) real_vec = e.vectors.col(at);
      }
      out.e_eigen = sgn * tau_real;
      if (std::isinf(tau_real)) append_reason(out.reason, "no real e of this sign makes A(e) singular");
    }
  }
  if (!bis) {
    out.mechanism = std::isinf(tau_real) ? InstabilityMechanism::None : InstabilityMechanism::RealCrossing;
    if (real_vec.size()) out.mode = real_vec;
    return;
  }
  // Bisection on the spectrum criterion (one dgeev per test). With the eigen route's first real crossing tau_real,
  // the scan tests tau_real x {1/16, 1/8, 1/4, 1/2, 3/4, 0.9, 1 - d} (d = spectrum_rtol / 4) from below, then
  // tau_real (1 + d): an instability found below tau_real is bisected; otherwise the bracket is
  // [tau_real (1 - d), tau_real (1 + d)], verified by the spectrum itself. Without tau_real: doubling from e_start.
  int tests = 0;
  auto stable = [&](double tau) {
    ++tests;
    return spectrum_stable(tau, nullptr);
  };
  double lo = 0, hi = kInf;
  if (std::isfinite(tau_real) && tau_real <= opt.e_max) {
    const double d = 0.25 * opt.spectrum_rtol;
    for (double f : {1.0 / 16, 1.0 / 8, 0.25, 0.5, 0.75, 0.9, 1 - d}) {
      if (!stable(f * tau_real)) {
        hi = f * tau_real;
        break;
      }
      lo = f * tau_real;
    }
    if (std::isinf(hi)) {
      if (!stable(tau_real * (1 + d))) {
        hi = tau_real * (1 + d);
      } else {
        append_reason(out.reason, "spectrum stable just past the real crossing: doubling from there");
        double tau = tau_real * (1 + d);
        lo = tau;
        while (std::isinf(hi)) {
          tau *= 2;
          if (tau > opt.e_max) break;
          (stable(tau) ? lo : hi) = tau;
        }
      }
    }
    if (lo == 0) {  // unstable already at tau_real / 16: halve down
      double tau = hi;
      while (lo == 0) {
        tau *= 0.5;
        if (tau < opt.e_min) break;
        (stable(tau) ? lo : hi) = tau;
      }
    }
  } else {
    const LoadBracket b = bracket_critical_load(stable, opt.e_start, opt.e_max, opt.e_min, 8.0);
    lo = b.lo;
    hi = b.hi;
  }
  if (std::isinf(hi)) {
    out.e_bisection = sgn * kInf;
    out.bisection_lo = sgn * lo;
    out.factorizations = tests;
    out.mechanism = InstabilityMechanism::None;
    append_reason(out.reason, "spectrum bisection: stable up to |e| = " + format_number(opt.e_max));
    return;
  }
  if (!(lo > 0)) {
    out.status = Status::NumericalIssue;
    out.factorizations = tests;
    append_reason(out.reason, "spectrum bisection: unstable down to |e| = " + format_number(opt.e_min));
    return;
  }
  LoadBracket refined;
  refined.lo = lo;
  refined.hi = hi;
  bisect_critical_load(refined, stable, opt.spectrum_rtol);
  lo = refined.lo;
  hi = refined.hi;
  out.factorizations = tests;
  out.e_bisection = sgn * refined.critical();
  out.bisection_lo = sgn * lo;
  out.bisection_hi = sgn * hi;
  // Mechanism and mode at the first unstable point.
  DenseGeneralEigen at_hi;
  spectrum_stable(hi, &at_hi);
  const double tol = opt.imag_tol * (a0 + hi * a1).norm();
  Eigen::Index worst = -1;
  bool complex_pair = false;
  double worst_re = kInf;
  for (Eigen::Index t = 0; t < at_hi.values.size(); ++t) {
    const auto mu = at_hi.values[t];
    if (!(mu.real() > 0) && std::abs(mu.imag()) <= tol && mu.real() < worst_re) worst_re = mu.real(), worst = t;
  }
  if (worst < 0) {
    double im = 0;
    for (Eigen::Index t = 0; t < at_hi.values.size(); ++t)
      if (std::abs(at_hi.values[t].imag()) > im) im = std::abs(at_hi.values[t].imag()), worst = t;
    complex_pair = worst >= 0;
  }
  out.mechanism = complex_pair ? InstabilityMechanism::ComplexPair : InstabilityMechanism::RealCrossing;
  if (opt.want_mode) {
    if (!complex_pair && real_vec.size() && std::isfinite(tau_real) &&
        std::abs(tau_real - std::sqrt(lo * hi)) <= 1e-6 * tau_real)
      out.mode = real_vec;
    else if (worst >= 0 && at_hi.vectors.size())
      out.mode = at_hi.vectors.col(worst);
  }
  if (complex_pair)
    append_reason(out.reason, "complex pair (flutter) before any real crossing" +
                                  (std::isfinite(tau_real)
                                       ? std::string(" (real crossing at |e| = ") + format_number(tau_real) + ")"
                                       : std::string("")));
}

}  // namespace

StrainCriterion parse_strain_criterion(const std::string& name) {
  if (name == "auto") return StrainCriterion::Auto;
  if (name == "definiteness") return StrainCriterion::Definiteness;
  if (name == "spectrum") return StrainCriterion::Spectrum;
  if (name == "symmetric-part") return StrainCriterion::SymmetricPart;
  throw std::invalid_argument("unknown criterion '" + name + "' (valid: auto, definiteness, spectrum, symmetric-part)");
}

std::string strain_criterion_name(StrainCriterion c) {
  switch (c) {
    case StrainCriterion::Auto:
      return "auto";
    case StrainCriterion::Definiteness:
      return "definiteness";
    case StrainCriterion::Spectrum:
      return "spectrum";
    case StrainCriterion::SymmetricPart:
      return "symmetric-part";
  }
  return "?";
}

CriticalStrain critical_strain(const ElasticJacobian2d& jac, LoadSign sign, const CriticalStrainOptions& opt) {
  validate(opt);
  const int m = jac.dofs();
  if (m == 0 || jac.A1.rows() != m || jac.A1.cols() != m || jac.A0.cols() != m)
    throw std::invalid_argument("critical_strain: A0 and A1 must both be square of the same size (got " +
                                std::to_string(jac.A0.rows()) + " and " + std::to_string(jac.A1.rows()) + ")");
  StrainCriterion crit = opt.criterion;
  if (crit == StrainCriterion::Auto)
    crit = jac.symmetric                 ? StrainCriterion::Definiteness
           : m <= opt.spectrum_dense_max ? StrainCriterion::Spectrum
                                         : StrainCriterion::SymmetricPart;
  if (crit == StrainCriterion::Definiteness && !jac.symmetric)
    throw std::invalid_argument(
        "critical_strain: criterion 'definiteness' needs a symmetric A(e) (conservative, minus or isotropic "
        "pre-strain on a complete lattice); use 'spectrum' or 'symmetric-part'");
  CriticalStrain out;
  out.size = m;
  out.sign = sign;
  out.criterion = crit;
  const double sgn = sign == LoadSign::Tension ? 1.0 : -1.0;

  const auto is_zero = [](const SparseMatrix<>& a) {
    return a.nonZeros() == 0 || a.coeffs().cwiseAbs().maxCoeff() == 0.0;
  };
  if (is_zero(jac.A0) && is_zero(jac.A1)) {  // no pair interacts: A = 0 is singular, stability is undefined
    out.e = out.e_eigen = out.e_bisection = kNaN;
    out.status = Status::NumericalIssue;
    out.mechanism = InstabilityMechanism::None;
    out.reason = "A0 = A1 = 0: no particle has a neighbour inside the kernel support (h too small for the lattice)";
    return out;
  }
  if (is_zero(jac.A1)) {
    out.e = out.e_eigen = out.e_bisection = sgn * kInf;
    out.status = Status::Successful;
    out.mechanism = InstabilityMechanism::None;
    out.reason = "A1 = 0 (e.g. the minus form): A does not depend on e";
    return out;
  }
  if (crit == StrainCriterion::Spectrum) {
    spectrum_routes(jac, opt, out);
    if (out.status == Status::NotComputed || out.status == Status::Successful) {
      const bool complex_first = out.mechanism == InstabilityMechanism::ComplexPair;
      out.e =
          (!std::isnan(out.e_bisection) && (complex_first || std::isnan(out.e_eigen))) ? out.e_bisection : out.e_eigen;
    }
  } else {
    ColSparseMatrix k, l;
    if (crit == StrainCriterion::Definiteness) {
      k = lower_from_symmetric_rows(jac.A0);
      l = lower_from_symmetric_rows(jac.A1);
    } else {
      k = lower_symmetric_part(jac.A0);
      l = lower_symmetric_part(jac.A1);
      append_reason(out.reason, "symmetric-part criterion: definiteness of (A + A^T)/2 (not the stability criterion)");
    }
    l *= -sgn;
    k.makeCompressed();
    l.makeCompressed();
    definiteness_routes(k, l, opt, out);
    out.e = !std::isnan(out.e_eigen) ? out.e_eigen : out.e_bisection;
  }
  if (!std::isnan(out.e_eigen) && !std::isnan(out.e_bisection) && out.mechanism != InstabilityMechanism::ComplexPair) {
    const double a = out.e_eigen, b = out.e_bisection;
    out.relative_difference = (std::isinf(a) && std::isinf(b))   ? 0.0
                              : (std::isinf(a) || std::isinf(b)) ? kInf
                                                                 : std::abs(a - b) / std::max(std::abs(a), std::abs(b));
    if (out.relative_difference > 1e-8) {
      append_reason(out.reason, "eigen and bisection routes disagree by " + format_number(out.relative_difference));
      if (out.relative_difference > 1e-6) out.status = Status::NumericalIssue;
    }
  }
  if (std::isinf(out.e)) out.mechanism = InstabilityMechanism::None;
  if (opt.want_mode && std::isfinite(out.e)) finish_mode(jac, out);
  if (out.status == Status::NotComputed) out.status = std::isnan(out.e) ? Status::NumericalIssue : Status::Successful;
  if (out.reason.empty()) out.reason = "ok";
  return out;
}

ParticleSet<2> strain_lattice_2d(LatticeType type, const Kernel<2>& kernel, double h, int n, bool periodic) {
  if (n < 1)
    throw std::invalid_argument("strain_lattice_2d: need at least one free particle per side (got " +
                                std::to_string(n) + ")");
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("strain_lattice_2d: h must be finite and > 0 (got " + format_number(h) + ")");
  if (type != LatticeType::Square && type != LatticeType::Hexagonal && type != LatticeType::FaceCentred)
    throw std::invalid_argument("strain_lattice_2d: lattice '" + lattice_name(type) +
                                "' is not two-dimensional (valid: square, hex, face-centred)");
  return make_lattice<2>(type, n, {.spacing = 1.0, .support_radius = kernel.support_radius(h), .periodic = periodic});
}

}  // namespace sphstab
