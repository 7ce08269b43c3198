#pragma once
/// \file boundary_particles.hpp
/// Boundary particles and outward normals from the kernel-gradient sum [Powell2012, §2.2, (2.51)-(2.53),
/// algorithm 2.2]: the particles on which a non-reflecting boundary condition replaces the momentum equation.
///
///   e_i = sum_{j in N(i), j != i} grad_i W(x_i - x_j),   n_i = -e_i / |e_i|                              (2.51)
///
/// is ~0 for a full neighbourhood and points inwards for a kernel-deficient one. Outer boundary particles (layer 0):
/// |e_i| > outer_ratio max_k |e_k| (2.52). Candidates: the other neighbours j of the outer layer (default), or with
/// exclusion_ratio > 0 only those with |e_j| > exclusion_ratio min_k |e_k| (2.53: the rest "have full support").
/// (2.53) as printed is decided by rounding on a regular lattice: the layer at grid distance floor(2h / dx) has full
/// support, |e| at rounding level, and 10 min |e| excludes it or not depending on the last bits; here |e| below
/// 1e-10 max |e| counts as 0, so (2.53) excludes that layer and finds floor(2h / dx) layers (non-integer 2h / dx),
/// while the default takes every neighbour of the outer layer and finds Powell's floor(2h / dx) + 1. Then
/// pass p = 1, 2, ... (algorithm 2.2): each candidate's e_i is recomputed over its neighbours that are not yet boundary
/// particles, and the candidates with |e_i| > outer_ratio max_k |e_k| (the original maximum) join as layer p with
/// n_i = -e_i / |e_i|. The passes are simultaneous (a pass reads the boundary set of the previous one), so the result
/// does not depend on the particle order. The thesis has no loop guard: a pass that moves no candidate ends the
/// detection (the candidates left are reported), and max_passes bounds it. Edge normals on a regular lattice are
/// exact, corner normals diagonal.
///
/// \code{.cpp}
/// auto b = sphstab::boundary_particles(disc->particles, disc->kernel, disc->h, disc->neighbours);
/// for (int i : b.particles) use(b.normal.row(i));
/// \endcode
#include <Eigen/Core>
#include <vector>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

struct BoundaryDetectionOptions {
  double outer_ratio = 0.75;   ///< (2.52) and algorithm 2.2: |e_i| > outer_ratio max |e|, in (0, 1)
  double exclusion_ratio = 0;  ///< (2.53) (Powell 10): candidates need |e_j| > exclusion_ratio min |e|; 0: all, >= 0
  int max_passes = 100;        ///< passes of algorithm 2.2 at most (>= 1)
};

template <int Dim>
struct BoundaryParticles {
  std::vector<int> particles;  ///< boundary particles, ascending
  std::vector<int> layer;      ///< per particle: 0 outer, p found in pass p, -1 not a boundary particle
  Eigen::Matrix<double, Eigen::Dynamic, Dim> normal;  ///< per particle: unit outward normal (0 for the others)
  Eigen::VectorXd e_norm;                             ///< |e_i| of (2.51) over the whole neighbourhood, per particle
  int layers = 0;                                     ///< number of layers found (outer included)
  int candidates_left = 0;  ///< candidates that never passed the test (full support after all)
  int passes = 0;           ///< passes of algorithm 2.2 run
  bool is_boundary(int i) const { return layer[i] >= 0; }
};

/// Detects the boundary particles of a particle set with its kernel, h and neighbour list (radius >= the support;
/// a Discretisation holds all four). Throws
/// std::invalid_argument for bad options, and std::domain_error (one line, with the counts) when no particle passes
/// the outer test (every |e_i| ~ 0: a periodic or empty set) or when max_passes is reached with candidates still
/// moving.
template <int Dim>
BoundaryParticles<Dim> boundary_particles(const ParticleSet<Dim>& particles, const Kernel<Dim>& kernel, double h,
                                          const NeighbourList& list, const BoundaryDetectionOptions& options = {});

/// Replaces the detected normals by `normals` (one row per boundary particle, in the order of b.particles; the thesis's
/// manual normals for corners), normalised. Throws std::invalid_argument for a wrong row count or a zero-length or
/// non-finite row (naming the particle).
template <int Dim>
void set_manual_normals(BoundaryParticles<Dim>& b, const Eigen::Matrix<double, Eigen::Dynamic, Dim>& normals);

}  // namespace sphstab
