#pragma once
/// \file block_lattice.hpp
/// A rectangular block of nx x ny free particles on the square lattice, inside fixed layers on every side: the bar or
/// plate of the 2D stretch and pairing tests. It is the square lattice of make_lattice (lattice.hpp) cut to the
/// rectangle, so positions, volumes, depths and the free-first ordering are those of make_lattice.
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

/// nx x ny free particles at ((i + 1/2) dx, (j + 1/2) dx), i < nx, j < ny (the free block spans [0, nx dx] x
/// [0, ny dx]), then the fixed layers around it, each block in lexicographic order (x fastest), as make_lattice.
/// @param[in] nx, ny   free particles along x and y (>= 1)
/// @param[in] options  spacing, fixed_layers or support_radius (layers as make_lattice: every lattice point within
///                     support_radius of a free particle; pass a multiple of the support to reach deeper), stretch;
///                     periodic and perturbation are rejected (a block is bounded by its layers and regular)
/// Throws std::invalid_argument (one line) for nx or ny < 1, a periodic or perturbed block, and as make_lattice.
ParticleSet<2> make_block_lattice_2d(int nx, int ny, const LatticeOptions& options);

}  // namespace sphstab
