#pragma once
/// \file cantilever_plate.hpp
/// The oscillating cantilever plate of Gray, Monaghan & Swift [GMS2001, §7.1]: a plate of length L along x from the
/// clamped edge x = 0 and thickness H (y in [-H/2, H/2]), clamped by layers of fixed particles of the same material
/// at x < 0, started with the first bending mode's velocity profile. Units of GMS: rho0 = c0 = 1 (K = rho0 c0^2 = 1).
///
/// Theory used to validate a run (plane strain, so the plate modulus is E/(1 - nu^2)):
///   [GMS2001, (7.1)]  omega^2 = E H^2 k^4 / (12 rho (1 - nu^2)),   [GMS2001, (7.2)]  cos(kL) cosh(kL) = -1,
///   fundamental kL = 1.8751040687...; isotropic E = 9K mu/(3K + mu), nu = (3K - 2mu)/(2(3K + mu)) from the bulk
///   modulus K of the equation of state and the shear modulus mu (GMS print a wrong nu formula (2.8); recomputing
///   shows their T_theory column is not reproducible and recompute it: 1448.8 / 1275.0 / 978.8 for H = 2 and
///   mu = 0.22 / 0.30 / 0.60, twice that for H = 1).
///   [GMS2001, (7.3)-(7.4)]  v_y(x) / c0 = V_f [M (cos kx - cosh kx) - N (sin kx - sinh kx)] / Q,
///   M = sin kL + sinh kL, N = cos kL + cosh kL, Q = 2 (cos kL sinh kL - sin kL cosh kL): the clamped-free mode
///   shape, 0 at the clamp and V_f at the tip.
#include <Eigen/Core>

#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

/// The first root of cos(z) cosh(z) = -1 (the clamped-free beam's fundamental), to rounding.
double cantilever_fundamental_kl();

/// Isotropic Young's modulus and Poisson ratio of bulk modulus K > 0 and shear modulus mu > 0 (3D relations, as the
/// plane-strain Jaumann rate with its 1/3 uses). Throws std::invalid_argument for non-positive moduli.
struct IsotropicModuli {
  double youngs = 0, poisson = 0;
};
IsotropicModuli isotropic_moduli(double bulk_modulus, double shear_modulus);

/// Period 2 pi / omega of the fundamental of a thin clamped-free plate, [GMS2001, (7.1)] in plane strain.
/// Throws std::invalid_argument for non-positive E, rho, H, L or nu outside (-1, 1/2).
double thin_plate_period(double youngs, double poisson, double density, double thickness, double length);

/// Period 2 pi / omega of the fundamental of a clamped-free Timoshenko beam of rectangular section (per unit width:
/// A = H, I = H^3 / 12) with shear deformation and rotary inertia:
///   rho A w_tt = kappa G A (w'' - phi'),   rho I phi_tt = D I phi'' + kappa G A (w' - phi),
/// clamped at x = 0 (w = phi = 0), free at x = L (phi' = 0, w' - phi = 0). D is the bending modulus (E / (1 - nu^2)
/// for a plate in plane strain), G the shear modulus, kappa the shear coefficient (5/6 for a rectangle). omega is the
/// lowest root of the 4 x 4 boundary determinant in the basis cosh, sinh, cos, sin (derivation in the .cpp), found by
/// bisection below the Euler-Bernoulli value (7.1). Used as the thick-plate correction of [GMS2001, (7.1)] at
/// H / L = 0.1. Throws std::invalid_argument for non-positive or non-finite arguments, or when the fundamental lies
/// above the shear cutoff sqrt(kappa G A / (rho I)) (a beam too thick for the theory).
double timoshenko_cantilever_period(double bending_modulus, double shear_modulus, double shear_coefficient,
                                    double density, double thickness, double length);

/// The initial velocity profile v_y(x) / c0 of [GMS2001, (7.3)-(7.4)] with tip speed V_f at x = L (x measured from
/// the clamp; any x, but meaningful for 0 <= x <= L).
double cantilever_mode_velocity(double x, double length, double tip_speed);

struct CantileverPlateOptions {
  double length = 20;    ///< L > 0, from the clamp to the tip
  double thickness = 2;  ///< H > 0
  int across = 10;       ///< particles across H (>= 2): dp = H / across
  int clamp_layers = 4;  ///< columns of fixed particles at x < 0 (>= 1); GMS do not give the clamp length
};

/// Particles on a square grid of spacing dp = H / across at cell centres: free plate particles (x > 0), fixed clamp
/// particles (x < 0), volume dp^2, spacing dp, depth = grid distance from the outside of the whole body. Particle
/// order: by column from the clamp's far end to the tip, bottom to top. Throws std::invalid_argument for bad options or
/// when L is not a whole number of spacings (to 1e-9).
ParticleSet<2> make_cantilever_plate(const CantileverPlateOptions& options);

}  // namespace sphstab
