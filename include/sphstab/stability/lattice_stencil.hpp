#pragma once
/// \file lattice_stencil.hpp
/// The interior stencil of the 2D linearisation on a square lattice, probed from the matrix-free operator itself.
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
/// (i, j), i along x, and dof = 2 f + c, c = 0 (x), 1 (y). square_lattice() checks this from the positions.
///
/// \code{.cpp}
/// sphstab::MatrixFreeLinearisation lin(*disc, material, sphstab::MomentumForm::Conservative,
///                                      sphstab::PreStrainKind::Isotropic);
/// auto st = sphstab::probe_lattice_stencil(lin, sphstab::LoadDirection::Tension);
/// double dev = sphstab::lattice_stencil_deviation(lin, sphstab::LoadDirection::Tension, st, {0, st.n * st.n / 2});
/// \endcode
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sphstab/core/load_direction.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"

namespace sphstab {

/// The free particles as an n x n square lattice in DOF order: free particle f = i + n j at origin + dx (i, j).
struct SquareLatticeDofs {
  int n = 0;                                         ///< particles per side
  double dx = 0;                                     ///< lattice spacing, > 0
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< position of free particle 0
};

/// Checks that `free_positions` (free_count x 2, DOF order) is an n x n square lattice in the order above, to
/// 1e-9 dx. Throws std::invalid_argument naming the problem (count not a square, n < 2, first particle that is off
/// its site), prefixed with `who`.
SquareLatticeDofs square_lattice(const Eigen::MatrixXd& free_positions, const std::string& who);

/// Interior stencils of K = A0 and L = -sgn A1 (sgn = load_sign(direction)) on a square lattice.
struct LatticeStencil {
  int n = 0;                          ///< lattice the stencil was probed on (particles per side)
  int radius = 0;                     ///< S(d) = 0 for max(|di|, |dj|) > radius
  std::vector<Eigen::Matrix2d> k, l;  ///< (2 radius + 1)^2 blocks each, index (dj + radius)(2 radius + 1) + di + radius

  int width() const { return 2 * radius + 1; }
  const Eigen::Matrix2d& k_at(int di, int dj) const { return k[(dj + radius) * width() + di + radius]; }
  const Eigen::Matrix2d& l_at(int di, int dj) const { return l[(dj + radius) * width() + di + radius]; }
  /// Largest |entry| over both stencils (the scale of lattice_stencil_deviation).
  double scale() const;
};

/// Probes the stencils at the central free particle (i, j) = (n/2, n/2): 2 products with A0 and 2 with A1.
/// Throws std::invalid_argument when the free particles are not a square lattice in DOF order, when the
/// linearisation is not symmetric, or when the probed column reaches the free edge (lattice too small: probe a larger
/// lattice of the same kernel, h, material and form).
LatticeStencil probe_lattice_stencil(const MatrixFreeLinearisation& lin, LoadDirection direction);

/// Largest |entry| of (A - R S R^T) over the rows of the given free particles (both components, both operators K and
/// L), relative to stencil.scale(), where R S R^T is the translation-invariant stencil restricted to the n x n lattice
/// (neighbours outside it dropped). Zero up to round-off for interior rows; rows near the free edge show how far the
/// fixed layers' incomplete neighbourhoods make the operator differ from the restricted stencil. 4 products per
/// particle. Throws std::invalid_argument for a particle index outside [0, free_count) or a stencil of another n.
double lattice_stencil_deviation(const MatrixFreeLinearisation& lin, LoadDirection direction,
                                 const LatticeStencil& stencil, const std::vector<int>& free_particles);

}  // namespace sphstab
