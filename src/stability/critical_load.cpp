#include "sphstab/stability/critical_load.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsSolver.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
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

SparseMatrix<> symmetric_part(const SparseMatrix<>& a) {
  SparseMatrix<> at = a.transpose();
  return SparseMatrix<>(0.5 * (a + at));
}

void validate(const Linearisation& lin, const CriticalLoadOptions& o) {
  const auto n = lin.A0.rows();
  if (n == 0 || lin.A0.cols() != n || lin.A1.rows() != n || lin.A1.cols() != n)
    throw std::invalid_argument("critical_load: A0 and A1 must be non-empty, square and of equal size (got " +
                                std::to_string(lin.A0.rows()) + " x " + std::to_string(lin.A0.cols()) + " and " +
                                std::to_string(lin.A1.rows()) + " x " + std::to_string(lin.A1.cols()) + ")");
  for (const SparseMatrix<>* m : {&lin.A0, &lin.A1})
    for (Eigen::Index k = 0; k < m->nonZeros(); ++k)
      if (!std::isfinite(m->valuePtr()[k])) throw std::invalid_argument("critical_load: A0 and A1 must be finite");
  if (lin.dofs_per_particle < 1 || n % lin.dofs_per_particle != 0)
    throw std::invalid_argument("critical_load: dofs_per_particle must divide the size (got " +
                                std::to_string(lin.dofs_per_particle) + " for " + std::to_string(n) + " dofs)");
  if (lin.x.size() != 0 && (lin.x.rows() != lin.free_count() || lin.x.cols() != lin.dofs_per_particle))
    throw std::invalid_argument("critical_load: x must be free_count x dofs_per_particle (got " +
                                std::to_string(lin.x.rows()) + " x " + std::to_string(lin.x.cols()) + ")");
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument(std::string("critical_load: option ") + name + " must be finite and > 0 (got " +
                                  format_number(v) + ")");
  };
  positive(o.start, "start");
  positive(o.max, "max");
  positive(o.min, "min");
  positive(o.rtol, "rtol");
  positive(o.spectrum_rtol, "spectrum_rtol");
  positive(o.imag_tol, "imag_tol");
  positive(o.spectra_tol, "spectra_tol");
  if (!(o.step > 1) || !std::isfinite(o.step))
    throw std::invalid_argument("critical_load: option step must be finite and > 1 (got " + format_number(o.step) +
                                ")");
  if (o.spectra_maxit <= 0) throw std::invalid_argument("critical_load: option spectra_maxit must be > 0");
  if (o.dense_max < 0 || o.spectrum_dense_max < 0)
    throw std::invalid_argument("critical_load: options dense_max and spectrum_dense_max must be >= 0");
  if (!(o.zero_tol >= 0)) throw std::invalid_argument("critical_load: option zero_tol must be >= 0");
  if (o.growth_factor != 0 && (!(o.growth_factor > 1) || !std::isfinite(o.growth_factor)))
    throw std::invalid_argument("critical_load: option growth_factor must be 0 or finite and > 1 (got " +
                                format_number(o.growth_factor) + ")");
}

double relative_difference(double a, double b) {
  if (std::isinf(a) && std::isinf(b)) return 0.0;
  if (std::isinf(a) || std::isinf(b)) return kInf;
  return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}

/// Basis (columns) of the complement of the translation (and, if `sawtooth`, of the sawtooth) on nf points ordered
/// by `order`: e_i - e_{i+1} (or e_i - e_{i+2}).
ColSparseMatrix deflation_basis(const std::vector<int>& order, bool sawtooth) {
  const int nf = static_cast<int>(order.size()), step = sawtooth ? 2 : 1;
  ColSparseMatrix d(nf, nf - step);
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < nf - step; ++c) {
    t.emplace_back(order[c], c, 1.0);
    t.emplace_back(order[c + step], c, -1.0);
  }
  d.setFromTriplets(t.begin(), t.end());
  return d;
}

/// The pencil A = K - tau L of the definiteness criteria, its deflation basis and the outcome of the deflation.
struct Pencil {
  ColSparseMatrix k, l;   ///< lower triangles (column-major)
  ColSparseMatrix basis;  ///< deflation basis (empty: none)
  bool decided = false;   ///< the deflation already decided the result (load and status set)
};

