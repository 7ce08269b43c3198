// Study: Powell's symmetric impact [Powell2012, ch. 4 §4.1, Figs. 4.5-4.9] with basic SPH, NCSPH, S-SPH and TL-SPH
// (problems/powell_impact.hpp), in initial compression (v0 > 0) and initial expansion (v0 < 0), at several
// resolutions. The rate forms run MCM's configuration: the staggered leap-frog (algorithm 1.1) with the velocity
// smoothing (2.71) eps = 0.1 and the material card's bulk viscosity, dt = TSSFAC h / c_P; TL-SPH the linear
// total-Lagrangian form with the velocity-Verlet leap-frog at the same dt. The finite-element reference and the
// errors against it are the post-processing step (fe_reference.py, called by plot.py).
//
// Writes to --out DIR: signals.csv (t, global KE, pressure and speed at particle A, per run), runs.csv (status,
// steps, CPU seconds), snapshots.csv (every particle's position and pressure at Powell's figure time, at the
// snapshot resolution), summary.json. Units g, cm, us (stress in Mbar).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/powell_impact.hpp"

using namespace sphstab;

namespace {

struct Config {
  std::string out = "results/powell-symmetric-impact";
  std::vector<double> spacings{0.05, 0.025, 0.02, 0.0125, 0.01, 0.00625};
  double snapshot_spacing = 0.02;  // the MCM deck's
  std::vector<std::string> formulations{"sph", "ncsph", "ssph", "tl"};
  double speed = 0.06;    // |v0| [§4.1, Fig. 4.5]
  double tssfac = 0.8;    // MCM deck, card 2
  double xsph = 0.1;      // Powell (2.71)
  double t_end = 6;       // us
  int threads = 2;
};

struct Case {
  std::string form;
  double v0 = 0, dx = 0;
  std::string name() const { return v0 > 0 ? "compression" : "expansion"; }
};

struct Snapshot {
  double t = 0;
  Eigen::Matrix2Xd x;
  Eigen::VectorXd p;
};

struct Outcome {
  RunResult run;
  int particles = 0, particle_a = -1;
  Eigen::Vector2d x_a = Eigen::Vector2d::Zero();
  Eigen::Matrix2Xd x0;  // initial positions (snapshot runs)
  double cpu = 0;
  std::vector<double> t, ke, p_a, speed_a;
  std::vector<Snapshot> snaps;
};

/// Powell's figure time of the case (Fig. 4.6: 3.05 us in compression; Fig. 4.8: 1.6 us in expansion).
std::vector<double> snapshot_times(const Case& c) { return {c.v0 > 0 ? 3.05 : 1.6}; }

/// Takes a snapshot at the first record at or after each wanted time.
template <class Fields>
void maybe_snapshot(Outcome& o, const std::vector<double>& wanted, double t, double dt, Fields fields) {
  for (double w : wanted)
    if (t >= w - 0.5 * dt && t < w + 0.5 * dt) {
      Snapshot s{t, {}, {}};
      fields(s);
      o.snaps.push_back(std::move(s));
    }
}

Outcome run_case(const Case& c, const Config& cfg, bool snapshots) {
  Outcome o;
  const bool tl = c.form == "tl";
  const PowellImpactOptions po{.problem = ImpactProblem::Symmetric,
                               .spacing = c.dx,
                               .speed = c.v0,
                               .t_end = cfg.t_end,
                               .scheme = powell_formulation_options(tl ? "sph" : c.form)};
  const Scene<2> scene = powell_impact_scene(po);
  const int a = impact_particle_a(po);
  o.particle_a = a;
  o.particles = scene.scheme->discretisation().size();
  o.x_a = scene.scheme->discretisation().particles.x.row(a).transpose();
  if (snapshots) o.x0 = scene.scheme->discretisation().particles.x.transpose();
  const double dt = scene.time_step(cfg.tssfac);
  const std::vector<double> wanted = snapshots ? snapshot_times(c) : std::vector<double>{};
  const double cpu0 = study::thread_cpu_seconds();
  if (!tl) {
    const RateFormScheme<2>& scheme = *scene.scheme;
    const auto& pressure = scene.measure("pressure_A");
    const auto& speed = scene.measure("speed_A");
    RateFormRunOptions ro{.dt = dt,
                          .t_end = scene.t_end,
                          .integrator = RateFormIntegrator::Leapfrog,
                          .leapfrog_xsph = cfg.xsph,
                          .neighbour_skin = scene.neighbour_skin};
    ro.observer = [&](long, double t, const Eigen::VectorXd& y) {
      const Eigen::Matrix2Xd x = rate_form_positions(scheme, y);
      o.t.push_back(t);
      o.p_a.push_back(pressure.value(x, y));
      o.speed_a.push_back(speed.value(x, y));
      maybe_snapshot(o, wanted, t, ro.dt, [&](Snapshot& s) {
        s.x = x;
        s.p = scene.scheme->material().bulk_modulus *
              (rate_form_densities(scheme, y).array() / scene.scheme->material().density - 1).matrix();
      });
    };
    const RateFormRunResult r = run_rate_form(scheme, scene.y0, ro);
    o.run = r;
    o.ke = r.kinetic_energy;
  } else {
    const ImpactTotalLagrangian m = impact_total_lagrangian(scene);
    const auto& disc = scene.scheme->discretisation();
    const Eigen::Matrix2Xd x0 = disc.particles.x.transpose();
    LeapfrogOptions lo;
    lo.dt = dt;
    lo.t_end = scene.t_end;
    lo.record_every = 1;
    lo.observe_every = 1;
    lo.observer = [&](const StepView& v) {
      o.t.push_back(v.time);
      o.p_a.push_back(m.pressure(v.u, a));
      o.speed_a.push_back(v.v.segment<2>(2 * disc.free_slot[a]).norm());
      maybe_snapshot(o, wanted, v.time, lo.dt, [&](Snapshot& s) {
        s.x = x0;
        s.p.resize(disc.size());
        for (int i = 0; i < disc.size(); ++i) {
          if (disc.free_slot[i] >= 0) s.x.col(i) += v.u.segment<2>(2 * disc.free_slot[i]);
          s.p[i] = m.pressure(v.u, i);
        }
      });
    };
    const LeapfrogResult r = run_leapfrog(m.system, Eigen::VectorXd::Zero(m.form->dofs()), m.v0, lo);
    o.run = r;
    for (const Diagnostics& d : r.history) o.ke.push_back(d.kinetic);
  }
  o.cpu = study::thread_cpu_seconds() - cpu0;
  if (o.ke.size() != o.t.size())
    throw std::runtime_error(c.form + " " + c.name() + ": " + std::to_string(o.ke.size()) + " energy records for " +
                             std::to_string(o.t.size()) + " observed states");
  return o;
}

}  // namespace

