#pragma once
/// \file analytic_jacobian_2d.hpp
/// Closed-form sparse linearisation A(e) = A0 + e A1 (A = -da/du) of the 2D elastic SPH forms (ElasticForm2D,
/// elasticity_2d.hpp) at the rest state u = 0 with zero fixed displacements, for any particle set (lattice or not,
/// free and fixed particles, periodic or not). It replaces the coloured complex-step Jacobian (about 180 complex force
/// evaluations in 2D) by one fused sparse triple product, which is what makes lattices of 10^5..10^6 particles
/// feasible. Checked entry by entry against affine_jacobian() (complex step) in
/// tests/jacobian/analytic_jacobian_2d_test.cpp.
///
/// ## Derivation
/// Notation (operators.hpp): G^b_ij = w^b(x_i - x_j) V_j, H^{bc}_ij = w^{bc}(x_i - x_j) V_j (H_ii = 0), with
/// dG^b_ij/du_k^c = H^{bc}_ij (delta_ik - delta_jk) because the kernel is evaluated at the current positions.
/// Row sums over ALL neighbours (free and fixed): g^b_i = sum_j G^b_ij, eta^{bc}_i = sum_j H^{bc}_ij.
/// Sum over repeated component indices a, b, c, d in {x, y}; i, k free particles, j any particle.
///
/// 1. Strain. (grad u)_i^{ab} = sum_j (u_j^a - u_i^a) G^b_ij. At u = 0 the factor (u_j - u_i) vanishes, so the
///    variation of G does not contribute: delta(grad u)_j^{cd} = sum_k Dm^d_jk du_k^c with the "minus" gradient
///    Dm^d = G^d - diag(g^d) on ALL particles j, restricted to the FREE columns k (fixed du = 0).
///    delta sigma_j^{ab} = C^{abcd} delta(grad u)_j^{cd},
///    C^{abcd} = lambda delta_ab delta_cd + mu (delta_ac delta_bd + delta_ad delta_bc) (plane strain; C kills the
///    antisymmetric part, so using grad u instead of eps is exact).
/// 2. Forms uncorrected / plus / minus (alpha = 0, 1, -1): a_i^a = (1/rho) sum_j (sigma_j^{ab} + alpha sigma_i^{ab})
///    G^b_ij. Varying sigma (first term) and G (second term; sigma = sigma0 e at rest):
///      delta a_i^a = (1/rho) sum_j P^b_ij delta sigma_j^{ab} + ((1 + alpha)/rho) sigma0^{ab} sum_j H^{bc}_ij
///                    (du_i^c - du_j^c),
///    P^b = G^b + alpha diag(g^b) (the diagonal collects the alpha sigma_i term).
/// 3. Conservative: a_i^c = (1/rho) sum_j S^{ab} [delta_ac G^b_ij + (u_i^a - u_j^a) H^{bc}_ij], S = sigma_i + sigma_j
///    (elasticity_2d.hpp). At u = 0: the first term varies as in 2. with alpha = 1 (sum_j (dsigma_j + dsigma_i) G_ij)
///    plus 2 sigma0^{cb} sum_j H^{bd}_ij (du_i^d - du_j^d); the second term gives 2 sigma0^{ab} sum_j H^{bc}_ij
///    (du_i^a - du_j^a).
///
/// With the free-block initial-stress ("geometric") operators L^{bc} = diag(eta^{bc}) - H^{bc} (free rows and free
/// columns; the diagonal sums run over all neighbours), and the 2 x 2 block of particle pair (i, k) written as a
/// matrix over (a, c):
///
///   A0_ik = -(1/rho) sum_j [lambda p q^T + mu q p^T + mu (p . q) I],   p = (P^x_ij, P^y_ij), q = (Dm^x_jk, Dm^y_jk)
///           (sum_{b,d} C^{abcd} p^b q^d written out; j runs over the neighbours of i, k over the free neighbours of j)
///   A1_ik = -((1 + alpha)/rho) s0 L_ik                      (uncorrected 1, plus 2, minus 0)
///   A1_ik = -(2/rho) (s0 L_ik + L_ik s0)                      (conservative)
///
/// where s0 = sigma0 at unit pre-strain (PreStrain{kind, 1}.stress) and L_ik = [L^{bc}_ik]. A(e) = A0 + e A1 is
/// exact: every form is affine in the pre-strain e. The conservative A0 uses alpha = 1 like plus.
///
/// \note Properties (all verified in the tests). (i) For equal volumes, G is antisymmetric, so P^b_F = -(Dm^b_{:,F})^T
///       for alpha = 1 and A0 = (1/rho) V^{-1} B^T (V C) B with B = Dm_{:,F}: symmetric positive semi-definite (the
///       Hessian of the strain energy over the mass). On a lattice whose free particles have complete neighbourhoods
///       (fixed layers or periodic) g^b_i = 0 on the free rows, so P^b_F = G^b_F for every alpha: A0 is the SAME for
///       all four forms. (ii) A1 is symmetric when s0 is isotropic (s0 = s I) for every form, and for the conservative
///       form always; for uniaxial s0 = diag(lambda + 2 mu, lambda) the uncorrected and plus A1 = -c s0 L are not
///       symmetric (their 1D ratios 1 : 2 : 4 with conservative hold only for isotropic s0). (iii) Uncorrected and plus
///       differ only by the factor 2 in A1: e_crit(uncorrected) = 2 e_crit(plus) exactly. (iv) Minus: A1 = 0.
/// \note Only the plain kernel gradient (no GradientProvider correction) and zero fixed displacements are covered.
///
/// \code{.cpp}
/// auto set = sphstab::make_lattice<2>(sphstab::LatticeType::Square, 20, {.spacing = 1.0, .support_radius = 2.6});
/// auto disc = sphstab::make_discretisation(set, sphstab::Kernel<2>(sphstab::KernelType::WendlandC2), 1.3);
/// sphstab::Linearisation jac = sphstab::analytic_jacobian_2d(*disc, sphstab::ElasticMaterial::from_lame(1, 1, 1),
///     sphstab::MomentumForm::Conservative, sphstab::PreStrainKind::Isotropic);
/// sphstab::SparseMatrix<> a = jac.at(1e-3);   // A(e) at e = 1e-3, dofs x dofs, interleaved f * 2 + a
/// \endcode
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/jacobian/linearisation.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// The result is a Linearisation (jacobian/linearisation.hpp) with dofs_per_particle = 2 (dof = f * 2 + a, free
/// particles in ascending index), A0 the material stiffness over rho (pattern: particles within 2 neighbour hops),
/// A1 the initial-stress stiffness per unit pre-strain (1 hop), `symmetric` when A(e) is symmetric for every e
/// (conservative, minus, or isotropic pre-strain, with equal volumes and complete neighbourhoods of the free
/// particles), `complete` when every free particle has sum_j G_ij = 0 (tolerance 1e-10 max |G|).

