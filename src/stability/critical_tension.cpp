#include "sphstab/stability/critical_tension.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "sphstab/io/format.hpp"
#include "sphstab/linalg/cholmod_cholesky_op.hpp"
#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/linalg/symmetric_pencil.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/load_bracket.hpp"

namespace sphstab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

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

struct EigenRoute {
  double lambda_max = CriticalTension::nan;
  Status status = Status::NotComputed;
  std::string backend, note;
  Eigen::VectorXd vector;
};

EigenRoute eigen_route(const ColSparseMatrix& k, const ColSparseMatrix& l, const CriticalTensionOptions& opt) {
  EigenRoute r;
  const int m = static_cast<int>(k.rows());
  const bool dense =
      opt.backend == EigenBackend::Dense || m < 3 || (opt.backend == EigenBackend::Auto && m <= opt.dense_max);
  if (dense) {
    r.backend = "dense";
    const Eigen::MatrixXd kd = Eigen::MatrixXd(k).selfadjointView<Eigen::Lower>();
    const Eigen::MatrixXd ld = Eigen::MatrixXd(l).selfadjointView<Eigen::Lower>();
    DenseSymmetricEigen e = generalized_symmetric_eigen(ld, kd, opt.want_mode);
    r.status = e.status;
    if (e.status != Status::Successful) {
      r.note = "dsygv failed (info " + std::to_string(e.lapack_info) + ")";
      return r;
    }
    r.lambda_max = e.values[m - 1];
    if (opt.want_mode) r.vector = e.vectors.col(m - 1);
    return r;
  }
  r.backend = "spectra";
  CholmodCholeskyOp bop(k, opt.variant);
  if (bop.info() != Status::Successful) {
    r.status = Status::NumericalIssue;
    r.note = "Cholesky of K failed";
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
      r.lambda_max = eigs.eigenvalues()[0];
      if (opt.want_mode) r.vector = eigs.eigenvectors().col(0);
      if (attempt > 0) r.note = "spectra converged with ncv = " + std::to_string(ncv);
      return r;
    }
    ncv *= 2;
  }
  r.status = Status::NotConverging;
  r.note = "spectra did not converge (ncv up to " + std::to_string(ncv / 2) + ")";
  return r;
}

struct BisectionRoute {
  double lo = CriticalTension::nan, hi = CriticalTension::nan, tau = CriticalTension::nan;
  int factorizations = 0;
  Status status = Status::NotComputed;
  std::string note;
};

BisectionRoute bisection_route(const ColSparseMatrix& k, const ColSparseMatrix& l, const CriticalTensionOptions& opt) {
  BisectionRoute r;
  SymmetricPencil pencil(k, l);
  CholmodDefiniteness check(opt.variant);
  check.analyze_pattern(pencil.pattern());
  auto pd = [&](double tau) { return check.is_positive_definite(pencil.evaluate(tau)); };
  LoadBracket b = bracket_critical_load(pd, opt.tau_start, opt.tau_max, opt.tau_min, 2.0);
  bisect_critical_load(b, pd, opt.rtol);
  r.factorizations = b.tests;
  r.lo = b.lo;
  r.hi = b.hi;
  switch (b.outcome) {
    case LoadBracket::Outcome::StableToMax:
      r.tau = kInf;
      r.status = Status::Successful;
      r.note = "bisection: A positive definite up to n T = " + format_number(opt.tau_max);
      break;
    case LoadBracket::Outcome::UnstableToMin:
      r.status = Status::NumericalIssue;
      r.note = "bisection: A(T) not positive definite down to n T = " + format_number(opt.tau_min);
      break;
    case LoadBracket::Outcome::Bracketed:
      r.tau = b.critical();
      r.status = Status::Successful;
      break;
  }
  return r;
}

void validate(const CriticalTensionOptions& o) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument(std::string("critical_tension: option ") + name + " must be finite and > 0 (got " +
                                  format_number(v) + ")");
  };
  positive(o.tau_start, "tau_start");
  positive(o.tau_max, "tau_max");
  positive(o.tau_min, "tau_min");
  positive(o.rtol, "rtol");
  positive(o.spectra_tol, "spectra_tol");
  if (o.spectra_maxit <= 0) throw std::invalid_argument("critical_tension: option spectra_maxit must be > 0");
  if (o.dense_max < 0) throw std::invalid_argument("critical_tension: option dense_max must be >= 0");
}

}  // namespace

