#pragma once
/// \file elastic_bar.hpp
/// Linear SPH for the 1D elastic bar rho ü = ∂σ/∂x, σ = E ∂u/∂x, in total-Lagrangian (fixed reference
/// operators, two sparse matrix-vector products per step) or updated-Lagrangian (operators reassembled at the
/// current positions every step) form.
///
/// Discretisation (docs/conventions.md §3 operators, G_ij = ∂W(|x_i - x_j|)/∂x_i V_j):
///   strain      ε = D_u u,   D_u = G (Plain), G - diag(G 1) (Minus, zeroth-order corrected, Powell 1.15), or
///                            diag(1/m1) (G - diag(G 1)) (Corrected: first-order, exact for linear u; the 1D
///                            form of the normalised gradient of Powell 1.19 without the Shepard step), with the
///                            discrete first moment m1_i = Σ_j (x_j - x_i) G_ij
///   stress      σ = E ε
///   divergence  ü = (1/rho) D_σ σ with
///                 Plain:   Σ_j σ_j G_ij
///                 Plus:    Σ_j (σ_j + σ_i) G_ij = (G + diag(G 1)) σ          (Powell 1.35)
///                 Minus:   Σ_j (σ_j - σ_i) G_ij = (G - diag(G 1)) σ          (Powell 1.34)
///                 Adjoint: -V⁻¹ D_uᵀ V σ, the variational (energy-conserving) partner of D_u:
///                          M ü = -∂U/∂u for U = ½ E Σ_i V_i ε_i², M = rho V.
/// \note At fixed h/dx the plain and minus gradients of a linear field are m1 (not 1): on a regular lattice with a
///       full neighbourhood m1 depends only on the kernel and h/dx (cubic B-spline: 1 at h/dx = 1 and 2, 1.0224
///       at 1.3), so the SPH bar wave speed is m1 c and the error does NOT vanish as dx -> 0 at fixed h/dx.
/// For uniform volumes G V-weighted is antisymmetric (G_ij V_i = -G_ji V_j), so the adjoint of Minus is Plus and
/// the adjoint of Plain is Plain (without ghosts). The TL operator is ü = -A u with
/// A = -(E/rho) C B, B = D_u (free rows, ghosts folded in), C = D_σ (ditto).
///
/// Boundaries (both ends of the bar are free, σ = 0):
///   Mirror: ghost particles beyond each end (the lattice's fixed layers, as many as the kernel support needs)
///           take the displacement (and velocity) of their mirror image (even reflection, u_x = 0 at the end)
///           and the negated stress (odd reflection, σ = 0 at the end). On a regular lattice every free particle
///           then has a full, symmetric neighbourhood, G 1 = 0 on all free rows, and Plain = Minus = Plus;
///           Plain/Plain with mirror ghosts is exactly the adjoint pair (conservative).
///   None:   no ghosts; particles near the ends are kernel-deficient (G 1 != 0 there). The free surface is
///           implicit in the sums (no particles outside).
/// Updated-Lagrangian: positions x = X + u (ghosts: X_g + u_mirror), neighbour list built with radius
/// 2h + skin and reused while no particle moved more than skin/2 since the last build; G is reassembled at x
/// every evaluation; volumes stay V_0 (mass conservation with reference density; linear small-strain law).
///
/// DOFs: u, a hold the n free particles (Dim = 1), in lattice order (x_i = (i + ½) dx, dx = L / n).
///
/// \code{.cpp}
/// sphstab::ElasticBar1D bar({.particles = 200, .h_over_dx = 1.3});
/// sphstab::SecondOrderSystem sys = bar.system();   // captures &bar: keep bar alive
/// Eigen::VectorXd a(bar.size());
/// bar.acceleration(Eigen::VectorXd::Zero(bar.size()), a);
/// \endcode
#include <Eigen/Core>
#include <memory>
#include <string>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/particle_set.hpp"
#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

enum class StrainGradient { Plain, Minus, Corrected };
enum class StressDivergence { Plain, Plus, Minus, Adjoint };

/// alpha of the divergence a_i = (1/rho) sum_j (sigma_j + alpha sigma_i) G_ij: Plus +1, Minus -1, Plain (and Adjoint,
/// which the forms that take alpha reject first) 0.
inline double divergence_alpha(StressDivergence d) {
  return d == StressDivergence::Plus ? 1.0 : (d == StressDivergence::Minus ? -1.0 : 0.0);
}
enum class BarBoundary { Mirror, None };
enum class LagrangianFrame { Total, Updated };