/// 1D periodic lattice: project out the translation and, for even N, the sawtooth s (G s = 0, so s'As = -tau s'Ls).
Pencil deflate_periodic_1d(ColSparseMatrix k, ColSparseMatrix l, const Linearisation& lin, double sgn,
                           CriticalLoad& out) {
  Pencil p;
  const int nf = static_cast<int>(k.rows());
  std::vector<int> order(nf);
  std::iota(order.begin(), order.end(), 0);
  const Eigen::VectorXd x = lin.x.col(0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return x[a] < x[b]; });
  const bool even = nf % 2 == 0;
  if (even) {
    Eigen::VectorXd s(nf);
    for (int r = 0; r < nf; ++r) s[order[r]] = (r % 2 == 0) ? 1.0 : -1.0;
    const SparseMatrix<> lfull = SparseMatrix<>(-sgn * lin.A1);
    const double ls = s.dot(lfull * s) / nf;
    const double scale = lfull.diagonal().cwiseAbs().maxCoeff();
    const double tol = 1e-12 * std::max(scale, 1e-300);
    if (ls >= -tol) {
      out.load = out.load_eigen = out.load_bisection = 0.0;
      out.status = Status::Successful;
      out.reason = ls > tol
                       ? "periodic even N: sawtooth mode has G s = 0 and -s'A1s/s's = " + format_number(ls) +
                             " > 0 so A is indefinite for every load of this sign"
                       : "periodic even N: sawtooth mode has G s = 0 and s'A1s = 0 so A is singular for every load";
      p.decided = true;
      return p;
    }
    append_reason(out.reason, "sawtooth mode projected out (G s = 0 and -s'A1s/s's = " + format_number(ls) +
                                  " < 0: neutral at zero load and stabilised by it)");
  }
  append_reason(out.reason, "translation mode projected out");
  if (nf - (even ? 2 : 1) < 1) {
    out.status = Status::NumericalIssue;
    out.reason += "; no degrees of freedom left after deflation";
    p.decided = true;
    return p;
  }
  p.basis = deflation_basis(order, even);
  ColSparseMatrix bt = p.basis.transpose();
  // The full symmetric matrices (not their triangles) enter the projection.
  ColSparseMatrix kf = ColSparseMatrix(k.selfadjointView<Eigen::Lower>()),
                  lf = ColSparseMatrix(l.selfadjointView<Eigen::Lower>());
  p.k = lower_triangle(ColSparseMatrix(bt * kf * p.basis));
  p.l = lower_triangle(ColSparseMatrix(bt * lf * p.basis));
  return p;
}

struct EigenRoute {
  double tau = kNaN;
  double lambda_max = kNaN;
  Status status = Status::NotComputed;
  Eigen::VectorXd vector;
};

/// L x = lambda K x: tau = 1/lambda_max (dense or Spectra, optionally shifted by `shift` > 0: B = K - shift L).
EigenRoute eigen_route(const ColSparseMatrix& k, const ColSparseMatrix& l, const CriticalLoadOptions& opt, bool dense,
                       double shift, const ColSparseMatrix* shifted_b, CriticalLoad& out) {
  EigenRoute r;
  const int m = static_cast<int>(k.rows());
  if (dense) {
    out.eigen_backend = "dense";
    require_dense_memory(m, 5, "critical_load (dense generalised eigenproblem)");
    const Eigen::MatrixXd kd = Eigen::MatrixXd(k).selfadjointView<Eigen::Lower>();
    const Eigen::MatrixXd ld = Eigen::MatrixXd(l).selfadjointView<Eigen::Lower>();
    DenseSymmetricEigen e = generalized_symmetric_eigen(ld, kd, opt.want_mode);
    r.status = e.status;
    if (e.status != Status::Successful) {
      append_reason(out.reason, "dsygv failed (info " + std::to_string(e.lapack_info) + ")");
      return r;
    }
    r.lambda_max = e.values[m - 1];
    r.tau = r.lambda_max > 0 ? 1.0 / r.lambda_max : kInf;
    if (opt.want_mode) r.vector = e.vectors.col(m - 1);
    return r;
  }
  out.eigen_backend = "spectra";
  CholmodCholeskyOp bop(shifted_b ? *shifted_b : k, opt.variant);
  if (bop.info() != Status::Successful) {
    r.status = Status::NumericalIssue;
    append_reason(out.reason, shifted_b ? "Cholesky of the shifted B = A(lo) failed" : "Cholesky of K failed");
    return r;
  }
  Spectra::SparseSymMatProd<double, Eigen::Lower, Eigen::ColMajor> op(l);
  int ncv = opt.spectra_ncv > 0 ? opt.spectra_ncv : 40;
  for (int attempt = 0; attempt < 3; ++attempt) {
    ncv = std::min(m, std::max(ncv, 3));
    Spectra::SymGEigsSolver<decltype(op), CholmodCholeskyOp, Spectra::GEigsMode::Cholesky> eigs(op, bop, 1, ncv);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, opt.spectra_maxit, opt.spectra_tol, Spectra::SortRule::LargestAlge);
    if (eigs.info() == Spectra::CompInfo::Successful) {
      r.status = Status::Successful;
      const double nu = eigs.eigenvalues()[0];
      if (shifted_b) {
        r.tau = nu > 0 ? shift + 1.0 / nu : kInf;
      } else {
        r.lambda_max = nu;
        r.tau = nu > 0 ? 1.0 / nu : kInf;
      }
      if (opt.want_mode) r.vector = eigs.eigenvectors().col(0);
      if (attempt > 0) append_reason(out.reason, "spectra converged with ncv = " + std::to_string(ncv));
      return r;
    }
    ncv *= 2;
  }
  r.status = Status::NotConverging;
  append_reason(out.reason, "spectra did not converge (ncv up to " + std::to_string(ncv / 2) + ")");
  return r;
}

