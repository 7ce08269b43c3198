#pragma once
/// \file minus_gradient.hpp
/// Zeroth-order corrected ("minus") gradient matrix, Powell (1.15):
///   <d_a f>_i = sum_j (f_j - f_i) G^a_ij   <=>   G^a_minus = G^a - diag(G^a 1).
#include <complex>

#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// G - diag(G 1): the "minus" gradient of Powell (1.15), exact (zero) for a constant field on any particle set.
///
/// @tparam Scalar double or std::complex<double> (complex-step differentiation passes through unchanged).
/// @param[in] G  N x N gradient matrix of one axis (e.g. assemble_operators(...).G[a]), finite entries.
/// @return N x N matrix with the pattern of G (plus the diagonal if G did not store it); its rows sum to 0.
/// Throws std::invalid_argument if G is empty, not square or has a non-finite entry.
/// \note Applies to any square matrix, e.g. also to the Hessian-like matrices of the 1D forms.
template <class Scalar>
SparseMatrix<Scalar> minus_gradient(const SparseMatrix<Scalar>& G);

}  // namespace sphstab
