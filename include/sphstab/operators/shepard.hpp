#pragma once
/// \file shepard.hpp
/// Shepard (zeroth-order normalised) kernel and its gradient, Powell (1.14), (3.56), (3.61), and the
/// first-step ("frozen reference") Shepard gradient of Powell (4.18).
///
/// With S_i = sum_k W_ik (row sums of W, volumes included) and g^a_i = sum_k G^a_ik:
///   W~_ij    = W_ij / S_i                                   (1.14)
///   G~^a_ij  = (G^a_ij S_i - W_ij g^a_i) / S_i^2             (3.61)
/// (3.61) is the exact derivative of W~_ij with respect to x_i^a (G^a_ii = 0, so S_i only varies through its
/// off-diagonal terms). Rows of W~ sum to 1, rows of G~ sum to 0 on ANY particle set; on a regular periodic
/// lattice S_i = S and g_i = 0, so G~ = G / S stays antisymmetric (its columns then sum to 0 too).
///
/// \code{.cpp}
/// auto ops = sphstab::assemble_operators(set, nl, w, h);
/// auto Wt = sphstab::shepard_kernel(ops.W);             // rows sum to 1
/// auto Gt = sphstab::shepard_gradient(ops.W, ops.G[0]);  // rows sum to 0
/// \endcode
#include <Eigen/Core>
#include <complex>

#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// W~ = diag(1 / (W 1)) W, Powell (1.14).
/// @param[in] W  N x N kernel matrix, finite entries, every row sum with a non-zero real part.
/// @return N x N, pattern of W, rows summing to 1.
/// Throws std::invalid_argument for a non-square/empty/non-finite W or a zero row sum.
template <class Scalar>
SparseMatrix<Scalar> shepard_kernel(const SparseMatrix<Scalar>& W);

/// Shepard gradient of one axis, Powell (3.61): G~_ij = (G_ij S_i - W_ij (G 1)_i) / S_i^2, S = W 1.
/// @param[in] W  N x N kernel matrix (row sums non-zero).
/// @param[in] G  N x N gradient matrix of the same axis, same size as W.
/// @return N x N with the union of the patterns of W and G (the pattern of both when assembled together);
///         rows sum to 0. Call once per axis in 2D/3D.
template <class Scalar>
SparseMatrix<Scalar> shepard_gradient(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G);

/// Row sums of the kernel and of one gradient matrix in a reference configuration (the first time step),
/// stored for the first-step Shepard normalisation of Powell (4.18). Both have N entries.
struct ShepardReference {
  Eigen::VectorXd kernel_sum;    ///< sum_k W^0_ik
  Eigen::VectorXd gradient_sum;  ///< sum_k dW^0_ik/dx_i^a (one axis a)
};

/// Records S^0 = W^0 1 and g^0 = G^0 1 of one axis from reference operators (real-valued).
ShepardReference shepard_reference(const SparseMatrix<double>& W0, const SparseMatrix<double>& G0);

/// First-step Shepard gradient, Powell (4.18): (G_ij S^0_i - W_ij g^0_i) / (S^0_i)^2 with the current W, G and
/// the frozen reference sums. Equals shepard_gradient(W0, G0) in the reference configuration itself; its rows
/// sum to (g_i S^0_i - S_i g^0_i)/(S^0_i)^2, which is zero only there.
/// @param[in] reference  sums with N entries each, kernel_sum non-zero.
template <class Scalar>
SparseMatrix<Scalar> reference_shepard_gradient(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G,
                                                const ShepardReference& reference);

}  // namespace sphstab