/// Definiteness of A(tau) = K - tau L (the Definiteness and SymmetricPart criteria).
void definiteness_routes(const Linearisation& lin, const SparseMatrix<>& a0, const SparseMatrix<>& a1,
                         const CriticalLoadOptions& opt, CriticalLoad& out) {
  const double sgn = load_sign(out.direction);
  Pencil p;
  p.k = lower_from_symmetric_rows(a0);
  p.l = lower_from_symmetric_rows(a1);
  p.l *= -sgn;
  if (lin.periodic && lin.dofs_per_particle == 1 && opt.deflate_periodic && lin.x.size() > 0) {
    p = deflate_periodic_1d(p.k, p.l, lin, sgn, out);
    if (p.decided) return;
  }
  p.k.makeCompressed();
  p.l.makeCompressed();
  const int m = static_cast<int>(p.k.rows());
  out.size = m;

  // A(0) = K must be positive definite for both routes.
  {
    CholmodFactor kf(opt.variant);
    if (!kf.compute(p.k)) {
      if (opt.a0_failure_is_zero_load) {
        out.load = out.lo = out.hi = 0.0;
        out.status = Status::Successful;
        append_reason(out.reason, "A(0) is not positive definite: unstable at zero load");
        return;
      }
      out.status = Status::NumericalIssue;
      append_reason(out.reason, "A0 is not positive definite (Cholesky failed at column " +
                                    std::to_string(kf.failed_column()) +
                                    "): A(0) singular or indefinite so the critical load is undefined here (periodic "
                                    "2D set? use the symbol route)");
      return;
    }
    out.a0_rcond = kf.rcond_estimate();
    if (out.a0_rcond < 1e-14)
      append_reason(out.reason, "A0 near-singular (rcond estimate " + format_number(out.a0_rcond) + ")");
  }

  const bool eig = opt.method != CriticalLoadMethod::Bisection, bis = opt.method != CriticalLoadMethod::Eigen;
  const bool dense =
      opt.backend == EigenBackend::Dense || m < 3 || (opt.backend == EigenBackend::Auto && m <= opt.dense_max);
  SymmetricPencil pencil(p.k, p.l);
  CholmodDefiniteness check(opt.variant);
  LoadBracket br;
  auto pd = [&](double tau) { return check.is_positive_definite(pencil.evaluate(tau)); };
  const bool need_bracket = bis || (eig && !dense && opt.shift_spectra);
  if (need_bracket) {
    check.analyze_pattern(pencil.pattern());
    br = bracket_critical_load(pd, opt.start, opt.max, opt.min, opt.step);
  }

  Eigen::VectorXd vec;
  if (eig) {
    // Shift (sparse route): the positive definite end of the bracket, or max when A is positive definite up to max
    // (then nu_max <= 0 means stable for every load; without a shift Lanczos crawls towards lambda_max ~ 0-).
    const bool stable_to_max = need_bracket && br.outcome == LoadBracket::Outcome::StableToMax;
    const bool shifted = !dense && opt.shift_spectra &&
                         (stable_to_max || (need_bracket && br.outcome == LoadBracket::Outcome::Bracketed));
    const double shift = !shifted ? 0.0 : stable_to_max ? opt.max : br.lo;
    const ColSparseMatrix b = shifted ? ColSparseMatrix(pencil.evaluate(shift)) : ColSparseMatrix();
    EigenRoute e = eigen_route(p.k, p.l, opt, dense, shift, shifted ? &b : nullptr, out);
    if (e.status == Status::Successful) {
      double tau = e.tau;
      if (shifted && stable_to_max && std::isfinite(tau)) {
        append_reason(out.reason, "eigen route: first crossing beyond max at |load| = " + format_number(tau));
        tau = kInf;
      }
      if (shifted && !stable_to_max && !(tau > shift && tau <= br.hi * (1 + 1e-10)))
        append_reason(out.reason, "shifted eigen route outside the bracket [" + format_number(br.lo) + " " +
                                      format_number(br.hi) + "]");
      out.lambda_max = e.lambda_max;
      out.load_eigen = sgn * tau;
      if (std::isinf(tau))
        append_reason(out.reason, "lambda_max <= 0: A positive definite for every load of this sign");
      if (opt.want_mode && e.vector.size() > 0)
        vec = p.basis.size() > 0 ? Eigen::VectorXd(p.basis * e.vector) : e.vector;
    } else {
      out.status = e.status;
    }
  }
  if (bis) {
    bisect_critical_load(br, pd, opt.rtol);
    out.evaluations = br.tests;
    if (br.outcome == LoadBracket::Outcome::UnstableToMin) {
      out.status = Status::NumericalIssue;
      append_reason(out.reason, "bisection: not positive definite down to |load| = " + format_number(opt.min));
    } else {
      if (br.outcome == LoadBracket::Outcome::StableToMax)
        append_reason(out.reason, "bisection: positive definite up to |load| = " + format_number(opt.max));
      out.load_bisection = sgn * br.critical();
      out.lo = sgn * br.lo;
      out.hi = sgn * br.hi;
    }
  }
  if (!std::isnan(out.load_eigen) && !std::isnan(out.load_bisection)) {
    out.relative_difference = relative_difference(out.load_eigen, out.load_bisection);
    if (out.relative_difference > 1e-8) {
      // Both routes see K only through its rounded entries: the load is determined to about eps / rcond(K).
      append_reason(out.reason, "eigen and bisection routes disagree by " + format_number(out.relative_difference) +
                                    " (conditioning of K limits accuracy to about eps/rcond = " +
                                    format_number(std::numeric_limits<double>::epsilon() / out.a0_rcond) + ")");
      if (out.relative_difference > 1e-6) out.status = Status::NumericalIssue;
    }
  }
  out.load = !std::isnan(out.load_eigen) ? out.load_eigen : out.load_bisection;
  out.mechanism = InstabilityMechanism::RealCrossing;
  if (vec.size() > 0) out.mode = vec.cast<std::complex<double>>();
}

