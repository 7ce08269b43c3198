#pragma once
/// \file colliding_rings.hpp
/// The colliding rubber rings of Gray, Monaghan & Swift [GMS2001, §7.2] (after Swegle's rubber cylinders, [GMS2001,
/// ref. 18]): two identical annuli of inner radius r_in and outer radius r_out, cut from a square grid of spacing dp
/// ("as a result the rings have a slightly roughened appearance"), moving towards each other along x at equal speeds.
/// GMS values (units rho0 = c0 = 1, cm): r_in = 3, r_out = 4, dp = 0.1, speed 0.059 each (relative 0.118 c0),
/// mu = 0.22; with eps = 0 the rings fracture, with eps = 0.3 they bounce intact ([GMS2001, §7.2, Figs. 6-7]).
///
/// Geometry (our choices where GMS give none):
///   - Each ring has its own grid, aligned with its centre c: the cell centres c + ((i + 1/2) dp, (j + 1/2) dp) for all
///     integers i, j, kept when r_in <= |x - c| <= r_out (closed annulus; tolerance 1e-9 relative on the squared
///     radii in grid units). Each ring is then mirror-symmetric about the lines x = c_x and y = c_y (and under the
///     90-degree rotation), and no particle lies on its axes. When the centre distance is a multiple of dp the two
///     grids are one grid, as in GMS's "grid of square cells".
///   - Centres c_0 = (-(r_out + gap/2), 0) (ring 0, left) and c_1 = (+(r_out + gap/2), 0) (ring 1, right): the outer
///     circles are `gap` apart (GMS do not give the initial gap; default 0.2 = 2 dp at GMS's dp). The closest particles
///     of the two rings are farther apart than `gap`: for the GMS grid the outermost particle on a ring's x axis row is
///     at |x - c_x| = 3.95, so they are gap + dp = 0.3 apart (tested).
///   - Ring 0 moves with (+speed, 0), ring 1 with (-speed, 0): total momentum zero; the scene is mirror-symmetric
///     about x = 0 with the velocity reversed.
///
/// The SI configuration (inner 0.03 m, outer 0.04 m, dx = 5e-4 m) is the same builder:
/// \code{.cpp}
/// sphstab::CollidingRings si = sphstab::make_colliding_rings(
///     {.inner_radius = 0.03, .outer_radius = 0.04, .spacing = 5e-4, .gap = 1e-3, .speed = v});  // v in m/s
/// \endcode
/// Particle counts (tested): GMS 2196 per ring (annulus area / dp^2 = 2199.1), SI 8804 per ring (8796.5).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

struct CollidingRingsOptions {
  double inner_radius = 3;  ///< r_in >= 0 (0 gives two discs)
  double outer_radius = 4;  ///< r_out > r_in, with r_out - r_in >= 2 dp (at least two particles across)
  double spacing = 0.1;     ///< dp > 0, the grid spacing
  double gap = 0.2;         ///< >= 0, distance between the two outer circles (not GMS's: they give none)
  double speed = 0.059;     ///< finite; ring 0 moves along +x, ring 1 along -x (negative: the rings separate)
};

struct CollidingRings {
  CollidingRingsOptions options;
  /// 2 n particles: ring 0 first (indices 0 .. n-1), then ring 1 (n .. 2n-1), each by grid column (x ascending)
  /// then row (y ascending); particle n + k of ring 1 is particle k of ring 0 moved by c_1 - c_0. All Role::Free,
  /// volume dp^2, spacing dp, depth = Chebyshev grid distance to the nearest grid cell outside the ring minus 1 (0
  /// for a particle missing any of its 8 grid neighbours, inner and outer surface alike).
  ParticleSet<2> particles;
  /// Initial velocity, 2 x N: column i is particle i's velocity, so velocity.data() is in the interleaved DOF order
  /// i * 2 + a of docs/conventions.md §1. (+speed, 0) on ring 0, (-speed, 0) on ring 1.
  Eigen::Matrix2Xd velocity;
  std::vector<int> ring;                  ///< 0 or 1 per particle
  std::array<Eigen::Vector2d, 2> centre;  ///< c_0, c_1
  int per_ring = 0;                       ///< n, the particles of one ring

  int size() const { return particles.size(); }
};

/// Builds the two rings of [GMS2001, §7.2] (see the file comment for the grid and the placement). Throws
/// std::invalid_argument with a one-line message for non-finite options, r_in < 0, r_out <= r_in, dp <= 0,
/// r_out - r_in < 2 dp, gap < 0 or lengths outside check_length()'s range; MemoryLimitError (core/memory_budget.hpp)
/// when the grid does not fit the memory limit.
CollidingRings make_colliding_rings(const CollidingRingsOptions& options = {});

}  // namespace sphstab
