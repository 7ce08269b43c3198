// Study: the oscillating cantilever plate of Gray, Monaghan & Swift [GMS2001, §7.1] with the rate-form scheme
// (forms/rate_form.hpp: continuity -rho div vhat, EOS, Jaumann rate, XSPH 1/2, viscosity, artificial stress 0.3, n 4;
// GMS predictor-corrector). Periods from tip zero crossings (analysis/oscillation.hpp) against GMS Tables 1 and 2,
// thin-plate theory (7.1) and the Timoshenko beam; the linear SPH period from the spectrum of the initial state
// (growth/rate_form_spectrum.hpp); resolution, clamp length and time-step sensitivity; the eps = 0 root break.
// See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: periods.csv, convergence.csv, clamp.csv, dt.csv, root.csv, series/<tag>.csv, vtk/<tag>/*,
// summary.json. GMS units: rho0 = c0 = 1 (K = 1), lengths in cm, time in cm / c0.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <numeric>
#include <string>
#include <vector>

#include "common/gms.hpp"
#include "common/study.hpp"
#include "sphstab/analysis/fragments.hpp"
#include "sphstab/analysis/oscillation.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/rate_form_vtk.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/problems/cantilever_plate.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct PlateCase {
  std::string tag;
  double thickness = 2;
  int across = 10;
  double mu = 0.22, tip_speed = 0.01, eps = 0.3;
  int clamp_layers = 4;
  double periods = 1.45;  ///< run length in thin-plate periods (SPH plates at these resolutions are 10-35 % slower)
  double cfl = 0.25;      ///< dt = cfl h / c_P
  double paper = kNaN;    ///< GMS T_sph
  double length = 20, h_factor = 1.5;
  /// Material: GMS units (rho0 = K = 1, shear modulus mu) unless youngs is set (then SI: E, nu, rho0).
  double youngs = kNaN, poisson = kNaN, density = 1;
  double alpha = 1, beta = 2;  ///< viscosity coefficients (compression switch; Monaghan's standard, GMS give none)
  int vtk_frames = 0;          ///< VTK snapshots over the run (0: none)
};

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

ElasticMaterial material_of(const PlateCase& c) {
  if (std::isnan(c.youngs)) return ElasticMaterial::from_bulk_shear(1, c.mu, 1);
  return ElasticMaterial::from_young_poisson(c.youngs, c.poisson, c.density);
}
IsotropicModuli moduli_of(const PlateCase& c) {
  const ElasticMaterial m = material_of(c);
  return isotropic_moduli(m.bulk_modulus(), m.mu());
}
double thin_period(const PlateCase& c) {
  const IsotropicModuli m = moduli_of(c);
  return thin_plate_period(m.youngs, m.poisson, material_of(c).density(), c.thickness, c.length);
}
double timoshenko_period(const PlateCase& c) {
  const IsotropicModuli m = moduli_of(c);
  return timoshenko_cantilever_period(m.youngs / (1 - m.poisson * m.poisson), material_of(c).mu(), 5.0 / 6,
                                      material_of(c).density(), c.thickness, c.length);
}
/// The GMS-unit plate of thickness H and shear modulus mu (for the theory columns).
PlateCase gms_plate(double H, double mu) {
  PlateCase c;
  c.thickness = H, c.mu = mu;
  return c;
}

struct PlateScene {
  ParticleSet<2> particles;
  std::shared_ptr<const Discretisation<2>> disc;
  std::unique_ptr<RateFormScheme<2>> scheme;
  Eigen::VectorXd y0;
  std::vector<int> tip;
  std::vector<std::pair<int, int>> bonds;  ///< grid neighbours (distance dp) at the start
};