/// Which way a spectrum fails the criterion ("" when it passes).
std::string spectrum_failure(const Eigen::MatrixXd& a, const CriticalLoadOptions& opt, DenseGeneralEigen* keep) {
  DenseGeneralEigen e = general_eigen(a, keep != nullptr);
  if (e.status != Status::Successful) throw std::runtime_error("critical_load: dgeev failed");
  const double scale = opt.imag_scale == ImagScale::FrobeniusNorm ? a.norm() : e.values.cwiseAbs().maxCoeff();
  const double tol = opt.imag_tol * scale;
  bool complex_pair = false, nonpositive = false;
  for (Eigen::Index t = 0; t < e.values.size(); ++t) {
    if (std::abs(e.values[t].imag()) > tol) complex_pair = true;
    if (!(e.values[t].real() > 0)) nonpositive = true;
  }
  if (keep) *keep = std::move(e);
  if (complex_pair && nonpositive) return "complex pair and Re mu <= 0";
  if (complex_pair) return "complex pair (flutter)";
  if (nonpositive) return "real mu <= 0 (divergence)";
  return "";
}

/// The eigen route of the spectrum criterion: the real crossings det A(load) = 0 from the eigenvalues nu of M =
/// A0^-1 (sgn A1): A0 + tau sgn A1 is singular iff nu = -1/tau, so tau_real = -1/nu for the most negative real nu
/// (+inf: none). false: dgeev failed (out says so).
bool first_real_crossing(const Eigen::MatrixXd& a0, const Eigen::MatrixXd& a1, const CriticalLoadOptions& opt,
                         CriticalLoad& out, double& tau_real, Eigen::VectorXcd& real_vec) {
  const double sgn = load_sign(out.direction);
  out.eigen_backend = "dgeev";
  const Eigen::MatrixXd mm = a0.partialPivLu().solve(a1);
  DenseGeneralEigen e = general_eigen(mm, opt.want_mode);
  if (e.status != Status::Successful) {
    out.status = Status::NumericalIssue;
    append_reason(out.reason, "dgeev of A0^-1 A1 failed");
    return false;
  }
  double nu_min = 0;
  Eigen::Index at = -1;
  for (Eigen::Index t = 0; t < e.values.size(); ++t)
    if (e.values[t].imag() == 0.0 && e.values[t].real() < nu_min) nu_min = e.values[t].real(), at = t;
  if (at >= 0) {
    tau_real = -1.0 / nu_min;
    if (opt.want_mode) real_vec = e.vectors.col(at);
  }
  out.load_eigen = sgn * tau_real;
  if (std::isinf(tau_real)) append_reason(out.reason, "no real load of this sign makes A singular");
  return true;
}

