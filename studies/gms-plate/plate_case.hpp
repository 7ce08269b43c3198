#pragma once
/// \file plate_case.hpp
/// A case of the GMS cantilever plate study [GMS2001, §7.1]: the plate, its material, the scheme's switches and the
/// run length; the scene it runs (problems/gms_scenes.hpp, the one the CLI's `sphstab scene plate` runs); the theory
/// periods it is compared with (thin plate (7.1), Timoshenko) and GMS's Tables 1 and 2.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/problems/cantilever_plate.hpp"
#include "sphstab/problems/gms_scenes.hpp"

namespace sphstab::gms_plate {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Zero crossings of the tip a period is measured from: two full cycles after the first crossing (the first half
/// cycle carries the start transient). A run with fewer (a plate that stops oscillating) has no period.
inline constexpr std::size_t kMinCrossings = 5;

struct PlateCase {
  std::string tag;
  double thickness = 2;
  int across = 10;
  double mu = 0.22, tip_speed = 0.01, eps = 0.3;
  int clamp_layers = 4;
  /// Run length in thin-plate periods: 3.6 gives at least 5 zero crossings of the tip (two full cycles after the
  /// first crossing, which comes a quarter period in) for SPH plates up to 60 % slower than the thin plate.
  double periods = 3.6;
  double cfl = 0.25;      ///< dt = cfl h / c_P
  double paper = kNaN;    ///< GMS T_sph
  double length = 20, h_factor = 1.5;
  /// Material: GMS units (rho0 = K = 1, shear modulus mu) unless youngs is set (then SI: E, nu, rho0).
  double youngs = kNaN, poisson = kNaN, density = 1;
  double alpha = 1, beta = 2;  ///< viscosity coefficients (compression switch; Monaghan's standard, GMS give none)
  int vtk_frames = 0;          ///< VTK snapshots over the run (0: none)
};

inline ElasticMaterial material_of(const PlateCase& c) {
  if (std::isnan(c.youngs)) return ElasticMaterial::from_bulk_shear(1, c.mu, 1);
  return ElasticMaterial::from_young_poisson(c.youngs, c.poisson, c.density);
}
inline IsotropicModuli moduli_of(const PlateCase& c) {
  const ElasticMaterial m = material_of(c);
  return isotropic_moduli(m.bulk_modulus(), m.mu());
}
inline double thin_period(const PlateCase& c) {
  const IsotropicModuli m = moduli_of(c);
  return thin_plate_period(m.youngs, m.poisson, material_of(c).density(), c.thickness, c.length);
}
inline double timoshenko_period(const PlateCase& c) {
  const IsotropicModuli m = moduli_of(c);
  return timoshenko_cantilever_period(m.youngs / (1 - m.poisson * m.poisson), material_of(c).mu(), 5.0 / 6,
                                      material_of(c).density(), c.thickness, c.length);
}
/// The GMS-unit plate of thickness H and shear modulus mu (for the theory columns).
inline PlateCase gms_plate(double H, double mu) {
  PlateCase c;
  c.thickness = H, c.mu = mu;
  return c;
}

/// The case's scene: GMS's scheme (with its pair loop) with the case's eps, alpha and beta, started in the first mode's
/// velocity, as `sphstab scene plate` runs it.
inline Scene<2> plate_scene(const PlateCase& c) {
  return gms_plate_scene(
      {.length = c.length, .thickness = c.thickness, .across = c.across, .clamp_layers = c.clamp_layers}, c.tip_speed,
      {.material = material_of(c), .scheme = gms_scheme_options(c.eps, c.alpha, c.beta), .h_over_spacing = c.h_factor});
}
/// dt = cfl h / c_P of the case on particles of spacing dp.
inline double time_step(const PlateCase& c, double dp) {
  const double h = c.h_factor * dp;
  return c.cfl * h / material_of(c).p_wave_speed();
}

/// GMS Tables 1 and 2 (T_sph, cm / c0), [GMS2001, §7.1, Tables 1-2].
struct PaperRow {
  double thickness, mu, tip_speed, period;
};
inline const std::vector<PaperRow>& paper_periods() {
  static const std::vector<PaperRow> rows = {
      {2, 0.22, 0.001, 1674.6}, {2, 0.22, 0.01, 1671.5}, {2, 0.22, 0.03, 1688.2}, {2, 0.22, 0.05, 1705.0},
      {2, 0.30, 0.001, 1473.6}, {2, 0.30, 0.01, 1469.8}, {2, 0.30, 0.03, 1482.1}, {2, 0.30, 0.05, 1495.4},
      {2, 0.60, 0.001, 1131.6}, {2, 0.60, 0.01, 1127.2}, {2, 0.60, 0.03, 1130.7}, {2, 0.60, 0.05, 1136.1},
      {1, 0.22, 0.01, 3333.6},  {1, 0.22, 0.03, 3385.7}, {1, 0.22, 0.05, 3322.8}, {1, 0.30, 0.01, 2902.0},
      {1, 0.30, 0.03, 2977.7},  {1, 0.30, 0.05, 2934.9}, {1, 0.60, 0.01, 2214.4}, {1, 0.60, 0.03, 2221.7},
      {1, 0.60, 0.05, 2200.4}};
  return rows;
}

inline std::string tag_of(const PlateCase& c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "H%g_n%d_mu%g_vf%g_eps%g_clamp%d_cfl%g_a%g", c.thickness, c.across, c.mu, c.tip_speed,
                c.eps, c.clamp_layers, c.cfl, c.alpha);
  return buf;
}

inline PlateCase with_tag(PlateCase c) {
  c.tag = tag_of(c);
  return c;
}

}  // namespace sphstab::gms_plate