std::string strain_gradient_name(StrainGradient g);
std::string stress_divergence_name(StressDivergence d);
std::string bar_boundary_name(BarBoundary b);
std::string lagrangian_frame_name(LagrangianFrame f);

struct ElasticBarOptions {
  int particles = 100;          ///< n free particles, >= 2
  double length = 1.0;          ///< L (cm)
  double density = 7.8;         ///< rho (g/cm³)
  double youngs_modulus = 2.1;  ///< E (Mbar)
  KernelType kernel = KernelType::CubicSpline;
  double h_over_dx = 1.3;  ///< h / dx > 0 (support 2h)
  StrainGradient gradient = StrainGradient::Plain;
  StressDivergence divergence = StressDivergence::Plain;
  BarBoundary boundary = BarBoundary::Mirror;
  LagrangianFrame frame = LagrangianFrame::Total;
  double skin_over_dx = 0.5;  ///< UL neighbour-list skin / dx (>= 0)
};

class ElasticBar1D {
 public:
  /// Throws std::invalid_argument for fewer than 2 particles, non-positive parameters, or ghost layers deeper
  /// than the bar (mirror images would not exist).
  explicit ElasticBar1D(const ElasticBarOptions& options);

  const ElasticBarOptions& options() const { return m_opt; }
  int size() const { return m_n; }
  double spacing() const { return m_dx; }
  double h() const { return m_h; }
  double wave_speed() const;
  int ghost_count() const { return m_set.size() - m_n; }
  /// Reference positions X of the free particles (n).
  const Eigen::VectorXd& positions() const { return m_X; }
  const Eigen::VectorXd& volumes() const { return m_V; }
  Eigen::VectorXd masses() const { return m_opt.density * m_V; }

  /// a(u), both of size n.
  void acceleration(const Eigen::VectorXd& u, Eigen::VectorXd& a) const;
  /// ε = D_u u at the reference (TL) or current (UL) positions.
  Eigen::VectorXd strain(const Eigen::VectorXd& u) const;
  /// U = ½ E Σ_i V_i ε_i² (the potential of the Adjoint form, and of Plain/Plain with mirror ghosts).
  double strain_energy(const Eigen::VectorXd& u) const;
  /// XSPH velocity hook (Powell 2.71): w_i = v_i + eps Σ_j (v_j - v_i) W_ij (reference W; ghosts mirror v).
  VelocityHook xsph_hook(double eps) const;

  /// The system for run_leapfrog (acceleration, strain energy, masses, reference positions); captures this.
  SecondOrderSystem system() const;

  /// TL matrices: ε = B u and ü = C ε (C includes E/rho); n x n.
  const SparseMatrix<>& strain_matrix() const { return m_B; }
  const SparseMatrix<>& divergence_matrix() const { return m_C; }
  /// A = -C B (ü = -A u) as a sparse matrix (TL).
  SparseMatrix<> stiffness_matrix() const;

  long neighbour_builds() const { return m_builds; }
  long operator_assemblies() const { return m_assemblies; }

 private:
  void build_tl();
  /// ε = D_u u and the row sums of G, for a G assembled at positions x (N x 1).
  void strain_rows(const SparseMatrix<>& G, const Positions<1>& x, const Eigen::VectorXd& u, Eigen::VectorXd& eps,
                   Eigen::VectorXd& rowsum, Eigen::VectorXd& scale) const;
  void update_current(const Eigen::VectorXd& u) const;

  ElasticBarOptions m_opt;
  int m_n = 0;
  double m_dx = 0, m_h = 0;
  Kernel<1> m_kernel;
  ParticleSet<1> m_set;          // free particles first, then ghosts
  std::vector<int> m_map;        // particle -> free index (itself or mirror)
  std::vector<double> m_sign_u;  // +1 (free, ghost displacement) ...
  std::vector<double> m_sign_s;  // +1 free, -1 ghost (stress)
  Eigen::VectorXd m_X, m_V;
  NeighbourList m_nl;             // reference list (radius 2h)
  SparseMatrix<> m_B, m_C, m_Wx;  // TL strain, divergence (E/rho), XSPH smoothing (W P - diag(W 1))

  // UL caches
  mutable NeighbourList m_nl_current;
  mutable ParticleSet<1> m_current;
  mutable Eigen::VectorXd m_u_at_build;
  mutable Positions<1> m_x;
  mutable Eigen::VectorXd m_eps, m_sig, m_rowsum, m_scale;
  mutable long m_builds = 0, m_assemblies = 0;
};

}  // namespace sphstab