/// Refines [lo, hi] by bisection on the spectrum criterion and classifies the first instability (mechanism, mode);
/// returns true when it is a complex pair (flutter). `tests` is the stability test's counter.
template <class Stable>
bool bisect_spectrum(Stable& stable, const int& tests, const Eigen::MatrixXd& a0, const Eigen::MatrixXd& a1,
                     const CriticalLoadOptions& opt, CriticalLoad& out, double& lo, double& hi, double tau_real,
                     const Eigen::VectorXcd& real_vec) {
  const double sgn = load_sign(out.direction);
  LoadBracket refined;
  refined.lo = lo;
  refined.hi = hi;
  bisect_critical_load(refined, stable, opt.spectrum_rtol);
  lo = refined.lo;
  hi = refined.hi;
  out.load_bisection = sgn * refined.critical();
  out.lo = sgn * lo;
  out.hi = sgn * hi;
  // Mechanism and mode at the first unstable point.
  DenseGeneralEigen at_hi;
  const std::string failure = spectrum_failure(a0 + hi * a1, opt, &at_hi);
  const double scale =
      opt.imag_scale == ImagScale::FrobeniusNorm ? (a0 + hi * a1).norm() : at_hi.values.cwiseAbs().maxCoeff();
  const double tol = opt.imag_tol * scale;
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
  append_reason(out.reason, "eigenvalue leaves the positive real axis: " + failure);
  if (opt.want_mode) {
    if (!complex_pair && real_vec.size() && std::isfinite(tau_real) &&
        std::abs(tau_real - std::sqrt(lo * hi)) <= 1e-6 * tau_real)
      out.mode = real_vec;
    else if (worst >= 0 && at_hi.vectors.size())
      out.mode = at_hi.vectors.col(worst);
  }
  if (complex_pair && std::isfinite(tau_real))
    append_reason(out.reason, "complex pair before the real crossing at |load| = " + format_number(tau_real));
  out.evaluations = tests;
  return complex_pair;
}

/// The bracket [lo, hi] of the spectrum criterion from the first real crossing tau_real (see spectrum_routes).
template <class Stable>
void scan_from_real_crossing(Stable& stable, double tau_real, const CriticalLoadOptions& opt, CriticalLoad& out,
                             double& lo, double& hi) {
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
        if (tau > opt.max) break;
        (stable(tau) ? lo : hi) = tau;
      }
    }
  }
  if (lo == 0) {  // unstable already at tau_real / 16: halve down
    double tau = hi;
    while (lo == 0) {
      tau *= 0.5;
      if (tau < opt.min) break;
      (stable(tau) ? lo : hi) = tau;
    }
  }
}

