// Issue 35 item 1: should GMS's scenes step with one rate evaluation per step? PC2 is GMS's predictor-corrector
// [GMS2001, (6.14)-(6.18)] with F^0 evaluated at every step's start (two rates per step); PC1 takes F^0 from the
// previous step's corrector evaluation (RateFormRunOptions::reuse_corrector_rate, one rate per step). Both carry GMS's
// XSPH-moved, uncorrected positions. Per scene (GMS units, GMS's scheme, the pair loop), from the same state:
// PC2 and PC1 at the scene's time step dt0 (CFL 0.5, the CLI's default), dt0 / 2 and dt0 / 4, and a reference PC2 run
// at dt0 / R; the error of a run is the largest particle displacement from the reference at the common end time, in
// particle spacings. The cost of a run is its rate evaluations (machine independent) and its thread CPU time.
// The decision rule, fixed before the data (README.md): PC1 becomes a scene's default where the scene admits it, PC1
// completes the horizon at dt0, and PC1 at dt0 / 2 (the rate evaluations of PC2 at dt0) is at least as accurate as PC2
// at dt0.
// Writes to --out DIR: runs.csv, summary.json.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/driver.hpp"
#include "common/study.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/integrate/run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/gms_scenes.hpp"

using namespace sphstab;

namespace {

constexpr double kCfl = 0.5;               // `sphstab scene`'s default for the GMS scenes
constexpr int kRefinements[] = {1, 2, 4};  // dt = dt0 / refinement
const double kNaN = std::numeric_limits<double>::quiet_NaN();

struct SceneCase {
  std::string name;
  Scene<2> scene;
  double dt0 = 0;
  long base_steps = 0;  ///< the horizon in steps of dt0
  int reference = 0;    ///< the reference run's refinement
};

struct Run {
  int scene = 0;
  bool pc1 = false;
  int refinement = 1;
};

struct Outcome {
  std::string status = "completed", reason;
  long steps = 0, evaluations = 0;
  double cpu = 0, error = kNaN, kinetic = kNaN, measure = kNaN;
  Eigen::Matrix2Xd x;
};

SceneCase plate_case(bool quick) {
  SceneCase c{.name = "plate"};
  // GMS's table resolution (10 across H = 2), V_f = 0.01; half a thin-plate period (t_end is 1.25 of them)
  c.scene = gms_plate_scene({.length = 20, .thickness = 2, .across = quick ? 6 : 10}, 0.01, {});
  c.dt0 = c.scene.time_step(kCfl);
  c.base_steps = std::lround((quick ? 0.05 : 0.4) * c.scene.t_end / c.dt0);
  c.reference = quick ? 8 : 32;
  return c;
}

SceneCase rings_case(bool quick) {
  SceneCase c{.name = "rings"};
  // the GMS-unit rings at dp = 0.1 (0.2 quick), from the start through the first 30 time units of the impact
  c.scene = gms_rings_scene({.spacing = quick ? 0.2 : 0.1, .speed = 0.059}, {});
  c.dt0 = c.scene.time_step(kCfl);
  c.base_steps = std::lround((quick ? 10.0 : 30.0) / c.dt0);
  c.reference = quick ? 8 : 32;
  return c;
}

Outcome run(const SceneCase& c, bool pc1, int refinement) {
  Outcome o;
  const RateFormScheme<2>& scheme = *c.scene.scheme;
  const double dt = c.dt0 / refinement;
  RateFormRunOptions opt{.dt = dt,
                         .t_end = dt * static_cast<double>(c.base_steps * refinement),
                         .yield_stress = c.scene.yield_stress,
                         .neighbour_skin = c.scene.neighbour_skin};
  opt.reuse_corrector_rate = pc1;
  const double cpu0 = study::thread_cpu_seconds();
  try {
    RateFormStepper<2> stepper(scheme, c.scene.y0, opt);
    // the run loop, exactly base_steps x refinement steps of dt (no last-step adjustment to t_end)
    const RunResult rr = sphstab::run(stepper, {.dt = dt, .max_steps = c.base_steps * refinement}, "gms-pc1");
    o.steps = rr.steps;
    o.evaluations = stepper.evaluations();
    const Eigen::VectorXd& y = stepper.state();
    if (!rr.completed()) {
      o.status = run_status_name(rr.status);
      o.reason = rr.reason;
    } else {
      o.x = rate_form_positions(scheme, y);
      o.kinetic = scheme.kinetic_energy(y);
      o.measure = c.scene.measures.front().value(o.x, y);
    }
  } catch (const std::invalid_argument& e) {
    o.status = "refused";  // the scheme does not admit this integrator (e.g. PC1 with a yield stress)
    o.reason = e.what();
  } catch (const std::exception& e) {
    o.status = "failed";
    o.reason = e.what();
  }
  o.cpu = study::thread_cpu_seconds() - cpu0;
  return o;
}

/// Largest particle displacement between two end states, in particle spacings.
double distance(const Eigen::Matrix2Xd& a, const Eigen::Matrix2Xd& b, double dp) {
  if (a.cols() == 0 || b.cols() != a.cols()) return kNaN;
  return (a - b).colwise().norm().maxCoeff() / dp;
}

std::string name_of(const Run& r) { return r.pc1 ? "PC1" : "PC2"; }

}  // namespace

