#include "sphstab/integrate/stable_time_step.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_symmetric_eigen.hpp"

namespace sphstab {

StableTimeStep stable_time_step(const SparseMatrix<>& a, const Eigen::VectorXd& mass,
                                const StableTimeStepOptions& opt) {
  const Eigen::Index n = a.rows();
  if (a.cols() != n || n < 1)
    throw std::invalid_argument("stable_time_step: A must be square and non-empty (got " + std::to_string(a.rows()) +
                                " x " + std::to_string(a.cols()) + ")");
  if (mass.size() != n)
    throw std::invalid_argument("stable_time_step: mass has " + std::to_string(mass.size()) + " entries, A has " +
                                std::to_string(n) + " rows");
  for (Eigen::Index k = 0; k < n; ++k)
    if (!(mass[k] > 0) || !std::isfinite(mass[k]))
      throw std::invalid_argument("stable_time_step: mass[" + std::to_string(k) + "] must be finite and > 0");
  // S = M^{1/2} A M^{-1/2}, then its symmetric part
  const Eigen::VectorXd r = mass.cwiseSqrt();
  Eigen::SparseMatrix<double> s = r.asDiagonal() * Eigen::SparseMatrix<double>(a) * r.cwiseInverse().asDiagonal();
  const Eigen::SparseMatrix<double> st = s.transpose();
  const double norm = s.norm();
  StableTimeStep out;
  out.dofs = static_cast<int>(n);
  out.asymmetry = norm > 0 ? (s - st).norm() / norm : 0.0;
  s = 0.5 * (s + st);
  const bool dense = opt.route == EigenRoute::Dense || (opt.route == EigenRoute::Auto && n <= opt.dense_max) || n < 12;
  if (dense) {
    const DenseSymmetricEigen e = symmetric_eigen(Eigen::MatrixXd(s));
    out.route = "dense";
    out.status = e.status;
    if (e.status == Status::Successful) out.lambda_max = e.values[n - 1];
  } else {
    Spectra::SparseSymMatProd<double> op(s);
    const int ncv = static_cast<int>(std::min<Eigen::Index>(n, opt.ncv > 0 ? opt.ncv : 40));
    Spectra::SymEigsSolver<Spectra::SparseSymMatProd<double>> solver(op, 1, ncv);
    solver.init();
    solver.compute(Spectra::SortRule::LargestAlge, opt.max_iterations, opt.tolerance);
    out.route = "spectra";
    out.status = solver.info() == Spectra::CompInfo::Successful ? Status::Successful : Status::NotConverging;
    if (out.status == Status::Successful) out.lambda_max = solver.eigenvalues()[0];
  }
  out.dt = out.lambda_max > 0 ? 2.0 / std::sqrt(out.lambda_max) : std::numeric_limits<double>::infinity();
  return out;
}

StableTimeStep stable_time_step(const ForceFunction& force, const Eigen::VectorXd& u,
                                const StableTimeStepOptions& opt) {
  if (u.size() != force.dofs())
    throw std::invalid_argument("stable_time_step: u has " + std::to_string(u.size()) + " entries, the force has " +
                                std::to_string(force.dofs()) + " dofs");
  return stable_time_step(ComplexStepJacobian(force).compute(u), force.dof_mass(), opt);
}

}  // namespace sphstab
