#pragma once
/// \file fourier_symbol_2d.hpp
/// von Neumann (Fourier) analysis of the 2D elastic SPH Jacobian A(e) = A0 + e A1 (analytic_jacobian_2d.hpp) on an
/// infinite or periodic Bravais lattice (square, hexagonal, face-centred). The operators are translation invariant,
/// so u_j = v exp(i k . x_j) (v in C^2) is mapped to (A^(k) v) exp(i k . x_j) with the 2 x 2 symbol
///
///   s^b(k)    = -V sum_m W'(r_m) (r_m^b / r_m) sin(k . r_m)          (the SPH gradient symbol is i s(k))
///   l^{bc}(k) = sum_m H^{bc}(r_m) (1 - cos(k . r_m)),  H^{bc}(r) = V [W'' e e^T + (W'/r)(I - e e^T)]^{bc}
///   A0^(k)    = (1/rho) [(lambda + mu) s s^T + mu |s|^2 I]           (real symmetric, positive semi-definite)
///   A1^(k)    = -((1 + alpha)/rho) s0 l(k)   (uncorrected, plus, minus)      A1^(k) = -(2/rho)(s0 l + l s0) (cons.)
///
/// (sums over the lattice vectors r_m with 0 < |r_m| < 2h; V = cell area; s0 = sigma0 at unit pre-strain). The
/// symbols are REAL 2 x 2 matrices (G is odd, H even), so A^(k, e) = A0^ + e A1^ has real eigenvalues unless its
/// discriminant is negative; A1^ is not symmetric for uniaxial plus/uncorrected.
///
/// Stability of one wavevector: A^(k, e) has both eigenvalues real and positive (trace > 0, determinant > 0,
/// discriminant >= 0). Each is a polynomial of degree <= 2 in e, so the critical strain of one k is found exactly
/// from their roots (critical_strain_2x2). For symmetric symbols this is the determinant root: the generalised
/// eigenvalue of the pencil (-A1^, A0^).
///
/// Zone-boundary zeros: wherever 2k is a reciprocal lattice vector (square (pi, 0), (0, pi), (pi, pi); the three
/// M points of hex and face-centred lattices), sin(k . r_m) = 0 for every lattice vector, so s = 0 and A0^ = 0 (the
/// 2D analogue of the 1D sawtooth). There A^ = e A1^: if -sign(e) A1^ has a positive eigenvalue the lattice is
/// unstable for every |e| > 0 in that direction (e_crit = 0); Gray, Monaghan & Swift (2001) B_x = l^{xx}(pi, 0) > 0
/// (tension) and B_y = l^{yy}(pi, 0) < 0 (compression) on the square lattice are exactly these eigenvalues.
///
/// Periodic n x n lattices (make_lattice periodic box n dx by n dy): the admissible wavevectors
/// k = 2 pi (m1 / (n dx), m2 / (n dy)), 0 <= m1, m2 < n, are distinct modulo the reciprocal lattice and number n^2, so
/// the spectrum of the assembled periodic A(e) is exactly the union of the eigenvalues of A^(k_m, e)
/// (tests/stability/fourier_symbol_2d_test.cpp).
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/bravais_lattice.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {

/// Symbols of one 2D SPH discretisation (lattice, kernel, h, material, form, pre-strain kind).
class ElasticSymbol2D {
 public:
  struct Value {
    Eigen::Vector2d s;   ///< SPH gradient symbol / i
    Eigen::Matrix2d l;   ///< initial-stress symbol l(k)
    Eigen::Matrix2d a0;  ///< A0^(k)
    Eigen::Matrix2d a1;  ///< A1^(k)
  };

  /// Throws std::invalid_argument for h <= 0, dx <= 0, a non-2D lattice or an invalid material.
  ElasticSymbol2D(LatticeType type, const Kernel<2>& kernel, double h, double dx, const ElasticMaterial& material,
                  MomentumForm form, PreStrainKind kind);

  Value operator()(const Eigen::Vector2d& k) const;
  const BravaisLattice2D& lattice() const { return m_lattice; }
  /// sum_m |W'(r_m)| V (scale of s) and sum_m ||H(r_m)|| (scale of l), for tolerances.
  double gradient_scale() const { return m_gscale; }
  double hessian_scale() const { return m_hscale; }
  /// Number of lattice vectors in the support (excluding 0).
  int stencil_size() const { return static_cast<int>(m_r.size()); }
  MomentumForm form() const { return m_form; }
  PreStrainKind kind() const { return m_kind; }

 private:
  BravaisLattice2D m_lattice;
  ElasticMaterial m_material;
  MomentumForm m_form;
  PreStrainKind m_kind;
  Eigen::Matrix2d m_s0;
  std::vector<Eigen::Vector2d> m_r;     // lattice vectors r_m
  std::vector<Eigen::Vector2d> m_grad;  // -V W'(r) r/|r| (so that s = sum grad sin(k.r))
  std::vector<Eigen::Matrix2d> m_hess;  // H(r_m)
  double m_gscale = 0, m_hscale = 0;
};

/// How a 2 x 2 (or finite) A(e) first leaves the stable set {all eigenvalues real and > 0}.
enum class InstabilityMechanism {
  None,          ///< stable for every e of the sign (up to the search limit)
  RealCrossing,  ///< a real eigenvalue passes through 0 (det A = 0: divergence / static buckling)
  ComplexPair,   ///< two real eigenvalues merge and leave the real axis (flutter; only for non-symmetric A)
  ZeroSymbol,    ///< A0^ = 0 at a zone-boundary zero and -sign(e) A1^ has a positive eigenvalue: e_crit = 0
  Neutral        ///< A singular for every e (A0^ = 0 and A1^ singular)
};
std::string mechanism_name(InstabilityMechanism m);

struct CriticalStrain2x2 {
  double e = std::numeric_limits<double>::infinity();  ///< signed: > 0 tension, < 0 compression; +-inf if none
  InstabilityMechanism mechanism = InstabilityMechanism::None;
};

/// Smallest |e| (of the given sign) at which a0 + e a1 stops having two real positive eigenvalues, from the roots of
/// trace, determinant and discriminant (exact up to rounding). a0 must be stable (both eigenvalues real and > 0) or
/// zero (|a0| <= zero_tol): then the ZeroSymbol / Neutral cases apply with |eig(a1)| <= zero_tol as zero.
CriticalStrain2x2 critical_strain_2x2(const Eigen::Matrix2d& a0, const Eigen::Matrix2d& a1, LoadDirection sign,
                                      double zero_tol = 0);

struct SymbolCriticalStrain {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double e = std::numeric_limits<double>::infinity();  ///< signed critical pre-strain; +-inf if none
  double kx_over_pi = nan, ky_over_pi = nan;           ///< k dx / pi of the minimiser (folded, >= 0)
  InstabilityMechanism mechanism = InstabilityMechanism::None;
  int neutral_points = 0;  ///< zone-boundary zeros skipped because A1^ is singular there (neutral modes)
  std::string reason;      ///< how the value arose (no commas)
};

/// Infinite lattice: inf over the Brillouin zone of the per-k critical strain. The zone-boundary zeros are evaluated
/// exactly (e = 0 when unstable there); elsewhere a grid x grid sampling of the reciprocal cell, then 6 levels of
/// local patch refinement (9 x 9, step / 4 each) around the best 4 grid points (k dx / pi to about 1e-6). Neutral
/// zone-boundary zeros are skipped (the limit k -> k* is taken from the neighbourhood, as in 1D).
/// Throws std::invalid_argument for grid < 16.
SymbolCriticalStrain critical_strain_infinite_2d(const ElasticSymbol2D& symbol, LoadDirection sign, int grid = 256);

/// Periodic n x n lattice (make_lattice periodic): minimum over the n^2 - 1 admissible wavevectors (translation
/// k = 0 excluded). Exact when the box holds the support (n dx >= 4h, as find_neighbours requires). A neutral
/// zone-boundary zero (n even) gives e = 0 (A singular for every e), as in the 1D periodic analysis.
/// Throws std::invalid_argument for n < 2, or odd n on hexagonal / face-centred lattices.
SymbolCriticalStrain critical_strain_periodic_symbol_2d(const ElasticSymbol2D& symbol, int n, LoadDirection sign);

/// The admissible wavevectors of a periodic n x n lattice (m1 fastest; n^2 entries, k = 0 first).
std::vector<Eigen::Vector2d> periodic_wavevectors(const BravaisLattice2D& lattice, int n);

}  // namespace sphstab