int main(int argc, char** argv) try {
  Config cfg;
  bool quick = false;
  CLI::App app{"Powell ch. 4 §4.1: symmetric impact with SPH, NCSPH, S-SPH and TL-SPH"};
  app.add_option("--out", cfg.out, "output directory");
  app.add_option("--spacings", cfg.spacings, "particle spacings dx (cm)")->check(CLI::PositiveNumber);
  app.add_option("--t-end", cfg.t_end, "run length (us)")->check(CLI::PositiveNumber);
  app.add_option("--threads", cfg.threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_flag("--quick", quick, "one coarse resolution (dx 0.05), to t = 2 us");
  CLI11_PARSE(app, argc, argv);
  if (!std::isfinite(cfg.t_end) || !(cfg.t_end > 0))  // NaN would mean the scene's default t_end
    throw std::invalid_argument("--t-end must be finite and > 0");
  if (quick) cfg.spacings = {0.05}, cfg.snapshot_spacing = 0.05, cfg.t_end = 2;
  std::filesystem::create_directories(cfg.out);
  set_threads(1);  // cases run side by side; each on one thread (CPU seconds are per run)

  std::vector<Case> cases;
  for (double dx : cfg.spacings)
    for (double sign : {1.0, -1.0})
      for (const std::string& f : cfg.formulations) cases.push_back({f, sign * cfg.speed, dx});
  std::vector<Outcome> outcomes(cases.size());
  const auto wall0 = study::Clock::now();
  study::parallel_for(cases.size(), cfg.threads, [&](std::size_t k) {
    const Case& c = cases[k];
    outcomes[k] = run_case(c, cfg, std::abs(c.dx - cfg.snapshot_spacing) < 1e-12);
    std::fprintf(stderr, "  %-6s %-11s dx %-5g: %s (%.1f s CPU)\n", c.form.c_str(), c.name().c_str(), c.dx,
                 outcomes[k].run.message.c_str(), outcomes[k].cpu);
  });

  CsvWriter signals(cfg.out + "/signals.csv",
                    {"formulation", "case", "dx", "t", "kinetic_energy", "pressure_A", "speed_A"}, false);
  CsvWriter runs(cfg.out + "/runs.csv", {"formulation", "case", "dx", "v0", "particles", "particle_A", "x_A", "y_A", "dt", "steps",
                                         "status", "t_stop", "cpu_seconds", "message"});
  CsvWriter snaps(cfg.out + "/snapshots.csv", {"formulation", "case", "dx", "t", "particle", "x0", "y0", "x", "y", "pressure"},
                  false);
  int completed = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const Outcome& o = outcomes[k];
    for (std::size_t r = 0; r < o.t.size(); ++r)
      signals.row({c.form, c.name(), c.dx, o.t[r], o.ke[r], o.p_a[r], o.speed_a[r]});
    runs.row({c.form, c.name(), c.dx, c.v0, o.particles, o.particle_a, o.x_a.x(), o.x_a.y(), o.run.dt, o.run.steps,
              run_status_name(o.run.status), o.run.time, o.cpu, o.run.message});
    completed += o.run.completed();
    for (const Snapshot& s : o.snaps)
      for (int i = 0; i < s.x.cols(); ++i) snaps.row({c.form, c.name(), c.dx, s.t, i, o.x0(0, i), o.x0(1, i), s.x(0, i), s.x(1, i), s.p[i]});
  }
  study::Summary s;
  s.set("runs", static_cast<long>(cases.size()));
  s.set("completed", completed);
  s.set("spacings", [&] {
    std::string t;
    for (double dx : cfg.spacings) t += (t.empty() ? "" : ", ") + study::sig(dx);
    return t;
  }());
  s.set("snapshot_spacing", cfg.snapshot_spacing);
  s.set("speed", cfg.speed);
  s.set("tssfac", cfg.tssfac);
  s.set("xsph", cfg.xsph);
  s.set("t_end", cfg.t_end);
  s.set("quick", quick ? "yes" : "no");
  s.set("wall_seconds", study::seconds_since(wall0));
  s.write(cfg.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "powell-symmetric-impact: error: %s\n", e.what());
  return 1;
}
