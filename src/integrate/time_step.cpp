#include "sphstab/integrate/time_step.hpp"

#include <Spectra/GenEigsSolver.h>
#include <Spectra/SymEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sphstab {

double cfl_time_step(double courant, double h, double wave_speed) {
  auto ok = [](double x) { return x > 0 && std::isfinite(x); };
  if (!ok(courant) || !ok(h) || !ok(wave_speed))
    throw std::invalid_argument("cfl_time_step: courant, h and wave_speed must be finite and > 0 (got " +
                                std::to_string(courant) + ", " + std::to_string(h) + ", " + std::to_string(wave_speed) +
                                ")");
  return courant * h / wave_speed;
}

namespace detail {

/// y = A x with A = -(a(s x) - a(0)) / s, in Spectra's matrix-operation concept.
class LinearisedOperator {
 public:
  using Scalar = double;
  LinearisedOperator(const AccelerationFunction& f, long n, double s) : m_f(f), m_n(n), m_s(s) {
    m_a0.resize(n);
    m_x.resize(n);
    m_y.resize(n);
    Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    m_f(zero, m_a0);
  }
  Eigen::Index rows() const { return m_n; }
  Eigen::Index cols() const { return m_n; }
  void perform_op(const double* x_in, double* y_out) const {
    m_x = m_s * Eigen::Map<const Eigen::VectorXd>(x_in, m_n);
    m_f(m_x, m_y);
    Eigen::Map<Eigen::VectorXd>(y_out, m_n) = -(m_y - m_a0) / m_s;
  }

 private:
  const AccelerationFunction& m_f;
  long m_n;
  double m_s;
  Eigen::VectorXd m_a0;
  mutable Eigen::VectorXd m_x, m_y;
};

/// The largest-magnitude eigenvalue by a Spectra solver (Lanczos or Arnoldi), into est (converged, dominant).
template <class Solver>
void dominant_eigenvalue(Solver&& solver, const StabilityOptions& opt, StabilityEstimate& est) {
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, opt.max_iterations, opt.tolerance);
  est.converged = solver.info() == Spectra::CompInfo::Successful;
  if (est.converged) est.dominant = solver.eigenvalues()[0];
}

}  // namespace detail

StabilityEstimate estimate_stability_limit(const AccelerationFunction& accel, long n, const StabilityOptions& opt) {
  if (!accel) throw std::invalid_argument("estimate_stability_limit: missing acceleration callable");
  if (n < 1) throw std::invalid_argument("estimate_stability_limit: ndof must be >= 1 (got " + std::to_string(n) + ")");
  if (!(opt.probe_scale > 0)) throw std::invalid_argument("estimate_stability_limit: probe_scale must be > 0");
  detail::LinearisedOperator op(accel, n, opt.probe_scale);
  StabilityEstimate est;
  est.min_real = std::nan("");

  // Small Krylov problems are unreliable in Spectra (nev + 2 < ncv <= n): go dense.
  if (n <= std::max<long>(opt.dense_limit, 12)) {
    Eigen::MatrixXd A(n, n);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
    for (long k = 0; k < n; ++k) {
      e[k] = 1.0;
      op.perform_op(e.data(), A.col(k).data());
      e[k] = 0.0;
    }
    Eigen::VectorXcd mu;
    if (opt.symmetric) {
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()), Eigen::EigenvaluesOnly);
      mu = es.eigenvalues().cast<std::complex<double>>();
      est.converged = es.info() == Eigen::Success;
    } else {
      Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
      mu = es.eigenvalues();
      est.converged = es.info() == Eigen::Success;
    }
    long best = 0;
    for (long k = 1; k < n; ++k)
      if (std::abs(mu[k]) > std::abs(mu[best])) best = k;
    est.dominant = mu[best];
    est.min_real = mu.real().minCoeff();
    est.method = "dense";
  } else if (opt.symmetric) {
    detail::dominant_eigenvalue(Spectra::SymEigsSolver<detail::LinearisedOperator>(op, 1, std::min<long>(n, 20)), opt,
                                est);
    est.method = "spectra-sym";
  } else {
    detail::dominant_eigenvalue(Spectra::GenEigsSolver<detail::LinearisedOperator>(op, 3, std::min<long>(n, 30)), opt,
                                est);
    est.method = "spectra-gen";
  }
  est.lambda_max = std::abs(est.dominant);
  est.dominant_real_positive = est.dominant.real() > 0 && std::abs(est.dominant.imag()) <= 1e-8 * est.lambda_max;
  est.dt_limit = est.lambda_max > 0 ? 2.0 / std::sqrt(est.lambda_max) : std::numeric_limits<double>::infinity();
  return est;
}

