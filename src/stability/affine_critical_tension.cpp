#include "sphstab/stability/affine_critical_tension.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sphstab/io/format.hpp"
#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"
#include "sphstab/stability/growth_rate.hpp"
#include "sphstab/stability/load_bracket.hpp"

namespace sphstab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

SparseMatrix<> symmetric_part(const SparseMatrix<>& a) {
  SparseMatrix<> at = a.transpose();
  return SparseMatrix<>(0.5 * (a + at));
}

void validate(const AffineJacobian& j, const Eigen::VectorXd* x, const AffineCriticalOptions& o) {
  const auto n = j.A0.rows();
  if (n == 0 || j.A0.cols() != n || j.A1.rows() != n || j.A1.cols() != n)
    throw std::invalid_argument("affine_critical_tension: A0 and A1 must be non-empty, square and of equal size (got " +
                                std::to_string(j.A0.rows()) + " x " + std::to_string(j.A0.cols()) + " and " +
                                std::to_string(j.A1.rows()) + " x " + std::to_string(j.A1.cols()) + ")");
  for (const SparseMatrix<>* m : {&j.A0, &j.A1})
    for (Eigen::Index k = 0; k < m->nonZeros(); ++k)
      if (!std::isfinite(m->valuePtr()[k]))
        throw std::invalid_argument("affine_critical_tension: A0 and A1 must have finite entries");
  if (x && x->size() != n)
    throw std::invalid_argument("affine_critical_tension: x has " + std::to_string(x->size()) + " entries, expected " +
                                std::to_string(n));
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument(std::string("affine_critical_tension: option ") + name +
                                  " must be finite and > 0 (got " + format_number(v) + ")");
  };
  positive(o.t_start, "t_start");
  positive(o.t_max, "t_max");
  positive(o.t_min, "t_min");
  positive(o.rtol, "rtol");
  positive(o.imag_tol, "imag_tol");
  if (!(o.symmetry_tol >= 0) || !(o.zero_tol >= 0))
    throw std::invalid_argument("affine_critical_tension: symmetry_tol and zero_tol must be >= 0");
  if (!(o.growth_factor > 1) || !std::isfinite(o.growth_factor))
    throw std::invalid_argument("affine_critical_tension: growth_factor must be finite and > 1 (got " +
                                format_number(o.growth_factor) + ")");
}

/// Growth rate and fastest mode of A(t) = A0 + t A1 (t signed).
void growth_at(const AffineJacobian& j, double t, const Eigen::VectorXd& x, AffineCriticalTension& r) {
  if (!std::isfinite(t)) return;
  const Eigen::MatrixXd a = Eigen::MatrixXd(j.A0) + t * Eigen::MatrixXd(j.A1);
  const GrowthAnalysis g = growth_rate(a, x, false);
  r.growth_load = t;
  r.growth_rate = g.growth_rate;
  if (!g.unstable.empty()) r.mode_wavenumber = g.unstable.front().wavenumber;
}

/// Which way the spectrum of a fails the criterion (empty when it passes).
std::string spectrum_failure(const Eigen::MatrixXd& a, double imag_tol) {
  const DenseGeneralEigen e = general_eigen(a);
  if (e.status != Status::Successful) return "dgeev failed (info " + std::to_string(e.lapack_info) + ")";
  const double scale = e.values.cwiseAbs().maxCoeff();
  bool complex_pair = false, nonpositive = false;
  for (Eigen::Index k = 0; k < e.values.size(); ++k) {
    const std::complex<double> mu = e.values[k];
    if (std::abs(mu.imag()) > imag_tol * scale) complex_pair = true;
    if (!(mu.real() > 0)) nonpositive = true;
  }
  if (complex_pair && nonpositive) return "complex pair and Re mu <= 0";
  if (complex_pair) return "complex pair (flutter)";
  if (nonpositive) return "real mu <= 0 (divergence)";
  return "";
}

