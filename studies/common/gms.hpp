#pragma once
/// \file gms.hpp
/// What the Gray-Monaghan-Swift studies (gms-plate, gms-rings, gms-slab) share beyond the library's scenes
/// (problems/gms_scenes.hpp: GMS's scheme, the three set-ups): the cost of a run and the frozen-state spectrum of a
/// state along a run, with its options on a driver's command line.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/gms_scenes.hpp"

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
  /// With a mirror-symmetric scene: the mirror class (px, py) of the most unstable mode (growth/mirror_symmetry.hpp;
  /// +1 even, -1 odd under x -> 2 cx - x and y -> 2 cy - y; 0 without an unstable eigenvalue), and the largest
  /// invariance residual of the four classes
  int class_x = 0, class_y = 0;
  double symmetry_residual = std::numeric_limits<double>::quiet_NaN();
};

/// A scene symmetric about the lines x = centre.x and y = centre.y (the colliding rings): frozen_spectrum then takes
/// the spectrum class by class, so that the most unstable mode is one eigenvector of one class rather than whichever
/// combination of its mirror images rounding selects (they share an eigenvalue, or nearly: the run's summation
/// order breaks the symmetry at the rounding level), and the mode is named canonically (peak in the quadrant
/// x >= cx, y >= cy, and there its larger velocity component positive).
struct FrozenMirror {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double tolerance = 0;  ///< partners match to this distance (absolute), > 0
};

namespace detail {

/// The spectrum of `scheme` at rest at y, whole or (mirror) as the union of the four mirror classes' spectra; in the
/// latter case out's class and residual fields are set. Throws std::runtime_error when a spectrum fails.
inline RateFormSpectrum frozen_eigen(const RateFormScheme<2>& s, const Eigen::VectorXd& y, const Eigen::Matrix2Xd& x,
                                     const FrozenMirror* mirror, FrozenSpectrum& out) {
  if (!mirror) {
    RateFormSpectrum sp = rate_form_spectrum(s, y, {.want_mode = true});
    if (sp.info() != Status::Successful) throw std::runtime_error("frozen spectrum: " + sp.reason);
    return sp;
  }
  const Discretisation<2>& d = s.discretisation();
  Eigen::VectorXd free_x(2 * d.free_count());
  for (int k = 0; k < d.free_count(); ++k) free_x.segment<2>(2 * k) = x.col(d.free[k]);
  const MirrorSymmetry sym = mirror_symmetry(free_x, mirror->centre, mirror->tolerance);
  RateFormSpectrum best;
  std::vector<std::complex<double>> all;
  out.symmetry_residual = 0;
  for (int px : {1, -1})
    for (int py : {1, -1}) {
      RateFormSpectrum sp = rate_form_spectrum(s, y, {.want_mode = true, .basis = symmetry_basis(sym, px, py)});
      if (sp.info() != Status::Successful)
        throw std::runtime_error("frozen spectrum, class (" + std::to_string(px) + ", " + std::to_string(py) +
                                 "): " + sp.reason);
      out.symmetry_residual = std::max(out.symmetry_residual, sp.invariance_residual);
      all.insert(all.end(), sp.eigenvalues.begin(), sp.eigenvalues.end());
      if (best.status != Status::Successful || sp.growth_rate > best.growth_rate)
        best = std::move(sp), out.class_x = px, out.class_y = py;
    }
  best.eigenvalues = Eigen::Map<const Eigen::VectorXcd>(all.data(), static_cast<Eigen::Index>(all.size()));
  return best;
}

}  // namespace detail

