#pragma once
/// \file linear_elastic.hpp
/// Small-strain linear elasticity rho ü = ∇·σ, σ = λ tr(ε) I + 2µ ε, ε = sym(∇u), discretised with the SPH
/// operators G^a of docs/conventions.md §3, in three interchangeable implementations of the SAME force:
///   - TL, sparse matrices (acceleration, frame Total): B^a = D_u^a and C^a = D_σ^a assembled once at the reference
///     positions; one evaluation = Dim gradient SpMVs (each on the Dim displacement components at once), a pointwise
///     stress update and Dim divergence SpMVs. Pure SpMV, no kernel evaluations.
///   - UL, reassembly (acceleration, frame Updated): G^a reassembled at x = X + u every evaluation on a neighbour list
///     of radius 2h + skin, rebuilt when a particle moved more than skin/2 since the last build. The matrices keep
///     their pattern (and storage) between rebuilds; only the values are recomputed in place.
///   - Pair loop (acceleration_pair_loop): no stored operators; two passes over the neighbour pairs evaluating ∇W on
///     the fly at the reference (TL) or current (UL) positions.
///
/// Operators (G^a_ij = ∂W/∂x_i^a V_j):
///   (∂_a u_b)_i = Σ_j u_j^b G^a_ij (Plain) or Σ_j (u_j^b - u_i^b) G^a_ij (Minus, Powell 1.15)
///   ü_i^b = (1/rho) Σ_a Σ_j (σ_j^{ab} + α σ_i^{ab}) G^a_ij with α = 0 (Plain), +1 (Plus, Powell 1.35), -1 (Minus)
/// Minus gradient + Plus divergence is the variational (momentum- and energy-conserving) pair for uniform volumes.
///
/// DOFs: u and a hold the FREE particles (the particle set's free block, indices 0..n_free-1), interleaved
/// i * Dim + b. Fixed particles have u = 0 (clamped); their strain and stress enter the divergence of free rows.
/// \note On a regular lattice with a full neighbourhood the gradient of a linear field is m1 ∇u (m1 = the discrete
///       first moment, e.g. 1.0224 for the 1D cubic B-spline at h = 1.3 dx), so SPH wave speeds are m1 times the
///       continuum ones at fixed h/dx.
#include <Eigen/Core>
#include <array>

#include "sphstab/forms/elastic_bar.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/models/elastic_material.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/particle_set.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

struct LinearElasticOptions {
  ElasticMaterial material = ElasticMaterial::from_lame(1.0, 1.0, 1.0);  ///< λ, µ > 0, rho > 0
  StrainGradient gradient = StrainGradient::Minus;       ///< Plain or Minus
  StressDivergence divergence = StressDivergence::Plus;  ///< Plain, Plus or Minus
  LagrangianFrame frame = LagrangianFrame::Total;
  double skin = 0;  ///< UL neighbour-list skin (length, >= 0)
};

template <int Dim>
class LinearElasticSph {
 public:
  /// Throws std::invalid_argument for bad material constants, an unsupported form (Corrected, Adjoint), h <= 0 or an
  /// invalid particle set.
  LinearElasticSph(const ParticleSet<Dim>& particles, const Kernel<Dim>& kernel, double h,
                   const LinearElasticOptions& options);

  int free_count() const { return m_nfree; }
  int size() const { return m_p.size(); }
  const ParticleSet<Dim>& particles() const { return m_p; }
  double p_wave_speed() const;
  double h() const { return m_h; }

  /// a(u) with the configured frame: TL sparse matrices or UL reassembly. u, a: n_free * Dim.
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const;
  /// The same force by a matrix-free pair loop (reference positions for TL, current for UL).
  void acceleration_pair_loop(const Eigen::VectorXd& u, Eigen::VectorXd& a) const;

  /// System for run_leapfrog (masses rho V and reference positions of the free particles, strain energy
  /// ½ Σ V_i σ_i : ε_i over all particles with the TL gradient); captures this. pair_loop selects
  /// acceleration_pair_loop as the force.
  SecondOrderSystem system(bool pair_loop = false) const;

  /// Nonzeros stored in the TL matrices B^a and C^a (sum; 0 for the UL frame, which stores none).
  long stored_nonzeros() const;
  /// Minimal memory traffic of one TL acceleration in bytes (each byte crosses the memory bus once; perfect cache
  /// reuse of gathered vector entries). B^a share one CSR pattern and are applied in one fused pass, as are C^a:
  ///   gradient pass:   nnz_B (4 + 8 Dim) + 4 (N + 1) + 8 Dim n_free (u) + 8 Dim² N (∇u written)
  ///   stress pass:     8 Dim² N (∇u read) + 8 S N (σ written, S = Dim(Dim+1)/2 components)
  ///   divergence pass: nnz_C (4 + 8 Dim) + 4 (n_free + 1) + 8 S N (σ read) + 8 Dim n_free (a written)
  double tl_bytes_per_acceleration() const;
  /// Strain energy ½ Σ_i V_i σ_i : ε_i (gradient at the reference (TL) or current (UL) positions).
  double strain_energy(const Eigen::VectorXd& u) const;
  long neighbour_builds() const { return m_builds; }

 private:
  void build_tl();
  void update_current(const Eigen::VectorXd& u) const;
  /// Row loops shared by UL (G at current positions): full-set strain -> stress -> free-row divergence.
  void accumulate_from_gradients(const std::array<SparseMatrix<>, Dim>& G, const Eigen::VectorXd& u,
                                 Eigen::VectorXd& a) const;
  /// Recomputes the values of m_Gul (pattern = m_nl_current) at the current positions m_x; fills m_rowsum.
  void reassemble_in_place() const;
  /// σ (compact, S components per particle: xx, yy, [zz,] xy, [xz, yz]) from m_grad for all N particles.
  void stress_from_gradients(int N) const;
  /// Fused gradient pass over a CSR pattern with Dim value arrays: grad[a](i, b) = Σ_k val_a[k] u_all(col[k], b)
  /// (+ minus correction with row sums when rowsum != nullptr).
  void gradient_pass(const int* outer, const int* inner, const std::array<const double*, Dim>& val, int rows) const;
  void divergence_pass(const int* outer, const int* inner, const std::array<const double*, Dim>& val, int rows,
                       const std::array<const double*, Dim>* rowsum, double alpha, Eigen::VectorXd& a) const;

  ParticleSet<Dim> m_p;
  Kernel<Dim> m_kernel;
  double m_h;
  LinearElasticOptions m_opt;
  int m_nfree = 0;
  NeighbourList m_nl;                   // reference list, radius 2h
  std::array<SparseMatrix<>, Dim> m_B;  // N x n_free
  std::array<SparseMatrix<>, Dim> m_C;  // n_free x N
  // work buffers (N x Dim each, interleaved)
  mutable Eigen::VectorXd m_grad;  // N x Dim x Dim: (i, a, b) -> ∂_a u_b at i
  mutable Eigen::VectorXd m_sig;   // N x S compact stress
  mutable Eigen::VectorXd m_uall;
  // UL state
  mutable ParticleSet<Dim> m_current;
  mutable NeighbourList m_nl_current;
  mutable Positions<Dim> m_x;
  mutable Eigen::VectorXd m_u_at_build;
  mutable std::array<SparseMatrix<>, Dim> m_Gul;  // UL operators, pattern of m_nl_current
  mutable std::array<Eigen::VectorXd, Dim> m_rowsum;
  mutable long m_builds = 0;
};

}  // namespace sphstab