PlateScene make_scene(const PlateCase& c) {
  PlateScene s;
  s.particles = make_cantilever_plate(
      {.length = c.length, .thickness = c.thickness, .across = c.across, .clamp_layers = c.clamp_layers});
  const double dp = s.particles.spacing;
  const Kernel<2> kernel(KernelType::CubicSpline);
  s.disc = make_discretisation(s.particles, kernel, c.h_factor * dp);
  s.scheme = std::make_unique<RateFormScheme<2>>(s.disc, material_of(c), gms_scheme_options(c.eps, c.alpha, c.beta));
  s.y0 = s.scheme->uniform_state();
  const ParticleSet<2>& p = s.particles;
  for (int i = 0; i < p.size(); ++i) {
    if (p.role[i] == Role::Free)
      s.scheme->set_velocity(s.y0, i, Eigen::Vector2d(0, cantilever_mode_velocity(p.x(i, 0), c.length, c.tip_speed)));
    if (p.x(i, 0) > c.length - dp) s.tip.push_back(i);
  }
  // Particle order: column by column (make_cantilever_plate), `across` per column.
  for (int i = 0; i < p.size(); ++i) {
    if (i % c.across + 1 < c.across) s.bonds.emplace_back(i, i + 1);
    if (i + c.across < p.size()) s.bonds.emplace_back(i, i + c.across);
  }
  return s;
}

PlateRun run_plate(const PlateCase& c, const std::string& out) {
  PlateRun r{.c = c};
  PlateScene s = make_scene(c);
  const double dp = s.particles.spacing, h = c.h_factor * dp;
  r.particles = s.particles.size();
  const double c_p = s.scheme->material().p_wave_speed();
  const double T = thin_period(c);
  std::vector<std::pair<double, std::string>> frames;
  const std::string vtk_dir = out + "/vtk/" + c.tag;
  if (c.vtk_frames > 0) fs::create_directories(vtk_dir);
  const double frame_every = c.periods * T / std::max(c.vtk_frames, 1);
  RateFormRunOptions ro{.dt = c.cfl * h / c_p, .t_end = c.periods * T};
  ro.record_every = std::max(1, static_cast<int>(T / 400 / ro.dt));
  ro.observer = [&](long, double t, const Eigen::VectorXd& y) {
    double u = 0;
    for (int i : s.tip) u += y[s.scheme->position_offset(i) + 1] - s.particles.x(i, 1);
    const Eigen::Matrix2Xd pts = rate_form_positions(*s.scheme, y);
    double stretch = 0;
    int at = -1;
    for (auto [i, j] : s.bonds) {
      const double d = (pts.col(i) - pts.col(j)).norm() / dp;
      if (d > stretch) stretch = d, at = i;
    }
    r.t.push_back(t);
    r.tip.push_back(u / static_cast<double>(s.tip.size()));
    r.ke.push_back(s.scheme->kinetic_energy(y));
    r.stretch.push_back(stretch);
    const Fragments fr = find_fragments(pts, 1.5 * dp);
    r.fragments.push_back(fr.count());
    if (fr.count() > 1 && std::isnan(r.break_time)) {
      r.break_time = t;
      r.break_x = std::numeric_limits<double>::infinity();
      for (int i = 0; i < s.particles.size(); ++i)
        if (fr.label[i] != fr.label[0]) r.break_x = std::min(r.break_x, pts(0, i));  // particle 0 is in the clamp
    }
    if (stretch > r.max_stretch) r.max_stretch = stretch, r.max_stretch_x = pts(0, at), r.max_stretch_t = t;
    if (c.vtk_frames > 0 && t >= frames.size() * frame_every - 0.5 * ro.dt) {
      const std::string name = c.tag + "_" + std::to_string(frames.size()) + ".vtp";
      write_rate_form_vtp(vtk_dir + "/" + name, *s.scheme, y);
      frames.emplace_back(t, name);
    }
  };
  study::RunCost cost;
  const RateFormRunResult res = study::timed_run(*s.scheme, s.y0, ro, cost);
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
  fs::create_directories(out + "/series");
  std::ofstream f(out + "/series/" + c.tag + ".csv");
  f << "t,tip_displacement,kinetic_energy,max_bond_stretch,fragments\n";
  for (std::size_t k = 0; k < r.t.size(); ++k)
    f << csv_line({format_number(r.t[k], 10), format_number(r.tip[k], 10), format_number(r.ke[k], 10),
                   format_number(r.stretch[k], 8), std::to_string(r.fragments[k])});
  std::fprintf(stderr,
               "  %-28s N %5d dt %.4f steps %7ld  T %8.2f  (%zu crossings) decay %+.3f stretch %.2f at x %.2f t %.0f  "
               "%s  %.0f s\n",
               c.tag.c_str(), r.particles, r.dt, r.steps, r.osc.period, r.osc.crossings.size(), r.osc.decay_per_period,
               r.max_stretch, r.max_stretch_x, r.max_stretch_t, r.status.c_str(), r.wall);
  return r;
}

