#pragma once
// The runs of Powell's impact studies [Powell2012, ch. 4 §4] (powell-symmetric-impact, powell-bar-impact,
// powell-clamped-beam): one case is a formulation on one scene (problems/powell_impact.hpp), run to its end or to its
// first stop, with the scene's measures recorded at every step and snapshots of every particle at given times.
//
// Formulations: "sph", "ncsph", "ssph" (MCM's rate forms, powell_formulation_options) run with the staggered leap-frog
// (algorithm 1.1) and the velocity smoothing (2.71); "ssph-g", a sensitivity of the studies, not one of Powell's: his
// S-SPH with the means of G itself instead of the first-step Shepard gradient's (4.18) (first_step_shepard = false);
// "tl" (Powell's linear TL-SPH) and "tl-svk" (the same operators with St Venant-Kirchhoff finite strain) with the
// velocity-Verlet leap-frog; all at dt = TSSFAC h / c_P.
//
// Writes signals.csv (t, global KE and the study's measures per run), runs.csv (status, steps, CPU seconds),
// a VTK series of every run with snapshots (Settings::vtk_dir: <form>_<case>/series.pvd, a frame every vtk_every us;
// not kept in git),
// snapshots.csv (every particle's initial and current position and pressure at the snapshot times) and order.csv
// (every Settings::order_every: the share of clumped particles, those with a neighbour closer than 0.5 dx, and the
// fragments of the bonds shorter than 1.5 dx, analysis/fragments.hpp: numerical fracture as a count).
//
// Verdicts (Case::verdict_times): the stability verdict (growth/stability_verdict.hpp) of the run's state at given
// times (its initial state, t = 0, and a mid-run one): the state's configuration, densities and stresses AT REST
// (velocities set to zero), the semi-discrete growth gamma_J = max Re lambda(J) of the system linearised there, the
// one-step map's growth gamma_M of the run's integrator at the run's dt, the detection floor ln(energy_ratio) /
// (2 t_end) of the run, and the class S / U / I / B. Why at rest: linearised with its velocities, the state's own flow
// enters J (the continuity equation's d(rho')/d(rho) = -tr L is a "growth" of |tr L| ~ v0 / dx at the impact
// plane, the compression of the base flow, not an instability of the scheme); at rest what remains is the stiffness
// of the stressed, deformed configuration, where the tensile instability lives. The state is not an equilibrium:
// acceleration_max says how far from one, and J is frozen there (how perturbations of that stressed configuration
// grow, not what the run did). Rate forms: the scheme rebuilt on the neighbour list of the state's positions
// (RateFormScheme::rebuilt), at rest both rates from the exact reduction (growth/rate_form_spectrum.hpp, the
// leap-frog with the velocity smoothing (2.71)). TL-SPH: J = [0 I; -A 0] with A = -da/du at the state's
// displacement (complex step; the velocities do not enter), the leap-frog's map in closed form (dense). Written to
// verdicts.csv.
//
// The drivers' shared frame (StudyOptions): the options every study takes (add_options), their check and the output
// directory (prepare), the run of the study's cases and verdict cases (run_study) and the summary keys (set_run_keys,
// set_body_keys); each driver keeps its cases, its --quick settings and its own summary keys.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/analysis/fragments.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/rate_form_vtk.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/problems/powell_impact.hpp"