/// Spectrum criterion (dense, any A).
void spectrum_routes(const Linearisation& lin, const CriticalLoadOptions& opt, CriticalLoad& out) {
  const double sgn = load_sign(out.direction);
  require_dense_memory(lin.A0.rows(), 5, "critical_load (dense spectrum criterion)");
  const Eigen::MatrixXd a0(lin.A0);
  const Eigen::MatrixXd a1 = sgn * Eigen::MatrixXd(lin.A1);
  int tests = 0;
  std::string last_failure;
  auto stable = [&](double tau) {
    ++tests;
    last_failure = spectrum_failure(a0 + tau * a1, opt, nullptr);
    return last_failure.empty();
  };
  if (!stable(0.0)) {
    if (opt.a0_failure_is_zero_load) {
      out.load = out.load_bisection = out.lo = out.hi = 0.0;
      out.status = Status::Successful;
      append_reason(out.reason, "spectrum of A(0) already fails: " + last_failure);
    } else {
      out.status = Status::NumericalIssue;
      append_reason(out.reason, "A0 has an eigenvalue that is not real and positive: " + last_failure +
                                    " (periodic set? use the symbol route)");
    }
    return;
  }
  tests = 0;  // evaluations count the search, not the check of A(0) (as the Cholesky check of the definiteness route)
  // Eigen route: real crossings det A(load) = 0 from the eigenvalues nu of M = A0^-1 (sgn A1):
  // A0 + tau sgn A1 singular iff nu = -1/tau, so tau_real = -1/nu for the most negative real nu.
  double tau_real = kInf;
  Eigen::VectorXcd real_vec;
  if (opt.spectrum_real_crossing && !first_real_crossing(a0, a1, opt, out, tau_real, real_vec)) return;
  // Bisection on the criterion (one dgeev per test). With the first real crossing tau_real, the scan tests
  // tau_real x {1/16, 1/8, 1/4, 1/2, 3/4, 0.9, 1 - d} (d = spectrum_rtol / 4) from below, then tau_real (1 + d): an
  // instability found below tau_real is bisected; otherwise the bracket is [tau_real (1 - d), tau_real (1 + d)],
  // verified by the spectrum itself. Without tau_real: the geometric bracket from `start`.
  double lo = 0, hi = kInf;
  if (std::isfinite(tau_real) && tau_real <= opt.max) {
    scan_from_real_crossing(stable, tau_real, opt, out, lo, hi);
  } else {
    const LoadBracket b = bracket_critical_load(stable, opt.start, opt.max, opt.min, opt.step);
    lo = b.lo;
    hi = b.hi;
  }
  out.evaluations = tests;
  bool complex_first = false;
  if (std::isinf(hi)) {
    out.load_bisection = sgn * kInf;
    out.lo = sgn * lo;
    out.mechanism = InstabilityMechanism::None;
    append_reason(out.reason, "spectrum real and positive up to |load| = " + format_number(opt.max));
  } else if (!(lo > 0)) {
    out.load = out.load_bisection = 0.0;
    out.lo = 0.0;
    out.hi = sgn * hi;
    append_reason(out.reason,
                  "spectrum fails for every sampled |load| >= " + format_number(opt.min) + " (" + last_failure + ")");
    if (!opt.a0_failure_is_zero_load) {
      out.load = out.load_bisection = kNaN;
      out.status = Status::NumericalIssue;
    }
    return;
  } else {
    complex_first = bisect_spectrum(stable, tests, a0, a1, opt, out, lo, hi, tau_real, real_vec);
  }
  // The result: the real crossing when it is the first instability, else the bisection.
  out.load = (complex_first || std::isnan(out.load_eigen)) ? out.load_bisection : out.load_eigen;
  if (!complex_first && !std::isnan(out.load_eigen) && !std::isnan(out.load_bisection)) {
    out.relative_difference = relative_difference(out.load_eigen, out.load_bisection);
    if (out.relative_difference > 1e-8) {
      append_reason(out.reason, "eigen and bisection routes disagree by " + format_number(out.relative_difference));
      if (out.relative_difference > 1e-6) out.status = Status::NumericalIssue;
    }
  }
}

/// The dominant wavenumber (1D) or wavevector (2D) of the critical mode.
void finish_mode(const Linearisation& lin, CriticalLoad& out) {
  if (out.mode.size() == 0 || lin.x.size() == 0) return;
  const double nm = out.mode.norm();
  if (nm > 0) out.mode /= nm;
  if (lin.dofs_per_particle == 1) {
    out.mode_wavenumber = dominant_wavenumber(Eigen::VectorXd(out.mode.real()), lin.x.col(0), lin.periodic);
  } else if (lin.dofs_per_particle == 2) {
    const Eigen::MatrixX2d x = lin.x;
    out.mode_wavevector =
        dominant_wavevector(out.mode, x, detect_bravais_lattice_2d(x, lin.spacing > 0 ? lin.spacing : 1.0));
  }
}

}  // namespace

constexpr NamedValue<Criterion> kCriterionNames[] = {{Criterion::Auto, "auto"},
                                                     {Criterion::Definiteness, "definiteness"},
                                                     {Criterion::Spectrum, "spectrum"},
                                                     {Criterion::SymmetricPart, "symmetric-part"},
                                                     {Criterion::Definiteness, "pd"},
                                                     {Criterion::Spectrum, "real-positive-spectrum"},
                                                     {Criterion::SymmetricPart, "symmetric-part-pd"}};
