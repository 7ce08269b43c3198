#pragma once
/// \file ismail_boundary.hpp
/// Ismail's boundary treatments [Ismail2009, §2.8.3, §2.9]: the corrective eta method (1D, Dirichlet and Neumann) and
/// the modified-SPH-matrix Dirichlet method (any dimension). Both set the values of the boundary / ghost particles so
/// that an SPH approximation takes a prescribed value exactly; neither moves particles.
///
/// Eta method, boundary particle b, correction set Q (one-sided: the ghosts beyond b, b itself excluded):
///   f_q <- f_q + eta W(x_b - x_q, h)  for q in Q                                        [Ismail2009, (2.39)]
///   Dirichlet: eta = (fbar - <f>_b) / D,   D = sum_{q in Q} W(x_b - x_q)^2 dV_q         [Ismail2009, (2.42)]
///   Neumann:   eta = (hbar - <f_x n>_b) / N,  N = sum_{q in Q} W(x_b - x_q) n dW(x_b - x_q)/dx_b dV_q  [(2.45)]
/// with <f>_b = sum_q f_q W(x_b - x_q) dV_q and <f_x>_b = sum_q f_q dW(x_b - x_q)/dx_b dV_q (Ismail's direct sums,
/// the rows of his W and X, over every particle within the support of b).
/// \note [Ismail2009] prints the sums over B + I + G (both sides of b). Over a symmetric cover N = sum W W' dV = 0
///       (W W' is odd), so the Neumann correction must be one-sided ([Ismail2009, §2.8.3]; his algorithm 4.1
///       comments "set G"); b itself is excluded (W'(0) = 0, and (2.39) says 0 < |x_b - x_q|). A vanishing
///       denominator throws.
///
/// Modified SPH matrix, constrained set C = B u G (boundary and ghost particles), interior I:
///   (W f_new)_c = fbar_c for every c in C,  f_new = f on I:   W_CC f_C = fbar_C - W_CI f_I  [Ismail2009, (2.46),
///   (2.47)]
/// i.e. the SPH matrix with the interior ROWS replaced by identity rows, inverted. W_CC is factorised once (Eigen
/// SparseLU), never inverted densely. \note [Ismail2009] §5.4 ("all entries in the rows AND columns ... set to zero")
///       and the last step of the derivation before (2.46) drop W_CI f_I (the block-diagonal matrix of (2.46)); then
///       <f>_C = fbar_C + W_CI f_I, not fbar_C, unless the interior values vanish within the support of C. The
///       printed (2.46) also has W_BB in the GG block [!]. Implemented here: the exact version.
///
/// \code{.cpp}
/// sphstab::EtaBoundary1D wall(set, kernel, h, b, ghosts, sphstab::BoundaryCondition::Dirichlet);
/// double eta = wall.apply(u_all, 0.0);                  // <u>_b == 0 afterwards
/// sphstab::ModifiedMatrixDirichlet mm(sphstab::kernel_matrix(set, nl, kernel, h), constrained);
/// mm.apply(u_all, Eigen::VectorXd::Zero(constrained.size()));   // (W u)_c == 0 for c in constrained
/// \endcode
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

enum class BoundaryCondition { Dirichlet, Neumann };

/// The corrective eta method at one boundary particle of a 1D set [Ismail2009, §2.8.3].
class EtaBoundary1D {
 public:
  /// @param[in] particles  1D particle set (positions, volumes dV)
  /// @param[in] kernel, h  the kernel of the SPH sums (h > 0)
  /// @param[in] boundary   index b of the boundary particle
  /// @param[in] targets    indices of the corrected particles (distinct, != b, within the support of b)
  /// @param[in] condition  Dirichlet (2.42) or Neumann (2.45)
  /// @param[in] normal     outward normal n = +1 or -1 (Neumann: the prescribed value is f_x n)
  /// Throws std::invalid_argument (one line) for an index out of range, b among the targets, a target outside the
  /// support, |normal| != 1, or a denominator D or N that vanishes (|.| <= 1e-12 sum W^2 dV).
  EtaBoundary1D(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h, int boundary,
                std::vector<int> targets, BoundaryCondition condition, double normal = 1);
  /// The same at a boundary POINT x_b that need not be a particle (e.g. the wall half-way between the last free
  /// particle and the first ghost of a cell-centred lattice): the SPH sums are the interpolant at x_b.
  EtaBoundary1D(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h, double boundary_point,
                std::vector<int> targets, BoundaryCondition condition, double normal = 1);
  /// <f>_b (Dirichlet) or <f_x>_b n (Neumann) of the field f (N entries).
  double value(const Eigen::VectorXd& f) const;
  /// Adds eta W(x_b - x_q) to f_q for q in the targets so that value(f) == prescribed afterwards; returns eta.
  double apply(Eigen::VectorXd& f, double prescribed) const;
  /// D (Dirichlet) or N (Neumann).
  double denominator() const { return m_denominator; }
  /// The boundary particle (-1 for a boundary point).
  int boundary() const { return m_boundary; }
  const std::vector<int>& targets() const { return m_targets; }

 private:
  void init(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h, double xb, BoundaryCondition condition,
            double normal);
  int m_boundary = -1;
  int m_size = 0;
  std::vector<int> m_targets;
  Eigen::VectorXd m_shape;   ///< W(x_b - x_q) per target
  std::vector<int> m_cover;  ///< particles within the support of b
  Eigen::VectorXd m_weight;  ///< W(x_b - x_q) dV_q or n dW/dx_b dV_q per cover particle
  double m_denominator = 0;
};

/// The modified-SPH-matrix Dirichlet method [Ismail2009, (2.46), (2.47)], exact form (see the file comment).
class ModifiedMatrixDirichlet {
 public:
  /// @param[in] w            N x N SPH matrix W_ij = W(x_i - x_j) V_j (operators.hpp kernel_matrix)
  /// @param[in] constrained  indices C = B u G (distinct, in range, non-empty)
  /// Throws std::invalid_argument (one line) for a non-square w, a bad index, or a singular W_CC.
  ModifiedMatrixDirichlet(const SparseMatrix<>& w, std::vector<int> constrained);
  /// Overwrites f (N entries) on C so that (W f)_c = prescribed_c (one value per constrained index, in its order).
  void apply(Eigen::VectorXd& f, const Eigen::VectorXd& prescribed) const;
  const std::vector<int>& constrained() const { return m_constrained; }

 private:
  std::vector<int> m_constrained;
  std::vector<char> m_is_constrained;
  SparseMatrix<> m_w_c;                                                ///< rows C of W, columns of C zeroed (|C| x N)
  std::shared_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>>> m_lu;  ///< of W_CC
};

}  // namespace sphstab
