#pragma once
// Energy conservation of the conservative form (the 2D version of [Powell2012, (3.27)]) and of TL-SPH in the
// Swegle block at xi = 1: leap-frog runs at the CFL step, 2 dt and dt/2 with the relative energy error, its end
// value and the least-squares drift; writes energy_series.csv and energy.csv.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/run_output.hpp"
#include "sphstab/problems/swegle.hpp"
#include "swegle_options.hpp"

namespace swegle_study {

using namespace sphstab;

struct EnergyRow {
  std::string form;
  double dt;
  long steps;
  double max_dev, end_drift, slope_drift, wall;
};

/// Conservative form (and TL, linear) at xi = 1 (stable), a finite kick v0 = 0.01 cm/us so that the kernel really
/// moves (max |u| ~ 1e-2 dx); T = energy_steps * dt0 at dt0 (CFL 0.3), 2 dt0, dt0/2. Writes energy_series.csv and
/// energy.csv.
inline std::vector<EnergyRow> energy_conservation(const Config& c, double dt) {
  std::cout << "energy conservation: " << c.energy_steps << " steps at the CFL step, plus 2 dt and dt/2\n";
  std::vector<EnergyRow> energy;
  CsvWriter series(c.out + "/energy_series.csv", {"formulation", "dt", "t", "relative_energy_error"});
  const SwegleScene es = make_swegle_scene({.area_ratio = 1.0, .velocity = 0.01});
  const double T = c.energy_steps * dt;
  for (std::string name : {"conservative", "tl"}) {
    std::shared_ptr<ForceFunction> force;
    if (name == "conservative")
      force = std::make_shared<ElasticForm2D>(es.discretisation, es.material, MomentumForm::Conservative, es.prestrain);
    else
      force = std::make_shared<TotalLagrangianForm2D>(es.discretisation, es.material, es.prestrain);
    for (double h : {2 * dt, dt, dt / 2}) {
      const auto t0 = study::Clock::now();
      SecondOrderSystem sys;
      sys.acceleration = acceleration_function(force);
      sys.strain_energy = [force](const Eigen::VectorXd& u) { return force->strain_energy(u); };
      sys.dofs_per_particle = 2;
      sys.mass = es.material.density() * es.discretisation->particles.volume.head(es.discretisation->free_count());
      LeapfrogOptions o;
      o.dt = h;
      o.t_end = T;
      o.record_every = std::max<long>(1, static_cast<long>(std::llround(T / h)) / 1000);
      ProgressReport progress("energy " + name);
      o.observers = {&progress};
      const LeapfrogResult rr = run_leapfrog(sys, Eigen::VectorXd::Zero(force->dofs()), es.v0, o);
      const double e0 = rr.history.front().total;
      double dev = 0, st = 0, se = 0, stt = 0, ste = 0;
      for (const Diagnostics& d : rr.history) {
        const double e = (d.total - e0) / e0;
        dev = std::max(dev, std::abs(e));
        st += d.time, se += e, stt += d.time * d.time, ste += d.time * e;
        if (name == "conservative") series.row({name, h, d.time, e});
      }
      const double n = static_cast<double>(rr.history.size());
      const double slope = (ste / n - st / n * se / n) / (stt / n - st / n * st / n);
      energy.push_back(
          {name, h, rr.steps, dev, (rr.history.back().total - e0) / e0, slope * T, study::seconds_since(t0)});
      std::printf("  %-12s dt = %.4g (%ld steps): max |dE|/E0 = %.3e, end %.3e, fitted drift over T %.3e (%.1f s)\n",
                  name.c_str(), h, rr.steps, dev, energy.back().end_drift, energy.back().slope_drift,
                  energy.back().wall);
    }
  }
  CsvWriter csv(c.out + "/energy.csv", {"formulation", "dt", "steps", "max_rel_energy_error", "end_rel_energy_error",
                                        "fitted_drift_over_T", "wall_seconds"});
  for (const EnergyRow& e : energy) csv.row({e.form, e.dt, e.steps, e.max_dev, e.end_drift, e.slope_drift, e.wall});
  return energy;
}

}  // namespace swegle_study