constexpr NamedValue<CriticalLoadMethod> kCriticalLoadMethodNames[] = {
    {CriticalLoadMethod::Eigen, "eig"}, {CriticalLoadMethod::Bisection, "bisect"}, {CriticalLoadMethod::Both, "both"}};
constexpr NamedValue<EigenBackend> kEigenBackendNames[] = {
    {EigenBackend::Auto, "auto"}, {EigenBackend::Dense, "dense"}, {EigenBackend::Spectra, "spectra"}};

Criterion parse_criterion(const std::string& name) { return parse_named(name, kCriterionNames, "criterion"); }
std::string criterion_name(Criterion c) { return name_of(c, kCriterionNames); }
CriticalLoadMethod parse_critical_load_method(const std::string& name) {
  return parse_named(name, kCriticalLoadMethodNames, "method");
}
std::string critical_load_method_name(CriticalLoadMethod method) { return name_of(method, kCriticalLoadMethodNames); }
EigenBackend parse_eigen_backend(const std::string& name) {
  return parse_named(name, kEigenBackendNames, "eigen backend");
}

CriticalLoadOptions CriticalLoadOptions::tension_1d() {
  CriticalLoadOptions o;
  o.want_mode = false;
  return o;
}

CriticalLoadOptions CriticalLoadOptions::strain_2d() {
  CriticalLoadOptions o;
  o.dense_max = 400;
  o.variant = CholmodVariant::Supernodal;
  o.start = 1e-3;
  o.max = 1e3;
  o.min = 1e-14;
  o.step = 8;
  o.rtol = 1e-12;
  o.shift_spectra = true;
  o.spectra_tol = 1e-12;
  o.imag_tol = 1e-9;
  o.imag_scale = ImagScale::FrobeniusNorm;
  o.spectrum_real_crossing = true;
  o.symmetrize = false;
  return o;
}

CriticalLoadOptions CriticalLoadOptions::force_function() {
  CriticalLoadOptions o;
  o.growth_factor = 2;
  o.a0_failure_is_zero_load = true;
  return o;
}

CriticalLoad critical_load(const Linearisation& lin, LoadDirection direction, const CriticalLoadOptions& opt) {
  validate(lin, opt);
  const int m = lin.dofs();
  const SparseMatrix<> a_one = lin.at(1.0);  // A at unit load, formed once
  const double asymmetry0 = relative_asymmetry(lin.A0), asymmetry1 = relative_asymmetry(a_one);
  Criterion crit = opt.criterion;
  if (crit == Criterion::Auto)
    crit = lin.symmetric                 ? Criterion::Definiteness
           : m <= opt.spectrum_dense_max ? Criterion::Spectrum
                                         : Criterion::SymmetricPart;
  if (crit == Criterion::Definiteness && !lin.symmetric)
    throw std::invalid_argument("critical_load: criterion 'definiteness' needs a symmetric A (relative asymmetry " +
                                format_number(std::max(asymmetry0, asymmetry1)) +
                                "); use 'spectrum' or 'symmetric-part'");
  CriticalLoad out;
  out.size = m;
  out.direction = direction;
  out.criterion = crit;
  const double sgn = load_sign(direction);
  const double n0 = lin.A0.norm(), n1 = lin.A1.norm();
  out.asymmetry0 = asymmetry0;
  out.asymmetry1 = asymmetry1;
  out.a1_relative = n0 > 0 ? n1 / n0 : (n1 > 0 ? kInf : 0.0);

  if (n0 == 0 && n1 == 0) {  // no pair interacts: A = 0 is singular, stability is undefined
    out.status = Status::NumericalIssue;
    out.reason = "A0 = A1 = 0: no particle has a neighbour inside the kernel support (h too small for the lattice)";
    return out;
  }
  if (n1 <= opt.zero_tol * (n0 + a_one.norm())) {  // [Powell2012, (3.38)]: no load dependence
    bool holds = false;
    if (crit == Criterion::Spectrum) {
      require_dense_memory(lin.A0.rows(), 3, "critical_load (dense spectrum criterion)");
      holds = spectrum_failure(Eigen::MatrixXd(lin.A0), opt, nullptr).empty();
    } else {
      ColSparseMatrix k = lower_from_symmetric_rows(crit == Criterion::SymmetricPart ? symmetric_part(lin.A0) : lin.A0);
      k.makeCompressed();
      holds = is_positive_definite(k, opt.variant);
    }
    out.load = out.load_eigen = out.load_bisection = holds ? sgn * kInf : 0.0;
    out.status = Status::Successful;
    out.reason = "A1 = 0 (||A1||/||A0|| = " + format_number(out.a1_relative) + "; e.g. the minus form): A(0) " +
                 (holds ? "passes so every load does" : "already fails");
    return out;
  }
  if (crit == Criterion::Spectrum) {
    spectrum_routes(lin, opt, out);
  } else {
    if (crit == Criterion::SymmetricPart) {
      append_reason(out.reason, "symmetric-part criterion: definiteness of (A + A^T)/2 (not the stability criterion)");
      definiteness_routes(lin, symmetric_part(lin.A0), symmetric_part(lin.A1), opt, out);
    } else if (opt.symmetrize) {
      definiteness_routes(lin, symmetric_part(lin.A0), symmetric_part(lin.A1), opt, out);
    } else {
      definiteness_routes(lin, lin.A0, lin.A1, opt, out);
    }
  }
  if (std::isinf(out.load) || out.load == 0) out.mechanism = InstabilityMechanism::None;
  if (out.load == 0) out.mode.resize(0);
  // An infinite load keeps the eigenvector of lambda_max (the mode closest to instability) in 1D; the 2D wavevector
  // is reported for a finite load only.
  if (opt.want_mode && (std::isfinite(out.load) || lin.dofs_per_particle == 1)) finish_mode(lin, out);
  if (opt.growth_factor > 0 && std::isfinite(out.load) && out.load != 0) {
    out.growth_load = opt.growth_factor * out.load;
    const Eigen::VectorXd x = lin.x.size() ? Eigen::VectorXd(lin.x.col(0)) : Eigen::VectorXd::Zero(lin.free_count());
    require_dense_memory(m, 3, "critical_load (dense growth rate)");
    const GrowthAnalysis g = growth_rate(Eigen::MatrixXd(lin.at(out.growth_load)),
                                         lin.dofs_per_particle == 1 ? x : Eigen::VectorXd::Zero(m), lin.periodic);
    out.growth_rate = g.growth_rate;
    out.unstable_modes = static_cast<int>(g.unstable.size());
    if (!g.unstable.empty()) out.growth_wavenumber = g.unstable.front().wavenumber;
    append_reason(out.reason, "gamma(" + format_number(opt.growth_factor) + " load) = " + format_number(g.growth_rate));
  }
  if (out.status == Status::NotComputed)
    out.status = std::isnan(out.load) ? Status::NumericalIssue : Status::Successful;
  if (out.reason.empty()) out.reason = "ok";
  return out;
}

