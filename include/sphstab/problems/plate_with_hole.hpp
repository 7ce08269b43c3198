#pragma once
/// \file plate_with_hole.hpp
/// The quarter of a square plate with a central circular hole under remote uniaxial tension [Ismail2009, §5.4.4]
/// (Kirsch's problem): the quarter [0, W] x [0, W] minus the hole r < a, symmetry planes x = 0 and y = 0, a uniform
/// traction sigma_xx = S on the edge x = W, the edge y = W and the hole surface free.
///
/// Particles sit at the cell centres ((i + 1/2) dx, (j + 1/2) dx), i, j = 0 .. W/dx - 1, volume dx^2; the sites with
/// r < a are removed (Ismail: "turned into ghosts"). The symmetry planes are MIRROR layers: every real particle within
/// `ghost_depth` of a plane has an image across it (and across both planes near the origin), whose displacement is
/// the mirrored displacement of its real particle, u_g = (s_x u_x, s_y u_y), s = -1 across the plane. This is the
/// roller condition u_x = 0 on x = 0 (u_y = 0 on y = 0) and it also makes F, P and the kernel sums at the real
/// particles those of the whole plate. Every particle (real and image) has Role::Free, so a force function over the
/// whole set is differentiated with the images as unknowns, and the chain rule through u_all = T u_real
/// (mirror_map) gives the Jacobian of the real unknowns: A_real = S A_all T, S = the first 2 * real_count rows.
///
/// Traction. Two nodal load vectors of the real particles (interleaved x, y per real particle):
///   lumped:     f_i = S l_i e_x on the last column x = W - dx/2, edge length l_i = dx (they sum to W);
///   consistent: f_i = -2 V_i S (sum_j G^x_ij) e_x on the real particles with x_i > W - support: the nodal forces that
///               make the uniform first Piola-Kirchhoff stress P = S e_x (x) e_x an EXACT equilibrium of the
///               momentum equation a_i = (1/rho0_i) sum_j (P_j + P_i) G_ij (the Plus divergence of
///               forms/finite_strain_total_lagrangian.hpp) when the strain operator reproduces affine fields (NCSPH).
///               Their total tends to S W (sum_i V_i g_i over the band is the jump of the kernel sum across the edge,
///               -1/2 per unit length times the factor 2), to within the lattice quadrature error of the kernel.
///
/// \note Units are those of the caller (a, W, dx lengths; S a stress); the study uses a = 1.
///
/// \code{.cpp}
/// sphstab::PlateWithHole p = sphstab::make_plate_with_hole({.radius = 1, .width = 5, .spacing = 0.125,
///                                                           .ghost_depth = 6 * 0.125});
/// sphstab::SparseMatrix<> T = sphstab::mirror_map(p);   // u_all = T u_real
/// \endcode
#include <Eigen/Core>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

struct PlateWithHoleOptions {
  double radius = 1;       ///< hole radius a > 0
  double width = 5;        ///< half width W > a of the plate (the quarter is [0, W]^2)
  double spacing = 0.25;   ///< dx > 0, with W / dx a whole number (to 1e-9)
  double ghost_depth = 0;  ///< mirror layers cover the real particles within this distance of a plane (>= 0)
};

struct PlateWithHole {
  PlateWithHoleOptions options;
  ParticleSet<2> particles;           ///< N = real_count + images; real particles first; all Role::Free
  int real_count = 0;                 ///< real particles (the unknowns)
  int removed = 0;                    ///< lattice sites inside the hole (r < a)
  std::vector<int> image_of;          ///< per image (index - real_count): its real particle
  std::vector<Eigen::Vector2d> sign;  ///< per image: (s_x, s_y), -1 across a plane
  std::vector<int> edge;              ///< real particles of the loaded column x = W - dx/2, ascending y
  Eigen::VectorXd edge_length;        ///< per edge particle: its share of the edge x = W (dx; the sum is W)
};

/// Builds the quarter plate (file comment). Throws std::invalid_argument (one line) for a <= 0, W <= a, dx <= 0,
/// W / dx not whole, a negative or non-finite ghost depth, or a hole that leaves no particle.
PlateWithHole make_plate_with_hole(const PlateWithHoleOptions& options);

/// T, (2 N) x (2 real_count): u_all = T u_real, the identity on the real particles and the signed copy on the images.
SparseMatrix<> mirror_map(const PlateWithHole& plate);

/// The lumped edge load (file comment), 2 * real_count entries.
Eigen::VectorXd lumped_traction(const PlateWithHole& plate, double traction);

/// The consistent edge load (file comment) for the discretisation built on plate.particles (same order), 2 *
/// real_count entries. Throws std::invalid_argument when the discretisation does not match the plate, or when the
/// hole's kernel-deficient band meets the loaded band (W - a < 2 support).
Eigen::VectorXd consistent_traction(const PlateWithHole& plate, const Discretisation<2>& discretisation,
                                    double traction);

/// Kirsch's infinite-plate stresses (sigma_rr, sigma_tt, sigma_rt) at (r >= a, theta from the load axis x) under
/// remote sigma_xx = S [Kirsch 1898; Timoshenko & Goodier §35]:
///   sigma_rr = S/2 (1 - a^2/r^2) + S/2 (1 - 4a^2/r^2 + 3a^4/r^4) cos 2theta,
///   sigma_tt = S/2 (1 + a^2/r^2) - S/2 (1 + 3a^4/r^4) cos 2theta,
///   sigma_rt = -S/2 (1 + 2a^2/r^2 - 3a^4/r^4) sin 2theta.
/// Throws std::invalid_argument for a <= 0 or r < a.
Eigen::Vector3d kirsch_polar_stress(double a, double r, double theta, double traction);

/// Heywood's finite-width stress concentration of a hole of diameter d = 2a in a long strip of width 2W, referred to
/// the GROSS remote stress: K_t = (2 + (1 - a/W)^3) / (1 - a/W). Throws std::invalid_argument unless 0 < a < W.
double heywood_gross_concentration(double a, double W);

}  // namespace sphstab
