#pragma once
/// \file linearisation.hpp
/// The one linearisation type of sphstab: A(load) = A0 + load A1, A = -da/du at an equilibrium, on the free
/// degrees of freedom. Every producer returns it — the analytic 1D Jacobian [Powell2012, (3.40)], the analytic 2D
/// Jacobian (analytic_jacobian_2d.hpp) and the coloured complex-step Jacobian of any force function
/// (complex_step_jacobian.hpp) — and every consumer takes it: the critical-load engine (stability/critical_load.hpp),
/// the Matrix Market export and the studies.
///
/// The load is the physical one of the force function: the 1D pre-tension T, the 2D pre-strain e. Every SPH form of
/// sphstab is affine in it, so the split is exact (docs/conventions.md, "Linearisation").
///
/// \code{.cpp}
/// sphstab::Linearisation lin = sphstab::analytic_jacobian_1d(set, kernel, h, sphstab::MomentumForm::Plus);
/// sphstab::SparseMatrix<> a = lin.at(1e-3);            // A(T = 1e-3)
/// auto r = sphstab::critical_load(lin, sphstab::LoadDirection::Tension);
/// \endcode
#include <Eigen/Core>
#include <vector>

#include "sphstab/operators/operators.hpp"

namespace sphstab {

struct Linearisation {
  SparseMatrix<> A0;            ///< dofs x dofs: A at zero load (material stiffness over the mass)
  SparseMatrix<> A1;            ///< dofs x dofs: dA/dload (initial-stress / geometric stiffness over the mass)
  int dofs_per_particle = 1;    ///< components per free particle; dof = f * dofs_per_particle + a
  std::vector<int> free_index;  ///< particle index of each free particle (ascending); may be empty (unknown)
  Eigen::MatrixXd x;            ///< free-particle positions, free_count x dofs_per_particle (may be empty)
  /// A(load) is symmetric for every load (to round-off): conservative forms, and the plain forms at a lattice
  /// equilibrium with equal volumes; set by the producer (analytically) or measured (complex step).
  bool symmetric = false;
  bool complete = false;  ///< every free particle has sum_j G_ij = 0 (a complete neighbourhood)
  bool periodic = false;  ///< the particle set is periodic (translations are null modes of A0 and A1)
  double spacing = 0;     ///< lattice spacing dx (0 if unknown)

  int dofs() const { return static_cast<int>(A0.rows()); }
  int free_count() const { return dofs() / dofs_per_particle; }
  /// A0 + load A1 (row-major, compressed).
  SparseMatrix<> at(double load) const { return SparseMatrix<>(A0 + load * A1); }
};

/// ||A - A^T||_F / ||A||_F (0 for the zero matrix). [Powell2012, Thm 3.8]: 0 (to round-off) iff the form is
/// conservative, for equal particle masses.
double relative_asymmetry(const SparseMatrix<>& a);

}  // namespace sphstab