AffineCriticalTension spectrum_route(const AffineJacobian& j, double sign, const AffineCriticalOptions& o,
                                     AffineCriticalTension r) {
  const Eigen::MatrixXd a0 = Eigen::MatrixXd(j.A0), a1 = sign * Eigen::MatrixXd(j.A1);
  std::string last_failure;
  auto ok = [&](double t) {
    ++r.evaluations;
    last_failure = spectrum_failure(a0 + t * a1, o.imag_tol);
    return last_failure.empty();
  };
  if (!ok(0.0)) {
    r.tcrit = 0.0;
    r.lo = r.hi = 0.0;
    r.status = Status::Successful;
    append_reason(r.reason, "spectrum of A(0) already fails: " + last_failure);
    return r;
  }
  if (r.info.load_independent) {
    r.tcrit = sign * kInf;
    r.status = Status::Successful;
    append_reason(r.reason, "A1 = 0 (no T dependence) and A(0) passes");
    return r;
  }
  LoadBracket b = bracket_critical_load(ok, o.t_start, o.t_max, o.t_min, 2.0);
  if (b.outcome == LoadBracket::Outcome::StableToMax) {
    r.tcrit = sign * kInf;
    r.lo = b.lo;
    r.status = Status::Successful;
    append_reason(r.reason, "spectrum real and positive at |T| = 0 and t_start 2^k up to " + format_number(o.t_max));
    return r;
  }
  if (b.outcome == LoadBracket::Outcome::UnstableToMin) {
    r.tcrit = 0.0;
    r.lo = 0;
    r.hi = b.hi;
    r.status = Status::Successful;
    append_reason(r.reason,
                  "spectrum fails for every sampled |T| >= " + format_number(o.t_min) + " (" + last_failure + ")");
    return r;
  }
  bisect_critical_load(b, ok, o.rtol);
  const double lo = b.lo, hi = b.hi;
  ok(hi);  // the failure mode just beyond T_crit
  r.lo = lo;
  r.hi = hi;
  r.tcrit = sign * std::sqrt(lo * hi);
  r.status = Status::Successful;
  append_reason(r.reason, "eigenvalue leaves the positive real axis: " + last_failure);
  return r;
}

AffineCriticalTension pd_route(const AffineJacobian& j, double sign, const Eigen::VectorXd& x,
                               const AffineCriticalOptions& o, AffineCriticalTension r) {
  const SparseMatrix<> s0 = symmetric_part(j.A0);
  const SparseMatrix<> s1 = symmetric_part(j.A1);
  {
    ColSparseMatrix lower = lower_triangle(s0);
    lower.makeCompressed();
    ++r.evaluations;
    if (!is_positive_definite(lower)) {
      r.tcrit = 0.0;
      r.lo = r.hi = 0.0;
      r.status = Status::Successful;
      append_reason(r.reason, "A(0) (symmetric part) is not positive definite");
      return r;
    }
  }
  if (r.info.load_independent) {
    r.tcrit = sign * kInf;
    r.status = Status::Successful;
    append_reason(r.reason, "A1 = 0 (no T dependence) and A(0) is positive definite");
    return r;
  }
  TensionJacobian1d jac;
  jac.K = s0;
  jac.L = SparseMatrix<>(-sign * s1);  // A0 + |T| sign A1 = K - |T| L
  jac.free_index.resize(s0.rows());
  for (int k = 0; k < static_cast<int>(s0.rows()); ++k) jac.free_index[k] = k;
  jac.x = x;
  CriticalTensionOptions opt = o.symmetric;
  opt.want_mode = opt.method != TcritMethod::Bisection;
  r.pd = critical_tension(jac, 1, opt);
  r.evaluations += r.pd.factorizations;
  r.tcrit = sign * r.pd.tcrit;
  r.lo = r.pd.bisection_lo;
  r.hi = r.pd.bisection_hi;
  r.status = r.pd.status;
  r.mode_wavenumber = r.pd.mode_wavenumber;
  if (sign < 0) append_reason(r.reason, "compression searched as A0 + |T| (-A1) (T in the messages below is |T|)");
  append_reason(r.reason, r.pd.reason == "ok" ? "" : r.pd.reason);
  return r;
}

}  // namespace

std::string criterion_name(StabilityCriterion c) {
  switch (c) {
    case StabilityCriterion::PositiveDefinite:
      return "pd";
    case StabilityCriterion::RealPositiveSpectrum:
      return "real-positive-spectrum";
    case StabilityCriterion::SymmetricPartPositiveDefinite:
      return "symmetric-part-pd";
  }
  return "?";
}

