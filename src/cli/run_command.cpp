// `sphstab run`: the rate-form SPH scheme (forms/rate_form.hpp) run in time on a lattice (integrate/rate_form_run.hpp),
// its time series printed as CSV. The scene is the library's Swegle block (problems/rate_form_block.hpp: fixed layers,
// the free particle nearest the centre gets the velocity V0 along x) or a periodic lattice (a sinusoidal velocity V0
// sin(k (x - x_lo)) along x at the shortest wavelength the box holds). A run that stops (non-finite state, density <=
// 0, kinetic-energy growth beyond --energy-growth: rate_form_run's statuses; a particle moved beyond
// --max-displacement: this command's check, since the run never rebuilds its neighbour list; a numerical exception in
// the scheme) keeps the rows printed so far and ends with a row that names the status, the step, the time and the
// particle; it is a result (exit 0), not an input error.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "parse.hpp"
#include "rate_form_args.hpp"
#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/growth/rate_form_time_step.hpp"
#include "sphstab/integrate/linear_step_map.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/progress.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/models/von_mises.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab::cli {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct RunArgs {
  RateFormArgs scheme;
  std::string kick = "1e-10", integrator = "leapfrog", dt, cfl = "0.5", t_end, record_every = "10", yield,
              energy_growth, max_displacement = "1", out;
  bool block = false;
};

/// The run's own options, parsed.
struct RunSetup {
  RateFormSetup scheme;
  double kick = 0;
  RateFormIntegrator integrator = RateFormIntegrator::Leapfrog;
  bool reuse_rate = false;  ///< pc1: the predictor-corrector with one rate evaluation per step
  double dt = kNaN;         ///< NaN: cfl x the leap-frog limit
  double cfl = 0.5;
  double t_end = kNaN;  ///< NaN: 1000 dt
  int record_every = 10;
  double yield = std::numeric_limits<double>::infinity();
  double energy_growth = std::numeric_limits<double>::infinity();
  double max_displacement = 1;  ///< in dx; infinity: off
  std::string out;
};

std::string num(double v) { return format_csv_cell(CsvCell(v)); }

double positive(const std::string& text, const std::string& what) {
  const double v = parse_double(text, what);
  if (!(v > 0)) throw std::invalid_argument(what + " must be > 0 (got " + text + ")");
  return v;
}

