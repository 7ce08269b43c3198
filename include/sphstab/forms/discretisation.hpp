#pragma once
/// \file discretisation.hpp
/// What every force function needs to know about the particles: the reference set, kernel, smoothing length,
/// neighbour list (the fixed pattern of every operator) and the free-particle numbering of the DOFs.
#include <memory>
#include <vector>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

/// Reference configuration x0 of an SPH body. The neighbour list is built once at x0 with radius = kernel
/// support (2h) and kept during motion (Eulerian kernel, Lagrangian neighbour list); callers that move particles
/// by more than a small fraction of dx should rebuild the discretisation with a neighbour radius margin.
///
/// DOF numbering (sphstab-wide): free particles in ascending particle index, f = free_slot[i], interleaved
/// components dof = f * Dim + a.
template <int Dim>
struct Discretisation {
  ParticleSet<Dim> particles;  ///< reference positions x0, volumes, roles
  Kernel<Dim> kernel;
  double h = 0;                ///< smoothing length, > 0
  NeighbourList neighbours;    ///< at x0, radius >= kernel.support_radius(h)
  std::vector<int> free;       ///< particle indices of the free particles, ascending
  std::vector<int> free_slot;  ///< N entries: position in `free`, or -1 for a fixed particle

  int size() const { return particles.size(); }
  int free_count() const { return static_cast<int>(free.size()); }
  int dofs() const { return Dim * free_count(); }
  /// Reference positions of the free particles, free_count x Dim (the DOF order).
  Eigen::MatrixXd free_positions() const { return particles.positions(Role::Free); }
};

/// Builds a Discretisation: validates the set, finds neighbours within `neighbour_radius` (default, when <= 0:
/// the kernel support 2h) and numbers the free particles. Throws std::invalid_argument for h <= 0, an invalid
/// set, a radius smaller than the support, or a set without free particles.
template <int Dim>
std::shared_ptr<const Discretisation<Dim>> make_discretisation(ParticleSet<Dim> particles, const Kernel<Dim>& kernel,
                                                               double h, double neighbour_radius = 0);

}  // namespace sphstab