int main(int argc, char** argv) try {
  study::DriverCli cli{"Issue 35: GMS's predictor-corrector with one rate per step (PC1) against two (PC2), per scene",
                       "results/gms-pc1",
                       "pipeline check: the plate 6 across over 0.04 periods, the rings at dp = 0.2 over 10 time "
                       "units, references at dt0 / 8"};
  int threads = 2;
  cli.add_threads(threads, "runs side by side (each on one thread)");
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  const auto t0 = study::Clock::now();

  // ---- 1. The scenes and the runs: PC2 and PC1 at dt0 / {1, 2, 4}, the reference PC2 at dt0 / R. ----
  std::vector<SceneCase> scenes = {plate_case(cli.quick), rings_case(cli.quick)};
  std::vector<Run> runs;
  for (int s = 0; s < static_cast<int>(scenes.size()); ++s) {
    runs.push_back({s, false, scenes[s].reference});
    for (bool pc1 : {false, true})
      for (int r : kRefinements) runs.push_back({s, pc1, r});
  }
  const std::vector<Outcome> outcomes = study::run_costliest_first(
      runs, threads,
      [&](const Run& r) {
        return static_cast<double>(r.refinement * (r.pc1 ? 1 : 2) * scenes[r.scene].base_steps) *
               scenes[r.scene].scene.scheme->size();
      },
      [&](const Run& r) { return run(scenes[r.scene], r.pc1, r.refinement); });
  // GMS's slab has a yield stress: does the one-rate step admit it? (one step suffices to ask)
  SceneCase slab{.name = "slab", .scene = gms_slab_scene({.spacing = 0.1}, 0.03, {})};
  slab.dt0 = slab.scene.time_step(kCfl);
  slab.base_steps = 1;
  const Outcome slab_pc1 = run(slab, true, 1);

  // ---- 2. runs.csv: every run's cost and its error against its scene's reference. ----
  CsvWriter csv(cli.out + "/runs.csv", {"scene", "integrator", "refinement", "dt", "t_end", "steps", "rate_evaluations",
                                        "cpu_s", "status", "error_dp", "end_measure", "end_kinetic"});
  study::Summary summary;
  std::string table;
  for (int s = 0; s < static_cast<int>(scenes.size()); ++s) {
    const SceneCase& c = scenes[s];
    const Outcome* ref = nullptr;
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (runs[k].scene == s && runs[k].refinement == c.reference) ref = &outcomes[k];
    double error[2][3] = {{kNaN, kNaN, kNaN}, {kNaN, kNaN, kNaN}}, cpu[2][3] = {};
    long evaluations[2][3] = {};
    for (std::size_t k = 0; k < runs.size(); ++k) {
      if (runs[k].scene != s) continue;
      const Outcome& o = outcomes[k];
      const double e = &o == ref ? 0.0 : distance(o.x, ref->x, c.scene.spacing);
      csv.row({c.name, name_of(runs[k]), runs[k].refinement, c.dt0 / runs[k].refinement,
               c.dt0 * static_cast<double>(c.base_steps), o.steps, o.evaluations, o.cpu,
               o.status + (o.reason.empty() ? "" : ": " + o.reason), e, o.measure, o.kinetic});
      study::md_row(table, {c.name, &o == ref ? "PC2 (reference)" : name_of(runs[k]),
                            "dt0 / " + std::to_string(runs[k].refinement), std::to_string(o.evaluations),
                            study::sig(o.cpu, 3), &o == ref ? "0" : study::sig(e, 3), o.status});
      for (int i = 0; i < 3; ++i)
        if (&o != ref && runs[k].refinement == kRefinements[i])
          error[runs[k].pc1][i] = e, cpu[runs[k].pc1][i] = o.cpu, evaluations[runs[k].pc1][i] = o.evaluations;
    }
    // ---- 3. Key numbers and the decision, from the errors above. ----
    const std::string p = c.name + "_";
    summary.set(p + "particles", c.scene.scheme->discretisation().size());
    summary.set(p + "dt0", c.dt0, 4);
    summary.set(p + "t_end", c.dt0 * static_cast<double>(c.base_steps), 4);
    summary.set(p + "steps", c.base_steps);
    summary.set(p + "reference", c.reference);
    const std::vector<double> dts = {c.dt0, c.dt0 / 2, c.dt0 / 4};
    for (int pc1 = 0; pc1 < 2; ++pc1) {
      const std::string q = p + (pc1 ? "pc1_" : "pc2_");
      for (int i = 0; i < 3; ++i) summary.set(q + "error_" + std::to_string(kRefinements[i]), error[pc1][i], 3);
      summary.set(q + "order", study::loglog_slope(dts, {error[pc1][0], error[pc1][1], error[pc1][2]}), 3);
      summary.set(q + "evaluations_1", evaluations[pc1][0]);
    }
    const double equal_cost = error[1][1] / error[0][0], half_cost = error[1][0] / error[0][0];
    summary.set(p + "equal_cost_ratio", equal_cost, 3);
    summary.set(p + "half_cost_ratio", half_cost, 3);
    summary.set(p + "cpu_ratio", cpu[1][0] / cpu[0][0], 3);
    const bool pc1_completes = std::isfinite(error[1][0]);
    summary.set(p + "decision", pc1_completes && equal_cost <= 1 ? "PC1" : "PC2");
  }
  summary.set("runs_table", table);
  summary.set("slab_pc1", slab_pc1.status + (slab_pc1.reason.empty() ? "" : ": " + slab_pc1.reason));
  summary.set("slab_decision", slab_pc1.status == "refused" ? "PC2" : "undecided (no slab runs)");
  study::write_summary(summary, cli.out, t0, {.load = true, .threads = threads});
  return 0;
} catch (const std::exception& e) {
  return study::exit_on_error("gms-pc1", e);
}