/// The small-amplitude SPH bending period: the initial state's spectrum (at rest and stress free, so the artificial
/// stress and the viscosity's compression switch are off in the linearisation) gives the vibration modes; of the
/// modes below three times the thin-plate frequency, the bending mode is the one whose velocity shape overlaps most
/// with the initial velocity (7.3)-(7.4) (|cos| of the angle between them, `overlap`). Softer modes exist: the
/// plain SPH gradient's near-zero-energy patterns, which `softer` counts.
struct LinearPeriod {
  double period = kNaN, overlap = kNaN, growth_rate = kNaN;
  int softer = -1;             ///< vibration modes of lower frequency than the bending mode
  std::vector<double> lowest;  ///< the candidates' periods, lowest frequency first
};

LinearPeriod linear_period(const PlateCase& c) {
  PlateScene s = make_scene(c);
  const Eigen::VectorXd y = s.scheme->uniform_state();
  const RateFormSpectrum all = rate_form_spectrum(*s.scheme, y);
  if (all.info() != Status::Successful) throw std::runtime_error("plate spectrum: " + all.reason);
  std::vector<std::complex<double>> w;
  for (const auto& l : all.eigenvalues)
    if (l.imag() > 1e-12) w.push_back(l);
  std::sort(w.begin(), w.end(), [](auto a, auto b) { return a.imag() < b.imag(); });
  const double w_max = 3 * 2 * M_PI / thin_period(c);
  w.erase(std::find_if(w.begin(), w.end(), [&](auto l) { return l.imag() > w_max; }), w.end());
  Eigen::VectorXcd targets(static_cast<Eigen::Index>(w.size()));
  for (std::size_t k = 0; k < w.size(); ++k) targets[static_cast<Eigen::Index>(k)] = w[k];
  const RateFormSpectrum sp = rate_form_spectrum(*s.scheme, y, {.mode_targets = targets});
  const Discretisation<2>& d = *s.disc;
  Eigen::VectorXd v0(2 * d.free_count());
  for (int f = 0; f < d.free_count(); ++f) v0.segment<2>(2 * f) = s.y0.segment<2>(s.scheme->velocity_offset(d.free[f]));
  LinearPeriod out;
  out.growth_rate = all.growth_rate;
  for (int k = 0; k < sp.modes.cols(); ++k) {
    const double o = std::abs(sp.modes.col(k).dot(v0)) / (sp.modes.col(k).norm() * v0.norm());
    out.lowest.push_back(2 * M_PI / w[k].imag());
    if (!(o <= out.overlap)) out.overlap = o, out.softer = k, out.period = out.lowest.back();
  }
  return out;
}

/// Runs the cases on `threads` threads (one scheme per thread), results in case order.
/// Runs every case, the most expensive first (particles x steps, both known before the run) so that the 40-across
/// run does not start last on an otherwise idle pool.
std::vector<PlateRun> run_all(const std::vector<PlateCase>& cases, const std::string& out, int threads) {
  std::vector<double> cost(cases.size());
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const PlateCase& c = cases[k];
    const double dp = c.thickness / c.across;
    const double particles = (c.length / dp + c.clamp_layers) * c.across;
    const double c_p = material_of(c).p_wave_speed();
    cost[k] = particles * c.periods * thin_period(c) / (c.cfl * c.h_factor * dp / c_p);
  }
  std::vector<std::size_t> order(cases.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  std::vector<PlateRun> runs(cases.size());
  study::parallel_for(cases.size(), threads, [&](std::size_t k) { runs[order[k]] = run_plate(cases[order[k]], out); });
  return runs;
}

