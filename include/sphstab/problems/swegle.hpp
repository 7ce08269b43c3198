#pragma once
/// \file swegle.hpp
/// The Swegle stability test of Powell ch. 4 §2.2 (Fig. 4.1/4.2; after Swegle et al. 1995): a square block of free
/// particles on a square lattice, surrounded by fixed layers, held at a uniform volume strain xi = V/V0, with one
/// particle at the centre given a tiny initial velocity. Tensile instability shows as exponential growth of the
/// kinetic energy.
///
/// Scene (units g, cm, us; stress in Mbar = 10^11 Pa... i.e. g cm^-1 us^-2):
///   - n x n free particles (default 21 x 21), spacing dx = 0.01 cm, plus fixed layers out to the kernel support
///     (2 layers for the cubic B-spline with h = 1.3 dx, support 2.6 dx), equal volumes dx^2 (per unit thickness);
///   - linear elastic, plane strain: rho = 7.8, E = 2.1, nu = 0.3 -> lambda = E nu/((1 + nu)(1 - 2 nu)) = 1.2115,
///     mu = E/(2(1 + nu)) = 0.8077, c_P = sqrt((lambda + 2 mu)/rho) = 0.6020 cm/us;
///   - pre-stress from xi as an isotropic linear pre-strain e = sqrt(xi) - 1 per axis (plane strain):
///     sigma0 = 2 (lambda + mu) e I (PreStrain::from_area_ratio); tension positive. As in Powell §3.3 the lattice is
///     the CURRENT configuration (spacing dx, density rho) and the pre-stress an additive constant;
///   - the centre particle (index of the middle of the free block) gets v0 = 1e-10 cm/us along +x.
///
/// The run itself (leap-frog, kinetic-energy growth) is growth/swegle_run.hpp.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/system/force_function.hpp"

namespace sphstab {

struct SwegleOptions {
  int n = 21;              ///< free particles per side (>= 3; odd for an exact centre particle)
  double spacing = 0.01;   ///< dx (cm)
  double h_over_dx = 1.3;  ///< h / dx
  KernelType kernel = KernelType::CubicSpline;
  double youngs_modulus = 2.1;
  double poisson_ratio = 0.3;
  double density = 7.8;
  double area_ratio = 1.0;     ///< xi = V/V0 (> 0): > 1 tension, < 1 compression
  double velocity = 1e-10;     ///< initial speed of the centre particle (cm/us)
  double direction_angle = 0;  ///< direction of v0 from +x (radians)
  /// Fixed layers reach layer_supports x 2h (>= 1): 1 completes the free particles' neighbourhoods; the corrected
  /// rate forms read neighbours of neighbours (NCSPH antisymmetrised, C_ij: 2; S-SPH: 3).
  int layer_supports = 1;
};

struct SwegleScene {
  SwegleOptions options;
  std::shared_ptr<const Discretisation<2>> discretisation;
  ElasticMaterial material = ElasticMaterial::from_lame(1.0, 1.0, 1.0);
  PreStrain prestrain;
  int centre = -1;        ///< particle index of the perturbed particle (a free particle)
  Eigen::VectorXd v0;     ///< initial velocity of the free DOFs
  double wave_speed = 0;  ///< c_P
  double h = 0;

  /// Initial kinetic energy 1/2 m v0^2 (per unit thickness).
  double initial_kinetic_energy() const;
  /// Reference positions of the free particles, interleaved (for VTK snapshots and SecondOrderSystem).
  Eigen::VectorXd free_positions() const;
};

/// Builds the scene; throws std::invalid_argument for n < 3, non-positive spacing/h/velocity or a bad material.
SwegleScene make_swegle_scene(const SwegleOptions& options);

}  // namespace sphstab