namespace sphstab::study::impact {

struct Case {
  std::string form;                    ///< sph | ncsph | ssph | ssph-g | tl | tl-svk
  std::string name;                    ///< the case column (e.g. "compression")
  PowellImpactOptions scene;           ///< problem, spacing, speed, t_end, ...; the scheme is set from `form`
  std::vector<double> snapshot_times;  ///< empty: no snapshots
  std::vector<double> verdict_times;   ///< the verdict of the state at these times (empty: none)
};

struct Settings {
  std::vector<std::string> measures;  ///< scene measures recorded per step (signals.csv columns, in this order)
  double tssfac = 0.8;                ///< MCM deck, card 2: dt = TSSFAC h / c_P
  double xsph = 0.1;                  ///< Powell (2.71)
  double order_every = 1.0;           ///< us between the particle-order records (order.csv)
  /// The verdicts' detection floor is ln(energy_ratio) / (2 t_end): the slowest amplitude growth that raises the
  /// kinetic energy by this factor within the run.
  double verdict_energy_ratio = 100;
  std::string vtk_dir;     ///< VTK series of the runs with snapshots go to vtk_dir/<form>_<case>/ (empty: none)
  double vtk_every = 0.5;  ///< us between VTK frames
};

/// A VTK series being written: frames at the first record at or after each multiple of `every`, the .pvd kept
/// current (a run that stops leaves a readable series).
struct VtkSeries {
  std::string dir;
  double every = 0;
  std::vector<std::pair<double, std::string>> frames;
  template <class Write>
  void maybe_write(double t, Write write) {
    if (dir.empty() || t < every * static_cast<double>(frames.size()) - 1e-9 * every) return;
    const std::string name = "frame_" + std::to_string(frames.size()) + ".vtp";
    write(dir + "/" + name);
    frames.emplace_back(t, name);
    write_pvd(dir + "/series.pvd", frames);
  }
};

/// The particle order of a state at one time: clumped share and fragments.
struct Order {
  double t = 0, clumped = 0, largest = 0;  ///< largest: the largest fragment's share of the particles
  int fragments = 0;
};

inline Order particle_order(const Eigen::Matrix2Xd& x, double dx, double t) {
  const double n = static_cast<double>(x.cols());
  const Fragments near = find_fragments(x, 0.5 * dx);  // a particle with a neighbour closer than 0.5 dx is clumped
  long single = 0;
  for (int size : near.sizes) single += size == 1;
  const Fragments bonds = find_fragments(x, 1.5 * dx);
  return {.t = t,
          .clumped = (n - static_cast<double>(single)) / n,
          .largest = bonds.largest() / n,
          .fragments = bonds.count()};
}

struct Snapshot {
  double t = 0;
  Eigen::Matrix2Xd x;
  Eigen::VectorXd p;
};

/// The verdict of the state nearest a wanted time (reached = false: the run stopped before it).
struct VerdictRecord {
  double wanted = 0, t = 0;
  bool reached = false;
  StabilityVerdict verdict;
  Eigen::Vector2d mode_position = Eigen::Vector2d::Constant(std::nan(""));  ///< the semi-discrete mode's particle
  double acceleration_max = 0;  ///< max |dv_i/dt| at the state at rest: how far it is from an equilibrium
};

struct Outcome {
  RunResult run;
  int particles = 0, particle_a = -1;
  Eigen::Vector2d x_a = Eigen::Vector2d::Zero();
  Eigen::Matrix2Xd x0;  ///< initial positions (runs with snapshots)
  double cpu = 0;
  std::vector<double> t, ke;
  std::vector<std::vector<double>> values;  ///< per record, one value per Settings::measures
  std::vector<Snapshot> snaps;
  std::vector<Order> order;
  std::vector<VerdictRecord> verdicts;
};

inline bool is_tl(const std::string& form) { return form == "tl" || form == "tl-svk"; }

/// The rate-form scheme of a formulation: Powell's (powell_formulation_options), or "ssph-g", his S-SPH with the means
/// of G itself (first_step_shepard = false, everything else his): a sensitivity of the studies, not in the library.
inline RateFormOptions formulation_options(const std::string& form) {
  if (form != "ssph-g") return powell_formulation_options(form);
  RateFormOptions o = powell_formulation_options("ssph");
  o.first_step_shepard = false;
  return o;
}

/// Records the particle order at the first record at or after each multiple of `every` (not of a non-finite state,
/// which the run reports as its stop).
inline void maybe_order(Outcome& o, const Eigen::Matrix2Xd& x, double dx, double t, double every) {
  if (t >= every * static_cast<double>(o.order.size()) - 1e-9 * every && x.allFinite())
    o.order.push_back(particle_order(x, dx, t));
}

/// Takes a snapshot at the record nearest each wanted time (within dt / 2).
template <class Fields>
void maybe_snapshot(Outcome& o, const std::vector<double>& wanted, double t, double dt, Fields fields) {
  for (double w : wanted)
    if (t >= w - 0.5 * dt && t < w + 0.5 * dt) {
      Snapshot s{t, {}, {}};
      fields(s);
      o.snaps.push_back(std::move(s));
    }
}

inline Outcome run_case(const Case& c, const Settings& settings) {
  Outcome o;
  const bool tl = is_tl(c.form);
  PowellImpactOptions po = c.scene;
  po.scheme = formulation_options(tl ? "sph" : c.form);
  const Scene<2> scene = powell_impact_scene(po);
  const int a = impact_particle_a(po);
  const auto& disc = scene.scheme->discretisation();
  o.particle_a = a;
  o.particles = disc.size();
  o.x_a = disc.particles.x.row(a).transpose();
  if (!c.snapshot_times.empty()) o.x0 = disc.particles.x.transpose();
  std::vector<const SceneMeasure<2>*> measures;
  for (const std::string& m : settings.measures) measures.push_back(&scene.measure(m));
  const double dt = scene.time_step(settings.tssfac);
  const double cpu0 = thread_cpu_seconds();
  const double floor = detection_floor(scene.t_end, settings.verdict_energy_ratio);
  VtkSeries vtk;
  if (!settings.vtk_dir.empty() && !c.snapshot_times.empty()) {
    vtk = {.dir = settings.vtk_dir + "/" + c.form + "_" + c.name, .every = settings.vtk_every};
    std::filesystem::create_directories(vtk.dir);
  }
  std::vector<std::pair<double, Eigen::VectorXd>> states;  // (t, y) at the verdict times
  const auto keep_state = [&](double t, double step, const auto& y) {
    for (double w : c.verdict_times)
      if (t >= w - 0.5 * step && t < w + 0.5 * step) states.emplace_back(t, y);
  };
  if (!tl) {
    const RateFormScheme<2>& scheme = *scene.scheme;
    RateFormRunOptions ro{.dt = dt,
                          .t_end = scene.t_end,
                          .integrator = RateFormIntegrator::Leapfrog,
                          .leapfrog_xsph = settings.xsph,
                          .neighbour_skin = scene.neighbour_skin};
    ro.observer = [&](long, double t, const Eigen::VectorXd& y) {
      const Eigen::Matrix2Xd x = rate_form_positions(scheme, y);
      o.t.push_back(t);
      std::vector<double> row;
      for (const auto* m : measures) row.push_back(m->value(x, y));
      o.values.push_back(std::move(row));
      maybe_order(o, x, c.scene.spacing, t, settings.order_every);
      maybe_snapshot(o, c.snapshot_times, t, ro.dt, [&](Snapshot& s) {
        s.x = x;
        s.p = scheme.material().bulk_modulus() *
              (rate_form_densities(scheme, y).array() / scheme.material().density() - 1).matrix();
      });
      keep_state(t, ro.dt, y);
      if (x.allFinite()) vtk.maybe_write(t, [&](const std::string& path) { write_rate_form_vtp(path, scheme, y); });
    };
    const RateFormRunResult r = run_rate_form(scheme, scene.y0, ro);
    o.run = r;
    o.ke = r.kinetic_energy;
    RateFormRunOptions vo = ro;  // the verdict's integrator: the run's, on the list built at the state
    vo.dt = r.dt;
    vo.neighbour_skin = 0;
    vo.observer = {};
    for (const auto& [t, y] : states) {
      Eigen::VectorXd rest = y;  // the state's configuration, densities and stresses, at rest (see the file comment)
      for (int i = 0; i < disc.size(); ++i)
        if (scheme.velocity_offset(i) >= 0) rest.segment<2>(scheme.velocity_offset(i)).setZero();
      const RateFormScheme<2> at = scheme.rebuilt(rest);
      VerdictRecord v{.t = t, .reached = true, .verdict = stability_verdict(at, rest, vo, {.floor = floor})};
      const int particle = v.verdict.semi_discrete_mode.particle;
      if (particle >= 0) v.mode_position = rate_form_positions(at, rest).col(particle);
      Eigen::VectorXd f;
      at.rate(rest, f);
      for (int i = 0; i < disc.size(); ++i)
        if (at.velocity_offset(i) >= 0)
          v.acceleration_max = std::max(v.acceleration_max, f.segment<2>(at.velocity_offset(i)).norm());
      o.verdicts.push_back(std::move(v));
    }
  } else {
    const ImpactTotalLagrangian m =
        impact_total_lagrangian(scene, c.form == "tl" ? ImpactTLModel::Linear : ImpactTLModel::StVenantKirchhoff);
    const Eigen::Matrix2Xd x0 = disc.particles.x.transpose();
    LeapfrogOptions lo;
    lo.dt = dt;
    lo.t_end = scene.t_end;
    lo.record_every = 1;
    lo.observe_every = 1;
    // The TL state as the scene's measures read it: positions x0 + u, the velocity of A, and TL's own pressure at A
    // (the rate-form state's density is not a TL variable).
    lo.observer = [&](const StepView& v) {
      Eigen::Matrix2Xd x = x0;
      for (int i = 0; i < disc.size(); ++i)
        if (disc.free_slot[i] >= 0) x.col(i) += v.u.segment<2>(2 * disc.free_slot[i]);
      o.t.push_back(v.time);
      std::vector<double> row;
      for (const SceneMeasure<2>* measure : measures) {  // looked up once, before the run
        if (measure->name == "pressure_A")
          row.push_back(m.pressure(v.u, a));
        else if (measure->name == "speed_A")
          row.push_back(v.v.segment<2>(2 * disc.free_slot[a]).norm());
        else
          row.push_back(measure->value(x, scene.y0));  // length, deflection: positions only
      }
      o.values.push_back(std::move(row));
      maybe_order(o, x, c.scene.spacing, v.time, settings.order_every);
      maybe_snapshot(o, c.snapshot_times, v.time, lo.dt, [&](Snapshot& s) {
        s.x = x;
        s.p.resize(disc.size());
        for (int i = 0; i < disc.size(); ++i) s.p[i] = m.pressure(v.u, i);
      });
      vtk.maybe_write(v.time, [&](const std::string& path) {  // TL: positions, displacement, TL pressure
        VtkField u{"displacement", 2, Eigen::VectorXd::Zero(2 * disc.size())},
            p{"pressure", 1, Eigen::VectorXd(disc.size())};
        for (int i = 0; i < disc.size(); ++i) {
          u.values.segment<2>(2 * i) = x.col(i) - x0.col(i);
          p.values[i] = m.pressure(v.u, i);
        }
        write_vtp(path, x.transpose(), {u, p});
      });
      if (!c.verdict_times.empty()) keep_state(v.time, lo.dt, v.u);  // J does not depend on the velocities
    };
    const LeapfrogResult r = run_leapfrog(m.system, Eigen::VectorXd::Zero(m.form->dofs()), m.v0, lo);
    o.run = r;
    for (const Diagnostics& d : r.history) o.ke.push_back(d.kinetic);
    // y = (u, v), y' = J y with J = [0 I; -A 0]; the velocity Verlet leap-frog has the staggered leap-frog's map
    // (the same recurrence for u, sampled half a step apart in v).
    const int n = m.form->dofs();
    StateLayout layout{.size = 2 * n};
    for (int k = 0; k < n; ++k) layout.position.push_back(k), layout.velocity.push_back(n + k);
    const RateFormRunOptions vo{.dt = r.dt, .t_end = scene.t_end, .integrator = RateFormIntegrator::Leapfrog};
    for (const auto& [t, u] : states) {
      Eigen::VectorXd a;
      m.form->acceleration(u, a);
      Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * n, 2 * n);
      J.topRightCorner(n, n).setIdentity();
      J.bottomLeftCorner(n, n) = -Eigen::MatrixXd(jacobian(*m.form, u));
      VerdictRecord v{.t = t, .reached = true, .verdict = stability_verdict(J, layout, vo, floor)};
      for (int k = 0; k < n; k += 2) v.acceleration_max = std::max(v.acceleration_max, a.segment<2>(k).norm());
      const int dof = v.verdict.semi_discrete_mode.particle;  // without particles: the largest velocity DOF
      if (dof >= 0) {
        const int slot = (dof >= n ? dof - n : dof) / 2;
        for (int i = 0; i < disc.size(); ++i)
          if (disc.free_slot[i] == slot) v.mode_position = x0.col(i) + u.segment<2>(2 * slot);
      }
      o.verdicts.push_back(std::move(v));
    }
  }
  o.cpu = thread_cpu_seconds() - cpu0;
  // Match each wanted time with its state (the first within dt / 2), or record that the run stopped before it.
  std::vector<VerdictRecord> by_time;
  for (double w : c.verdict_times) {
    VerdictRecord rec{.wanted = w};
    for (const VerdictRecord& v : o.verdicts)
      if (v.reached && std::abs(v.t - w) <= 0.5 * o.run.dt + 1e-12) {
        rec = v;
        rec.wanted = w;
        break;
      }
    by_time.push_back(std::move(rec));
  }
  o.verdicts = std::move(by_time);
  if (o.ke.size() != o.t.size())
    throw std::runtime_error(c.form + " " + c.name + ": " + std::to_string(o.ke.size()) + " energy records for " +
                             std::to_string(o.t.size()) + " observed states");
  return o;
}

