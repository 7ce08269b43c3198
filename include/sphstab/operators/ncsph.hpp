#pragma once
/// \file ncsph.hpp
/// Normalised-corrected SPH (NCSPH) gradient, Powell (1.19) (the first-order method of the MCM code):
///   1. the Shepard gradient G~^b of every axis b, Powell (3.61) (shepard.hpp), whose rows sum to 0;
///   2. per particle the Dim x Dim moment matrix M_i^{ab} = sum_j (x_j^a - x_i^a) G~^b_ij, with the
///      minimum-image separation in periodic axes (equal to (1.19)'s sum_j x_j^a G~^b_ij because the rows of
///      G~ sum to 0, and well defined across a periodic seam);
///   3. G^b_ij = sum_c G~^c_ij (M_i^{-1})_{cb}   (row vector grad W~_ij times M_i^{-1}, as printed in (1.19)).
/// Then sum_j G^b_ij = 0 (1.13a) and sum_j (x_j^a - x_i^a) G^b_ij = delta_ab (1.13b): the gradient
/// <d_b f>_i = sum_j (f_j - f_i) G^b_ij (and also (G^b f)_i) is exact for every linear field f.
#include <array>
#include <complex>

#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

/// NCSPH gradient matrices of all axes, Powell (1.19) (see the file comment).
///
/// @tparam Dim 1, 2 or 3.  @tparam Scalar double or std::complex<double>.
/// @param[in] particles  the particle set the operators were assembled on (periodic box, N particles).
/// @param[in] W          N x N kernel matrix.
/// @param[in] G          G[a], N x N gradient matrices; W and every G[a] must share one sparsity pattern
///                       (assemble them together with assemble_operators).
/// @param[in] positions  optional N x Dim positions used for the separations instead of particles.x (the same
///                       positions the operators were assembled at, e.g. complex-step displaced ones).
/// @param[in] min_rcond  smallest accepted reciprocal condition number sigma_min/sigma_max of Re(M_i).
/// @return G[b] corrected, N x N, the pattern of W.
/// Throws std::invalid_argument for size/pattern mismatches, non-finite entries, a zero kernel row sum, or a
/// moment matrix M_i with rcond < min_rcond (e.g. a particle with too few neighbours, or neighbours all on a
/// line in 2D); the message names the particle index.
template <int Dim, class Scalar>
std::array<SparseMatrix<Scalar>, Dim> ncsph_gradient(const ParticleSet<Dim>& particles, const SparseMatrix<Scalar>& W,
                                                     const std::array<SparseMatrix<Scalar>, Dim>& G,
                                                     const Positions<Dim, Scalar>* positions = nullptr,
                                                     double min_rcond = 1e-12);

}  // namespace sphstab
