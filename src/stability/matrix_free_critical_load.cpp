#include "sphstab/stability/matrix_free_critical_load.hpp"

#include <Spectra/SymGEigsSolver.h>

#include <algorithm>
#include <cmath>
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

}  // namespace

MatrixFreeCriticalLoad matrix_free_critical_load(const MatrixFreeLinearisation& lin, LoadDirection direction,
                                                 const MatrixFreeCriticalLoadOptions& o) {
  if (!lin.symmetric())
    throw std::invalid_argument(
        "matrix_free_critical_load: the linearisation is not symmetric (needs equal volumes, complete "
        "neighbourhoods, and the conservative form or isotropic pre-strain)");
  if (lin.form() == MomentumForm::Minus)
    throw std::invalid_argument("matrix_free_critical_load: the minus form has A1 = 0 (no critical load)");
  if (!(o.cg_rtol > 0 && o.cg_rtol < 1) || !(o.tol > 0) || o.cg_maxit < 0 || o.maxit < 1 || o.ncv < 0 || o.ncv == 1 ||
      o.ncv > lin.dofs())
    throw std::invalid_argument(
        "matrix_free_critical_load: options need 0 < cg_rtol < 1, tol > 0, cg_maxit >= 0, "
        "maxit >= 1 and ncv 0 or in [2, dofs = " +
        std::to_string(lin.dofs()) + "]");
  const int n = lin.dofs();
  const double sgn = load_sign(direction);
  MatrixFreeOperator op(lin, 0.0, -sgn);  // L = -sgn A1
  StiffnessCgOp bop(lin, o.cg_rtol, o.cg_maxit > 0 ? o.cg_maxit : 10 * n);
  const int ncv = o.ncv > 0 ? o.ncv : std::min(30, n);

  MatrixFreeCriticalLoad r;
  Spectra::SymGEigsSolver<MatrixFreeOperator, StiffnessCgOp, Spectra::GEigsMode::RegularInverse> eigs(op, bop, 1, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, o.maxit, o.tol);
  r.solves = bop.solves;
  r.cg_iterations = bop.iterations;
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

}  // namespace sphstab