std::string load_direction_name(LoadDirection d) { return d == LoadDirection::Tension ? "tension" : "compression"; }

AffineJacobianInfo analyse_affine_jacobian(const AffineJacobian& j, const AffineCriticalOptions& o) {
  validate(j, nullptr, o);
  AffineJacobianInfo info;
  const SparseMatrix<> a_one = SparseMatrix<>(j.A0 + j.A1);
  info.asymmetry0 = relative_asymmetry(j.A0);
  info.asymmetry1 = relative_asymmetry(a_one);
  const double n0 = j.A0.norm(), n1 = j.A1.norm();
  info.a1_relative = n0 > 0 ? n1 / n0 : (n1 > 0 ? kInf : 0.0);
  info.symmetric = info.asymmetry0 <= o.symmetry_tol && info.asymmetry1 <= o.symmetry_tol;
  info.load_independent = n1 <= o.zero_tol * (n0 + a_one.norm());
  return info;
}

AffineCriticalTension affine_critical_load(const AffineJacobian& j, StabilityCriterion criterion,
                                           LoadDirection direction, const Eigen::VectorXd& x,
                                           const AffineCriticalOptions& o) {
  validate(j, &x, o);
  AffineCriticalTension r;
  r.criterion = criterion;
  r.direction = direction;
  r.info = analyse_affine_jacobian(j, o);
  if (criterion == StabilityCriterion::PositiveDefinite && !r.info.symmetric)
    throw std::invalid_argument("affine_critical_load: A(T) is not symmetric (relative asymmetry " +
                                format_number(std::max(r.info.asymmetry0, r.info.asymmetry1)) +
                                "); use real-positive-spectrum or symmetric-part-pd");
  if (r.info.load_independent) append_reason(r.reason, "||A1||/||A0|| = " + format_number(r.info.a1_relative));
  const double sign = direction == LoadDirection::Tension ? 1.0 : -1.0;
  r = criterion == StabilityCriterion::RealPositiveSpectrum ? spectrum_route(j, sign, o, r)
                                                            : pd_route(j, sign, x, o, r);
  if (!std::isfinite(r.tcrit) || r.tcrit == 0.0) r.mode_wavenumber = {};  // no critical mode
  if (std::isfinite(r.tcrit) && r.tcrit != 0.0) {
    growth_at(j, o.growth_factor * r.tcrit, x, r);
    append_reason(r.reason, "gamma(" + format_number(o.growth_factor) + " T_crit) = " + format_number(r.growth_rate));
  }
  if (r.reason.empty()) r.reason = "ok";
  return r;
}

std::vector<AffineCriticalTension> affine_critical_tension(const AffineJacobian& j, LoadDirection direction,
                                                           const Eigen::VectorXd& x, const AffineCriticalOptions& o) {
  const AffineJacobianInfo info = analyse_affine_jacobian(j, o);
  if (info.symmetric) return {affine_critical_load(j, StabilityCriterion::PositiveDefinite, direction, x, o)};
  return {affine_critical_load(j, StabilityCriterion::RealPositiveSpectrum, direction, x, o),
          affine_critical_load(j, StabilityCriterion::SymmetricPartPositiveDefinite, direction, x, o)};
}

ForceCriticalLoad critical_load(const ForceFunction& force, LoadDirection direction, const Eigen::VectorXd& x,
                                const AffineCriticalOptions& options) {
  ForceCriticalLoad out;
  const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(force.dofs());
  out.jacobian = affine_jacobian(force, u0);
  Eigen::VectorXd a;
  for (double load : {0.0, 1.0}) {
    force.with_load(load)->acceleration(u0, a);
    out.equilibrium_residual = std::max(out.equilibrium_residual, a.cwiseAbs().maxCoeff());
  }
  const double scale = Eigen::MatrixXd(out.jacobian.A0).cwiseAbs().maxCoeff();
  out.residual_relative = scale > 0 ? out.equilibrium_residual / scale : out.equilibrium_residual;
  out.results = affine_critical_tension(out.jacobian, direction, x, options);
  return out;
}

}  // namespace sphstab
