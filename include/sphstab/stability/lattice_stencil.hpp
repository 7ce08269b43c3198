#pragma once
/// \file lattice_stencil.hpp
/// The interior stencil of the linearisation on a square (2D) or cubic (3D) lattice, probed from the matrix-free
/// operator itself. Written below for 2D; in 3D every offset, site and block has a third index (k along z).
///
/// On an n x n square lattice of free particles with complete neighbourhoods (fixed layers around it) the free-free
/// blocks of K = A0 and L = -sgn A1 are, away from the free edge, translation invariant: row block (p, c), column
/// block (p + d, e) equals S(d)_{ce} for a 2 x 2 block S(d) per lattice offset d = (di, dj) (di along x, dj along y).
/// A0 couples neighbours of neighbours, so S(d) is non-zero for |d| < 2 x (twice the kernel support) / dx; A1 couples
/// neighbours only. The stencil is read off the operator: y = A e_(p, e) for a unit vector at the central free
/// particle p gives column (p, e), and y_(p - d, c) = S(d)_{ce} (the translation-invariant row of particle p - d).
/// Every particle within two hops of p must be free and interior: the probe refuses a lattice on which the non-zeros
/// of the probed column reach the free edge (n below about 4 x support / dx + 1; n >= 11 at h = 1.3 dx, cubic spline).
///
/// DOF order (MatrixFreeLinearisation, ascending free particle index): free particle f = i + n j sits at lattice site
/// (i, j), i along x, and dof = 2 f + c, c = 0 (x), 1 (y) (3D: f = i + n j + n^2 k, dof = 3 f + c).
/// lattice_dofs() checks this from the positions.
///
/// \code{.cpp}
/// sphstab::MatrixFreeLinearisation lin(*disc, material, sphstab::MomentumForm::Conservative,
///                                      sphstab::PreStrainKind::Isotropic);
/// auto st = sphstab::probe_lattice_stencil(lin, sphstab::LoadDirection::Tension);
/// double dev = sphstab::lattice_stencil_deviation(lin, sphstab::LoadDirection::Tension, st, {0, st.n * st.n / 2});
/// \endcode
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"

namespace sphstab {

/// The free particles as an n x n square (n x n x n cubic) lattice in DOF order: free particle f = i + n j [+ n^2 k]
/// at origin + dx (i, j[, k]).
template <int Dim>
struct LatticeDofs {
  int n = 0;                                                                     ///< particles per side
  double dx = 0;                                                                 ///< lattice spacing, > 0
  Eigen::Matrix<double, Dim, 1> origin = Eigen::Matrix<double, Dim, 1>::Zero();  ///< position of free particle 0
  long count() const;                                                            ///< n^Dim
  /// Lattice site of free particle f (component a along axis a).
  std::array<int, Dim> site(long f) const;
  /// Free particle at a site.
  long flat(const std::array<int, Dim>& site) const;
};
using SquareLatticeDofs = LatticeDofs<2>;

/// Checks that `free_positions` (free_count x Dim, DOF order) is an n^Dim lattice in the order above, to 1e-9 dx.
/// Throws std::invalid_argument naming the problem (wrong column count, count not an n^Dim, n < 2, first particle
/// that is off its site), prefixed with `who`.
template <int Dim>
LatticeDofs<Dim> lattice_dofs(const Eigen::MatrixXd& free_positions, const std::string& who);
/// lattice_dofs<2>: the 2D square lattice.
inline SquareLatticeDofs square_lattice(const Eigen::MatrixXd& free_positions, const std::string& who) {
  return lattice_dofs<2>(free_positions, who);
}

/// Interior stencils of K = A0 and L = -sgn A1 (sgn = load_sign(direction)) on a square or cubic lattice.
template <int Dim>
struct LatticeStencil {
  using Block = Eigen::Matrix<double, Dim, Dim>;
  int n = 0;                ///< lattice the stencil was probed on (particles per side)
  int radius = 0;           ///< S(d) = 0 for max_a |d_a| > radius
  std::vector<Block> k, l;  ///< (2 radius + 1)^Dim blocks each, index sum_a (d_a + radius) (2 radius + 1)^a

  int width() const { return 2 * radius + 1; }
  long blocks() const;  ///< (2 radius + 1)^Dim
  long index(const std::array<int, Dim>& d) const;
  template <class... I>
  const Block& k_at(I... d) const requires(sizeof...(I) == Dim) {
    return k[index({static_cast<int>(d)...})];
  }
  template <class... I>
  const Block& l_at(I... d) const requires(sizeof...(I) == Dim) {
    return l[index({static_cast<int>(d)...})];
  }
  /// Largest |entry| over both stencils (the scale of lattice_stencil_deviation).
  double scale() const;
};

/// Probes the stencils at the central free particle (n/2 on every axis): Dim products with A0 and Dim with A1.
/// Throws std::invalid_argument when the free particles are not a square (cubic) lattice in DOF order, when the
/// linearisation is not symmetric, or when the probed column reaches the free edge (lattice too small: probe a larger
/// lattice of the same kernel, h, material and form).
template <int Dim>
LatticeStencil<Dim> probe_lattice_stencil(const MatrixFreeLinearisation<Dim>& lin, LoadDirection direction);

/// Largest |entry| of (A - R S R^T) over the rows of the given free particles (all components, both operators K and
/// L), relative to stencil.scale(), where R S R^T is the translation-invariant stencil restricted to the lattice
/// (neighbours outside it dropped). Zero up to round-off for interior rows; rows near the free edge show how far the
/// fixed layers' incomplete neighbourhoods make the operator differ from the restricted stencil. 2 Dim products per
/// particle. Throws std::invalid_argument for a particle index outside [0, free_count) or a stencil of another n.
template <int Dim>
double lattice_stencil_deviation(const MatrixFreeLinearisation<Dim>& lin, LoadDirection direction,
                                 const LatticeStencil<Dim>& stencil, const std::vector<int>& free_particles);

}  // namespace sphstab