TcritMethod parse_tcrit_method(const std::string& name) {
  if (name == "eig") return TcritMethod::Eigen;
  if (name == "bisect") return TcritMethod::Bisection;
  if (name == "both") return TcritMethod::Both;
  throw std::invalid_argument("unknown method '" + name + "' (valid: eig, bisect, both)");
}

EigenBackend parse_eigen_backend(const std::string& name) {
  if (name == "auto") return EigenBackend::Auto;
  if (name == "dense") return EigenBackend::Dense;
  if (name == "spectra") return EigenBackend::Spectra;
  throw std::invalid_argument("unknown eigen backend '" + name + "' (valid: auto, dense, spectra)");
}

CriticalTension critical_tension(const TensionJacobian1d& jac, int n, const CriticalTensionOptions& opt) {
  if (n < 0) throw std::invalid_argument("critical_tension: n must be >= 0 (got " + std::to_string(n) + ")");
  validate(opt);
  const int nf = jac.size();
  if (nf == 0 || jac.K.rows() != nf || jac.K.cols() != nf || jac.L.rows() != nf || jac.L.cols() != nf)
    throw std::invalid_argument("critical_tension: K and L must both be " + std::to_string(nf) + " x " +
                                std::to_string(nf) + " (one row per free particle)");
  CriticalTension out;
  out.size = nf;
  if (n == 0) {
    out.tcrit = out.tcrit_eigen = out.tcrit_bisection = kInf;
    out.status = Status::Successful;
    out.reason = "minus form: A does not depend on T (Powell 3.38)";
    return out;
  }

  ColSparseMatrix k = jac.K, l = jac.L;
  ColSparseMatrix basis;  // deflation basis (empty: none)
  if (jac.periodic && opt.deflate_periodic) {
    std::vector<int> order(nf);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return jac.x[a] < jac.x[b]; });
    const bool even = nf % 2 == 0;
    if (even) {
      Eigen::VectorXd s(nf);
      for (int r = 0; r < nf; ++r) s[order[r]] = (r % 2 == 0) ? 1.0 : -1.0;
      const double ls = s.dot(jac.L * s) / nf;
      const double scale = jac.L.diagonal().cwiseAbs().maxCoeff();
      const double tol = 1e-12 * std::max(scale, 1e-300);
      if (ls > tol) {
        out.tcrit = out.tcrit_eigen = out.tcrit_bisection = 0.0;
        out.status = Status::Successful;
        out.reason = "periodic even N: sawtooth mode has G s = 0 and s'Ls/s's = " + format_number(ls) +
                     " > 0 so A(T) is indefinite for every T > 0";
        return out;
      }
      if (ls >= -tol) {
        out.tcrit = out.tcrit_eigen = out.tcrit_bisection = 0.0;
        out.status = Status::Successful;
        out.reason = "periodic even N: sawtooth mode has G s = 0 and s'Ls = 0 so A(T) is singular for every T";
        return out;
      }
      append_reason(out.reason, "sawtooth mode projected out (G s = 0 and s'Ls/s's = " + format_number(ls) +
                                    " < 0: neutral at T = 0 and stabilised by tension)");
    }
    append_reason(out.reason, "translation mode projected out");
    if (nf - (even ? 2 : 1) < 1) {
      out.status = Status::NumericalIssue;
      out.reason += "; no degrees of freedom left after deflation";
      return out;
    }
    basis = deflation_basis(order, even);
    ColSparseMatrix bt = basis.transpose();
    k = bt * k * basis;
    l = bt * l * basis;
  }
  k.makeCompressed();
  l.makeCompressed();
  out.size = static_cast<int>(k.rows());

  // K must be positive definite for both routes (A(0) = K).
  {
    CholmodFactor kf(opt.variant);
    ColSparseMatrix kl = lower_triangle(k);
    kl.makeCompressed();
    if (!kf.compute(kl)) {
      out.status = Status::NumericalIssue;
      append_reason(out.reason, "K = G_f G_f^T is not positive definite (Cholesky failed at column " +
                                    std::to_string(kf.failed_column()) +
                                    "): A(0) is singular or indefinite so T_crit is undefined here");
      return out;
    }
    out.k_rcond = kf.rcond_estimate();
    if (out.k_rcond < 1e-14)
      append_reason(out.reason,
                    "K near-singular (rcond estimate " + format_number(out.k_rcond) + "): accuracy limited");
  }

  const bool eig = opt.method != TcritMethod::Bisection, bis = opt.method != TcritMethod::Eigen;
  if (eig) {
    EigenRoute e = eigen_route(lower_triangle(k), lower_triangle(l), opt);
    out.eigen_backend = e.backend;
    if (!e.note.empty()) append_reason(out.reason, e.note);
    if (e.status == Status::Successful) {
      out.lambda_max = e.lambda_max;
      out.tcrit_eigen = e.lambda_max > 0 ? 1.0 / (n * e.lambda_max) : kInf;
      if (!(e.lambda_max > 0)) append_reason(out.reason, "lambda_max <= 0: A(T) positive definite for every T > 0");
      if (opt.want_mode && e.vector.size() > 0) {
        out.mode = basis.size() > 0 ? Eigen::VectorXd(basis * e.vector) : e.vector;
        const double nm = out.mode.norm();
        if (nm > 0) out.mode /= nm;
        out.mode_wavenumber = dominant_wavenumber(out.mode, jac.x, jac.periodic);
      }
    } else {
      out.status = e.status;
    }
  }
  if (bis) {
    BisectionRoute b = bisection_route(k, l, opt);
    out.factorizations = b.factorizations;
    if (!b.note.empty()) append_reason(out.reason, b.note);
    if (b.status == Status::Successful) {
      out.tcrit_bisection = b.tau / n;
      out.bisection_lo = b.lo / n;
      out.bisection_hi = std::isinf(b.tau) ? kInf : b.hi / n;
    } else {
      out.status = b.status;
    }
  }
  if (eig && bis && !std::isnan(out.tcrit_eigen) && !std::isnan(out.tcrit_bisection)) {
    const double a = out.tcrit_eigen, b = out.tcrit_bisection;
    out.relative_difference = (std::isinf(a) && std::isinf(b))   ? 0.0
                              : (std::isinf(a) || std::isinf(b)) ? kInf
                                                                 : std::abs(a - b) / std::max(std::abs(a), std::abs(b));
    if (out.relative_difference > 1e-8) {
      // Both routes see K only through its rounded entries: T_crit is determined to about eps / rcond(K).
      append_reason(out.reason, "eigen and bisection routes disagree by " + format_number(out.relative_difference) +
                                    " (conditioning of K limits accuracy to about eps/rcond = " +
                                    format_number(std::numeric_limits<double>::epsilon() / out.k_rcond) + ")");
      if (out.relative_difference > 1e-6) out.status = Status::NumericalIssue;
    }
  }
  out.tcrit = !std::isnan(out.tcrit_eigen) ? out.tcrit_eigen : out.tcrit_bisection;
  if (out.status == Status::NotComputed)
    out.status = std::isnan(out.tcrit) ? Status::NumericalIssue : Status::Successful;
  if (out.reason.empty()) out.reason = "ok";
  return out;
}

ParticleSet<1> tension_lattice_1d(const Kernel<1>& kernel, double h, int free, bool periodic, int layer_supports) {
  if (layer_supports < 1)
    throw std::invalid_argument("tension_lattice_1d: layer_supports must be >= 1 (got " +
                                std::to_string(layer_supports) + ")");
  if (free < 1)
    throw std::invalid_argument("tension_lattice_1d: need at least one free particle (got " + std::to_string(free) +
                                ")");
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("tension_lattice_1d: h must be finite and > 0 (got " + format_number(h) + ")");
  return make_lattice<1>(
      LatticeType::Line, free,
      {.spacing = 1.0, .support_radius = layer_supports * kernel.support_radius(h), .periodic = periodic});
}

CriticalTension critical_tension_1d(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h,
                                    MomentumForm form, const CriticalTensionOptions& options) {
  return critical_tension(analytic_jacobian_1d(particles, kernel, h), initial_stress_multiplier(form), options);
}

}  // namespace sphstab
