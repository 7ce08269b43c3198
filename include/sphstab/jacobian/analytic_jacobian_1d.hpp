#pragma once
/// \file analytic_jacobian_1d.hpp
/// Closed-form linearisation of the 1D pre-tensioned SPH forms at the equilibrium u = 0 (Powell (3.40),
/// docs/conventions.md §4):
///
///   A(T) = -df/du = K - n T L   on the free block, n = initial_stress_multiplier(form) (1, 2, 4; 0 for minus),
///   K = G_f G_f^T                  (material stiffness; G_f = free ROWS of G, ALL columns: the sum over j runs over
///                                   free and fixed neighbours), K_ik = sum_j G_ij G_kj
///   L = diag(sum_{j != i} H_ij) - H_ff   (geometric / initial-stress stiffness; the row sum runs over ALL j)
///
/// with G = G^x, H = H^xx = W''(r) V_j (operators.hpp). T is a dimensionless pre-strain (s_i = <u_x>_i + T).
/// For the conservative form U = 1/2 sum_i s_i^2 is summed over ALL particles, free and fixed.
///
/// Derivation (checked in tests/jacobian/analytic_jacobian_1d_test.cpp by complex-step differentiation of the
/// force functions): with s_i = sum_j (u_j - u_i) G_ij(x + u) + T and dG_ij/du_k = H_ij (delta_ik - delta_jk),
/// ds_j/du_k = G_jk for free k (complete neighbourhood: sum_m G_km = 0) and G_jk = -G_kj (equal volumes), so the
/// stress term gives (G G)_ik = -(G G^T)_ik and the tension term (1 + alpha) T sum_j dG_ij/du_k = (1 + alpha) T L_ik.
/// The conservative Hessian T sum_i d^2 s_i/du_p du_k = -4 T L_pk gives n = 4.
///
/// \note Typos in Powell: (3.41) prints W'_ij W'_ji in the diagonal, but A_ii = sum_j G_ij^2 > 0 (W'_ij W'_ji =
///       -W'_ij^2); (3.48) prints W_ij W_{i+1,j} where W'_ij W'_{i+1,j} (= K_{i,i+1}) is meant.
/// \note Preconditions (checked): equal volumes (G antisymmetric) and complete, symmetric neighbourhoods of the free
///       particles (sum_j G_ij = 0 for free i): a regular line lattice with fixed layers, or a periodic one.
#include <vector>

#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/jacobian/linearisation.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

/// A(T) = K - n T L of Powell (3.40) on the free block as a Linearisation: A0 = K, A1 = -n L
/// (n = initial_stress_multiplier(form); n is a power of two, so A1 is exact). Free degree of freedom k is particle
/// free_index[k]; x holds the free positions; `symmetric` is true (K and L are symmetric for every 1D form here).
/// For the uncorrected form (n = 1) A1 = -L itself. Throws std::invalid_argument if an operator is missing, sizes
/// differ, there are no free particles, or the preconditions above fail (tolerance 1e-10 of the largest |G_ij|).
Linearisation analytic_jacobian_1d(const ParticleSet<1>& particles, const Operators<1>& operators,
                                   MomentumForm form = MomentumForm::Uncorrected);

/// Convenience: neighbour search with the kernel's support and operator assembly, then the overload above.
Linearisation analytic_jacobian_1d(const ParticleSet<1>& particles, const Kernel<1>& kernel, double h,
                                   MomentumForm form = MomentumForm::Uncorrected);

}  // namespace sphstab
