#pragma once
/// \file complex_step_jacobian.hpp
/// The generic exact sparse Jacobian A = -da/du of any ForceFunction (and J = dF/dy of any SemiDiscreteSystem), by
/// complex-step differentiation with
/// column colouring: for each colour c, one complex evaluation a(u + i h e_c) with e_c = sum of the unit vectors
/// of the columns of colour c gives A_rk = -Im a_r / h for the (unique) column k of colour c in row r.
/// With h = 1e-30 there is no subtractive cancellation: the result is exact to round-off (Squire & Trapp 1998;
/// Curtis, Powell & Reid 1974 for the colouring).
///
/// **The step scales with the variable** (complex_step_size): a step is exact only while it is tiny against the
/// length on which the variable enters nonlinearly (|x + i h|^2 = |x|^2 - h^2 + 2 i h x: at a lattice spacing of
/// 1e-40, h = 1e-30 would swamp |x|^2), and its imaginary parts must not underflow at huge scales. Column k steps
/// by h_k = step * s_k / clamp(s_k, 1e-12, 1e12) with s_k the system's variable_scale(): exactly `step` for every
/// variable whose scale lies in [1e-12, 1e12] (all of the studies' states), proportional to s_k outside, so the
/// Jacobian rescales exactly over the supported length range [1e-60, 1e60] (tests/jacobian: spectrum, J and dt of
/// the rate-form scheme at dx = 1e-40 and 1e58 against dx = 1). One complex evaluation per colour still suffices:
/// the columns of a colour share no row.
///
/// \code{.cpp}
/// sphstab::WaveForm1D force(disc, sphstab::MomentumForm::Conservative, 1e-3);
/// sphstab::ComplexStepJacobian jac(force);            // pattern + colouring, once
/// Eigen::VectorXd u = Eigen::VectorXd::Zero(force.dofs());
/// sphstab::SparseMatrix<> A = jac.compute(u);          // A = -da/du, dofs x dofs, row-major
/// int evaluations = jac.colours();                     // complex force evaluations per Jacobian
/// sphstab::Linearisation lin = sphstab::affine_jacobian(force, u);  // A(T) = lin.A0 + T * lin.A1
/// \endcode
#include <Eigen/Core>
#include <vector>

#include "sphstab/core/status.hpp"
#include "sphstab/jacobian/linearisation.hpp"
#include "sphstab/neighbours/sparsity.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/system/force_function.hpp"
#include "sphstab/system/semi_discrete_system.hpp"

namespace sphstab {

enum class ColouringStrategy {
  Greedy,  ///< greedy distance-2 colouring (colours independent of N)
  None     ///< one column per evaluation (dense reference; dofs() evaluations)
};

/// The complex step of a variable of magnitude `scale` (> 0, finite): step * scale / clamp(scale, 1e-12, 1e12) (see
/// above). Throws std::invalid_argument for a scale that is not finite and > 0.
double complex_step_size(double step, double scale);

/// Complex-step Jacobian with a precomputed pattern and colouring (reused across compute() calls and across
/// force functions with the same pattern, e.g. other loads).
class ComplexStepJacobian {
 public:
  static constexpr double default_step = 1e-30;

  /// Analyses force.dof_pattern() and colours its columns; compute() then returns A = -da/du.
  explicit ComplexStepJacobian(const ForceFunction& force, ColouringStrategy strategy = ColouringStrategy::Greedy,
                               double step = default_step);
  /// Analyses system.pattern() and colours its columns; compute() then returns J = dF/dy (the system must stay
  /// alive).
  explicit ComplexStepJacobian(const SemiDiscreteSystem& system, ColouringStrategy strategy = ColouringStrategy::Greedy,
                               double step = default_step);

  /// A = -da/du at u (size dofs()), on the pattern (explicit zeros kept). Uses `force` if given (it must have
  /// the same dofs() and pattern; e.g. with_load()), else the force function given to the constructor, which
  /// must still be alive. For a system: J = dF/dy at y = u (`force` must be null).
  SparseMatrix<> compute(const Eigen::VectorXd& u, const ForceFunction* force = nullptr) const;

  /// Successful, or NumericalIssue when the last compute() met a non-finite force value (the affected entries are
  /// NaN).
  Status info() const { return m_info; }
  /// Complex force evaluations per compute() (= number of colours).
  int colours() const { return m_ncolours; }
  const std::vector<int>& colouring() const { return m_colour; }
  const SparsityPattern& pattern() const { return m_pattern; }
  double step() const { return m_step; }
  /// The step of each column (complex_step_size of the system's variable_scale(); `step` for a force function).
  const Eigen::VectorXd& column_steps() const { return m_column_step; }

 private:
  void analyse(ColouringStrategy strategy, int size, const char* who);
  const ForceFunction* m_force = nullptr;
  const SemiDiscreteSystem* m_system = nullptr;
  double m_step;
  Eigen::VectorXd m_column_step;
  SparsityPattern m_pattern;
  std::vector<int> m_colour;
  int m_ncolours = 0;
  mutable Status m_info = Status::NotComputed;
  std::vector<std::vector<int>> m_columns_of_colour;
  SparsityPattern m_transpose;             ///< rows of each column
  std::vector<long> m_transpose_position;  ///< for each transposed entry, its position in the row-major values
};

/// A = -da/du at u (greedy colouring). Throws std::runtime_error if the force is not finite at u.
SparseMatrix<> jacobian(const ForceFunction& force, const Eigen::VectorXd& u);
/// J = dF/dy at y (greedy colouring). Throws std::runtime_error if the rate is not finite at y.
SparseMatrix<> jacobian(const SemiDiscreteSystem& system, const Eigen::VectorXd& y);

/// The affine split in the load: A(load) = A0 + load * A1, with A0 = A(0) and A1 = A(1) - A(0) (exact because
/// every form is affine in its load; verified in the tests). dofs_per_particle = force.dim(); `symmetric` is
/// measured: relative_asymmetry of A(0) and A(1) both <= symmetry_tol. Positions (x) are left to the caller.
/// Throws std::runtime_error if the force is not finite at u.
Linearisation affine_jacobian(const ForceFunction& force, const Eigen::VectorXd& u, double symmetry_tol = 1e-12);

}  // namespace sphstab