/// GMS Tables 1 and 2 (T_sph, cm / c0), [GMS2001, §7.1, Tables 1-2].
struct PaperRow {
  double thickness, mu, tip_speed, period;
};
const std::vector<PaperRow>& paper_periods() {
  static const std::vector<PaperRow> rows = {
      {2, 0.22, 0.001, 1674.6}, {2, 0.22, 0.01, 1671.5}, {2, 0.22, 0.03, 1688.2}, {2, 0.22, 0.05, 1705.0},
      {2, 0.30, 0.001, 1473.6}, {2, 0.30, 0.01, 1469.8}, {2, 0.30, 0.03, 1482.1}, {2, 0.30, 0.05, 1495.4},
      {2, 0.60, 0.001, 1131.6}, {2, 0.60, 0.01, 1127.2}, {2, 0.60, 0.03, 1130.7}, {2, 0.60, 0.05, 1136.1},
      {1, 0.22, 0.01, 3333.6},  {1, 0.22, 0.03, 3385.7}, {1, 0.22, 0.05, 3322.8}, {1, 0.30, 0.01, 2902.0},
      {1, 0.30, 0.03, 2977.7},  {1, 0.30, 0.05, 2934.9}, {1, 0.60, 0.01, 2214.4}, {1, 0.60, 0.03, 2221.7},
      {1, 0.60, 0.05, 2200.4}};
  return rows;
}

std::string tag_of(const PlateCase& c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "H%g_n%d_mu%g_vf%g_eps%g_clamp%d_cfl%g_a%g", c.thickness, c.across, c.mu, c.tip_speed,
                c.eps, c.clamp_layers, c.cfl, c.alpha);
  return buf;
}

PlateCase with_tag(PlateCase c) {
  c.tag = tag_of(c);
  return c;
}

std::vector<CsvCell> run_cells(const PlateRun& r) {
  const PlateCase& c = r.c;
  const double thin = thin_period(c), timo = timoshenko_period(c);
  return {c.tag,
          c.thickness,
          c.across,
          c.thickness / c.across,
          c.mu,
          c.tip_speed,
          c.eps,
          c.alpha,
          c.beta,
          c.clamp_layers,
          c.cfl,
          r.particles,
          r.dt,
          r.steps,
          r.status,
          r.osc.period,
          static_cast<int>(r.osc.crossings.size()),
          r.osc.crossings.empty() ? kNaN : r.osc.crossings[0],
          r.osc.decay_per_period,
          r.osc.extremes.empty() ? kNaN : std::abs(r.osc.extremes[0]),
          c.paper,
          r.osc.period / c.paper - 1,
          thin,
          timo,
          r.osc.period / timo - 1,
          r.max_stretch,
          *std::max_element(r.fragments.begin(), r.fragments.end()),
          r.break_time,
          r.break_x,
          r.wall,
          r.cpu};
}

const std::vector<std::string> kRunColumns = {"tag",
                                              "H",
                                              "across",
                                              "dp",
                                              "mu",
                                              "tip_speed",
                                              "eps",
                                              "alpha",
                                              "beta",
                                              "clamp_layers",
                                              "cfl",
                                              "particles",
                                              "dt",
                                              "steps",
                                              "status",
                                              "period",
                                              "crossings",
                                              "first_crossing",
                                              "decay_per_period",
                                              "first_amplitude",
                                              "paper_period",
                                              "error_vs_paper",
                                              "thin_period",
                                              "timoshenko_period",
                                              "error_vs_timoshenko",
                                              "max_bond_stretch",
                                              "max_fragments",
                                              "break_time",
                                              "break_x",
                                              "wall_seconds",
                                              "cpu_seconds"};

