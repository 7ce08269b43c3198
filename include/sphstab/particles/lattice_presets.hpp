#pragma once
/// \file lattice_presets.hpp
/// The lattices of the stability studies, at spacing dx = 1 (loads are dimensionless and independent of dx), with
/// fixed layers that complete every free particle's neighbourhood for the kernel's support 2h, or periodic.
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

/// `free` free particles on a line, either periodic or with fixed layers at every m dx < 2h, strictly, so that the
/// layers match find_neighbours (a kernel truncated with W' != 0 at its support, like the Gaussian, then keeps
/// complete neighbourhoods even when 2h is a multiple of dx up to rounding). With layer_supports = m > 1 the fixed
/// layers reach m supports (m 2h) instead: then every particle within m - 1 supports of the free block also has a
/// complete neighbourhood, which the corrected kernels need (their rows read neighbours of neighbours; m = 3 makes
/// u = 0 an equilibrium of every corrected 1D form, Powell's regular grid [Powell2012, ch. 3 footnote h]).
/// Throws std::invalid_argument for free < 1, h <= 0 or layer_supports < 1.
ParticleSet<1> tension_lattice_1d(const Kernel<1>& kernel, double h, int free, bool periodic = false,
                                  int layer_supports = 1);

/// n x n free particles (square, hexagonal or face-centred) with fixed layers completing every neighbourhood
/// (support 2h), or periodic. Throws std::invalid_argument for n < 1, h <= 0, a lattice that is not 2D.
ParticleSet<2> strain_lattice_2d(LatticeType type, const Kernel<2>& kernel, double h, int n, bool periodic = false);

}  // namespace sphstab
