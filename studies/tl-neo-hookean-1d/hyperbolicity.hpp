#pragma once
// The loss of hyperbolicity of the tl-neo-hookean-1d study (Ismail (2009) §5.3 at nu = 0.49): the root of the
// material tangent dP/dF (bisection on the model, models/neo_hookean.hpp) and the stretch at which the linearised TL
// Jacobian A = -da/du of the bar (neo_hookean_bar.hpp, complex step at the stretched equilibrium) stops being
// positive definite (regula falsi on the critical-load engine's definiteness routes, stability/critical_load.hpp).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>
#include <stdexcept>

#include "neo_hookean_bar.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace nh1d {

inline double smallest_eigenvalue(const Eigen::MatrixXd& A) { return symmetric_eigen(A).values[0]; }

/// Root of g in [a, b] (g(a) > 0 > g(b)) by bisection to |b - a| <= tol.
template <class G>
double bisect(G g, double a, double b, double tol) {
  while (b - a > tol) {
    const double m = 0.5 * (a + b);
    (g(m) > 0 ? a : b) = m;
  }
  return 0.5 * (a + b);
}

struct Crossing {
  double lambda = std::nan("");  ///< the converged prediction of the engine
  bool verified = false;         ///< A positive definite at lambda - tol and indefinite at lambda + tol
  int iterations = 0;
};

/// The stretch at which A(lambda) stops being positive definite, by regula falsi on the critical-load engine: on the
/// bracket [lo, hi] (A(lo) positive definite, A(hi) not) the affine interpolation A(lo) + t (A(hi) - A(lo)) / (hi -
/// lo) is a Linearisation whose critical load t (CHOLMOD bisection and the generalised eigenproblem, which must agree)
/// predicts the crossing lo + t; the bracket end on the same side as the prediction moves there. Stops when two
/// predictions differ by less than tol, then checks definiteness at the prediction -+ tol.
inline Crossing definiteness_crossing(Bar& bar, double lo, double hi, double tol) {
  Crossing c;
  Eigen::MatrixXd Alo = bar.jacobian_at(lo), Ahi = bar.jacobian_at(hi);
  CriticalLoadOptions opt = CriticalLoadOptions::tension_1d();
  opt.criterion = Criterion::Definiteness;
  opt.want_mode = false;
  opt.start = 1e-6 * (hi - lo);
  double previous = std::nan("");
  for (; c.iterations < 100; ++c.iterations) {
    Linearisation lin;
    lin.A0 = Alo.sparseView();
    lin.A1 = ((Ahi - Alo) / (hi - lo)).sparseView();
    lin.symmetric = true;
    const CriticalLoad r = critical_load(lin, LoadDirection::Tension, opt);
    if (r.info() != Status::Successful || !std::isfinite(r.load))
      throw std::runtime_error("critical_load: " + r.reason);
    c.lambda = lo + r.load;
    if (std::abs(c.lambda - previous) < tol) break;
    previous = c.lambda;
    const Eigen::MatrixXd A = bar.jacobian_at(c.lambda);
    if (smallest_eigenvalue(A) > 0)
      lo = c.lambda, Alo = A;
    else
      hi = c.lambda, Ahi = A;
  }
  c.verified = smallest_eigenvalue(bar.jacobian_at(c.lambda - tol)) > 0 &&
               smallest_eigenvalue(bar.jacobian_at(c.lambda + tol)) <= 0;
  return c;
}

}  // namespace nh1d