/// Runs every case side by side on `threads` threads (each run on one), printing a line per run.
inline std::vector<Outcome> run_cases(const std::vector<Case>& cases, const Settings& settings, int threads) {
  std::vector<Outcome> outcomes(cases.size());
  parallel_for(cases.size(), threads, [&](std::size_t k) {
    const Case& c = cases[k];
    outcomes[k] = run_case(c, settings);
    std::fprintf(stderr, "  %-6s %-11s dx %-7g: %s (%.1f s CPU)\n", c.form.c_str(), c.name.c_str(), c.scene.spacing,
                 outcomes[k].run.message.c_str(), outcomes[k].cpu);
  });
  return outcomes;
}

/// signals.csv, runs.csv, snapshots.csv and order.csv in `out`, each name preceded by `prefix` (e.g. "sensitivity_");
/// returns the number of completed runs.
inline int write_runs(const std::string& out, const std::vector<Case>& cases, const std::vector<Outcome>& outcomes,
                      const Settings& settings, const std::string& prefix = "") {
  std::vector<std::string> columns{"formulation", "case", "dx", "t", "kinetic_energy"};
  columns.insert(columns.end(), settings.measures.begin(), settings.measures.end());
  CsvWriter signals(out + "/" + prefix + "signals.csv", columns, false);
  CsvWriter runs(out + "/" + prefix + "runs.csv", {"formulation", "case", "dx", "v0", "particles", "particle_A", "x_A",
                                                   "y_A", "dt", "steps", "status", "t_stop", "cpu_seconds", "message"});
  CsvWriter snaps(out + "/" + prefix + "snapshots.csv",
                  {"formulation", "case", "dx", "t", "particle", "x0", "y0", "x", "y", "pressure"}, false);
  CsvWriter order(out + "/" + prefix + "order.csv",
                  {"formulation", "case", "dx", "t", "clumped_share", "fragments", "largest_fragment_share"});
  int completed = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const Outcome& o = outcomes[k];
    const double dx = c.scene.spacing;
    for (std::size_t r = 0; r < o.t.size(); ++r) {
      std::vector<CsvCell> row{c.form, c.name, dx, o.t[r], o.ke[r]};
      for (double v : o.values[r]) row.push_back(v);
      signals.row(row);
    }
    runs.row({c.form, c.name, dx, c.scene.speed, o.particles, o.particle_a, o.x_a.x(), o.x_a.y(), o.run.dt, o.run.steps,
              run_status_name(o.run.status), o.run.time, o.cpu, o.run.message});
    completed += o.run.completed();
    for (const Order& q : o.order) order.row({c.form, c.name, dx, q.t, q.clumped, q.fragments, q.largest});
    for (const Snapshot& s : o.snaps)
      for (int i = 0; i < s.x.cols(); ++i)
        snaps.row({c.form, c.name, dx, s.t, i, o.x0(0, i), o.x0(1, i), s.x(0, i), s.x(1, i), s.p[i]});
  }
  return completed;
}

