#include "sphstab/jacobian/complex_step_jacobian.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace sphstab {

double complex_step_size(double step, double scale) {
  if (!(scale > 0) || !std::isfinite(scale))
    throw std::invalid_argument("complex_step_size: the variable scale must be finite and > 0 (got " +
                                std::to_string(scale) + ")");
  const double band = std::clamp(scale, 1e-12, 1e12);
  return band == scale ? step : step * (scale / band);  // exactly `step` inside the band
}

ComplexStepJacobian::ComplexStepJacobian(const ForceFunction& force, ColouringStrategy strategy, double step)
    : m_force(&force), m_step(step) {
  m_pattern = force.dof_pattern();
  analyse(strategy, force.dofs(), "force");
  m_column_step = Eigen::VectorXd::Constant(force.dofs(), m_step);
}

ComplexStepJacobian::ComplexStepJacobian(const SemiDiscreteSystem& system, ColouringStrategy strategy, double step)
    : m_system(&system), m_step(step) {
  m_pattern = system.pattern();
  analyse(strategy, system.size(), "system");
  const Eigen::VectorXd scale = system.variable_scale();
  if (scale.size() != system.size())
    throw std::invalid_argument("ComplexStepJacobian: variable_scale() of " + system.name() + " has " +
                                std::to_string(scale.size()) + " entries, expected " + std::to_string(system.size()));
  m_column_step.resize(scale.size());
  for (Eigen::Index k = 0; k < scale.size(); ++k) m_column_step[k] = complex_step_size(m_step, scale[k]);
}

void ComplexStepJacobian::analyse(ColouringStrategy strategy, int size, const char* who) {
  if (!(m_step > 0) || !std::isfinite(m_step))
    throw std::invalid_argument("ComplexStepJacobian: step must be finite and > 0 (got " + std::to_string(m_step) +
                                ")");
  if (m_pattern.rows != size || m_pattern.cols != size)
    throw std::invalid_argument("ComplexStepJacobian: " + std::string(who) + " pattern is " +
                                std::to_string(m_pattern.rows) + " x " + std::to_string(m_pattern.cols) + " but the " +
                                who + " has " + std::to_string(size) + " unknowns");
  if (strategy == ColouringStrategy::Greedy) {
    m_colour = colour_columns(m_pattern);
  } else {
    m_colour.resize(m_pattern.cols);
    std::iota(m_colour.begin(), m_colour.end(), 0);
  }
  m_ncolours = colour_count(m_colour);
  m_columns_of_colour.assign(m_ncolours, {});
  for (int c = 0; c < m_pattern.cols; ++c) m_columns_of_colour[m_colour[c]].push_back(c);
  m_transpose = m_pattern.transpose();
  // Position in the row-major value array of every transposed entry (same fill order as transpose()).
  m_transpose_position.assign(m_transpose.indices.size(), -1);
  std::vector<long> next(m_transpose.offsets.begin(), m_transpose.offsets.end() - 1);
  for (int r = 0; r < m_pattern.rows; ++r)
    for (long k = m_pattern.offsets[r]; k < m_pattern.offsets[r + 1]; ++k)
      m_transpose_position[next[m_pattern.indices[k]]++] = k;
}

SparseMatrix<> ComplexStepJacobian::compute(const Eigen::VectorXd& u, const ForceFunction* force) const {
  if (m_system && force)
    throw std::invalid_argument("ComplexStepJacobian::compute: a force function was given to a system's Jacobian");
  const ForceFunction* f = force ? force : m_force;
  const int n = m_pattern.rows;
  if (f && f->dofs() != n)
    throw std::invalid_argument("ComplexStepJacobian::compute: force has " + std::to_string(f->dofs()) +
                                " dofs, the analysed pattern " + std::to_string(n));
  if (u.size() != n)
    throw std::invalid_argument("ComplexStepJacobian::compute: u has " + std::to_string(u.size()) +
                                " entries, expected " + std::to_string(n));
  SparseMatrix<> A(n, n);
  A.resizeNonZeros(m_pattern.nonzeros());
  for (int r = 0; r <= n; ++r) A.outerIndexPtr()[r] = static_cast<int>(m_pattern.offsets[r]);
  std::copy(m_pattern.indices.begin(), m_pattern.indices.end(), A.innerIndexPtr());
  double* values = A.valuePtr();
  std::fill(values, values + m_pattern.nonzeros(), 0.0);

  bool finite = true;
  const double sign = f ? -1.0 : 1.0;
  Eigen::VectorXcd uc = u.cast<std::complex<double>>(), a;
  for (const std::vector<int>& columns : m_columns_of_colour) {
    for (int k : columns) uc[k] += std::complex<double>(0.0, m_column_step[k]);
    if (f)
      f->acceleration(uc, a);
    else
      m_system->rate(uc, a);
    for (int k : columns) {
      uc[k] = u[k];
      for (long e = m_transpose.offsets[k]; e < m_transpose.offsets[k + 1]; ++e) {
        const std::complex<double> v = a[m_transpose.indices[e]];
        if (!std::isfinite(v.real()) || !std::isfinite(v.imag())) finite = false;
        values[m_transpose_position[e]] = sign * v.imag() / m_column_step[k];  // A = -da/du, J = dF/dy
      }
    }
  }
  m_info = finite ? Status::Successful : Status::NumericalIssue;
  return A;
}

namespace {

/// The complex-step Jacobian of f (a force function or a system) at x; throws "jacobian: <failure>" where it is not
/// finite.
template <class Function>
SparseMatrix<> checked_jacobian(const Function& f, const Eigen::VectorXd& x, const std::string& failure) {
  ComplexStepJacobian jac(f);
  SparseMatrix<> J = jac.compute(x);
  if (jac.info() != Status::Successful) throw std::runtime_error("jacobian: " + failure);
  return J;
}

}  // namespace

SparseMatrix<> jacobian(const ForceFunction& force, const Eigen::VectorXd& u) {
  return checked_jacobian(force, u, "the force function " + force.name() + " is not finite at u");
}

SparseMatrix<> jacobian(const SemiDiscreteSystem& system, const Eigen::VectorXd& y) {
  return checked_jacobian(system, y, "the system " + system.name() + " is not finite at y");
}

Linearisation affine_jacobian(const ForceFunction& force, const Eigen::VectorXd& u, double symmetry_tol) {
  ComplexStepJacobian jac(force);
  auto f0 = force.with_load(0.0), f1 = force.with_load(1.0);
  Linearisation split;
  split.dofs_per_particle = force.dim();
  split.A0 = jac.compute(u, f0.get());
  if (jac.info() != Status::Successful)
    throw std::runtime_error("affine_jacobian: the force function " + force.name() + " is not finite at u");
  split.A1 = jac.compute(u, f1.get());
  if (jac.info() != Status::Successful)
    throw std::runtime_error("affine_jacobian: the force function " + force.name() + " is not finite at u");
  split.symmetric = relative_asymmetry(split.A0) <= symmetry_tol && relative_asymmetry(split.A1) <= symmetry_tol;
  // Same pattern: subtract value by value (keeps the structure, explicit zeros included).
  Eigen::Map<Eigen::VectorXd>(split.A1.valuePtr(), split.A1.nonZeros()) -=
      Eigen::Map<const Eigen::VectorXd>(split.A0.valuePtr(), split.A0.nonZeros());
  return split;
}

}  // namespace sphstab
