#include "sphstab/stability/matrix_free_critical_load.hpp"

#include <Spectra/SymGEigsSolver.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "sphstab/core/format.hpp"
#include "sphstab/jacobian/matrix_free_operator.hpp"

namespace sphstab {

namespace {

/// Spectra's B operation of the regular-inverse mode for B = K = A0: perform_op is B v, solve is B^{-1} v by
/// unpreconditioned conjugate gradients from zero; the statistics and the first failure are kept.
class StiffnessCgOp {
 public:
  using Scalar = double;

  StiffnessCgOp(const MatrixFreeLinearisation& lin, double rtol, int maxit)
      : m_lin(lin), m_rtol(rtol), m_maxit(maxit), m_r(lin.dofs()), m_p(lin.dofs()), m_q(lin.dofs()) {}

  Eigen::Index rows() const { return m_lin.dofs(); }
  Eigen::Index cols() const { return m_lin.dofs(); }

  void perform_op(const double* x_in, double* y_out) const {
    m_lin.apply_A0(Eigen::Map<const Eigen::VectorXd>(x_in, rows()), Eigen::Map<Eigen::VectorXd>(y_out, rows()));
  }

  void solve(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> b(x_in, rows());
    Eigen::Map<Eigen::VectorXd> x(y_out, rows());
    x.setZero();
    m_r = b;
    m_p = m_r;
    double rr = m_r.squaredNorm();
    const double bb = rr, stop = m_rtol * m_rtol * bb;
    int it = 0;
    while (rr > stop && rr > 0) {
      if (it == m_maxit) {
        fail(Status::NotConverging, "CG reached " + std::to_string(m_maxit) + " steps at relative residual " +
                                        format_number(std::sqrt(rr / bb), 3));
        break;
      }
      m_lin.apply_A0(m_p, m_q);
      const double pq = m_p.dot(m_q);
      if (!(pq > 0)) {
        fail(Status::NumericalIssue, "A0 is not positive definite (CG curvature " + format_number(pq, 3) + ")");
        break;
      }
      const double a = rr / pq;
      x += a * m_p;
      m_r -= a * m_q;
      const double rr_new = m_r.squaredNorm();
      m_p = m_r + (rr_new / rr) * m_p;
      rr = rr_new;
      ++it;
    }
    ++solves;
    iterations += it;
    max_iterations = std::max(max_iterations, it);
  }

  mutable int solves = 0, max_iterations = 0;
  mutable long iterations = 0;
  mutable Status status = Status::Successful;
  mutable std::string reason;

 private:
  void fail(Status s, const std::string& why) const {
    if (status != Status::Successful) return;
    status = s;
    reason = why;
  }