/// verdicts.csv: one row per case and verdict time (reached = 0: the run stopped before it; the rates are then empty).
inline void write_verdicts(const std::string& out, const std::vector<Case>& cases,
                           const std::vector<Outcome>& outcomes) {
  CsvWriter w(out + "/verdicts.csv", {"formulation",
                                      "case",
                                      "dx",
                                      "t_wanted",
                                      "t",
                                      "reached",
                                      "class",
                                      "semi_discrete_growth",
                                      "map_growth",
                                      "integrator_excess",
                                      "floor",
                                      "lambda_max",
                                      "resolution",
                                      "map_route",
                                      "mode_particle",
                                      "mode_x",
                                      "mode_y",
                                      "mode_share",
                                      "acceleration_max",
                                      "status",
                                      "reason"});
  for (std::size_t k = 0; k < cases.size(); ++k)
    for (const VerdictRecord& r : outcomes[k].verdicts) {
      const StabilityVerdict& v = r.verdict;
      const bool ok = r.reached && v.status == Status::Successful;
      w.row({cases[k].form,
             cases[k].name,
             cases[k].scene.spacing,
             r.wanted,
             r.reached ? r.t : std::nan(""),
             r.reached ? 1 : 0,
             ok ? v.letter() : std::string("-"),
             v.semi_discrete_growth,
             v.map_growth,
             v.integrator_excess,
             v.floor,
             v.lambda_max,
             v.resolution,
             v.map_route,
             v.semi_discrete_mode.particle,
             r.mode_position.x(),
             r.mode_position.y(),
             v.semi_discrete_mode.particle_share,
             r.reached ? r.acceleration_max : std::nan(""),
             r.reached ? status_name(v.status) : std::string("not-reached"),
             r.reached ? v.reason : std::string("the run stopped before this time")});
    }
}