void write_runs(const std::string& path, const std::vector<PlateRun>& runs) {
  CsvWriter w(path, kRunColumns);
  for (const PlateRun& r : runs) w.row(run_cells(r));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"GMS cantilever plate study"};
  std::string out = "results/gms-plate";
  int threads = 2, table_across_h2 = 10, table_across_h1 = 6;
  std::vector<int> convergence = {6, 10, 14, 20, 30, 40};
  PlateCase probe;
  bool probe_mode = false, spectrum_mode = false;
  app.add_option("--out", out, "output directory");
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--table-across-h2", table_across_h2, "particles across H = 2 for Table 1")->check(CLI::Range(2, 100));
  app.add_option("--table-across-h1", table_across_h1, "particles across H = 1 for Table 2")->check(CLI::Range(2, 100));
  app.add_option("--convergence", convergence, "particles across H = 2 of the resolution study");
  app.add_flag("--spectrum", spectrum_mode, "print the linear bending period of the case below");
  app.add_flag("--probe", probe_mode, "one run of the case below");
  app.add_option("--H", probe.thickness);
  app.add_option("--across", probe.across);
  app.add_option("--mu", probe.mu);
  app.add_option("--vf", probe.tip_speed);
  app.add_option("--eps", probe.eps);
  app.add_option("--periods", probe.periods);
  app.add_option("--cfl", probe.cfl);
  app.add_option("--clamp", probe.clamp_layers);
  app.add_option("--frames", probe.vtk_frames);
  app.add_option("--alpha", probe.alpha);
  app.add_option("--beta", probe.beta);
  CLI11_PARSE(app, argc, argv);
  try {
    fs::create_directories(out);
    if (spectrum_mode) {
      const LinearPeriod lp = linear_period(probe);
      std::printf("bending mode: T %.4f overlap %.4f softer %d growth %.3e\n", lp.period, lp.overlap, lp.softer,
                  lp.growth_rate);
      return 0;
    }
    if (probe_mode) {
      probe.tag = "probe";
      const PlateRun r = run_plate(probe, out);
      for (std::size_t k = 0; k < r.osc.crossings.size(); ++k)
        std::printf("crossing %.3f extreme %.5g\n", r.osc.crossings[k], r.osc.extremes[k]);
      std::printf("T %.3f thin %.3f timoshenko %.3f\n", r.osc.period, thin_period(probe), timoshenko_period(probe));
      return 0;
    }
    const auto t_start = study::Clock::now();
    study::Summary sum;
    const PlateCase base{.cfl = 0.5};  // H = 2, mu = 0.22, V_f = 0.01, eps = 0.3, alpha 1, beta 2, clamp 4
    // 1. GMS Tables 1 and 2.
    std::vector<PlateCase> table;
    for (const PaperRow& p : paper_periods()) {
      PlateCase c = base;
      c.thickness = p.thickness, c.mu = p.mu, c.tip_speed = p.tip_speed, c.paper = p.period;
      c.across = p.thickness == 2 ? table_across_h2 : table_across_h1;
      table.push_back(with_tag(c));
    }
    // 2. Resolution (H = 2, mu = 0.22, V_f = 0.01), 3. clamp length, 4. time step, 5. viscosity, 6. eps at small V_f,
    // 7. the root break (mu = 0.6, V_f = 0.05, eps = 0 and 0.3, with snapshots).
    std::vector<PlateCase> conv, clamp, dt, visc, eps, root, si_group;
    for (int n : convergence) {
      PlateCase c = base;
      c.across = n, c.paper = 1671.5;
      conv.push_back(with_tag(c));
    }
    for (int layers : {2, 3, 4, 8}) {
      PlateCase c = base;
      c.across = table_across_h2, c.clamp_layers = layers, c.paper = 1671.5;
      clamp.push_back(with_tag(c));
    }
    for (double cfl : {0.25, 0.5}) {
      PlateCase c = base;
      c.across = table_across_h2, c.cfl = cfl, c.paper = 1671.5;
      dt.push_back(with_tag(c));
    }
    for (auto [a, b] : {std::pair{0.06, 1.5}, {0.5, 1.0}, {1.0, 2.0}, {2.0, 4.0}}) {
      PlateCase c = base;
      c.across = table_across_h2, c.alpha = a, c.beta = b, c.paper = 1671.5;
      visc.push_back(with_tag(c));
    }
    for (double e : {0.0, 0.3})
      for (double v : {0.001, 0.01}) {
        PlateCase c = base;
        c.across = table_across_h2, c.eps = e, c.tip_speed = v;
        c.paper = v == 0.001 ? 1674.6 : 1671.5;
        eps.push_back(with_tag(c));
      }
    for (double e : {0.0, 0.3}) {
      PlateCase c = base;
      c.across = table_across_h2, c.mu = 0.6, c.tip_speed = 0.05, c.eps = e, c.vtk_frames = 12, c.paper = 1136.1;
      root.push_back(with_tag(c));
    }
    // 8. The plate in SI units as commonly configured: L = 0.2 m, H = 0.02 m, E = 2 MPa, nu = 0.3975, rho0 = 1000
    // kg/m^3, dx = 0.002 m (10 across), h = 1.3 dx, V_f = 0.05 m/s at the tip, run to 1 s.
    PlateCase si = base;
    si.length = 0.2, si.thickness = 0.02, si.across = 10, si.h_factor = 1.3;
    si.youngs = 2e6, si.poisson = 0.3975, si.density = 1000, si.tip_speed = 0.05;
    si.mu = material_of(si).mu();
    si.periods = 1.0 / thin_period(si);
    si = with_tag(si);
    si_group.push_back(si);
    // One list, each distinct case run once.
    std::vector<PlateCase> all;
    for (const auto* group : {&table, &conv, &clamp, &dt, &visc, &eps, &root, &si_group})
      for (const PlateCase& c : *group) {
        auto same = std::find_if(all.begin(), all.end(), [&](const PlateCase& a) { return a.tag == c.tag; });
        if (same == all.end())
          all.push_back(c);
        else
          same->vtk_frames = std::max(same->vtk_frames, c.vtk_frames);
      }
    std::fprintf(stderr, "gms-plate: %zu runs on %d threads\n", all.size(), threads);
    const std::vector<PlateRun> runs = run_all(all, out, threads);
    auto find = [&](const PlateCase& c) -> const PlateRun& {
      for (const PlateRun& r : runs)
        if (r.c.tag == c.tag) return r;
      throw std::logic_error("missing run " + c.tag);
    };
    auto pick = [&](const std::vector<PlateCase>& group) {
      std::vector<PlateRun> g;
      for (const PlateCase& c : group) g.push_back(find(c));
      return g;
    };
    write_runs(out + "/periods.csv", pick(table));
    write_runs(out + "/convergence.csv", pick(conv));
    write_runs(out + "/clamp.csv", pick(clamp));
    write_runs(out + "/dt.csv", pick(dt));
    write_runs(out + "/viscosity.csv", pick(visc));
    write_runs(out + "/eps.csv", pick(eps));
    write_runs(out + "/root.csv", pick(root));
    write_runs(out + "/si.csv", pick(si_group));
    {
      const PlateRun& r = find(si);
      sum.set("si_particles", r.particles);
      sum.set("si_steps", r.steps);
      sum.set("si_period", r.osc.period, 4);
      sum.set("si_thin", thin_period(si), 4);
      sum.set("si_timoshenko", timoshenko_period(si), 4);
      sum.set("si_vs_timoshenko", 100 * (r.osc.period / timoshenko_period(si) - 1), 3);
      sum.set("si_amplitude_mm", r.osc.extremes.empty() ? kNaN : 1e3 * std::abs(r.osc.extremes[0]), 3);
      sum.set("si_decay", 100 * r.osc.decay_per_period, 2);
      sum.set("si_crossings", static_cast<long>(r.osc.crossings.size()));
      sum.set("si_wall", r.wall, 3);
      sum.set("si_us", 1e6 * r.wall / (static_cast<double>(r.steps) * r.particles), 3);
      sum.set("si_status", r.status);
    }

    // Linear (spectral) bending periods of the initial state at the resolutions whose spectrum fits.
    {
      CsvWriter w(out + "/linear.csv", {"H", "across", "dp", "mu", "linear_period", "overlap", "softer_modes",
                                        "growth_rate", "run_period_vf0.01", "thin_period", "timoshenko_period"});
      for (const PlateCase& c0 : conv) {
        if (c0.across > 14) continue;
        const LinearPeriod lp = linear_period(c0);
        w.row({c0.thickness, c0.across, c0.thickness / c0.across, c0.mu, lp.period, lp.overlap, lp.softer,
               lp.growth_rate, find(c0).osc.period, thin_period(c0), timoshenko_period(c0)});
        if (c0.across == table_across_h2) {
          sum.set("linear_period", lp.period, 5);
          sum.set("linear_overlap", lp.overlap, 4);
          sum.set("linear_softer", lp.softer);
          sum.set("linear_vs_run", find(c0).osc.period / lp.period - 1, 2);
        }
      }
    }
    // Frozen-state spectra of the root-break case (eps = 0 run) at about T/16 and T/8 of GMS's period (t = 70, 140),
    // before the break (t = 289 at 10 across), the later one also with the viscosity on.
    {
      PlateCase c = root[0];
      const PlateScene scene = make_scene(c);
      const double h = c.h_factor * scene.particles.spacing;
      study::frozen_spectra_along_run(*scene.scheme, scene.y0,
                                      {.dt = c.cfl * h / scene.scheme->material().p_wave_speed()}, {70, 140}, 140, out,
                                      sum);
    }

    // Summary numbers.
    double worst_h2 = 0, worst_h1 = 0;
    std::string table_md;
    for (const PlateCase& c : table) {
      const PlateRun& r = find(c);
      const double e = r.osc.period / c.paper - 1;
      (c.thickness == 2 ? worst_h2 : worst_h1) = std::max(c.thickness == 2 ? worst_h2 : worst_h1, std::abs(e));
      study::md_row(table_md,
                    {study::fixed(c.thickness, 0), study::fixed(c.mu, 2), study::sig(c.tip_speed, 2),
                     std::to_string(c.across), study::fixed(c.paper, 1), study::fixed(r.osc.period, 1),
                     study::fixed(100 * e, 1, true), study::fixed(thin_period(c), 1),
                     study::fixed(timoshenko_period(c), 1), study::fixed(100 * r.osc.decay_per_period, 1), r.status});
    }
    sum.set("table", table_md);
    sum.set("worst_h2", 100 * worst_h2, 2);
    sum.set("worst_h1", 100 * worst_h1, 2);
    sum.set("across_h2", table_across_h2);
    sum.set("across_h1", table_across_h1);
    // Resolution: observed order of the period from the three finest, Richardson limit.
    std::string conv_md;
    std::vector<double> dps, Ts;
    for (const PlateCase& c : conv) {
      const PlateRun& r = find(c);
      dps.push_back(c.thickness / c.across), Ts.push_back(r.osc.period);
      study::md_row(conv_md,
                    {std::to_string(c.across), study::sig(c.thickness / c.across, 3), std::to_string(r.particles),
                     study::fixed(r.osc.period, 1), study::fixed(100 * (r.osc.period / 1671.5 - 1), 1, true),
                     study::fixed(100 * r.osc.decay_per_period, 2), study::fixed(r.wall, 0)});
    }
    sum.set("convergence", conv_md);
    const std::size_t m = Ts.size();
    if (m >= 3) {
      // T(dp) = T0 + C dp^p through the three finest: p from the ratio of differences (any spacing, by bisection).
      const double d1 = dps[m - 3], d2 = dps[m - 2], d3 = dps[m - 1];
      const double q = (Ts[m - 3] - Ts[m - 2]) / (Ts[m - 2] - Ts[m - 1]);
      auto g = [&](double p) { return (std::pow(d1, p) - std::pow(d2, p)) / (std::pow(d2, p) - std::pow(d3, p)) - q; };
      double lo = 0.05, hi = 8, p = kNaN;
      if (g(lo) * g(hi) < 0) {
        for (int it = 0; it < 200; ++it) {
          const double mid = 0.5 * (lo + hi);
          (g(lo) * g(mid) <= 0 ? hi : lo) = mid;
        }
        p = 0.5 * (lo + hi);
      }
      const double C = (Ts[m - 2] - Ts[m - 1]) / (std::pow(d2, p) - std::pow(d3, p));
      const double T0 = Ts[m - 1] - C * std::pow(d3, p);
      sum.set("observed_order", p, 3);
      sum.set("extrapolated_period", T0, 5);
      sum.set("extrapolated_vs_timoshenko", 100 * (T0 / timoshenko_period(gms_plate(2, 0.22)) - 1), 2);
      sum.set("extrapolated_vs_paper", 100 * (T0 / 1671.5 - 1), 2);
      CsvWriter w(out + "/extrapolation.csv", {"observed_order", "extrapolated_period", "from_across"});
      w.row({p, T0,
             std::to_string(convergence[m - 3]) + "/" + std::to_string(convergence[m - 2]) + "/" +
                 std::to_string(convergence[m - 1])});
    }
    sum.set("finest_across", convergence.back());
    sum.set("finest_period", Ts.back(), 5);
    sum.set("finest_decay", 100 * find(conv.back()).osc.decay_per_period, 2);
    sum.set("thin_022", thin_period(gms_plate(2, 0.22)), 5);
    sum.set("timo_022", timoshenko_period(gms_plate(2, 0.22)), 5);
    sum.set("timo_ratio_h2", timoshenko_period(gms_plate(2, 0.22)) / thin_period(gms_plate(2, 0.22)), 4);
    sum.set("timo_ratio_h1", timoshenko_period(gms_plate(1, 0.22)) / thin_period(gms_plate(1, 0.22)), 4);
    // Clamp, dt, viscosity, eps.
    std::string clamp_md, visc_md, eps_md;
    for (const PlateCase& c : clamp) {
      const PlateRun& r = find(c);
      study::md_row(clamp_md, {std::to_string(c.clamp_layers), study::fixed(c.clamp_layers * c.thickness / c.across, 2),
                               study::fixed(r.osc.period, 1),
                               study::fixed(100 * (r.osc.period / find(clamp[2]).osc.period - 1), 2, true)});
    }
    sum.set("clamp", clamp_md);
    sum.set("dt_change", std::abs(find(dt[0]).osc.period / find(dt[1]).osc.period - 1), 2);
    for (const PlateCase& c : visc) {
      const PlateRun& r = find(c);
      study::md_row(visc_md, {study::sig(c.alpha, 2), study::sig(c.beta, 2), r.status, study::fixed(r.osc.period, 1),
                              study::fixed(100 * r.osc.decay_per_period, 2), study::fixed(r.max_stretch, 2)});
    }
    sum.set("viscosity", visc_md);
    for (const PlateCase& c : eps) {
      const PlateRun& r = find(c);
      study::md_row(eps_md, {study::sig(c.eps, 2), study::sig(c.tip_speed, 2), study::fixed(r.osc.period, 1),
                             study::fixed(100 * r.osc.decay_per_period, 2)});
    }
    sum.set("eps", eps_md);
    for (std::size_t k = 0; k < root.size(); ++k) {
      const PlateRun& r = find(root[k]);
      const std::string key = k == 0 ? "root_eps0" : "root_eps03";
      sum.set(key + "_break_time", r.break_time, 4);
      sum.set(key + "_break_x", r.break_x, 3);
      sum.set(key + "_fragments", static_cast<long>(*std::max_element(r.fragments.begin(), r.fragments.end())));
      sum.set(key + "_period", r.osc.period, 5);
      sum.set(key + "_status", r.status);
    }
    sum.set("runs", static_cast<long>(runs.size()));
    sum.set("wall_minutes", study::seconds_since(t_start) / 60, 3);
    sum.write(out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "study_gms_plate: %s\n", e.what());
    return 1;
  }
  return 0;
}
