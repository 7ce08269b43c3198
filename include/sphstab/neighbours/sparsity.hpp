#pragma once
/// \file sparsity.hpp
/// Sparsity patterns of force Jacobians and greedy distance-2 column colouring (Curtis-Powell-Reid).
///
/// A force on particle i that depends on particles up to `radius` hops away in the neighbour graph (radius 2
/// for every SPH momentum form: f_i reads s_j, j in N(i), and s_j reads u_m, m in N(j)) has a Jacobian whose
/// row i is nonzero only in the columns of those particles. Columns that share no row can be perturbed
/// together; one complex force evaluation per colour then recovers the whole Jacobian exactly.
#include <vector>

#include "sphstab/neighbours/neighbour_list.hpp"

namespace sphstab {

/// A boolean sparse pattern in compressed-row form: row r has the columns indices[offsets[r] .. offsets[r+1]),
/// sorted ascending, no duplicates.
struct SparsityPattern {
  int rows = 0;
  int cols = 0;
  std::vector<long> offsets;  ///< rows + 1 entries
  std::vector<int> indices;   ///< offsets[rows] entries

  long nonzeros() const { return offsets.empty() ? 0 : offsets.back(); }
  /// The transposed pattern (column-compressed view of this one).
  SparsityPattern transpose() const;
};

/// DOF-level pattern of a force Jacobian on the free particles. Particles are vertices of the neighbour graph;
/// free particle i couples to every free particle k within `radius` hops (any intermediate particle, free or
/// fixed). DOFs are interleaved: dof = free_slot[i] * dim + a; every coupled pair gives a full dim x dim block.
/// @param[in] neighbours  neighbour list of all N particles (self included)
/// @param[in] free_slot   N entries: index of the particle among the free particles, or -1 for fixed
/// @param[in] dim         components per particle (>= 1)
/// @param[in] radius      graph distance (>= 0)
SparsityPattern coupling_pattern(const NeighbourList& neighbours, const std::vector<int>& free_slot, int dim,
                                 int radius);

/// Greedy distance-2 colouring of the columns of `pattern`, in natural column order: two columns that have a
/// nonzero in a common row never share a colour. Returns colour[c] in 0..ncolours-1 for every column.
std::vector<int> colour_columns(const SparsityPattern& pattern);

/// Number of colours used by a colouring (max + 1, 0 when empty).
int colour_count(const std::vector<int>& colours);

/// True if no two columns of the same colour share a row (the property the complex-step recovery relies on).
bool is_valid_column_colouring(const SparsityPattern& pattern, const std::vector<int>& colours);

}  // namespace sphstab