/// Analytic A0, A1 from operators G, H assembled at the rest positions (`operators` must hold G and H with the
/// neighbour-list pattern of `discretisation`). Throws std::invalid_argument for an invalid material, missing or
/// mis-sized operators.
Linearisation analytic_jacobian_2d(const Discretisation<2>& discretisation, const Operators<2>& operators,
                                   const ElasticMaterial& material, MomentumForm form, PreStrainKind kind);

/// As above, assembling G and H first.
Linearisation analytic_jacobian_2d(const Discretisation<2>& discretisation, const ElasticMaterial& material,
                                   MomentumForm form, PreStrainKind kind);

/// The Jacobian of a force function's form, material and pre-strain kind (its load e is not used: A0 and A1 do not
/// depend on it). Throws std::invalid_argument if the closed form does not cover the force
/// (require_closed_form_coverage).
Linearisation analytic_jacobian_2d(const ElasticForm2D& force);

/// The checks shared by the closed-form routes (assembled and matrix_free_linearisation.hpp); `who` starts the
/// one-line message. Coverage: a plain gradient, zero fixed displacements and no additional momentum terms (e.g. the
/// artificial stress). Operators: G and H (xx, xy, yy) N x N, compressed, with the neighbour list's pattern.
void require_closed_form_coverage(const ElasticForm2D& force, const std::string& who);
void require_closed_form_operators(const Discretisation<2>& d, const Operators<2>& ops, const std::string& who);

}  // namespace sphstab
