#pragma once
/// \file turek_hron_csm3.hpp
/// The structural benchmark CSM3 of Turek & Hron (S. Turek, J. Hron, "Proposal for numerical benchmarking of
/// fluid-structure interaction between an elastic object and laminar incompressible flow", in: Fluid-Structure
/// Interaction, LNCSE 53, Springer 2006, 371-385, doi:10.1007/3-540-34596-5_15): an elastic beam attached to a rigid
/// cylinder, oscillating under its own weight from rest (no damping). SI units.
///
///   cylinder: centre (0.2, 0.2), radius 0.05 (rigid; the beam is clamped to it);
///   beam:     the rectangle [0.2, 0.6] x [0.19, 0.21] outside the cylinder, i.e. from x = 0.2 + sqrt(0.05^2 - 0.01^2)
///             = 0.2489898 (at y = 0.19, 0.21; 0.25 at y = 0.2) to the free end x = 0.6; the point A = (0.6, 0.2);
///   material: St Venant-Kirchhoff, rho = 1000, nu = 0.4, mu = 0.5e6 (E = 1.4e6), plane strain; gravity 2 m/s^2 in -y.
/// Reference (finest level of the paper, mean +- amplitude [frequency]; [TurekHron2006], CSM3 results table):
///   u_x(A) = -14.305e-3 +- 14.645e-3 m [1.0995 Hz],  u_y(A) = -63.607e-3 +- 65.160e-3 m [1.0995 Hz].
///
/// The particles: a square grid of spacing dx = 0.02 / across at cell centres, x_i = 0.6 - (i + 1/2) dx,
/// y_j = 0.19 + (j + 1/2) dx. A grid point outside the cylinder is a free beam particle; a grid point inside it whose
/// depth into the cylinder along -x, x_c(y_j) - x_i with x_c(y) = 0.2 + sqrt(0.05^2 - (y - 0.2)^2), is at most
/// clamp_layers * dx is a fixed clamp particle (zero displacement): the beam continued into the cylinder by a clamp
/// of width clamp_layers * dx. Volumes dx^2; free particles first (ascending in j, then i), then the clamp.
#include <array>
#include <vector>

#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

/// The benchmark's constants (SI).
struct TurekHronCsm3 {
  static constexpr double cylinder_x = 0.2, cylinder_y = 0.2, radius = 0.05;
  static constexpr double tip_x = 0.6, bottom_y = 0.19, thickness = 0.02;
  static constexpr double density = 1000, shear_modulus = 0.5e6, poisson = 0.4, gravity = 2;
  /// Reference of CSM3: mean and amplitude of u_x(A), u_y(A) (m) and the frequency (Hz).
  static constexpr double ux_mean = -14.305e-3, ux_amplitude = 14.645e-3, uy_mean = -63.607e-3,
                          uy_amplitude = 65.160e-3, frequency = 1.0995;
  /// x of the beam's attachment at height y (the cylinder surface), for |y - 0.2| <= 0.05.
  static double attachment_x(double y);
};

struct TurekHronBeamOptions {
  int across = 4;        ///< particles through the thickness (>= 2): dx = 0.02 / across
  int clamp_layers = 4;  ///< clamp width in dx (>= 1); should reach the kernel support 2h
};

struct TurekHronBeam {
  ParticleSet<2> particles;
  double dx = 0;
  int free_count = 0, clamp_count = 0;
  /// The free particles nearest y = 0.2 in the last two columns (x = 0.6 - dx/2 and 0.6 - 3dx/2): two per column for
  /// an even `across`, one for an odd one. A's displacement is measured from their means (see the study).
  std::array<std::vector<int>, 2> tip;
};

/// Builds the particles of the beam and its clamp. Throws std::invalid_argument for across < 2 or clamp_layers < 1.
TurekHronBeam turek_hron_beam(const TurekHronBeamOptions& options = {});

}  // namespace sphstab
