#pragma once
/// \file neighbour_list.hpp
/// Cell-list neighbour search producing compressed-row (CSR) neighbour lists.
#include <vector>

#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

/// Neighbours of each particle in CSR form: the neighbours of i are indices[offsets[i] .. offsets[i+1]),
/// sorted ascending, including i itself, and every j with |x_i - x_j| < radius (minimum image in periodic
/// axes; coincident points included). The pattern is symmetric. It is the sparsity pattern of every operator
/// matrix, so a row maps directly onto a row-major Eigen sparse row.
struct NeighbourList {
  std::vector<long> offsets;  ///< N + 1 entries
  std::vector<int> indices;   ///< offsets[N] entries
  double radius = 0;

  int size() const { return offsets.empty() ? 0 : static_cast<int>(offsets.size()) - 1; }
  long nonzeros() const { return offsets.empty() ? 0 : offsets.back(); }
  int count(int i) const { return static_cast<int>(offsets[i + 1] - offsets[i]); }
};

/// Estimated number of (i, j) entries for `radius`: N (1 + ball volume / mean particle volume), at most N^2. The
/// exact count for a regular lattice's interior; used to check memory before the search.
template <int Dim>
double expected_neighbour_pairs(const ParticleSet<Dim>& particles, double radius);

/// O(N + pairs) cell-list search: cells of edge >= radius / 2, each row's candidates read as contiguous runs of cells;
/// the rows sorted by transposing the symmetric pattern (up to 4 M pairs; peak memory then twice the list's indices)
/// or, for larger lists, by a sort per row. The same list for any thread count. Throws std::invalid_argument for a
/// radius outside check_length()'s range (core/length_scale.hpp), an invalid particle set, or a periodic box shorter
/// than 2 * radius in a periodic axis (the minimum-image convention would then miss images); MemoryLimitError when the
/// estimated pairs do not fit the memory limit.
template <int Dim>
NeighbourList find_neighbours(const ParticleSet<Dim>& particles, double radius);

namespace detail {
/// How find_neighbours sorts its rows (it chooses by size; both here for the tests).
enum class RowOrder { Transpose, Sort };
template <int Dim>
NeighbourList find_neighbours(const ParticleSet<Dim>& particles, double radius, RowOrder order);
}  // namespace detail

/// O(N^2) reference search with the same conventions (for tests and small sets).
template <int Dim>
NeighbourList find_neighbours_brute_force(const ParticleSet<Dim>& particles, double radius);

}  // namespace sphstab