RunSetup parse_run_args(const RunArgs& a) {
  RunSetup r;
  r.scheme = parse_rate_form_args(a.scheme, "run", false, 3, 10'000'000, 10'000);
  if (a.block && a.scheme.periodic) throw std::invalid_argument("run: --block and --periodic exclude each other");
  r.kick = parse_double(a.kick, "run: --kick");
  RateFormRunOptions chosen;
  select_rate_form_integrator(chosen, a.integrator);
  r.integrator = chosen.integrator;
  r.reuse_rate = chosen.reuse_corrector_rate;
  if (!a.dt.empty()) r.dt = positive(a.dt, "run: --dt");
  r.cfl = positive(a.cfl, "run: --cfl");
  if (!a.t_end.empty()) r.t_end = positive(a.t_end, "run: --t-end");
  r.record_every = static_cast<int>(parse_integer(a.record_every, 1, 1'000'000'000, "run: --record-every"));
  if (!a.yield.empty()) r.yield = positive(a.yield, "run: --yield");
  if (r.reuse_rate && !a.yield.empty())
    throw std::invalid_argument(
        "run: --integrator pc1 with --yield: the radial return changes S after the rate that "
        "pc1 reuses (use pc)");
  if (!a.energy_growth.empty()) {
    r.energy_growth = parse_double(a.energy_growth, "run: --energy-growth");
    if (!(r.energy_growth > 1))
      throw std::invalid_argument("run: --energy-growth must be > 1 (got " + a.energy_growth + ")");
    if (r.kick == 0)
      throw std::invalid_argument(
          "run: --energy-growth compares with the initial kinetic energy: it needs --kick != 0");
  }
  r.max_displacement = a.max_displacement == "off" ? std::numeric_limits<double>::infinity()
                                                   : positive(a.max_displacement, "run: --max-displacement");
  r.out = a.out;
  return r;
}

/// The default step: cfl x the leap-frog limit 2 / max |Im lambda| of the spectrum at rest
/// (growth/rate_form_time_step.hpp), for either integrator. The predictor-corrector has no stable step when the
/// spectrum is undamped (Heun amplifies every oscillation, integrate/time_step.hpp), so it gets the same scale and a
/// note on stderr with its amplification per step.
template <int Dim>
double default_time_step(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& rest, const RunSetup& r) {
  const long m = static_cast<long>(Dim) * scheme.discretisation().free_count();
  if (m > 3000)
    std::fprintf(stderr,
                 "run: the default dt needs the eigenvalues of a dense %ld x %ld matrix (minutes; --dt skips it)\n", m,
                 m);
  const RateFormTimeStep ts = rate_form_time_step(scheme, rest);
  if (ts.info() != Status::Successful)
    throw std::invalid_argument("run: the stability limit for the default dt failed (" + ts.reason + "); give --dt");
  if (!std::isfinite(ts.leapfrog))
    throw std::invalid_argument(
        "run: no oscillatory mode at rest, so no stability limit for the default dt; give --dt");
  const double dt = r.cfl * ts.leapfrog;
  if (r.integrator == RateFormIntegrator::PredictorCorrector && !(dt <= ts.predictor_corrector))
    std::fprintf(stderr,
                 "run: note: dt = %s x the leap-frog limit %s; the predictor-corrector is stable only below %s and "
                 "amplifies the fastest mode by %s per step at this dt (integrate/time_step.hpp)\n",
                 format_number(r.cfl).c_str(), format_number(ts.leapfrog).c_str(),
                 format_number(ts.predictor_corrector).c_str(),
                 format_number(heun_amplification(dt * ts.dominant), 8).c_str());
  return dt;
}

double worst_max(double m, double v) { return (std::isnan(v) || v > m) ? v : m; }
double worst_min(double m, double v) { return (std::isnan(v) || v < m) ? v : m; }

/// One CSV row's state measures.
struct Measures {
  double kinetic = 0, max_speed = 0, min_density = INFINITY, max_density = -INFINITY, max_displacement = 0,
         max_von_mises = 0;
  int moved_most = -1;  ///< the particle of max_displacement
};

/// Measures of y; a NaN anywhere propagates into the measure it enters (a failing state shows as nan, not as the
/// extreme of the finite entries).
template <int Dim>
Measures measure(const RateFormScheme<Dim>& s, const Eigen::VectorXd& y) {
  const Discretisation<Dim>& d = s.discretisation();
  Measures m;
  m.kinetic = s.kinetic_energy(y);
  for (int i = 0; i < d.size(); ++i) {
    if (const int xo = s.position_offset(i); xo >= 0) {
      m.max_speed = worst_max(m.max_speed, y.template segment<Dim>(xo + Dim).stableNorm());
      // stableNorm: a displacement of 1e300 is reported as such, not as inf (the squared norm would overflow)
      const Eigen::Matrix<double, Dim, 1> du = y.template segment<Dim>(xo) - d.particles.x.row(i).transpose();
      const double u = du.stableNorm();
      if (worst_max(m.max_displacement, u) != m.max_displacement) m.moved_most = i;
      m.max_displacement = worst_max(m.max_displacement, u);
    }
    if (const int ro = s.density_offset(i); ro >= 0) {
      m.min_density = worst_min(m.min_density, y[ro]);
      m.max_density = worst_max(m.max_density, y[ro]);
      m.max_von_mises =
          worst_max(m.max_von_mises, von_mises_stress<Dim>(y.template segment<kDeviatorEntries<Dim>>(ro + 1)));
    }
  }
  return m;
}

/// Snapshots of every particle as <dir>/run_<step>.vtp and the index <dir>/run.pvd (rewritten each time, so it stays
/// valid if the run stops): current positions; velocity, displacement, density, pressure K (rho/rho0 - 1), the stored
/// deviator, the von Mises stress and fixed (0/1).
template <int Dim>
class Snapshots {
 public:
  Snapshots(const RateFormScheme<Dim>& s, std::string dir) : m_s(s), m_dir(std::move(dir)) {
    std::filesystem::create_directories(m_dir);
  }
  void write(long step, double time, const Eigen::VectorXd& y) {
    const Discretisation<Dim>& d = m_s.discretisation();
    constexpr int ks = RateFormScheme<Dim>::kStress;
    const int n = d.size();
    Eigen::MatrixXd x = d.particles.x;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(Dim * n), u = v, rho(n), p(n), S = Eigen::VectorXd::Zero(ks * n),
                    vm = Eigen::VectorXd::Zero(n), fixed(n);
    for (int i = 0; i < n; ++i) {
      fixed[i] = m_s.position_offset(i) < 0;
      if (const int xo = m_s.position_offset(i); xo >= 0) {
        x.row(i) = y.template segment<Dim>(xo).transpose();
        u.template segment<Dim>(Dim * i) = y.template segment<Dim>(xo) - d.particles.x.row(i).transpose();
        v.template segment<Dim>(Dim * i) = y.template segment<Dim>(xo + Dim);
      }
      const int ro = m_s.density_offset(i);
      rho[i] = ro >= 0 ? y[ro] : m_s.initial_density();
      p[i] = m_s.material().bulk_modulus() * (rho[i] / m_s.material().density() - 1);
      if (ro >= 0) {
        S.template segment<ks>(ks * i) = y.template segment<ks>(ro + 1);
        vm[i] = von_mises_stress<Dim>(y.template segment<ks>(ro + 1));
      }
    }
    char name[40];
    std::snprintf(name, sizeof(name), "run_%06ld.vtp", step);
    write_vtp(m_dir + "/" + name, x,
              {{"velocity", Dim, v},
               {"displacement", Dim, u},
               {"density", 1, rho},
               {"pressure", 1, p},
               {"deviator", ks, S},
               {"von_mises", 1, vm},
               {"fixed", 1, fixed}});
    m_pvd.emplace_back(time, name);
    write_pvd(m_dir + "/run.pvd", m_pvd);
  }

 private:
  const RateFormScheme<Dim>& m_s;
  std::string m_dir;
  std::vector<std::pair<double, std::string>> m_pvd;
};

/// The CSV on stdout, one record late: the last row printed carries the run's final status, the others "running".
class Series {
 public:
  explicit Series(double dt) : m_dt(dt) {}
  void record(long step, double time, const Measures& m) {
    if (m_pending) print(*m_pending, "running", -1);
    m_pending = Row{step, time, m};
  }
  bool started() const { return m_pending.has_value(); }
  long last_step() const { return m_pending ? m_pending->step : -1; }
  /// Ends the series: the pending row gets the status if it is the stopping step, otherwise it is printed as
  /// running and the stopping state (step, time, measures) follows with the status.
  void finish(const std::string& status, int particle, long step, double time, const Measures& last) {
    if (m_pending && m_pending->step == step) {
      print(*m_pending, status, particle);
    } else {
      if (m_pending) print(*m_pending, "running", -1);
      print(Row{step, time, last}, status, particle);
    }
    m_pending.reset();
  }
  /// Ends the series at the pending row (a run stopped by the command at that record, or ended by an exception after
  /// it).
  void finish_pending(const std::string& status, int particle) {
    if (m_pending) print(*m_pending, status, particle);
    m_pending.reset();
  }

 private:
  struct Row {
    long step;
    double time;
    Measures m;
  };
  void print(const Row& r, const std::string& status, int particle) {
    if (!m_header) {
      std::fputs(
          "step,time,dt,kinetic_energy,max_speed,min_density,max_density,max_displacement,max_von_mises,status,"
          "particle\n",
          stdout);
      m_header = true;
    }
    const Measures& m = r.m;
    std::fputs(
        csv_line({std::to_string(r.step), num(r.time), num(m_dt), num(m.kinetic), num(m.max_speed), num(m.min_density),
                  num(m.max_density), num(m.max_displacement), num(m.max_von_mises), status, std::to_string(particle)})
            .c_str(),
        stdout);
    std::fflush(stdout);  // a long run can be followed (tail -f) and keeps its rows if killed
  }
  double m_dt;
  bool m_header = false;
  std::optional<Row> m_pending;
};

/// After 2 s of stepping, a run projected to take more than a minute says so on stderr and then reports its progress
/// every 10 s (as `sphstab tcrit`'s sweeps).
class RunProgress {
 public:
  explicit RunProgress(long nsteps) : m_nsteps(nsteps), m_start(std::chrono::steady_clock::now()) {}
  void at(long step) {
    if (step == 0) return;
    if (!m_checked) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
      if (elapsed < 2) return;
      m_checked = true;
      const double total = elapsed * static_cast<double>(m_nsteps) / static_cast<double>(step);
      if (total > 60) {
        std::fprintf(stderr, "run: %ld steps; %ld took %.3g s, so about %.3g min in all\n", m_nsteps, step, elapsed,
                     total / 60);
        m_line.emplace("run", 10.0);
      }
    }
    if (m_line) m_line->update(static_cast<double>(step), static_cast<double>(m_nsteps));
  }

 private:
  long m_nsteps;
  std::chrono::steady_clock::time_point m_start;
  bool m_checked = false;
  std::optional<ProgressLine> m_line;
};

/// Thrown by the observer to stop a run whose particle moved beyond --max-displacement (rate_form_run has no such
/// limit: its neighbour list, built at t = 0, is never rebuilt).
struct DisplacementStop {
  long step;
  double time, displacement;
  int particle;
};

/// Peak memory of a run, estimated before anything is built (the library checks each allocation again): about
/// 250 bytes per particle and 40 per neighbour pair (lattice, neighbour list, state vectors, the scheme's per-pair
/// workspace; measured 36 MB for a 2D 200 x 200 block at h = 1.3 dx, 355 MB for 10^6 particles in 1D), and for the
/// default dt the dense spectrum of the free velocity DOFs (rate_form_spectrum: 8 dense copies).
void require_run_memory(const RunSetup& r) {
  const RateFormSetup& s = r.scheme;
  const BlockSize b = block_size(s);
  const double free = b.free, particles = b.particles, q = b.within(s, 1);
  const std::string what = "run: --dim " + std::to_string(s.dim) + " --n " + std::to_string(s.n);
  if (std::isnan(r.dt))
    require_dense_memory(static_cast<long>(free * s.dim), 8,
                         what + ": the default dt's dense spectrum (give --dt to skip it)");
  require_memory(particles * (250 + 40 * std::min(q, particles)), what + " with h/dx = " + num(s.h_over_dx.front()));
}

template <int Dim>
void run_scheme(const RunSetup& r) {
  const RateFormSetup& s = r.scheme;
  require_run_memory(r);
  // The scene of problems/rate_form_block.hpp: the Swegle block (or periodic lattice) with its kick.
  const Scene<Dim> scene =
      rate_form_block_scene<Dim>(block_options(s, s.kernels.front(), s.h_over_dx.front(), s.xi.front(), r.kick));
  const RateFormScheme<Dim>& scheme = *scene.scheme;
  Eigen::VectorXd y = scheme.uniform_state();  // at rest: the default dt's spectrum
  const double dt_asked = std::isnan(r.dt) ? default_time_step(scheme, y, r) : r.dt;
  const double t_end = std::isnan(r.t_end) ? 1000 * dt_asked : r.t_end;
  require_run_length(t_end, dt_asked, scheme.discretisation().particles.size(), "run");
  // rate_form_run.hpp: "dt is reduced to t_end / ceil(t_end / dt)"; the dt column is that step (the tests compare it
  // with RateFormRunResult::dt).
  const long nsteps =
      std::max(1L, checked_floor_count(std::ceil(t_end / dt_asked - 1e-9), 1L << 53, "run: steps --t-end / dt"));
  const double dt = t_end / static_cast<double>(nsteps);
  require_memory(16.0 * (static_cast<double>(nsteps) / r.record_every + 2) + 64.0 * scheme.size(),
                 "run: " + std::to_string(nsteps) + " steps recorded every " + std::to_string(r.record_every));
  y = scene.y0;
  if (!std::isfinite(scheme.kinetic_energy(y)))  // e.g. --kick 1e200: m v0^2 / 2 overflows before the first step
    throw std::invalid_argument("run: --kick " + format_number(r.kick) +
                                ": the initial kinetic energy m v0^2 / 2 overflows a double; use a smaller kick");

  std::optional<Snapshots<Dim>> snapshots;
  if (!r.out.empty()) snapshots.emplace(scheme, r.out);
  const double max_displacement = r.max_displacement * s.dx;
  Series series(dt);
  RunProgress progress(nsteps);
  RateFormRunOptions o{.dt = dt_asked,
                       .t_end = t_end,
                       .record_every = r.record_every,
                       .energy_growth = r.energy_growth,
                       .observer =
                           [&](long step, double time, const Eigen::VectorXd& state) {
                             const Measures m = measure(scheme, state);
                             series.record(step, time, m);
                             if (snapshots) snapshots->write(step, time, state);
                             progress.at(step);
                             if (m.max_displacement > max_displacement)
                               throw DisplacementStop{step, time, m.max_displacement, m.moved_most};
                           },
                       .integrator = r.integrator,
                       .reuse_corrector_rate = r.reuse_rate,
                       .yield_stress = r.yield};
  RateFormRunResult result;
  try {
    result = run_rate_form(scheme, y, o);
  } catch (const DisplacementStop& stop) {
    series.finish_pending(run_status_name(RunStatus::DisplacementLimit), stop.particle);
    std::fprintf(stderr, "run: stopped: %s: particle %d moved %s > %s dx at step %ld, t = %s\n",
                 run_status_name(RunStatus::DisplacementLimit).c_str(), stop.particle,
                 format_number(stop.displacement).c_str(), format_number(r.max_displacement).c_str(), stop.step,
                 format_number(stop.time).c_str());
    return;
  } catch (const std::domain_error& e) {  // the scheme's numerical failures (e.g. a singular NCSPH moment matrix)
    if (!series.started()) throw;
    std::fprintf(stderr, "run: stopped after step %ld by an exception: %s\n", series.last_step(), e.what());
    series.finish_pending("exception", -1);
    return;
  }
  series.finish(run_status_name(result.status), result.particle, result.steps, result.time, measure(scheme, result.y));
  if (!result.completed()) std::fprintf(stderr, "run: stopped: %s\n", result.message.c_str());
}

void run_run(const RunArgs& a) {
  const RunSetup r = parse_run_args(a);
  if (r.scheme.dim == 1)
    run_scheme<1>(r);
  else
    run_scheme<2>(r);
}

}  // namespace

void register_run_command(CLI::App& app) {
  auto a = std::make_shared<RunArgs>();
  a->scheme.n = "21";
  a->scheme.xi = "1";
  auto* cmd = app.add_subcommand(
      "run",
      "Run the rate-form scheme in time on a Swegle block (fixed layers, centre particle kicked along x) or a periodic "
      "lattice (sinusoidal kick along x); CSV time series of kinetic energy, speed, density, displacement, von Mises "
      "stress, with a final row giving the run's status, step, time and particle");
  add_rate_form_options(*cmd, a->scheme, false);
  cmd->add_flag("--block", a->block, "Swegle block with fixed layers (the default without --periodic)");
  cmd->add_option("--kick", a->kick,
                  "V0: velocity along x of the block's centre particle, or amplitude of the periodic lattice's "
                  "v_x = V0 sin(k (x - x_lo)) at the shortest wavelength (default 1e-10)");
  cmd->add_option("--integrator", a->integrator,
                  "leapfrog (Powell alg. 1.1, the default) | pc (GMS 6.14-6.18 predictor-corrector) | pc1 (the same, "
                  "one rate evaluation per step: a step reuses the previous corrector's rate)");
  auto* dt = cmd->add_option("--dt", a->dt, "time step > 0 (default: --cfl x the leap-frog stability limit)");
  cmd->add_option("--cfl", a->cfl,
                  "default dt as a fraction of the leap-frog limit 2 / max |Im lambda| of the spectrum at rest "
                  "(default 0.5)")
      ->excludes(dt);
  cmd->add_option("--t-end", a->t_end, "run length > 0 (default 1000 dt; dt is reduced to t_end / ceil(t_end / dt))");
  cmd->add_option("--record-every", a->record_every, "a row every k steps, and the last step (default 10)");
  cmd->add_option("--yield", a->yield, "von Mises yield stress Y > 0 (radial return; default: elastic)");
  cmd->add_option("--energy-growth", a->energy_growth,
                  "stop when the kinetic energy exceeds this factor (> 1) x its initial value (default: off)");
  cmd->add_option("--max-displacement", a->max_displacement,
                  "stop when a particle has moved more than D dx, checked at every row (default 1; off: no limit); "
                  "the neighbour list is built once at t = 0 and not rebuilt");
  cmd->add_option("--out", a->out, "also write VTK snapshots DIR/run_<step>.vtp at every row and DIR/run.pvd");
  cmd->callback([a, cmd] {
    // An option given with an empty value is malformed, not "the default" (which an empty field stands for here).
    for (const auto& [name, value] : {std::pair<const char*, const std::string*>{"--dt", &a->dt},
                                      {"--t-end", &a->t_end},
                                      {"--yield", &a->yield},
                                      {"--energy-growth", &a->energy_growth},
                                      {"--out", &a->out}})
      if (cmd->count(name) > 0 && value->empty())
        throw std::invalid_argument(std::string("run: ") + name + " needs a value (got '')");
    run_run(*a);
  });
}

}  // namespace sphstab::cli
