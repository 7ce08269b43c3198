#pragma once
/// \file mirror_symmetry.hpp
/// Mirror-symmetry classes of 2D vector fields on a particle block symmetric about the lines x = cx and y = cy
/// (e.g. the Swegle block). The reflections act on an interleaved field f (2 components per particle) as
///   (T_x f)_p = diag(-1, 1) f_{m_x(p)},   (T_y f)_p = diag(1, -1) f_{m_y(p)},
/// m_x, m_y = the mirror partners. A force function built from the lattice, an isotropic pre-stress and symmetric
/// boundaries commutes with T_x and T_y, so its Jacobian A is block diagonal in the four classes
/// (p_x, p_y) in {+1, -1}^2 of fields with T_x f = p_x f and T_y f = p_y f: eig(A) is the union of the eigenvalues of
/// the four projected blocks Q^T A Q (each about a quarter of the size, 1/16 of the dense eigen cost), and an initial
/// condition inside one class excites only that class. The centre particle of the Swegle test moving along +x is in
/// the class (p_x, p_y) = (-1, +1).
#include <Eigen/Core>
#include <vector>

#include "sphstab/operators/operators.hpp"

namespace sphstab {

struct MirrorSymmetry {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  std::vector<int> mirror_x;  ///< partner of particle p under x -> 2 cx - x (itself on the axis)
  std::vector<int> mirror_y;  ///< partner under y -> 2 cy - y
  int size() const { return static_cast<int>(mirror_x.size()); }
};

/// Finds the mirror partners of n particles (positions interleaved, size 2 n) about `centre`, matching positions to
/// `tolerance` (absolute). Throws std::invalid_argument if a partner is missing or sizes are wrong.
MirrorSymmetry mirror_symmetry(const Eigen::VectorXd& positions, const Eigen::Vector2d& centre, double tolerance);

/// T f for the reflection `axis` (0: x -> 2cx - x, 1: y -> 2cy - y). f has 2 n entries.
Eigen::VectorXd reflect(const MirrorSymmetry& symmetry, int axis, const Eigen::VectorXd& f);

/// Orthonormal basis (2n x m) of the class (px, py), px, py in {+1, -1}. Throws std::invalid_argument otherwise.
Eigen::MatrixXd symmetry_basis(const MirrorSymmetry& symmetry, int px, int py);

/// Share of the squared norm of f in the class (px, py) (the four shares sum to 1 for f != 0; 0 for f = 0).
double class_share(const MirrorSymmetry& symmetry, int px, int py, const Eigen::VectorXd& f);

/// max(||T_x A - A T_x||_F, ||T_y A - A T_y||_F) / ||A||_F: ~1e-16 when A commutes with the reflections.
double commutation_error(const MirrorSymmetry& symmetry, const SparseMatrix<>& A);

}  // namespace sphstab