/// Frozen spectrum of state y of a run of `scheme` under the same scheme with artificial stress eps: same material,
/// masses, initial density / deviator and driven particles. At rest the compression switch turns the viscosity off;
/// viscosity_on uses ViscositySwitch::Always (same alpha, beta): the run's damping of approaching pairs frozen on.
/// Writes the most unstable mode's velocity shape at the free particles' positions to `mode_csv` (x, y, vx, vy).
/// The linearisation is elastic: a von Mises return mapping is not part of the rate. `mirror`: see FrozenMirror
/// (nullptr: the whole spectrum at once, the mode as the eigensolver returns it).
inline FrozenSpectrum frozen_spectrum(const RateFormScheme<2>& scheme, const Eigen::VectorXd& y_run, double eps,
                                      bool viscosity_on, const std::string& mode_csv,
                                      const FrozenMirror* mirror = nullptr) {
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
  FrozenSpectrum out;
  RateFormSpectrum sp = detail::frozen_eigen(s, y, x, mirror, out);
  out.growth_rate = sp.growth_rate;
  double scale = 0;
  for (const auto& l : sp.eigenvalues) scale = std::max(scale, std::abs(l));
  for (const auto& l : sp.eigenvalues) out.unstable += l.real() > 1e-6 * scale;
  auto speed2 = [&](int k) { return sp.mode.segment<2>(2 * k).squaredNorm(); };
  int peak = 0;
  for (int k = 1; k < d.free_count(); ++k)
    if (speed2(k) > speed2(peak)) peak = k;
  // With classes, a state without an unstable eigenvalue has no mode to name: which class's rounding-level "growth"
  // of a rigid motion is largest is rounding itself. The mode file then holds zeros, the peak and class NaN.
  const bool no_mode = mirror && out.unstable == 0;
  if (no_mode) sp.mode.setZero(), out.class_x = out.class_y = 0;
  if (mirror && !no_mode) {  // the mirror images of the peak have its |v| to rounding: take the one in x, y >= c
    const double top = speed2(peak);
    auto quadrant = [&](int k) {
      const Eigen::Vector2d r = x.col(d.free[k]) - mirror->centre;
      return 2 * (r[0] > -mirror->tolerance) + (r[1] > -mirror->tolerance);
    };
    for (int k = 0; k < d.free_count(); ++k)
      if (speed2(k) >= (1 - 1e-9) * top && quadrant(k) > quadrant(peak)) peak = k;
    const Eigen::Vector2d v = sp.mode.segment<2>(2 * peak);
    if (v[std::abs(v[1]) > std::abs(v[0])] < 0) sp.mode = -sp.mode;
  }
  std::ofstream f(mode_csv);
  f << "x,y,vx,vy\n";
  for (int k = 0; k < d.free_count(); ++k) {
    const Eigen::Vector2d xk = x.col(d.free[k]), v = sp.mode.segment<2>(2 * k);
    f << csv_line({format_number(xk[0], 10), format_number(xk[1], 10), format_number(v[0], 8), format_number(v[1], 8)});
  }
  const Eigen::Vector2d xp = x.col(d.free[peak]);
  double near = 0;
  for (int k = 0; k < d.free_count(); ++k)
    if ((x.col(d.free[k]) - xp).norm() < 2 * d.h) near += speed2(k);
  out.peak_x = xp[0], out.peak_y = xp[1], out.peak_share = near / sp.mode.squaredNorm();
  if (no_mode) out.peak_x = out.peak_y = out.peak_share = std::numeric_limits<double>::quiet_NaN();
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
/// (a Markdown table body of the same). Throws std::runtime_error when the run stops early. With `mirror` (a scene
/// symmetric about two lines, FrozenMirror) the spectra are taken class by class, and frozen_spectrum.csv gains the
/// columns mode_class_x, mode_class_y and symmetry_residual.
inline std::vector<FrozenRow> frozen_spectra_along_run(const RateFormScheme<2>& scheme, const Eigen::VectorXd& y0,
                                                       RateFormRunOptions o, const std::vector<double>& times,
                                                       double viscosity_time, const std::string& out, Summary& sum,
                                                       const FrozenMirror* mirror = nullptr) {
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
  std::vector<std::string> columns = {"state",       "t",           "eps",
                                      "viscosity",   "growth_rate", "unstable_eigenvalues",
                                      "mode_peak_x", "mode_peak_y", "mode_share_within_2h"};
  if (mirror) columns.insert(columns.end(), {"mode_class_x", "mode_class_y", "symmetry_residual"});
  CsvWriter w(out + "/frozen_spectrum.csv", columns);
  const std::string visc_state = "t" + format_number(viscosity_time);
  std::vector<FrozenRow> rows;
  std::string table;
  for (const State& st : states)
    for (bool visc : {false, true}) {
      if (visc && st.name != visc_state) continue;
      for (double e : {0.0, 0.3}) {
        const std::string suffix = "_" + st.name + "_eps" + format_number(e, 2) + (visc ? "_visc" : "_novisc");
        const FrozenRow r{st.name, st.t, e, visc,
                          frozen_spectrum(scheme, st.y, e, visc, out + "/frozen_mode" + suffix + ".csv", mirror)};
        const FrozenSpectrum& f = r.spectrum;
        std::vector<CsvCell> cells = {st.name,          st.t,          e,
                                      visc ? 1.0 : 0.0, f.growth_rate, static_cast<double>(f.unstable),
                                      f.peak_x,         f.peak_y,      f.peak_share};
        const double nan = std::numeric_limits<double>::quiet_NaN();
        if (mirror)
          cells.insert(cells.end(), {f.class_x ? static_cast<double>(f.class_x) : nan,
                                     f.class_y ? static_cast<double>(f.class_y) : nan, f.symmetry_residual});
        w.row(cells);
        std::vector<std::string> md = {sig(st.t, 4),
                                       fixed(e, 1),
                                       visc ? "on" : "off",
                                       sig(f.growth_rate, 3),
                                       std::to_string(f.unstable),
                                       f.unstable ? "(" + fixed(f.peak_x, 2) + ", " + fixed(f.peak_y, 2) + ")" : "-",
                                       f.unstable ? fixed(f.peak_share, 2) : "-"};
        auto parity = [](int p) { return std::string(p > 0 ? "even" : "odd"); };
        if (mirror) md.push_back(f.unstable ? parity(f.class_x) + " in x, " + parity(f.class_y) + " in y" : "-");
        md_row(table, md);
        std::fprintf(stderr, "  frozen %-28s t %7.2f growth %.3g, %d unstable, mode peak (%.2f, %.2f), share %.2f\n",
                     suffix.c_str(), st.t, f.growth_rate, f.unstable, f.peak_x, f.peak_y, f.peak_share);
        rows.push_back(r);
      }
    }
  sum.set("frozen_table", table);
  return rows;
}

/// Adds a driver's options of the frozen spectra along one of its runs (frozen_spectra_along_run, on a coarser grid):
/// --dp-spectrum, that grid's spacing `dp` in [0, dp_max] (0: none), and --spectrum-times, the states' `times` in
/// [t_min, 1e4], a comma list (`times_help`: which of them is also taken with the viscosity on, in what units). The
/// driver sorts the times once parsed.
inline void add_frozen_spectra_options(CLI::App& app, double& dp, std::vector<double>& times, double dp_max,
                                       double t_min, const std::string& times_help) {
  app.add_option("--dp-spectrum", dp, "grid spacing of the frozen-state spectra (0: none)")
      ->check(CLI::Range(0.0, dp_max));
  app.add_option("--spectrum-times", times, times_help)->delimiter(',')->check(CLI::Range(t_min, 1e4));
}

}  // namespace sphstab::study