double leapfrog_time_step_limit(const Eigen::VectorXcd& eigenvalues) {
  double w = 0;
  for (const auto& l : eigenvalues) w = std::max(w, std::abs(l.imag()));
  return w > 0 ? 2.0 / w : std::numeric_limits<double>::infinity();
}

double heun_amplification(std::complex<double> z) { return std::abs(1.0 + z + 0.5 * z * z); }

double heun_time_step_limit(const Eigen::VectorXcd& eigenvalues) {
  double limit = std::numeric_limits<double>::infinity();
  for (const auto& l : eigenvalues) {
    const double a = l.real(), m2 = std::norm(l);
    if (m2 == 0) continue;
    if (a >= -1e-12 * std::sqrt(m2)) return 0.0;
    // The root t > 0 of p(t) = 2a + 2a^2 t + a m2 t^2 + m2^2 t^3 / 4: p(0) = 2a < 0, and p' = 2a^2 + 2a m2 t +
    // 3/4 m2^2 t^2 > 0 (discriminant 4a^2 m2^2 - 6a^2 m2^2 < 0), so the root is unique and |R| <= 1 exactly on
    // [0, root]. Bisection.
    auto p = [&](double t) { return 2 * a + 2 * a * a * t + a * m2 * t * t + 0.25 * m2 * m2 * t * t * t; };
    double lo = 0, hi = 1.0 / std::sqrt(m2);
    while (p(hi) <= 0) hi *= 2;
    for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (p(mid) > 0 ? hi : lo) = mid;
    }
    limit = std::min(limit, lo);
  }
  return limit;
}

double heun_growth_rate(const Eigen::VectorXcd& eigenvalues, double dt) {
  if (!(dt > 0) || !std::isfinite(dt))
    throw std::invalid_argument("heun_growth_rate: dt must be finite and > 0 (got " + std::to_string(dt) + ")");
  double g = 0;
  for (const auto& l : eigenvalues) g = std::max(g, std::log(heun_amplification(dt * l)) / dt);
  return g;
}

double heun_excess_growth_rate(const Eigen::VectorXcd& eigenvalues, double dt) {
  if (!(dt > 0) || !std::isfinite(dt))
    throw std::invalid_argument("heun_excess_growth_rate: dt must be finite and > 0 (got " + std::to_string(dt) + ")");
  double g = -std::numeric_limits<double>::infinity();
  for (const auto& l : eigenvalues) g = std::max(g, std::log(heun_amplification(dt * l)) / dt - l.real());
  return g;
}

double leapfrog_growth_rate(const Eigen::VectorXcd& mu, double dt) {
  if (!(dt > 0) || !std::isfinite(dt))
    throw std::invalid_argument("leapfrog_growth_rate: dt must be finite and > 0 (got " + std::to_string(dt) + ")");
  double g = 0;
  for (const auto& m : mu) {
    // z^2 - b z + 1 = 0, b = 2 - dt^2 mu: the roots z = b/2 +- sqrt(b^2/4 - 1) have product 1, so the larger modulus
    // is >= 1; take it from the larger root (no cancellation) rather than from both.
    const std::complex<double> b = 2.0 - dt * dt * m, d = std::sqrt(0.25 * b * b - 1.0);
    const double z = std::max(std::abs(0.5 * b + d), std::abs(0.5 * b - d));
    g = std::max(g, std::log(z) / dt);
  }
  return g;
}

}  // namespace sphstab