std::vector<CriticalLoad> critical_loads(const Linearisation& lin, LoadDirection direction,
                                         const CriticalLoadOptions& options) {
  std::vector<CriticalLoad> out;
  const std::vector<Criterion> criteria = lin.symmetric
                                              ? std::vector<Criterion>{Criterion::Definiteness}
                                              : std::vector<Criterion>{Criterion::Spectrum, Criterion::SymmetricPart};
  for (Criterion c : criteria) {
    CriticalLoadOptions o = options;
    o.criterion = c;
    out.push_back(critical_load(lin, direction, o));
  }
  return out;
}

CriticalLoad critical_tension_1d(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h, MomentumForm form,
                                 const CriticalLoadOptions& options, LoadDirection direction) {
  const int n = initial_stress_multiplier(form);
  CriticalLoadOptions o = options;
  o.criterion = Criterion::Definiteness;
  if (n > 1) {  // n is a power of two: the scaled bracket visits exactly the points of the uncorrected form
    o.start /= n;
    o.max /= n;
    o.min /= n;
  }
  return critical_load(analytic_jacobian_1d(particles, kernel, h, form), direction, o);
}

ForceCriticalLoad force_critical_loads(const ForceFunction& force, LoadDirection direction, const Eigen::MatrixXd& x,
                                       const CriticalLoadOptions& options) {
  ForceCriticalLoad out;
  const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(force.dofs());
  out.jacobian = affine_jacobian(force, u0);
  out.jacobian.x = x;
  Eigen::VectorXd a;
  for (double load : {0.0, 1.0}) {
    force.with_load(load)->acceleration(u0, a);
    out.equilibrium_residual = std::max(out.equilibrium_residual, a.cwiseAbs().maxCoeff());
  }
  const double scale = out.jacobian.A0.nonZeros() ? out.jacobian.A0.coeffs().cwiseAbs().maxCoeff() : 0.0;
  out.residual_relative = scale > 0 ? out.equilibrium_residual / scale : out.equilibrium_residual;
  out.results = critical_loads(out.jacobian, direction, options);
  return out;
}

}  // namespace sphstab
