#pragma once
/// \file gms.hpp
/// What the Gray-Monaghan-Swift studies (gms-plate, gms-rings, gms-slab) share beyond the library's scenes
/// (problems/gms_scenes.hpp: GMS's scheme, the three set-ups): the cost of a run and the frozen-state spectrum of a
/// state along a run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/problems/gms_scenes.hpp"
#include "sphstab/io/csv.hpp"

namespace sphstab::study {

/// The cost of a run: wall time (shared cores: depends on the load), the run thread's CPU time, steps, particles.
struct RunCost {
  double wall = 0, cpu = 0;
  long steps = 0;
  int particles = 0;
  long neighbour_builds = 0;
  double us_per_particle_step() const { return 1e6 * wall / (static_cast<double>(steps) * particles); }
  double us_cpu() const { return 1e6 * cpu / (static_cast<double>(steps) * particles); }
};

/// The cost columns of a run's row in a CSV table (wall,cpu,us_per_particle_step,us_cpu,neighbour_builds): the
/// seconds and the microseconds per particle-step with 4 significant digits, and the neighbour-list builds.
inline std::vector<std::string> cost_cells(const RunCost& c) {
  return {format_number(c.wall, 4), format_number(c.cpu, 4), format_number(c.us_per_particle_step(), 4),
          format_number(c.us_cpu(), 4), std::to_string(c.neighbour_builds)};
}

/// run_rate_form with the calling thread's CPU time measured around it.
template <int Dim>
RateFormRunResult timed_run(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y0, const RateFormRunOptions& o,
                            RunCost& cost) {
  const double cpu0 = thread_cpu_seconds();
  RateFormRunResult run = run_rate_form(scheme, y0, o);
  cost.cpu += thread_cpu_seconds() - cpu0;
  cost.wall += run.wall_seconds;
  cost.steps += run.steps;
  cost.neighbour_builds += run.neighbour_builds;
  cost.particles = scheme.discretisation().size();
  return run;
}

/// The linearised spectrum of a state along a run (growth/rate_form_spectrum.hpp), "frozen": the velocities are set
/// to 0 (the spectrum linearises at rest) and the neighbour list is built at the state's positions.
struct FrozenSpectrum {
  double growth_rate = std::numeric_limits<double>::quiet_NaN();
  int unstable = 0;  ///< eigenvalues with Re lambda > 1e-6 max |lambda|
  /// Where the most unstable mode lives: the position of its largest velocity, and the share of the mode's |v|^2 within
  /// 2h of that point (1: local; small: spread over the body)
  double peak_x = std::numeric_limits<double>::quiet_NaN();
  double peak_y = std::numeric_limits<double>::quiet_NaN();
  double peak_share = std::numeric_limits<double>::quiet_NaN();
};

/// Frozen spectrum of state y of a run of `scheme` under the same scheme with artificial stress eps: same material,
/// masses, initial density / deviator and driven particles. At rest the compression switch turns the viscosity off;
/// viscosity_on uses ViscositySwitch::Always (same alpha, beta): the run's damping of approaching pairs frozen on.
/// Writes the most unstable mode's velocity shape at the free particles' positions to `mode_csv` (x, y, vx, vy).
/// The linearisation is elastic: a von Mises return mapping is not part of the rate.
inline FrozenSpectrum frozen_spectrum(const RateFormScheme<2>& scheme, const Eigen::VectorXd& y_run, double eps,
                                      bool viscosity_on, const std::string& mode_csv) {
  const Discretisation<2>& d = scheme.discretisation();
  ParticleSet<2> p = d.particles;
  const Eigen::Matrix2Xd x = rate_form_positions(scheme, y_run);
  p.x = x.transpose();
  RateFormOptions o = scheme.options();
  o.artificial_stress = eps;
  if (viscosity_on) o.viscosity = ViscositySwitch::Always;
  RateFormScheme<2> s(make_discretisation(std::move(p), d.kernel, d.h), scheme.material(), o, scheme.initial_density(),
                      scheme.initial_deviator());
  s.set_driven(scheme.driven_particles(), scheme.driven_accelerations());
  Eigen::VectorXd y = y_run;
  for (int f = 0; f < d.free_count(); ++f) y.segment<2>(s.velocity_offset(d.free[f])).setZero();
  const RateFormSpectrum sp = rate_form_spectrum(s, y, {.want_mode = true});
  if (sp.info() != Status::Successful) throw std::runtime_error("frozen spectrum: " + sp.reason);
  FrozenSpectrum out;
  out.growth_rate = sp.growth_rate;
  double scale = 0;
  for (const auto& l : sp.eigenvalues) scale = std::max(scale, std::abs(l));
  for (const auto& l : sp.eigenvalues) out.unstable += l.real() > 1e-6 * scale;
  std::ofstream f(mode_csv);
  f << "x,y,vx,vy\n";
  int peak = 0;
  for (int k = 0; k < d.free_count(); ++k) {
    const Eigen::Vector2d xk = x.col(d.free[k]), v = sp.mode.segment<2>(2 * k);
    if (v.squaredNorm() > sp.mode.segment<2>(2 * peak).squaredNorm()) peak = k;
    f << csv_line({format_number(xk[0], 10), format_number(xk[1], 10), format_number(v[0], 8), format_number(v[1], 8)});
  }
  const Eigen::Vector2d xp = x.col(d.free[peak]);
  double near = 0;
  for (int k = 0; k < d.free_count(); ++k)
    if ((x.col(d.free[k]) - xp).norm() < 2 * d.h) near += sp.mode.segment<2>(2 * k).squaredNorm();
  out.peak_x = xp[0], out.peak_y = xp[1], out.peak_share = near / sp.mode.squaredNorm();
  return out;
}

/// One frozen spectrum of frozen_spectra_along_run.
struct FrozenRow {
  std::string state;  ///< "start" or "t<time>"
  double t = 0, eps = 0;
  bool viscosity = false;
  FrozenSpectrum spectrum;
};

/// Runs `scheme` from y0 with the options `o` (dt, skin, yield stress; t_end, records and observer are set here) to
/// the last of `times` (ascending, > 0) and takes the frozen spectra of y0 and of the recorded states at `times`
/// (the first record at or after each), under eps = 0 and 0.3 with the viscosity off, and at viscosity_time (one of
/// `times`) with it on too. Writes out/frozen_spectrum.csv (state, t, eps, viscosity, growth_rate, unstable
/// eigenvalues, mode means) and out/frozen_mode_<state>_eps<e>_<visc|novisc>.csv, and the summary key frozen_table
/// (a Markdown table body of the same). Throws std::runtime_error when the run stops early.
inline std::vector<FrozenRow> frozen_spectra_along_run(const RateFormScheme<2>& scheme, const Eigen::VectorXd& y0,
                                                       RateFormRunOptions o, const std::vector<double>& times,
                                                       double viscosity_time, const std::string& out, Summary& sum) {
  struct State {
    std::string name;
    double t;
    Eigen::VectorXd y;
  };
  std::vector<State> states = {{"start", 0.0, y0}};
  for (double t : times) states.push_back({"t" + format_number(t), t, {}});
  o.t_end = times.back() + o.dt;
  o.record_every = 1;
  o.observer = [&](long, double t, const Eigen::VectorXd& y) {
    for (std::size_t k = 1; k < states.size(); ++k)
      if (states[k].y.size() == 0 && t >= states[k].t - 0.5 * o.dt) states[k].t = t, states[k].y = y;
  };
  const RateFormRunResult run = run_rate_form(scheme, y0, o);
  if (!run.completed()) throw std::runtime_error("frozen spectra: the run stopped: " + run.message);
  CsvWriter w(out + "/frozen_spectrum.csv", {"state", "t", "eps", "viscosity", "growth_rate", "unstable_eigenvalues",
                                             "mode_peak_x", "mode_peak_y", "mode_share_within_2h"});
  const std::string visc_state = "t" + format_number(viscosity_time);
  std::vector<FrozenRow> rows;
  std::string table;
  for (const State& st : states)
    for (bool visc : {false, true}) {
      if (visc && st.name != visc_state) continue;
      for (double e : {0.0, 0.3}) {
        const std::string suffix = "_" + st.name + "_eps" + format_number(e, 2) + (visc ? "_visc" : "_novisc");
        const FrozenRow r{st.name, st.t, e, visc,
                          frozen_spectrum(scheme, st.y, e, visc, out + "/frozen_mode" + suffix + ".csv")};
        const FrozenSpectrum& f = r.spectrum;
        w.row({st.name, st.t, e, visc ? 1.0 : 0.0, f.growth_rate, static_cast<double>(f.unstable), f.peak_x, f.peak_y,
               f.peak_share});
        md_row(table,
               {sig(st.t, 4), fixed(e, 1), visc ? "on" : "off", sig(f.growth_rate, 3), std::to_string(f.unstable),
                f.unstable ? "(" + fixed(f.peak_x, 2) + ", " + fixed(f.peak_y, 2) + ")" : "-",
                f.unstable ? fixed(f.peak_share, 2) : "-"});
        std::fprintf(stderr, "  frozen %-28s t %7.2f growth %.3g, %d unstable, mode peak (%.2f, %.2f), share %.2f\n",
                     suffix.c_str(), st.t, f.growth_rate, f.unstable, f.peak_x, f.peak_y, f.peak_share);
        rows.push_back(r);
      }
    }
  sum.set("frozen_table", table);
  return rows;
}

}  // namespace sphstab::study