/// The options every impact study takes. The driver sets their defaults, and their --quick values through prepare.
struct StudyOptions {
  std::string out;               ///< --out: the output directory
  std::vector<double> spacings;  ///< --spacings: the runs' particle spacings dx (cm)
  double snapshot_spacing = 0;   ///< dx (cm) of the runs with snapshots (not an option)
  double verdict_spacing = 0.1;  ///< --verdict-spacing: dx (cm) of the runs whose states get a stability verdict
  double t_end = 0;              ///< --t-end: run length (us)
  int threads = 2;               ///< --threads: concurrent runs
  bool quick = false;            ///< --quick: the study's quick case
};

/// What differs between the studies' options: the help of --spacings and --verdict-spacing (the beam's spacings must
/// divide its clamp), the upper bound of --verdict-spacing (the lower is 0.02 cm in every study) and the help of
/// --quick (the study's quick case).
struct OptionTexts {
  std::string spacings = "particle spacings dx (cm)";
  std::string verdict_spacing = "dx (cm) of the runs whose states get a stability verdict";
  double verdict_spacing_max = 0.1;
  std::string quick;
};

/// Adds --out, --spacings, --t-end, --threads, --verdict-spacing and --quick, read into `o`.
inline void add_options(CLI::App& app, StudyOptions& o, const OptionTexts& texts) {
  app.add_option("--out", o.out, "output directory");
  app.add_option("--spacings", o.spacings, texts.spacings)->check(CLI::PositiveNumber);
  app.add_option("--t-end", o.t_end, "run length (us)")->check(CLI::PositiveNumber);
  app.add_option("--threads", o.threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--verdict-spacing", o.verdict_spacing, texts.verdict_spacing)
      ->check(CLI::Range(0.02, texts.verdict_spacing_max));
  app.add_flag("--quick", o.quick, texts.quick);
}

/// After parsing: refuses a --t-end that is not finite and > 0, then with --quick calls `apply_quick` (the driver's
/// quick settings; after the check, so a bad --t-end is an error with --quick too), creates o.out and points the VTK
/// series at o.out/vtk.
template <class Quick>
void prepare(StudyOptions& o, Settings& settings, Quick apply_quick) {
  if (!std::isfinite(o.t_end) || !(o.t_end > 0))  // NaN would mean the scene's default t_end
    throw std::invalid_argument("--t-end must be finite and > 0");
  if (o.quick) apply_quick();
  std::filesystem::create_directories(o.out);
  settings.vtk_dir = o.out + "/vtk";
  set_threads(1);  // cases run side by side; each on one thread (CPU seconds are per run)
}

/// Runs the study's cases, then its verdict cases, each set on o.threads threads; writes signals.csv, runs.csv,
/// snapshots.csv and order.csv (the cases) and verdicts.csv to o.out. Returns the number of completed cases.
inline int run_study(const StudyOptions& o, const std::vector<Case>& cases, const std::vector<Case>& verdict_cases,
                     const Settings& settings) {
  const int completed = write_runs(o.out, cases, run_cases(cases, settings, o.threads), settings);
  write_verdicts(o.out, verdict_cases, run_cases(verdict_cases, settings, o.threads));
  return completed;
}

/// "0.05, 0.025, ..." for the summary.
inline std::string list(const std::vector<double>& values) {
  std::string t;
  for (double v : values) t += (t.empty() ? "" : ", ") + sig(v);
  return t;
}

/// The summary keys every impact study writes: the runs, the resolutions, the speed and the integrator settings
/// (wall_seconds: since wall0, to now).
inline void set_run_keys(Summary& s, std::size_t runs, int completed, const StudyOptions& o, double speed,
                         const Settings& settings, Clock::time_point wall0) {
  s.set("runs", static_cast<long>(runs));
  s.set("completed", completed);
  s.set("spacings", list(o.spacings));
  s.set("snapshot_spacing", o.snapshot_spacing);
  s.set("speed", speed);
  s.set("tssfac", settings.tssfac);
  s.set("xsph", settings.xsph);
  s.set("t_end", o.t_end);
  s.set("quick", o.quick ? "yes" : "no");
  s.set("wall_seconds", seconds_since(wall0));
}

/// The summary keys of a study's snapshot times and of its body's size (length, height of `problem`'s defaults,
/// problem_defaults); returns those defaults, for the study's own keys.
inline PowellImpactOptions set_body_keys(Summary& s, ImpactProblem problem, const std::vector<double>& snapshot_times) {
  const PowellImpactOptions body = problem_defaults({.problem = problem});
  s.set("snapshot_times", list(snapshot_times));
  s.set("length", body.length);
  s.set("height", body.height);
  return body;
}

}  // namespace sphstab::study::impact
