#pragma once
/// \file fragments.hpp
/// Fragments of a particle state: the connected components of the bond graph in which particles i and j are bonded
/// when their current distance is below a radius, |x_i - x_j| < radius (the strict inequality and the coincident-
/// point convention of find_neighbours). Used to tell an intact body from a broken one ([GMS2001, §7.2-7.3]: rings
/// that fragment, a slab that breaks). The radius is the caller's: about 1.5 dp separates particles that have lost
/// their nearest neighbours; the kernel support 2h counts any interaction as a bond.
///
/// Cost O(N + pairs): one cell-list neighbour search (neighbours/neighbour_list.hpp) and union-find with path halving
/// and union by size.
///
/// \code{.cpp}
/// // positions of a run's state: x of particle i at y[i * stride], y[i * stride + 1]
/// Eigen::Map<const Eigen::Matrix2Xd, 0, Eigen::OuterStride<>> x(y.data(), 2, n, Eigen::OuterStride<>(stride));
/// sphstab::Fragments f = sphstab::find_fragments(x, 1.5 * dp);
/// if (f.count() > 1) std::printf("%d fragments, the largest has %d particles\n", f.count(), f.largest());
/// \endcode
#include <Eigen/Core>
#include <vector>

#include "sphstab/neighbours/neighbour_list.hpp"

namespace sphstab {

struct Fragments {
  /// Fragment of each particle, in [0, count()): numbered in the order of their lowest particle index (particle 0 is
  /// in fragment 0, the first particle not in fragment 0 starts fragment 1, ...), so the labels of a partition are
  /// unique.
  std::vector<int> label;
  std::vector<int> sizes;  ///< particles per fragment, count() entries

  int count() const { return static_cast<int>(sizes.size()); }
  /// Particles in the largest fragment (0 when there are no particles).
  int largest() const;
};

/// Fragments of the points (2 x N: column i = particle i; any outer stride, e.g. a Map into a state vector) for
/// bonds |x_i - x_j| < radius. N = 0 gives no fragments. Throws std::invalid_argument for non-finite positions or a
/// radius outside check_length()'s range; MemoryLimitError (core/memory_budget.hpp) when the neighbour pairs, as
/// estimated from the bounding box's area per point (each side at least the radius), do not fit the memory limit.
Fragments find_fragments(const Eigen::Ref<const Eigen::Matrix2Xd>& positions, double radius);

/// Fragments of the graph of a neighbour list (j bonded to i when j is in i's row; the pattern is symmetric), for a
/// caller that already has the list. Throws std::invalid_argument for an index outside [0, list.size()).
Fragments fragments_of(const NeighbourList& list);

}  // namespace sphstab
