#pragma once
// The case tables of the four phases of the 1D non-reflecting boundary study [Powell2012, ch. 2 §3.1]: the variants
// (end, timing, time step) of Table 2.1 and their cases (reference, 1-5 absorbing particles, upwind (2.67), and the
// references without MCM's viscosity), the CFL sweep, the step-limit cases, and the h-study of Fig. 2.12.
#include <cmath>
#include <vector>

#include "bar_problem.hpp"

namespace nrbc1d {

/// One variant of Table 2.1: timing (half: algorithm 2.3), end (mirror: symmetric bar; else Powell's free end),
/// c dt/dx, and its summary key.
struct Variant {
  bool half, mirror;
  double cfl;
  const char* key;
};

/// The five variants of Table 2.1 (why these: main.cpp, phase 1): the headline (free end, half timing, MCM's step
/// cfl_mcm), the symmetric bar at that step, and at the tuned cfl the symmetric bar with both timings and the free end.
inline std::vector<Variant> table_variants(double cfl_mcm, double cfl) {
  return {{true, false, cfl_mcm, "table_headline"},
          {true, true, cfl_mcm, "table_mcm_mirror"},
          {true, true, cfl, "table_half"},
          {false, true, cfl, "table_whole"},
          {true, false, cfl, "table_free"}};
}

/// The cases of Table 2.1, every variant, with the references without viscosity at the tuned step last.
inline std::vector<BarCase> table_cases(const std::vector<Variant>& variants, double cfl) {
  std::vector<BarCase> table;
  for (const Variant& v : variants)
    for (Form f : kForms) {
      // The reference has no absorbing particles: its timing flag is moot, run once per left end.
      if (v.half)
        table.push_back(
            {.form = f, .particles = 800, .mirror = v.mirror, .half_step = true, .cfl = v.cfl, .keep_series = true});
      for (int layers = 1; layers <= 5; ++layers)
        table.push_back(
            {.form = f, .mirror = v.mirror, .layers = layers, .half_step = v.half, .cfl = v.cfl, .keep_series = true});
      table.push_back({.form = f,
                       .mirror = v.mirror,
                       .layers = 8,
                       .upwind = true,
                       .half_step = v.half,
                       .cfl = v.cfl,
                       .keep_series = true});
    }
  for (Form f : kForms)  // the references without MCM's viscosity
    table.push_back({.form = f, .particles = 800, .cfl = cfl, .viscosity = ViscositySwitch::Off, .keep_series = true});
  return table;
}

/// CFL sweep: the truncated bars at each dt (both timings).
inline std::vector<BarCase> sweep_cases(const std::vector<double>& sweep) {
  std::vector<BarCase> sweep_cases;
  for (double s : sweep)
    for (bool half : {true, false})
      for (Form f : kForms)
        for (int layers = 1; layers <= 5; ++layers)
          sweep_cases.push_back({.form = f, .layers = layers, .half_step = half, .cfl = s});
  return sweep_cases;
}

/// Every truncated configuration and the reference, both timings (quick: the half-step timing, SPH with one absorbing
/// layer and NCXSPH with the upwind eight).
inline std::vector<BarCase> limit_cases(bool quick) {
  if (quick)
    return {{.form = Form::Sph, .layers = 1, .half_step = true},
            {.form = Form::Ncxsph, .layers = 8, .upwind = true, .half_step = true}};
  std::vector<BarCase> limit_cases;
  for (bool half : {true, false})
    for (Form f : kForms) {
      limit_cases.push_back({.form = f, .particles = 800, .half_step = half});
      for (int layers = 1; layers <= 5; ++layers)
        limit_cases.push_back({.form = f, .layers = layers, .half_step = half});
      limit_cases.push_back({.form = f, .layers = 8, .upwind = true, .half_step = half});
    }
  return limit_cases;
}

/// Fig. 2.12: NCXSPH, floor(2h/dx) + 1 absorbing particles, error over 3 < t < 10 us; per h / dx the reference, then
/// the truncated bar with the half and the whole timing.
inline std::vector<BarCase> h_cases(const std::vector<double>& h_values, double cfl) {
  std::vector<BarCase> hcases;
  for (double hd : h_values) {
    const int layers = static_cast<int>(std::floor(2 * hd + 1e-9)) + 1;
    hcases.push_back({.form = Form::Ncxsph, .particles = 800, .h_over_dx = hd, .cfl = cfl, .t_to = 10});
    for (bool half : {true, false})
      hcases.push_back(
          {.form = Form::Ncxsph, .layers = layers, .half_step = half, .h_over_dx = hd, .cfl = cfl, .t_to = 10});
  }
  return hcases;
}

}  // namespace nrbc1d