  const MatrixFreeLinearisation& m_lin;
  double m_rtol;
  int m_maxit;
  mutable Eigen::VectorXd m_r, m_p, m_q;
};

/// Lanczos on K^{-1} L (Spectra regular-inverse mode) with CG solves.
MatrixFreeCriticalLoad lanczos_cg(const MatrixFreeLinearisation& lin, double sgn,
                                  const MatrixFreeCriticalLoadOptions& o) {
  const int n = lin.dofs();
  MatrixFreeOperator op(lin, 0.0, -sgn);  // L = -sgn A1
  StiffnessCgOp bop(lin, o.cg_rtol, o.cg_maxit > 0 ? o.cg_maxit : 10 * n);
  const int ncv = o.ncv > 0 ? o.ncv : std::min(30, n);

  MatrixFreeCriticalLoad r;
  Spectra::SymGEigsSolver<MatrixFreeOperator, StiffnessCgOp, Spectra::GEigsMode::RegularInverse> eigs(op, bop, 1, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, o.maxit, o.tol);
  r.solves = bop.solves;
  r.cg_iterations = bop.iterations;
  r.iterations = bop.solves;
  r.a0_products = bop.iterations;
  r.max_cg_iterations = bop.max_iterations;
  if (bop.status != Status::Successful) {
    r.status = bop.status;
    r.reason = bop.reason;
    return r;
  }
  if (eigs.info() != Spectra::CompInfo::Successful) {
    r.status = Status::NotConverging;
    r.reason = "Spectra did not converge in " + std::to_string(o.maxit) + " restarts (ncv " + std::to_string(ncv) + ")";
    return r;
  }
  r.lambda_max = eigs.eigenvalues()[0];
  r.mode = eigs.eigenvectors().col(0);
  r.load = r.lambda_max > 0 ? sgn / r.lambda_max : sgn * std::numeric_limits<double>::infinity();
  r.status = Status::Successful;
  return r;
}

/// Block-size-1 LOBPCG for the largest eigenvalue of L x = lambda K x [Knyazev2001]: Rayleigh-Ritz on span{x, w, p}
/// with w the residual and p the previous step, all K-normalised, so that the 3 x 3 Gram matrix of K has a unit
/// diagonal; when it is not positive definite (w or p nearly in the span of the others) p is dropped for one step.
MatrixFreeCriticalLoad lobpcg(const MatrixFreeLinearisation& lin, double sgn, const MatrixFreeCriticalLoadOptions& o) {
  using Vector = Eigen::VectorXd;
  const int n = lin.dofs();
  MatrixFreeCriticalLoad r;
  auto apply_k = [&](const Vector& v, Vector& out) {
    lin.apply_A0(v, out);
    ++r.a0_products;
  };
  auto apply_l = [&](const Vector& v, Vector& out) { lin.apply_combination(0.0, -sgn, v, out); };
  // K-normalises (v, Kv, Lv); false if v^T K v <= 0.
  auto normalise = [&](Vector& v, Vector& kv, Vector* lv) {
    const double vkv = v.dot(kv);
    if (!(vkv > 0)) return false;
    const double s = 1.0 / std::sqrt(vkv);
    v *= s;
    kv *= s;
    if (lv) *lv *= s;
    return true;
  };
  auto not_definite = [&](double curvature) {
    r.status = Status::NumericalIssue;
    r.reason = "A0 is not positive definite (curvature " + format_number(curvature, 3) + ")";
    return r;
  };

  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Vector x(n), kx(n), lx(n), w(n), kw(n), lw(n), p(n), kp(n), lp(n), res(n);
  for (double& v : x) v = uniform(rng);
  apply_k(x, kx);
  if (!normalise(x, kx, nullptr)) return not_definite(x.dot(kx));
  apply_l(x, lx);
  double lambda = x.dot(lx);
  bool have_p = false;
  for (long it = 0;; ++it) {
    res = lx - lambda * kx;
    if (res.norm() <= o.residual_tol * std::abs(lambda) * kx.norm()) {
      r.iterations = it;
      break;
    }
    if (it == o.max_iterations) {
      r.iterations = it;
      r.status = Status::NotConverging;
      r.reason = "LOBPCG reached " + std::to_string(o.max_iterations) + " steps at relative residual " +
                 format_number(res.norm() / (std::abs(lambda) * kx.norm()), 3);
      return r;
    }
    w = res;
    apply_k(w, kw);
    if (!normalise(w, kw, nullptr)) return not_definite(w.dot(kw));
    apply_l(w, lw);
    const Vector* basis[3] = {&x, &w, &p};
    const Vector* kbasis[3] = {&kx, &kw, &kp};
    const Vector* lbasis[3] = {&lx, &lw, &lp};
    Eigen::VectorXd c;
    for (int m = have_p ? 3 : 2; m >= 2; --m) {
      Eigen::MatrixXd gk(m, m), gl(m, m);
      for (int a = 0; a < m; ++a)
        for (int b = a; b < m; ++b) {
          gk(a, b) = gk(b, a) = 0.5 * (basis[a]->dot(*kbasis[b]) + basis[b]->dot(*kbasis[a]));
          gl(a, b) = gl(b, a) = 0.5 * (basis[a]->dot(*lbasis[b]) + basis[b]->dot(*lbasis[a]));
        }
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(gl, gk);
      if (ritz.info() == Eigen::Success) {
        c = ritz.eigenvectors().col(m - 1);
        lambda = ritz.eigenvalues()[m - 1];
        break;
      }
    }
    if (c.size() == 0) {  // even {x, w} degenerate: w is in the direction of x
      r.iterations = it;
      r.status = Status::NumericalIssue;
      r.reason = "LOBPCG basis degenerate at step " + std::to_string(it);
      return r;
    }
    // p <- the step without x; x <- c0 x + p.
    Vector np = c[1] * w, nkp = c[1] * kw, nlp = c[1] * lw;
    if (c.size() == 3) {
      np += c[2] * p;
      nkp += c[2] * kp;
      nlp += c[2] * lp;
    }
    x = c[0] * x + np;
    kx = c[0] * kx + nkp;
    lx = c[0] * lx + nlp;
    if (!normalise(x, kx, &lx)) return not_definite(x.dot(kx));
    p = std::move(np);
    kp = std::move(nkp);
    lp = std::move(nlp);
    have_p = normalise(p, kp, &lp);
  }
  r.lambda_max = lambda;
  r.mode = x;
  r.load = lambda > 0 ? sgn / lambda : sgn * std::numeric_limits<double>::infinity();
  r.status = Status::Successful;
  return r;
}

}  // namespace

MatrixFreeCriticalLoad matrix_free_critical_load(const MatrixFreeLinearisation& lin, LoadDirection direction,
                                                 const MatrixFreeCriticalLoadOptions& o) {
  if (!lin.symmetric())
    throw std::invalid_argument(
        "matrix_free_critical_load: the linearisation is not symmetric (needs equal volumes, complete "
        "neighbourhoods, and the conservative form or isotropic pre-strain)");
  if (lin.form() == MomentumForm::Minus)
    throw std::invalid_argument("matrix_free_critical_load: the minus form has A1 = 0 (no critical load)");
  if (!(o.residual_tol > 0 && o.residual_tol < 1) || o.max_iterations < 0)
    throw std::invalid_argument("matrix_free_critical_load: options need 0 < residual_tol < 1 and max_iterations >= 0");
  if (!(o.cg_rtol > 0 && o.cg_rtol < 1) || !(o.tol > 0) || o.cg_maxit < 0 || o.maxit < 1 || o.ncv < 0 || o.ncv == 1 ||
      o.ncv > lin.dofs())
    throw std::invalid_argument(
        "matrix_free_critical_load: options need 0 < cg_rtol < 1, tol > 0, cg_maxit >= 0, "
        "maxit >= 1 and ncv 0 or in [2, dofs = " +
        std::to_string(lin.dofs()) + "]");
  const double sgn = load_sign(direction);
  return o.method == MatrixFreeEigenMethod::Lobpcg ? lobpcg(lin, sgn, o) : lanczos_cg(lin, sgn, o);
}

}  // namespace sphstab
