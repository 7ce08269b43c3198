#include "sphstab/stability/equilibrium.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace sphstab {

namespace {

double residual_of(const ForceFunction& f, const Eigen::VectorXd& u, Eigen::VectorXd& a) {
  f.acceleration(u, a);
  return a.allFinite() ? a.cwiseAbs().maxCoeff() : std::numeric_limits<double>::infinity();
}

/// Damped Newton at one load; `out` holds the start and receives the result.
void newton(const ForceFunction& force, const EquilibriumOptions& o, double reference, Equilibrium& out) {
  Eigen::VectorXd a;
  out.residual = residual_of(force, out.u, a);
  if (!std::isfinite(out.residual)) {
    out.status = Status::NumericalIssue;
    out.message = "non-finite acceleration at the start";
    return;
  }
  const double target = o.tolerance * std::max(reference, o.accel_scale);
  if (out.residual <= target) {
    out.status = Status::Successful;
    return;
  }
  ComplexStepJacobian jac(force);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  bool have_lu = false, fresh = false, refresh = true;
  for (int it = 1; it <= o.max_iterations; ++it) {
    if (refresh || !have_lu) {
      const SparseMatrix<> Ar = jac.compute(out.u);
      if (jac.info() != Status::Successful) {
        out.status = Status::NumericalIssue;
        out.message = "non-finite Jacobian";
        return;
      }
      const Eigen::SparseMatrix<double> A(Ar);  // column-major for SparseLU
      lu.compute(A);
      if (lu.info() != Eigen::Success) {
        out.status = Status::NumericalIssue;
        out.message = "singular Jacobian";
        return;
      }
      have_lu = fresh = true;
      ++out.jacobians;
    }
    const Eigen::VectorXd du = lu.solve(a);
    // Backtracking: halve the step until the residual decreases (at most 12 halvings).
    double step = 1.0, r = 0;
    Eigen::VectorXd trial, at;
    for (int h = 0; h <= 12; ++h, step *= 0.5) {
      trial = out.u + step * du;
      r = residual_of(force, trial, at);
      if (r < out.residual) break;
    }
    ++out.iterations;
    if (!(r < out.residual)) {
      if (!fresh) {  // a stale Jacobian: retry with a fresh one
        refresh = true;
        continue;
      }
      out.status = out.residual <= o.stagnation * reference ? Status::Successful : Status::NotConverging;
      out.message = out.status == Status::Successful ? "converged to round-off" : "Newton step does not decrease |a|";
      return;
    }
    // Keep the factorisation while it still reduces the residual at least fourfold (chord iterations are cheap:
    // one force evaluation and one solve instead of a complex-step Jacobian and a factorisation).
    refresh = r > 0.25 * out.residual;
    fresh = false;
    out.u = trial;
    a = at;
    out.residual = r;
    if (r <= target) {
      out.status = Status::Successful;
      return;
    }
  }
  out.status = out.residual <= o.stagnation * reference ? Status::Successful : Status::NotConverging;
  out.message = out.status == Status::Successful ? "converged to round-off" : "no convergence";
}

}  // namespace

Equilibrium find_equilibrium(const ForceFunction& force, const Eigen::VectorXd& u0, const EquilibriumOptions& o) {
  if (u0.size() != force.dofs())
    throw std::invalid_argument("find_equilibrium: u0 has " + std::to_string(u0.size()) + " entries, expected " +
                                std::to_string(force.dofs()));
  if (o.max_iterations < 1 || !(o.tolerance > 0) || !(o.accel_scale >= 0) || o.load_steps < 1 || !(o.stagnation > 0))
    throw std::invalid_argument(
        "find_equilibrium: need max_iterations >= 1, tolerance > 0, stagnation > 0, accel_scale >= 0, "
        "load_steps >= 1");
  Equilibrium out;
  out.u = u0;
  Eigen::VectorXd a;
  out.initial_residual = residual_of(force, u0, a);
  if (!std::isfinite(out.initial_residual)) {
    out.status = Status::NumericalIssue;
    out.message = "non-finite acceleration at u0";
    return out;
  }
  const double load = force.load();
  Eigen::VectorXd older = u0;  // solution two load steps back (u0 stands for the solution at zero load)
  for (int k = 1; k <= o.load_steps; ++k) {
    const double fraction = static_cast<double>(k) / o.load_steps;
    std::unique_ptr<ForceFunction> scaled;
    const ForceFunction* f = &force;
    if (k < o.load_steps) {
      scaled = force.with_load(load * fraction);
      f = scaled.get();
    }
    const Eigen::VectorXd last = out.u;
    if (k > 1) out.u = 2.0 * last - older;  // linear extrapolation in the load
    older = last;
    Eigen::VectorXd ak;
    const double reference = std::max(residual_of(*f, u0, ak), o.accel_scale);
    newton(*f, o, reference, out);
    if (out.status != Status::Successful) {
      out.message += " (load step " + std::to_string(k) + " of " + std::to_string(o.load_steps) + ")";
      return out;
    }
  }
  if (out.message.empty()) out.message = "converged in " + std::to_string(out.iterations) + " Newton steps";
  return out;
}

}  // namespace sphstab
