#pragma once
/// \file plate_run.hpp
/// One run of a plate case (its scene, GMS predictor-corrector) with what the study measures along it: the tip
/// deflection (the scene's measure) and its oscillation (analysis/oscillation.hpp: period from zero crossings, decay),
/// the kinetic energy, the largest stretch of a grid bond and the bond-graph fragments (the root break); the time
/// series written to series/<tag>.csv and, if asked, VTK snapshots. All cases on the threads, costliest first.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common/driver.hpp"
#include "common/gms.hpp"
#include "common/study.hpp"
#include "plate_case.hpp"
#include "sphstab/analysis/fragments.hpp"
#include "sphstab/analysis/oscillation.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/rate_form_vtk.hpp"
#include "sphstab/io/vtk.hpp"

namespace sphstab::gms_plate {

struct PlateRun {
  PlateCase c;
  int particles = 0;
  double dt = 0, wall = 0, cpu = 0;  ///< wall and run-thread CPU seconds of the run
  long steps = 0;
  std::string status;
  OscillationMeasure osc;
  std::vector<double> t, tip, ke, stretch;
  std::vector<int> fragments;
  double max_stretch = 1, max_stretch_x = kNaN, max_stretch_t = kNaN;  ///< largest grid-bond length / dp
  /// First record with more than one fragment (bonds < 1.5 dp, clamp included): time and the smallest x of the
  /// particles cut off from the clamp.
  double break_time = kNaN, break_x = kNaN;
  Eigen::VectorXd y_end;
};

/// The grid neighbours (distance dp) of the plate at the start. Particle order: column by column
/// (make_cantilever_plate), `across` per column.
inline std::vector<std::pair<int, int>> grid_bonds(int particles, int across) {
  std::vector<std::pair<int, int>> bonds;
  for (int i = 0; i < particles; ++i) {
    if (i % across + 1 < across) bonds.emplace_back(i, i + 1);
    if (i + across < particles) bonds.emplace_back(i, i + across);
  }
  return bonds;
}

inline void write_series(const std::string& out, const PlateRun& r) {
  std::filesystem::create_directories(out + "/series");
  std::ofstream f(out + "/series/" + r.c.tag + ".csv");
  f << "t,tip_displacement,kinetic_energy,max_bond_stretch,fragments\n";
  for (std::size_t k = 0; k < r.t.size(); ++k)
    f << csv_line({format_number(r.t[k], 10), format_number(r.tip[k], 10), format_number(r.ke[k], 10),
                   format_number(r.stretch[k], 8), std::to_string(r.fragments[k])});
}

inline PlateRun run_plate(const PlateCase& c, const std::string& out) {
  PlateRun r{.c = c};
  const Scene<2> s = plate_scene(c);
  const RateFormScheme<2>& scheme = *s.scheme;
  const ParticleSet<2>& particles = scheme.discretisation().particles;
  const double dp = s.spacing;
  const SceneMeasure<2>& tip = s.measures.front();
  const std::vector<std::pair<int, int>> bonds = grid_bonds(particles.size(), c.across);
  r.particles = particles.size();
  const double T = thin_period(c);
  std::vector<std::pair<double, std::string>> frames;
  const std::string vtk_dir = out + "/vtk/" + c.tag;
  if (c.vtk_frames > 0) std::filesystem::create_directories(vtk_dir);
  const double frame_every = c.periods * T / std::max(c.vtk_frames, 1);
  RateFormRunOptions ro{.dt = time_step(c, dp), .t_end = c.periods * T};
  ro.record_every = std::max(1, static_cast<int>(T / 400 / ro.dt));
  ro.observer = [&](long, double t, const Eigen::VectorXd& y) {
    const Eigen::Matrix2Xd pts = rate_form_positions(scheme, y);
    double stretch = 0;
    int at = -1;
    for (auto [i, j] : bonds) {
      const double d = (pts.col(i) - pts.col(j)).norm() / dp;
      if (d > stretch) stretch = d, at = i;
    }
    r.t.push_back(t);
    r.tip.push_back(tip.value(pts, y));
    r.ke.push_back(scheme.kinetic_energy(y));
    r.stretch.push_back(stretch);
    const Fragments fr = find_fragments(pts, 1.5 * dp);
    r.fragments.push_back(fr.count());
    if (fr.count() > 1 && std::isnan(r.break_time)) {
      r.break_time = t;
      r.break_x = std::numeric_limits<double>::infinity();
      for (int i = 0; i < particles.size(); ++i)
        if (fr.label[i] != fr.label[0]) r.break_x = std::min(r.break_x, pts(0, i));  // particle 0 is in the clamp
    }
    if (stretch > r.max_stretch) r.max_stretch = stretch, r.max_stretch_x = pts(0, at), r.max_stretch_t = t;
    if (c.vtk_frames > 0 && t >= frames.size() * frame_every - 0.5 * ro.dt) {
      const std::string name = c.tag + "_" + std::to_string(frames.size()) + ".vtp";
      write_rate_form_vtp(vtk_dir + "/" + name, scheme, y);
      frames.emplace_back(t, name);
    }
  };
  study::RunCost cost;
  const RateFormRunResult res = study::timed_run(scheme, s.y0, ro, cost);
  if (!frames.empty()) write_pvd(vtk_dir + "/" + c.tag + ".pvd", frames);
  r.dt = res.dt;
  r.steps = res.steps;
  r.wall = cost.wall;
  r.cpu = cost.cpu;
  r.status = run_status_name(res.status);
  r.y_end = res.y;
  r.osc = measure_oscillation(r.t, r.tip);
  // Decay over every half cycle's extreme, the first included: the start transient shifts the first crossing, not
  // the first peak.
  r.osc.decay_per_period = measure_oscillation(r.t, r.tip, false).decay_per_period;
  if (r.osc.crossings.size() < kMinCrossings) r.osc.period = kNaN;  // not two cycles: no period to report
  write_series(out, r);
  std::fprintf(stderr,
               "  %-28s N %5d dt %.4f steps %7ld  T %8.2f  (%zu crossings) decay %+.3f stretch %.2f at x %.2f t %.0f  "
               "%s  %.0f s\n",
               c.tag.c_str(), r.particles, r.dt, r.steps, r.osc.period, r.osc.crossings.size(), r.osc.decay_per_period,
               r.max_stretch, r.max_stretch_x, r.max_stretch_t, r.status.c_str(), r.wall);
  return r;
}

/// Every case on `threads` threads (one scheme per thread), the most expensive first (particles x steps, both known
/// before the run) so that the finest run does not start last on an otherwise idle pool; results in case order.
inline std::vector<PlateRun> run_all(const std::vector<PlateCase>& cases, const std::string& out, int threads) {
  auto cost = [](const PlateCase& c) {
    const double dp = c.thickness / c.across;
    const double particles = (c.length / dp + c.clamp_layers) * c.across;
    const double c_p = material_of(c).p_wave_speed();
    return particles * c.periods * thin_period(c) / (c.cfl * c.h_factor * dp / c_p);
  };
  return study::run_costliest_first(cases, threads, cost, [&](const PlateCase& c) { return run_plate(c, out); });
}

/// The run of case `c` among `runs` (by tag).
inline const PlateRun& find_run(const std::vector<PlateRun>& runs, const PlateCase& c) {
  for (const PlateRun& r : runs)
    if (r.c.tag == c.tag) return r;
  throw std::logic_error("missing run " + c.tag);
}

}  // namespace sphstab::gms_plate
