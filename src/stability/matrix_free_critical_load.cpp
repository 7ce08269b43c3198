#include "sphstab/stability/matrix_free_critical_load.hpp"

#include <Spectra/SymGEigsSolver.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>

#include "../linalg/tall_block_algebra.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/jacobian/matrix_free_operator.hpp"
#include "sphstab/stability/lattice_sine_preconditioner.hpp"
#include "sphstab/stability/lattice_stencil.hpp"

namespace sphstab {

namespace {

/// Spectra's B operation of the regular-inverse mode for B = K = A0: perform_op is B v, solve is B^{-1} v by
/// unpreconditioned conjugate gradients from zero; the statistics and the first failure are kept.
template <int Dim>
class StiffnessCgOp {
 public:
  using Scalar = double;

  StiffnessCgOp(const MatrixFreeLinearisation<Dim>& lin, double rtol, int maxit)
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

  const MatrixFreeLinearisation<Dim>& m_lin;
  double m_rtol;
  int m_maxit;
  mutable Eigen::VectorXd m_r, m_p, m_q;
};

/// Lanczos on K^{-1} L (Spectra regular-inverse mode) with CG solves.
template <int Dim>
MatrixFreeCriticalLoad lanczos_cg(const MatrixFreeLinearisation<Dim>& lin, double sgn,
                                  const MatrixFreeCriticalLoadOptions& o) {
  const int n = lin.dofs();
  MatrixFreeOperator<Dim> op(lin, 0.0, -sgn);  // L = -sgn A1
  StiffnessCgOp<Dim> bop(lin, o.cg_rtol, o.cg_maxit > 0 ? o.cg_maxit : 10 * n);
  const int ncv = o.ncv > 0 ? o.ncv : std::min(30, n);

  MatrixFreeCriticalLoad r;
  Spectra::SymGEigsSolver<MatrixFreeOperator<Dim>, StiffnessCgOp<Dim>, Spectra::GEigsMode::RegularInverse> eigs(op, bop,
                                                                                                                1, ncv);
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
template <int Dim>
MatrixFreeCriticalLoad lobpcg(const MatrixFreeLinearisation<Dim>& lin, double sgn,
                              const MatrixFreeCriticalLoadOptions& o) {
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

// Dense block algebra of BlockLobpcg on tall blocks: linalg/tall_block_algebra.hpp (the same bits for any thread
// count and any x86-64 machine).
using tall::gram;
using tall::transform_columns;

/// Block LOBPCG for the largest eigenvalues of L x = lambda K x in the orthogonal-basis form of
/// [HetmaniukLehoucq2006] (port of solvers.lobpcg of the Python prototype,
/// benchmarks/prototypes/lattice-preconditioner). The basis Q = [X | P | W] is stored in one dofs x 3b matrix per
/// operator (Q, K Q, L Q), so the Rayleigh-Ritz Gram matrices are one product each and no block is copied to stack
/// them.
template <int Dim>
class BlockLobpcg {
 public:
  BlockLobpcg(const MatrixFreeLinearisation<Dim>& lin, double sgn, const MatrixFreeCriticalLoadOptions& o,
              const LatticeSinePreconditioner<Dim>* t, MatrixFreeCriticalLoad& r)
      : m_lin(lin), m_sgn(sgn), m_o(o), m_t(t), m_r(r), m_b(o.block_size) {
    const int n = lin.dofs();
    m_v.resize(n, 3 * m_b);
    m_k.resize(n, 3 * m_b);
    m_l.resize(n, 3 * m_b);
    m_a.resize(n, m_b);
    for (const Eigen::MatrixXd* q : {&m_v, &m_k, &m_l, &m_a})  // before the first write (tall_block_algebra.hpp)
      tall::advise_huge_pages(q->data(), sizeof(double) * q->size());
  }

  /// Runs from the start block x0 (dofs x b); fills the result.
  void run(const Eigen::MatrixXd& x0) {
    const int b = m_b;
    m_v.leftCols(b) = x0;
    products(0, b);
    int nx = korth(0, b);
    if (nx < 0) return;
    if (nx == 0) return fail(Status::NumericalIssue, "block LOBPCG: the start block has no K-positive direction");
    Eigen::VectorXd theta = ritz_on_x(nx);
    int np = 0;
    for (long it = 0;; ++it) {
      // Residuals R = L X - K X diag(theta) (in m_a).
      auto res = m_a.leftCols(nx);
      tall::residuals(m_l.leftCols(nx), m_k.leftCols(nx), theta, res);
      m_r.residual = res.col(0).norm() / (std::abs(theta[0]) * m_k.col(0).norm());
      m_r.lambda_max = theta[0];
      if (m_r.residual <= m_o.residual_tol) {
        m_r.iterations = it;
        m_r.status = Status::Successful;
        return;
      }
      if (it == m_o.max_iterations) {
        m_r.iterations = it;
        return fail(Status::NotConverging, "block LOBPCG reached " + std::to_string(m_o.max_iterations) +
                                               " steps at relative residual " + format_number(m_r.residual, 3));
      }
      // W = T R, K-orthogonal to X and P, K-orthonormal.
      const int wpos = nx + np;
      if (m_t) {
        const auto t0 = std::chrono::steady_clock::now();
        m_t->apply(res, m_v.middleCols(wpos, nx));
        m_r.preconditioner_applications += nx;
        m_r.preconditioner_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      } else {
        tall::copy(res, m_v.middleCols(wpos, nx));
      }
      products(wpos, nx);
      // X and P are K-orthonormal together: one projection against both; then W's K-orthonormalisation and the
      // Rayleigh-Ritz Gram matrices on span{X, P, W} in one pass.
      Eigen::MatrixXd cw;
      const int nw = project_korth(wpos, nx, 0, nx + np, nullptr, cw);
      if (nw < 0) return;
      const int m = nx + np + nw;
      // Rayleigh-Ritz on span{X, P, W}: H c = theta G c, largest first.
      Eigen::MatrixXd g, h;
      std::vector<int> widths = {nx};
      if (np > 0) widths.push_back(np);
      if (nw > 0) widths.push_back(nw);
      tall::RowPass pass;
      if (nw > 0)
        for (Eigen::MatrixXd* q : {&m_v, &m_k, &m_l}) pass.transform(*q, wpos, cw, wpos);
      pass.ritz_grams(m_v.leftCols(m), m_k.leftCols(m), m_l.leftCols(m), widths, g, h).run();
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(h, g);
      if (ges.info() != Eigen::Success)
        return fail(Status::NumericalIssue,
                    "block LOBPCG: the Rayleigh-Ritz Gram matrix of K is not positive "
                    "definite at step " +
                        std::to_string(it));
      const int bn = std::min(b, m);
      const Eigen::MatrixXd vx = ges.eigenvectors().rowwise().reverse().leftCols(bn);
      const Eigen::VectorXd w = ges.eigenvalues().reverse();
      // X <- Q Vx, P <- Q[P, W] Vx[P, W] (the part of the step without the old X), in one pass over the three
      // operators, with the first projection coefficients of the new P against the new X.
      const Eigen::MatrixXd vpw = m > nx ? Eigen::MatrixXd(vx.bottomRows(m - nx)) : Eigen::MatrixXd();
      const bool have_p = m > nx;
      Eigen::MatrixXd c1;
      for (Eigen::MatrixXd* q : {&m_v, &m_k, &m_l}) pass.transform(*q, 0, vx, 0, vpw);
      if (have_p) pass.gram(m_k.leftCols(bn), m_v.middleCols(bn, bn), c1);
      pass.run();
      nx = bn;
      theta = w.head(nx);
      np = 0;
      if (have_p) {
        Eigen::MatrixXd cp;
        np = project_korth(nx, bn, 0, nx, &c1, cp);
        if (np < 0) return;
        if (np > 0)
          for (Eigen::MatrixXd* q : {&m_v, &m_k, &m_l}) pass.transform(*q, nx, cp, nx);
        pass.run();
      }
      m_r.iterations = it + 1;
      if (m_o.refresh_every > 0 && (it + 1) % m_o.refresh_every == 0) {  // against drift of K X, L X
        products(0, nx);
        nx = korth(0, nx);
        if (nx <= 0) {
          if (nx == 0) fail(Status::NumericalIssue, "block LOBPCG: X lost K-positivity at the refresh");
          return;
        }
        theta = ritz_on_x(nx);
        np = 0;
      }
    }
  }

  /// The top Ritz vector (K-normalised).
  Eigen::VectorXd mode() const { return m_v.col(0); }

 private:
  void fail(Status s, const std::string& why) {
    m_r.status = s;
    m_r.reason = why;
  }

  /// K and L products of columns [c0, c0 + m) of Q.
  void products(int c0, int m) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int j = c0; j < c0 + m; ++j) m_lin.apply_A0_and_A1(-m_sgn, m_v.col(j), m_k.col(j), m_l.col(j));
    m_r.a0_products += m;
    m_r.a1_products += m;
    m_r.product_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  /// Y <- Y - Z (Z^T K Y), twice, for K-orthonormal Z = columns [z0, z0 + mz), Y = [y0, y0 + my), then the
  /// coefficients c of Y's K-orthonormalisation (korth_coefficients; Y <- Y c is left to the caller, to fuse it
  /// with the caller's next pass). Three passes over the rows (tall::RowPass): c1 = Z^T K Y (unless given, from the
  /// caller's previous pass); Y -= Z c1 with c2 = Z^T K Y of the updated Y; Y -= Z c2, K Y -= K Z (c1 + c2) and
  /// L Y -= L Z (c1 + c2) (the second projection needs only the projected Y itself, so K Y and L Y take both
  /// coefficients in one update) with the Gram matrix Y^T K Y. Returns the new width of Y, or -1 (status set).
  int project_korth(int y0, int my, int z0, int mz, const Eigen::MatrixXd* c1, Eigen::MatrixXd& c) {
    const auto v = [&](Eigen::MatrixXd& q, int c0, int n) { return q.middleCols(c0, n); };
    Eigen::MatrixXd first, second, g;
    if (!c1) {
      tall::RowPass().gram(v(m_k, z0, mz), v(m_v, y0, my), first).run();
      c1 = &first;
    }
    tall::RowPass().subtract(v(m_v, y0, my), v(m_v, z0, mz), *c1).gram(v(m_k, z0, mz), v(m_v, y0, my), second).run();
    const Eigen::MatrixXd sum = (Eigen::MatrixXd::Zero(mz, my) + *c1) + second;
    tall::RowPass()
        .subtract(v(m_v, y0, my), v(m_v, z0, mz), second)
        .subtract(v(m_k, y0, my), v(m_k, z0, mz), sum)
        .subtract(v(m_l, y0, my), v(m_l, z0, mz), sum)
        .gram(v(m_v, y0, my), v(m_k, y0, my), g)
        .run();
    return korth_coefficients(g, c);
  }

  /// K-orthonormalises columns [c0, c0 + m) in place (the prototype's _korth). Returns the new width, or -1.
  int korth(int c0, int m) {
    if (m == 0) return 0;
    Eigen::MatrixXd c;
    const int mk = korth_coefficients(gram(m_v.middleCols(c0, m), m_k.middleCols(c0, m)), c);
    if (mk > 0)
      for (Eigen::MatrixXd* q : {&m_v, &m_k, &m_l}) transform_columns(*q, c0, c, c0);
    return mk;
  }

  /// The coefficients c (m x mk) that K-orthonormalise a block Y of m columns with K Gram matrix g = Y^T K Y: Y c
  /// (the prototype's _korth): eigen-decomposition of the diagonally scaled Gram matrix, directions below 1e-12 of
  /// the largest dropped. Returns mk (0: no K-positive direction, c empty), or -1 (status set) when the Gram matrix
  /// shows K is not positive definite.
  int korth_coefficients(Eigen::MatrixXd g, Eigen::MatrixXd& c) {
    const Eigen::Index m = g.rows();
    c.resize(m, 0);
    if (m == 0) return 0;
    g = 0.5 * (g + g.transpose()).eval();
    Eigen::VectorXd d = g.diagonal().cwiseAbs().cwiseSqrt();
    for (Eigen::Index i = 0; i < d.size(); ++i)
      if (d[i] == 0) d[i] = 1;
    const Eigen::MatrixXd gs = d.cwiseInverse().asDiagonal() * g * d.cwiseInverse().asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(gs);
    const Eigen::VectorXd& w = es.eigenvalues();
    const double wmax = w.maxCoeff();
    if (!(wmax > 0)) return 0;
    if (w.minCoeff() < -1e-8 * wmax) {
      fail(Status::NumericalIssue, "A0 is not positive definite (K Gram matrix eigenvalue " +
                                       format_number(w.minCoeff() / wmax, 3) + " relative to the largest)");
      return -1;
    }
    std::vector<int> keep;
    for (int i = 0; i < m; ++i)
      if (w[i] > 1e-12 * wmax) keep.push_back(i);
    const int mk = static_cast<int>(keep.size());
    c.resize(m, mk);
    for (int j = 0; j < mk; ++j) c.col(j) = es.eigenvectors().col(keep[j]) / std::sqrt(w[keep[j]]);
    c = d.cwiseInverse().asDiagonal() * c;
    return mk;
  }

  /// Rayleigh-Ritz on the K-orthonormal X = columns [0, nx): X <- X V, returns the Ritz values, largest first.
  Eigen::VectorXd ritz_on_x(int nx) {
    Eigen::MatrixXd h = gram(m_v.leftCols(nx), m_l.leftCols(nx));
    h = 0.5 * (h + h.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(h);
    const Eigen::MatrixXd v = es.eigenvectors().rowwise().reverse();
    for (Eigen::MatrixXd* q : {&m_v, &m_k, &m_l}) transform_columns(*q, 0, v, 0);
    return es.eigenvalues().reverse();
  }

  const MatrixFreeLinearisation<Dim>& m_lin;
  double m_sgn;
  const MatrixFreeCriticalLoadOptions& m_o;
  const LatticeSinePreconditioner<Dim>* m_t;
  MatrixFreeCriticalLoad& m_r;
  int m_b;
  Eigen::MatrixXd m_v, m_k, m_l;  ///< Q, K Q, L Q: dofs x 3b, columns [X | P | W]
  Eigen::MatrixXd m_a;            ///< dofs x b workspace (residuals)
};

/// Start block: zone-boundary modes polarised along each axis in turn, (-1)^i (x-polarised, k = (pi, 0[, 0])),
/// (-1)^j (y-polarised), [(-1)^k (z-polarised)], times sine envelopes sin(pi m_a (s_a + 1)/(n + 1)) per axis a, with
/// m = m1 along the polarisation and m2[, m3] along the following axes, (m1, m2[, m3]) = (1, 1[, 1]), (1, 2[, 1]),
/// (2, 1[, 1]), ... (2D: the prototype's zone_boundary_start); columns beyond the table uniform random.
template <int Dim>
Eigen::MatrixXd zone_boundary_start(int n, int b, std::uint64_t seed) {
  const int modes[8][3] = {{1, 1, 1}, {1, 2, 1}, {2, 1, 1}, {2, 2, 1}, {1, 3, 1}, {3, 1, 1}, {3, 2, 1}, {2, 3, 1}};
  auto s = [n](int m, int i) { return std::sin(std::numbers::pi * m * (i + 1) / (n + 1)); };
  LatticeDofs<Dim> g;
  g.n = n;
  const long sites = g.count();
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(Dim * sites, b);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int col = 0; col < b; ++col) {
    if (col >= 8 * Dim) {
      for (Eigen::Index q = 0; q < x.rows(); ++q) x(q, col) = uniform(rng);
      continue;
    }
    const int pol = col % Dim;
    const int* m = modes[col / Dim];
    for (long f = 0; f < sites; ++f) {
      const std::array<int, Dim> site = g.site(f);
      // Polarisation axis first: sign (-1)^s_pol times its envelope, then the envelopes of the following axes.
      double v = (site[pol] % 2 ? -1.0 : 1.0) * s(m[0], site[pol]);
      for (int t = 1; t < Dim; ++t) v *= s(m[t], site[(pol + t) % Dim]);
      x(Dim * f + pol, col) = v;
    }
  }
  return x;
}

Eigen::MatrixXd random_start(int dofs, int b, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd x(dofs, b);
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    for (Eigen::Index q = 0; q < x.rows(); ++q) x(q, j) = uniform(rng);
  return x;
}

template <int Dim>
std::optional<LatticeDofs<Dim>> lattice_of(const MatrixFreeLinearisation<Dim>& lin) {
  try {
    return lattice_dofs<Dim>(lin.free_positions(), "matrix_free_critical_load");
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <int Dim>
MatrixFreeCriticalLoad block_lobpcg(const MatrixFreeLinearisation<Dim>& lin, double sgn,
                                    const MatrixFreeCriticalLoadOptions& o, const LatticeSinePreconditioner<Dim>* t,
                                    MatrixFreeCriticalLoad r) {
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::MatrixXd x0;
  if (o.start == MatrixFreeStart::Random) {
    x0 = random_start(lin.dofs(), o.block_size, o.seed);
  } else {
    std::optional<LatticeDofs<Dim>> g = lattice_of(lin);
    if (!g && o.start == MatrixFreeStart::ZoneBoundary)
      lattice_dofs<Dim>(lin.free_positions(), "matrix_free_critical_load (start ZoneBoundary)");  // throws the reason
    x0 = g ? zone_boundary_start<Dim>(g->n, o.block_size, o.seed) : random_start(lin.dofs(), o.block_size, o.seed);
    if (g && o.start_noise > 0) {
      // The zone-boundary modes are symmetric under the lattice reflections, which K, L and the preconditioner
      // commute with: without noise the iteration stays in their symmetry classes and can miss the top mode.
      const Eigen::MatrixXd noise = random_start(lin.dofs(), o.block_size, o.seed + 1);
      for (Eigen::Index j = 0; j < x0.cols(); ++j)
        x0.col(j) += (o.start_noise * x0.col(j).norm() / noise.col(j).norm()) * noise.col(j);
    }
  }
  if (t) r.sigma_p = t->sigma();
  BlockLobpcg<Dim> solver(lin, sgn, o, t, r);
  solver.run(x0);
  r.solve_seconds = seconds_since(t0);
  if (r.status != Status::Successful) {
    r.lambda_max = MatrixFreeCriticalLoad::nan;
    return r;
  }
  r.mode = solver.mode();
  r.load = r.lambda_max > 0 ? sgn / r.lambda_max : sgn * std::numeric_limits<double>::infinity();
  return r;
}

template <int Dim>
void check_common(const MatrixFreeLinearisation<Dim>& lin, const MatrixFreeCriticalLoadOptions& o) {
  if (!lin.symmetric())
    throw std::invalid_argument(
        "matrix_free_critical_load: the linearisation is not symmetric (needs equal volumes, complete "
        "neighbourhoods, and the conservative form or isotropic pre-strain)");
  if (lin.form() == MomentumForm::Minus)
    throw std::invalid_argument("matrix_free_critical_load: the minus form has A1 = 0 (no critical load)");
  if (!(o.residual_tol > 0 && o.residual_tol < 1) || o.max_iterations < 0)
    throw std::invalid_argument("matrix_free_critical_load: options need 0 < residual_tol < 1 and max_iterations >= 0");
}

template <int Dim>
void check_block(const MatrixFreeLinearisation<Dim>& lin, const MatrixFreeCriticalLoadOptions& o) {
  if (o.block_size < 1 || 3L * o.block_size > lin.dofs() || o.refresh_every < 0 || !(o.start_noise >= 0) ||
      !std::isfinite(o.start_noise))
    throw std::invalid_argument(
        "matrix_free_critical_load: options need block_size in [1, dofs / 3 = " + std::to_string(lin.dofs() / 3) +
        "], refresh_every >= 0 and a finite start_noise >= 0 (got block_size " + std::to_string(o.block_size) +
        ", refresh_every " + std::to_string(o.refresh_every) + ", start_noise " + format_number(o.start_noise, 3) +
        ")");
}

}  // namespace

template <int Dim>
MatrixFreeCriticalLoad matrix_free_critical_load(const MatrixFreeLinearisation<Dim>& lin, LoadDirection direction,
                                                 const MatrixFreeCriticalLoadOptions& o,
                                                 const LatticeSinePreconditioner<Dim>& t) {
  check_common(lin, o);
  check_block(lin, o);
  if (t.dofs() != lin.dofs())
    throw std::invalid_argument("matrix_free_critical_load: the preconditioner is for " + std::to_string(t.dofs()) +
                                " DOFs (n = " + std::to_string(t.n()) + "), the linearisation has " +
                                std::to_string(lin.dofs()));
  MatrixFreeCriticalLoad r;
  r.preconditioner = "lattice-sine (given)";
  return block_lobpcg(lin, load_sign(direction), o, &t, std::move(r));
}

template <int Dim>
MatrixFreeCriticalLoad matrix_free_critical_load(const MatrixFreeLinearisation<Dim>& lin, LoadDirection direction,
                                                 const MatrixFreeCriticalLoadOptions& o) {
  check_common(lin, o);
  if (!(o.cg_rtol > 0 && o.cg_rtol < 1) || !(o.tol > 0) || o.cg_maxit < 0 || o.maxit < 1 || o.ncv < 0 || o.ncv == 1 ||
      o.ncv > lin.dofs())
    throw std::invalid_argument(
        "matrix_free_critical_load: options need 0 < cg_rtol < 1, tol > 0, cg_maxit >= 0, "
        "maxit >= 1 and ncv 0 or in [2, dofs = " +
        std::to_string(lin.dofs()) + "]");
  const double sgn = load_sign(direction);
  if (o.method == MatrixFreeEigenMethod::BlockLobpcg) {
    check_block(lin, o);
    if (o.preconditioner == MatrixFreePreconditioner::None) {
      MatrixFreeCriticalLoad r;
      r.preconditioner = "none";
      return block_lobpcg<Dim>(lin, sgn, o, nullptr, std::move(r));
    }
    if (!(o.margin > 0) || !std::isfinite(o.margin))
      throw std::invalid_argument("matrix_free_critical_load: options need margin > 0 (got " +
                                  format_number(o.margin, 3) + ")");
    const auto t0 = std::chrono::steady_clock::now();
    const LatticeStencil<Dim> st = probe_lattice_stencil(lin, direction);
    MatrixFreeCriticalLoad r;
    if (!(lattice_symbol_ratio_max(st, st.n) > 0)) {
      // No interior instability in this direction (e.g. compression): no shift sigma_p > 0 exists. The block may
      // still have a positive lambda_max from edge modes, so the iteration runs without a preconditioner.
      r.preconditioner = "none (symbol ratio L/K <= 0 on the lattice grid: no interior instability)";
      r.setup_seconds = seconds_since(t0);
      return block_lobpcg<Dim>(lin, sgn, o, nullptr, std::move(r));
    }
    const LatticeSinePreconditioner<Dim> t(st, st.n, o.margin, o.fftw_measure);
    r.preconditioner = "lattice-sine";
    r.setup_seconds = seconds_since(t0);
    return block_lobpcg(lin, sgn, o, &t, std::move(r));
  }
  return o.method == MatrixFreeEigenMethod::Lobpcg ? lobpcg(lin, sgn, o) : lanczos_cg(lin, sgn, o);
}

#define SPHSTAB_INSTANTIATE(D)                                                                                   \
  template MatrixFreeCriticalLoad matrix_free_critical_load<D>(const MatrixFreeLinearisation<D>&, LoadDirection, \
                                                               const MatrixFreeCriticalLoadOptions&);            \
  template MatrixFreeCriticalLoad matrix_free_critical_load<D>(const MatrixFreeLinearisation<D>&, LoadDirection, \
                                                               const MatrixFreeCriticalLoadOptions&,             \
                                                               const LatticeSinePreconditioner<D>&);
SPHSTAB_INSTANTIATE(2)
SPHSTAB_INSTANTIATE(3)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
