#pragma once
// The cases of the gms-rings study [GMS2001, §7.2]: the materials (GMS units rho0 = c0 = 1, K = 1, mu = 0.22; the SI
// rubber of the issue), one run's settings (RingCase), the units of a case against GMS's, and the table of runs (GMS
// units and the SI configuration, each with eps = 0 and 0.3; the same with the pair loop, and with one rate
// evaluation per step; the eps = 0.3 GMS run at half the time step).
#include <limits>
#include <string>
#include <vector>

#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"

namespace grings {

using namespace sphstab;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// GMS's material in GMS units: rho0 = 1, K = 1 (c0 = 1), mu = 0.22.
inline ElasticMaterial gms_material() { return ElasticMaterial::from_bulk_shear(1, 0.22, 1); }

/// The SI material of the issue: E = 1e7 Pa, nu = 0.3975 (mu / K = 0.22, GMS's ratio), rho0 = 1 kg/m^3.
inline ElasticMaterial si_material() { return ElasticMaterial::from_young_poisson(1e7, 0.3975, 1.0); }

struct RingCase {
  std::string tag;
  bool si = false;                 ///< the SI configuration (m, s, Pa) instead of GMS units
  double eps = 0.3;                ///< artificial stress
  double dp = 0.1;                 ///< grid spacing (case units)
  double gap = 0.2;                ///< between the outer circles (case units)
  double t_end = 250;              ///< run length (case units); with `steps` > 0 it is steps * dt
  long steps = 0;                  ///< > 0: a fixed number of steps (the SI timing run)
  int frames = 12;                 ///< VTK frames over the run (0: none)
  double skin = 0.5;               ///< Verlet skin of the neighbour list, in dp
  PairLoop loop = PairLoop::Rows;  ///< how the rate visits the pairs (forms/rate_form.hpp)
  bool one_rate = false;           ///< one rate evaluation per step (RateFormRunOptions::reuse_corrector_rate)
  double dt_scale = 1;             ///< dt = dt_scale x 0.5 h / c_p
};

/// The case's units against GMS's: length unit (1 cm), speed unit (c0) and time unit, in the case's own units.
struct Units {
  double length = 1, speed = 1;
  double time() const { return length / speed; }
};

/// The runs: GMS units first (longest), then the SI configuration (a timed run of si_steps steps, or with si_full
/// the whole collision); the same runs with the pair loop, and with the pair loop and one rate evaluation per step;
/// last the eps = 0.3 GMS run at half the time step. dp, gap and t_end are the GMS-unit case's (cm, cm / c0).
inline std::vector<RingCase> ring_cases(double dp, double gap, double t_end, int frames, double skin, long si_steps,
                                        bool si_full) {
  // GMS units first (longest), then the SI configuration: dx = 5e-4 m (half of GMS's dp in cm units: 0.05 cm), gap
  // 2e-3 m (the GMS-unit gap, 0.2 cm).
  std::vector<RingCase> cases;
  for (double eps : {0.0, 0.3})
    cases.push_back({.tag = "gms_eps" + format_number(eps),
                     .eps = eps,
                     .dp = dp,
                     .gap = gap,
                     .t_end = t_end,
                     .frames = frames,
                     .skin = skin});
  const ElasticMaterial si = si_material();
  for (double eps : {0.0, 0.3}) {
    RingCase c{.tag = "si_eps" + format_number(eps),
               .si = true,
               .eps = eps,
               .dp = 5e-4,
               .gap = 2e-3,
               .frames = 0,
               .skin = skin};
    if (si_full)
      c.t_end = t_end * 0.01 / si.sound_speed(), c.frames = frames;
    else
      c.steps = si_steps;
    cases.push_back(c);
  }
  // The same runs with the pair loop (each pair once, PairLoop::Pairs): the rates agree with the row loop's to
  // rounding, so the comparison shows what that rounding does to a collision and what the loop saves.
  const std::size_t row_cases = cases.size();
  // And with the pair loop and one rate evaluation per step ("fast": the predictor-corrector reusing the corrector's
  // rate, an O(dt^2) change of the integrator).
  for (bool one_rate : {false, true})
    for (std::size_t k = 0; k < row_cases; ++k) {
      RingCase c = cases[k];
      c.tag += one_rate ? "_fast" : "_pairs";
      c.loop = PairLoop::Pairs;
      c.one_rate = one_rate;
      c.frames = 0;
      cases.push_back(c);
    }
  // The dt sensitivity of the eps = 0.3 bounce: the row loop at half the time step.
  RingCase half = cases[1];
  half.tag += "_halfdt";
  half.dt_scale = 0.5;
  half.frames = 0;
  cases.push_back(half);
  return cases;
}

}  // namespace grings
