// Study: the colliding rubber rings of Gray, Monaghan & Swift [GMS2001, §7.2] with the rate-form scheme
// (forms/rate_form.hpp: continuity -rho tr L, EOS, Jaumann rate, XSPH 1/2, viscosity 1 / 2 with the compression switch,
// artificial stress eps = 0 or 0.3, n = 4; GMS predictor-corrector with a Verlet neighbour list). Measures over time:
// fragments (bond graph, analysis/fragments.hpp) of the whole scene and of each ring, contact (closest pair of
// particles of different rings against the kernel support 2h), ring centre-of-mass velocities (rebound) and kinetic
// energy. Also the SI configuration of the issue (17608 particles): a short timed run by default, the whole collision
// with --si-full. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, series/<tag>.csv, frames.csv, vtk/<tag>/*.vtp + <tag>.pvd, summary.json. GMS units:
// rho0 = c0 = 1 (K = 1), lengths in cm, time in cm / c0; the SI case in m, s, Pa, kg/m^3.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <numeric>
#include <string>
#include <vector>

#include "common/gms.hpp"
#include "common/study.hpp"
#include "sphstab/analysis/fragments.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/rate_form_vtk.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/problems/colliding_rings.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct RingCase {
  std::string tag;
  bool si = false;                 ///< the SI configuration (m, s, Pa) instead of GMS units
  double eps = 0.3;                ///< artificial stress
  double dp = 0.1;                 ///< grid spacing (case units)
  double gap = 0.2;                ///< between the outer circles (case units)
  double t_end = 250;              ///< run length (case units); with `steps` > 0 it is steps * dt
  long steps = 0;                  ///< > 0: a fixed number of steps (the SI timing run)
  int frames = 12;                 ///< VTK frames over the run (0: none)
  double skin = 0.5;               ///< Verlet skin of the neighbour list, in dp
  PairLoop loop = PairLoop::Rows;  ///< how the rate visits the pairs (forms/rate_form.hpp)
  bool one_rate = false;           ///< one rate evaluation per step (RateFormRunOptions::reuse_corrector_rate)
  double dt_scale = 1;             ///< dt = dt_scale x 0.5 h / c_p
};

/// The case's units against GMS's: length unit (1 cm), speed unit (c0) and time unit, in the case's own units.
struct Units {
  double length = 1, speed = 1;
  double time() const { return length / speed; }
};

struct RingRun {
  RingCase c;
  Units u;
  int particles = 0, per_ring = 0;
  double h = 0, dt = 0, speed = 0;
  study::RunCost cost;
  std::string status;
  // Series, one entry per record (times in GMS units, velocities over c0, lengths over the length unit).
  std::vector<double> t, ke, dmin, vx0, vx1, sxx_max;
  std::vector<double> dbody;  ///< closest distance between the rings' bodies (largest fragments)
  std::vector<int> frag_all, frag0, frag1, lost0, lost1;
  Eigen::VectorXd y_end;  ///< the state at the end
};

/// The SI material of the issue: E = 1e7 Pa, nu = 0.3975 (mu / K = 0.22, GMS's ratio), rho0 = 1 kg/m^3.
RateFormMaterial si_material() { return RateFormMaterial::from_youngs(1e7, 0.3975, 1.0); }

/// Smallest distance between a particle of ring 0 (indices [0, n)) and one of ring 1 ([n, 2n)), exact when below
/// `band`; otherwise some value >= band (the candidates are the particles within `band` in x of the other ring's
/// extent).
double ring_distance(const Eigen::Matrix2Xd& x, const std::vector<int>& left, const std::vector<int>& right,
                     double band) {
  double max0 = -kInf, min1 = kInf;
  for (int i : left) max0 = std::max(max0, x(0, i));
  for (int i : right) min1 = std::min(min1, x(0, i));
  std::vector<int> a, b;
  for (int i : left)
    if (x(0, i) >= min1 - band) a.push_back(i);
  for (int i : right)
    if (x(0, i) <= max0 + band) b.push_back(i);
  if (a.empty() || b.empty()) return std::max(band, min1 - max0);
  double d2 = kInf;
  for (int i : a)
    for (int j : b) d2 = std::min(d2, (x.col(i) - x.col(j)).squaredNorm());
  return std::sqrt(d2);
}

/// The particles of a ring's largest fragment (its body: torn-off particles excluded), offset by `first`.
std::vector<int> body(const Fragments& f, int first) {
  const int big = static_cast<int>(std::max_element(f.sizes.begin(), f.sizes.end()) - f.sizes.begin());
  std::vector<int> idx;
  for (int i = 0; i < static_cast<int>(f.label.size()); ++i)
    if (f.label[i] == big) idx.push_back(first + i);
  return idx;
}

RingRun run_rings(const RingCase& c, const std::string& out) {
  RingRun r{.c = c};
  const RateFormMaterial mat =
      c.si ? si_material() : RateFormMaterial{.density = 1, .bulk_modulus = 1, .shear_modulus = 0.22};
  r.u = c.si ? Units{.length = 0.01, .speed = mat.sound_speed()} : Units{};
  const double r_in = 3 * r.u.length, r_out = 4 * r.u.length;
  r.speed = 0.059 * mat.sound_speed();
  const CollidingRingsOptions geometry{
      .inner_radius = r_in, .outer_radius = r_out, .spacing = c.dp, .gap = c.gap, .speed = r.speed};
  const CollidingRings rings = make_colliding_rings(geometry);  // the ring of each particle
  const int n = rings.per_ring;
  r.particles = rings.size();
  r.per_ring = n;
  r.h = 1.5 * c.dp;
  const Kernel<2> kernel(KernelType::CubicSpline);
  RateFormOptions options = gms_scheme_options(c.eps);
  options.pair_loop = c.loop;
  const Scene<2> scene = gms_rings_scene(geometry, {.material = mat, .scheme = options});
  const RateFormScheme<2>& scheme = *scene.scheme;
  const Eigen::VectorXd& y0 = scene.y0;
  const double support = kernel.support_radius(r.h), bond = 1.5 * c.dp;
  r.dt = c.dt_scale * 0.5 * r.h / mat.p_wave_speed();
  const double t_end = c.steps > 0 ? c.steps * r.dt : c.t_end;

  const Eigen::VectorXd ring_field = Eigen::Map<const Eigen::VectorXi>(rings.ring.data(), r.particles).cast<double>();
  const std::string vtk_dir = out + "/vtk/" + c.tag;
  if (c.frames > 0) fs::create_directories(vtk_dir);
  std::vector<std::pair<double, std::string>> frames;
  const double frame_every = t_end / std::max(c.frames, 1);
  const double record_dt = c.steps > 0 ? t_end / 5 : 0.5 * r.u.time();  // a record every 0.5 cm/c0
  RateFormRunOptions ro{.dt = r.dt,
                        .t_end = t_end,
                        .record_every = std::max(1, static_cast<int>(std::lround(record_dt / r.dt))),
                        .reuse_corrector_rate = c.one_rate,
                        .neighbour_skin = c.skin * c.dp};
  ro.observer = [&](long step, double t, const Eigen::VectorXd& y) {
    const Eigen::Matrix2Xd x = rate_form_positions(scheme, y);
    const Fragments all = find_fragments(x, bond);
    const Fragments f0 = find_fragments(x.leftCols(n), bond), f1 = find_fragments(x.rightCols(n), bond);
    double v0 = 0, v1 = 0, smax = -kInf;
    for (int i = 0; i < 2 * n; ++i) {
      const double vx = y[scheme.velocity_offset(i)];
      (i < n ? v0 : v1) += vx / n;
      const double p = mat.bulk_modulus * (y[scheme.density_offset(i)] / mat.density - 1);
      smax = std::max(smax, y[scheme.stress_offset(i)] - p);
    }
    r.t.push_back(t / r.u.time());
    r.ke.push_back(scheme.kinetic_energy(y));
    std::vector<int> ring0(n), ring1(n);
    std::iota(ring0.begin(), ring0.end(), 0);
    std::iota(ring1.begin(), ring1.end(), n);
    r.dmin.push_back(ring_distance(x, ring0, ring1, 2 * support) / r.u.length);
    r.dbody.push_back(ring_distance(x, body(f0, 0), body(f1, n), 2 * support) / r.u.length);
    r.vx0.push_back(v0 / r.u.speed);
    r.vx1.push_back(v1 / r.u.speed);
    r.sxx_max.push_back(smax / (mat.density * r.u.speed * r.u.speed));
    r.frag_all.push_back(all.count());
    r.frag0.push_back(f0.count());
    r.frag1.push_back(f1.count());
    r.lost0.push_back(n - f0.largest());
    r.lost1.push_back(n - f1.largest());
    if (c.frames > 0 && (t >= frames.size() * frame_every - 0.5 * ro.dt || step * ro.dt >= t_end - 0.5 * ro.dt)) {
      char name[64];
      std::snprintf(name, sizeof name, "%s_%06ld.vtp", c.tag.c_str(), step);
      write_rate_form_vtp(vtk_dir + "/" + name, scheme, y, {{"ring", 1, ring_field}});
      frames.emplace_back(t, name);
    }
  };
  const RateFormRunResult run = study::timed_run(scheme, y0, ro, r.cost);
  r.dt = run.dt;
  r.status = run.completed() ? "completed" : run.message;
  r.y_end = run.y;
  if (!frames.empty()) write_pvd(vtk_dir + "/" + c.tag + ".pvd", frames);

  std::ofstream csv(out + "/series/" + c.tag + ".csv");
  csv << "t,kinetic,ring_distance,body_distance,com_vx0,com_vx1,sigma_xx_max,fragments,fragments_ring0,"
         "fragments_ring1,lost_ring0,lost_ring1\n";
  for (std::size_t k = 0; k < r.t.size(); ++k)
    csv << csv_line({format_number(r.t[k], 8), format_number(r.ke[k], 8), format_number(r.dmin[k], 8),
                     format_number(r.dbody[k], 8),
                     format_number(r.vx0[k], 8), format_number(r.vx1[k], 8), format_number(r.sxx_max[k], 8),
                     std::to_string(r.frag_all[k]), std::to_string(r.frag0[k]), std::to_string(r.frag1[k]),
                     std::to_string(r.lost0[k]), std::to_string(r.lost1[k])});
  return r;
}

/// Runs the cases on `threads` threads (one scheme per run), results in case order.
std::vector<RingRun> run_all(const std::vector<RingCase>& cases, const std::string& out, int threads) {
  std::vector<RingRun> runs(cases.size());
  std::mutex m;
  study::parallel_for(cases.size(), threads, [&](std::size_t k) {
    runs[k] = run_rings(cases[k], out);
    std::lock_guard<std::mutex> lock(m);
    const RingRun& r = runs[k];
    std::printf(
        "%-12s %5d particles, %6ld steps, %7.1f s wall (%.1f s CPU), %.3g us per particle-step (%.3g CPU), "
        "%ld builds: %s\n",
        r.c.tag.c_str(), r.particles, r.cost.steps, r.cost.wall, r.cost.cpu, r.cost.us_per_particle_step(),
        r.cost.us_cpu(), r.cost.neighbour_builds, r.status.c_str());
    std::fflush(stdout);
  });
  return runs;
}

/// A ring "breaks" when more of its particles than this share of the ring leave its largest fragment at some record;
/// fewer are torn-off particles ("sheds"), not a fracture. 1 %: a torn-off particle or two at the contact (the
/// reference integrator at dt/2 loses 2 of 2196 at eps = 0.3) stays below it, a fracture through the ring wall
/// (eps = 0: more than 1000) is far above it. summary.md shows the counts, so the reader can apply any other line.
constexpr double kBreakShare = 0.01;

/// What a run measured, from its series.
struct RingMeasures {
  double contact_first = kNaN, contact_last = kNaN;  ///< records with ring distance < 2h
  double touch_first = kNaN, touch_last = kNaN;      ///< records with ring distance < dp
  bool separated = false;  ///< the last record has the rings' bodies out of contact (body distance >= 2h)
  double vx0_after = kNaN, vx1_after = kNaN, restitution = kNaN;
  int frag_all_end = 0, frag_all_max = 0, frag_ring_end = 0, frag_ring_max = 0, lost_end = 0, lost_max = 0;
  double ring_break_time = kNaN;  ///< first record with a ring in more than one fragment
  double ke_end_over_ke0 = kNaN, sxx_max = kNaN;
};

RingMeasures measure(const RingRun& r) {
  RingMeasures m;
  const double two_h = 2 * r.h / r.u.length, dp = r.c.dp / r.u.length;
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    if (r.dmin[k] < two_h) {
      if (std::isnan(m.contact_first)) m.contact_first = r.t[k];
      m.contact_last = r.t[k];
    }
    if (r.dmin[k] < dp) {
      if (std::isnan(m.touch_first)) m.touch_first = r.t[k];
      m.touch_last = r.t[k];
    }
    const int fr = std::max(r.frag0[k], r.frag1[k]);
    if (fr > 1 && std::isnan(m.ring_break_time)) m.ring_break_time = r.t[k];
    m.frag_all_max = std::max(m.frag_all_max, r.frag_all[k]);
    m.frag_ring_max = std::max(m.frag_ring_max, fr);
    m.lost_max = std::max(m.lost_max, std::max(r.lost0[k], r.lost1[k]));
  }
  if (r.t.empty()) return m;
  // Separated: out of each other's support at the end. For intact rings (at most kBreakShare torn off) the distance
  // of their bodies, the largest fragments, so that a torn-off particle left between them does not hold them
  // together; for a broken ring every particle counts (its largest fragment is only part of it, the rest may be
  // fused with the other ring).
  const bool broken = m.lost_max > kBreakShare * r.per_ring;
  m.separated = (broken ? r.dmin.back() : r.dbody.back()) >= two_h && !std::isnan(m.contact_last);
  if (m.separated) {  // no force between the rings after the last contact: the COM velocities are constant
    m.vx0_after = r.vx0.back();
    m.vx1_after = r.vx1.back();
    m.restitution = (m.vx1_after - m.vx0_after) / (r.vx0.front() - r.vx1.front());
  }
  m.frag_all_end = r.frag_all.back();
  m.frag_ring_end = std::max(r.frag0.back(), r.frag1.back());
  m.lost_end = std::max(r.lost0.back(), r.lost1.back());
  m.ke_end_over_ke0 = r.ke.back() / r.ke.front();
  m.sxx_max = *std::max_element(r.sxx_max.begin(), r.sxx_max.end());
  return m;
}

bool breaks(const RingMeasures& m, int per_ring) { return m.lost_max > kBreakShare * per_ring; }

/// The outcome in a few words (a table cell): a ring breaks, or intact (shedding a few particles or not) and
/// separated or not.
std::string outcome(const RingMeasures& m, int per_ring) {
  if (breaks(m, per_ring)) return "a ring breaks (" + std::to_string(m.lost_end) + " particles lost)";
  const std::string shed = m.lost_max > 0 ? " (sheds " + std::to_string(m.lost_max) + ")" : "";
  return (m.separated ? "intact" + shed + ", separated" : "intact" + shed + ", not separated by t_end");
}

/// The in-plane n = 2 (ovalling) period of a thin ring of mean radius R and thickness t, plane strain:
/// omega^2 = E' I / (rho A R^4) n^2 (n^2 - 1)^2 / (n^2 + 1), E' = E / (1 - nu^2), I / A = t^2 / 12.
double ring_ovalling_period(double K, double mu, double R, double t) {
  const double E = 9 * K * mu / (3 * K + mu), nu = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  const double Ep = E / (1 - nu * nu);
  const double w = std::sqrt(Ep * t * t / 12 / std::pow(R, 4) * 4 * 9 / 5);
  return 2 * M_PI / w;
}

/// Frozen-state spectra (common/gms.hpp) along the eps = 0 collision at a coarser grid (dp_spectrum: dense
/// eigenproblems of 2N and, with the viscosity on, 4N for N particles): at the start (at rest in the rings' frame:
/// stress free, so stable) and at `times` (the first: the contact, when the closest particles of the two rings are
/// nearest, also with the viscosity on; the later ones: the rebound, with the rings in hoop tension).
void frozen_spectra(double dp_spectrum, double gap, double skin, const std::vector<double>& times,
                    const std::string& out, study::Summary& sum) {
  const RateFormMaterial mat{.density = 1, .bulk_modulus = 1, .shear_modulus = 0.22};
  const Scene<2> scene =
      gms_rings_scene({.inner_radius = 3, .outer_radius = 4, .spacing = dp_spectrum, .gap = gap, .speed = 0.059},
                      {.material = mat, .scheme = gms_scheme_options(0)});
  const double h = scene.scheme->discretisation().h;
  study::frozen_spectra_along_run(*scene.scheme, scene.y0,
                                  {.dt = 0.5 * h / mat.p_wave_speed(), .neighbour_skin = skin * dp_spectrum}, times,
                                  times.front(), out, sum);
  sum.set("frozen_dp", dp_spectrum, 3);
  sum.set("frozen_particles", scene.scheme->discretisation().size());
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"GMS 2001 §7.2: colliding rubber rings with and without the artificial stress"};
  std::string out = "results/gms-rings";
  double t_end = 250, dp = 0.1, gap = 0.2, skin = 0.5;
  int threads = 2, frames = 12;
  long si_steps = 300;
  bool si_full = false, quick = false;
  double dp_spectrum = 0.25;
  std::vector<double> spectrum_times = {5, 25, 45};
  app.add_option("--out", out, "output directory");
  app.add_option("--t-end", t_end, "run length in cm/c0 (default 250, about 2 ovalling periods)")
      ->check(CLI::Range(0.01, 1e5));
  app.add_option("--dp", dp, "grid spacing of the GMS-unit rings in cm (GMS 0.1; thickness 1 needs dp <= 0.5)")
      ->check(CLI::Range(1e-3, 0.5));
  app.add_option("--gap", gap, "distance between the outer circles in cm (GMS give none)")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--skin", skin, "Verlet skin of the neighbour list in dp (rebuild after skin / 2 of motion)")
      ->check(CLI::Range(0.05, 10.0));
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--frames", frames, "VTK frames per run (0: none)")->check(CLI::Range(0, 1000));
  app.add_option("--si-steps", si_steps, "steps of the timed SI run")->check(CLI::Range(1L, 1000000L));
  app.add_flag("--si-full", si_full, "run the SI configuration over the whole collision (about 20 min per eps)");
  app.add_option("--dp-spectrum", dp_spectrum, "grid spacing of the frozen-state spectra (0: none)")
      ->check(CLI::Range(0.0, 0.5));
  app.add_option("--spectrum-times", spectrum_times,
                 "times of the frozen spectra (the first also with the viscosity on), cm/c0")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 1e4));
  app.add_flag("--quick", quick, "pipeline check: t_end 20, 20 SI steps, 3 frames");
  CLI11_PARSE(app, argc, argv);
  if (quick) t_end = 20, si_steps = 20, frames = std::min(frames, 3), dp_spectrum = 0.4, spectrum_times = {5};
  std::sort(spectrum_times.begin(), spectrum_times.end());
  const auto t0 = study::Clock::now();
  const std::string load_start = study::load_average();
  fs::create_directories(out + "/series");

  // GMS units first (longest), then the SI configuration: dx = 5e-4 m (half of GMS's dp in cm units: 0.05 cm), gap
  // 2e-3 m (the GMS-unit gap, 0.2 cm).
  std::vector<RingCase> cases;
  for (double eps : {0.0, 0.3})
    cases.push_back({.tag = "gms_eps" + format_number(eps),
                     .eps = eps,
                     .dp = dp,
                     .gap = gap,
                     .t_end = t_end,
                     .frames = frames,
                     .skin = skin});
  const RateFormMaterial si = si_material();
  for (double eps : {0.0, 0.3}) {
    RingCase c{.tag = "si_eps" + format_number(eps),
               .si = true,
               .eps = eps,
               .dp = 5e-4,
               .gap = 2e-3,
               .frames = 0,
               .skin = skin};
    if (si_full)
      c.t_end = t_end * 0.01 / si.sound_speed(), c.frames = frames;
    else
      c.steps = si_steps;
    cases.push_back(c);
  }
  // The same runs with the pair loop (each pair once, PairLoop::Pairs): the rates agree with the row loop's to
  // rounding, so the comparison shows what that rounding does to a collision and what the loop saves.
  const std::size_t row_cases = cases.size();
  // And with the pair loop and one rate evaluation per step ("fast": the predictor-corrector reusing the corrector's
  // rate, an O(dt^2) change of the integrator).
  for (bool one_rate : {false, true})
    for (std::size_t k = 0; k < row_cases; ++k) {
      RingCase c = cases[k];
      c.tag += one_rate ? "_fast" : "_pairs";
      c.loop = PairLoop::Pairs;
      c.one_rate = one_rate;
      c.frames = 0;
      cases.push_back(c);
    }
  // The dt sensitivity of the eps = 0.3 bounce: the row loop at half the time step.
  RingCase half = cases[1];
  half.tag += "_halfdt";
  half.dt_scale = 0.5;
  half.frames = 0;
  cases.push_back(half);
  std::fprintf(stderr, "gms-rings: %zu runs on %d threads\n", cases.size(), threads);
  const std::vector<RingRun> runs = run_all(cases, out, threads);
  const auto run_of = [&](bool si_units, double eps, PairLoop loop, bool one_rate = false) -> const RingRun& {
    for (const RingRun& r : runs)
      if (r.c.si == si_units && r.c.eps == eps && r.c.loop == loop && r.c.one_rate == one_rate && r.c.dt_scale == 1)
        return r;
    throw std::logic_error("gms-rings: no run for that case");
  };

  std::ofstream runs_csv(out + "/runs.csv");
  runs_csv << "tag,units,eps,loop,rates_per_step,dp,gap,particles,per_ring,h,dt,steps,t_end,status,wall,cpu,us_per_"
              "particle_step,us_cpu,"
              "neighbour_builds,contact_first,contact_last,touch_first,touch_last,separated,com_vx0_after,"
              "com_vx1_after,restitution,fragments_end,fragments_max,ring_fragments_end,ring_fragments_max,"
              "ring_break_time,lost_end,lost_max,ke_end_over_ke0,sigma_xx_max\n";
  study::Summary s;
  std::string table, cost_table;
  double wall_runs = 0, cpu_runs = 0;
  const int n_ring = runs.front().per_ring;
  for (const RingRun& r : runs) {
    const RingMeasures m = measure(r);
    wall_runs += r.cost.wall;
    cpu_runs += r.cost.cpu;
    const double t_end_g = r.cost.steps * r.dt / r.u.time();
    runs_csv << csv_line({r.c.tag,
                          r.c.si ? "SI" : "GMS",
                          format_number(r.c.eps),
                          r.c.loop == PairLoop::Pairs ? "pairs" : "rows",
                          r.c.one_rate ? "1" : "2",
                          format_number(r.c.dp),
                          format_number(r.c.gap),
                          std::to_string(r.particles),
                          std::to_string(r.per_ring),
                          format_number(r.h),
                          format_number(r.dt, 8),
                          std::to_string(r.cost.steps),
                          format_number(t_end_g),
                          r.status,
                          format_number(r.cost.wall, 4),
                          format_number(r.cost.cpu, 4),
                          format_number(r.cost.us_per_particle_step(), 4),
                          format_number(r.cost.us_cpu(), 4),
                          std::to_string(r.cost.neighbour_builds),
                          format_number(m.contact_first),
                          format_number(m.contact_last),
                          format_number(m.touch_first),
                          format_number(m.touch_last),
                          m.separated ? "1" : "0",
                          format_number(m.vx0_after),
                          format_number(m.vx1_after),
                          format_number(m.restitution),
                          std::to_string(m.frag_all_end),
                          std::to_string(m.frag_all_max),
                          std::to_string(m.frag_ring_end),
                          std::to_string(m.frag_ring_max),
                          format_number(m.ring_break_time),
                          std::to_string(m.lost_end),
                          std::to_string(m.lost_max),
                          format_number(m.ke_end_over_ke0),
                          format_number(m.sxx_max)});
    study::md_row(cost_table, {r.c.tag, r.c.si ? "SI" : "GMS", std::to_string(r.particles),
                               std::to_string(r.cost.steps), study::sig(t_end_g, 4), study::fixed(r.cost.wall, 1),
                               study::fixed(r.cost.cpu, 1), study::sig(r.cost.us_per_particle_step(), 3),
                               study::sig(r.cost.us_cpu(), 3), std::to_string(r.cost.neighbour_builds)});
    const bool full = r.c.steps == 0;
    if (r.c.loop == PairLoop::Pairs || r.c.dt_scale != 1) {  // compared with the row loop below
      if (!r.c.si) {
        const std::string k = std::string(r.c.dt_scale != 1 ? "halfdt_"
                                          : r.c.one_rate    ? "fast_"
                                                            : "pairs_") +
                              (r.c.eps > 0 ? "eps03" : "eps0");
        s.set(k + "_vx_end", r.vx1.back(), 3);
        s.set(k + "_ring_fragments_end", m.frag_ring_end);
        s.set(k + "_ring_fragments_max", m.frag_ring_max);
        s.set(k + "_lost_end", m.lost_end);
        s.set(k + "_ring_break_time", m.ring_break_time, 4);
        s.set(k + "_touch_first", m.touch_first, 3);
        s.set(k + "_touch_last", m.touch_last, 4);
        s.set(k + "_contact_last", m.contact_last, 4);
        s.set(k + "_separated", m.separated ? "yes" : "no");
        s.set(k + "_restitution", m.restitution, 3);
        s.set(k + "_ke_end", m.ke_end_over_ke0, 3);
        s.set(k + "_sxx_max", m.sxx_max, 3);
        s.set(k + "_outcome", outcome(m, n_ring));
      }
      continue;
    }
    if (full)
      study::md_row(
          table, {r.c.tag, study::fixed(r.c.eps, 1), study::sig(t_end_g, 4), std::to_string(m.frag_all_end),
                  std::to_string(m.frag_ring_end) + " / " + std::to_string(m.frag_ring_max), std::to_string(m.lost_end),
                  study::sig(m.ring_break_time, 4), study::sig(m.contact_first, 3), study::sig(m.contact_last, 4),
                  study::sig(m.touch_first, 3), study::sig(m.touch_last, 4), m.separated ? "yes" : "no",
                  study::fixed(m.vx0_after, 4, true) + " / " + study::fixed(m.vx1_after, 4, true),
                  study::fixed(m.restitution, 3), study::sig(m.ke_end_over_ke0, 3)});
    if (r.c.si) {
      const std::string k = r.c.eps > 0 ? "si_eps03" : "si_eps0";
      // The whole collision (t_end in cm/c0) at this run's cost per particle-step.
      const double full_steps = std::ceil(t_end * r.u.time() / r.dt);
      s.set(k + "_full_steps", full_steps, 4);
      s.set(k + "_full_minutes", full_steps * r.particles * r.cost.us_cpu() * 1e-6 / 60, 2);
      s.set(k + "_cpu", r.cost.cpu, 3);
      s.set(k + "_us_cpu", r.cost.us_cpu(), 3);
      s.set(k + "_steps", r.cost.steps);
      s.set(k + "_wall", r.cost.wall, 3);
      s.set(k + "_us", r.cost.us_per_particle_step(), 3);
      continue;
    }
    const std::string k = r.c.eps > 0 ? "eps03" : "eps0";
    s.set(k + "_fragments_end", m.frag_all_end);
    s.set(k + "_fragments_max", m.frag_all_max);
    s.set(k + "_ring_fragments_end", m.frag_ring_end);
    s.set(k + "_ring_fragments_max", m.frag_ring_max);
    s.set(k + "_lost_end", m.lost_end);
    s.set(k + "_lost_max", m.lost_max);
    s.set(k + "_ring_break_time", m.ring_break_time, 4);
    s.set(k + "_contact_first", m.contact_first, 3);
    s.set(k + "_contact_last", m.contact_last, 4);
    s.set(k + "_touch_first", m.touch_first, 3);
    s.set(k + "_touch_last", m.touch_last, 4);
    s.set(k + "_separated", m.separated ? "yes" : "no");
    s.set(k + "_vx0_after", m.vx0_after, 3);
    s.set(k + "_vx1_after", m.vx1_after, 3);
    s.set(k + "_restitution", m.restitution, 3);
    s.set(k + "_ke_end", m.ke_end_over_ke0, 3);
    s.set(k + "_sxx_max", m.sxx_max, 3);
    s.set(k + "_wall", r.cost.wall, 3);
    s.set(k + "_us", r.cost.us_per_particle_step(), 3);
    s.set(k + "_us_cpu", r.cost.us_cpu(), 3);
    s.set(k + "_cpu", r.cost.cpu, 3);
    s.set(k + "_steps", r.cost.steps);
    s.set(k + "_status", r.status);
    s.set(k + "_outcome", outcome(m, n_ring));
    s.set(k + "_vx_end", r.vx1.back(), 3);
    if (k == "eps0")
      s.set("eps0_verdict", breaks(m, n_ring)
                                ? "**Reproduced**: the rings break (" + std::to_string(m.frag_ring_end) +
                                      " fragments in the more broken ring at the end, " + std::to_string(m.lost_end) +
                                      " of its " + std::to_string(n_ring) + " particles outside its largest fragment)"
                                : "**Not reproduced**: no ring loses more than " + study::sig(100 * kBreakShare) +
                                      " % of its particles");
    else
      s.set("eps03_verdict",
            !breaks(m, n_ring) && m.separated
                ? "**Reproduced**: no ring loses more than " + study::sig(100 * kBreakShare) +
                      " % of its particles (at most " + std::to_string(m.lost_max) + " torn off), and the rings separate"
                : std::string("**Not reproduced**: ") +
                      (breaks(m, n_ring) ? "a ring breaks" : "the rings do not separate by t_end"));
  }
  const RingRun& g = runs.front();
  const RingRun& si_run = run_of(true, 0.3, PairLoop::Rows);
  // Row loop against pair loop: positions at the end (the largest distance over dp) and the thread CPU per
  // particle-step (the run's own cost; the two runs of a pair need not share the machine's load).
  std::string loops_table;
  for (bool si_units : {false, true})
    for (double eps : {0.0, 0.3}) {
      const RingRun &a = run_of(si_units, eps, PairLoop::Rows), &b = run_of(si_units, eps, PairLoop::Pairs),
                    &c = run_of(si_units, eps, PairLoop::Pairs, true);
      // Every particle of the rings is free: x at 8 i in the state.
      const auto largest_difference = [&](const RingRun& q) {
        double d = 0;
        for (int i = 0; i < a.particles; ++i)
          d = std::max(d, (a.y_end.segment<2>(8 * i) - q.y_end.segment<2>(8 * i)).norm());
        return d / a.c.dp;
      };
      study::md_row(loops_table, {si_units ? "SI" : "GMS", study::fixed(eps, 1), std::to_string(a.cost.steps),
                                  study::sig(largest_difference(b), 3), study::sig(largest_difference(c), 3),
                                  study::sig(a.cost.us_cpu(), 3), study::sig(b.cost.us_cpu(), 3),
                                  study::sig(c.cost.us_cpu(), 3), study::fixed(a.cost.us_cpu() / b.cost.us_cpu(), 2),
                                  study::fixed(a.cost.us_cpu() / c.cost.us_cpu(), 2)});
    }
  s.set("loops_table", loops_table);
  s.set("results_table", table);
  s.set("cost_table", cost_table);
  s.set("particles", g.particles);
  s.set("per_ring", g.per_ring);
  s.set("break_share_pct", 100 * kBreakShare, 3);
  s.set("break_particles", static_cast<int>(kBreakShare * g.per_ring));
  s.set("dp", dp, 3);
  s.set("h", g.h, 3);
  s.set("gap", gap, 3);
  s.set("dt", g.dt, 4);
  s.set("t_end", t_end, 4);
  s.set("speed", g.speed, 3);
  s.set("c_p", RateFormMaterial{.density = 1, .bulk_modulus = 1, .shear_modulus = 0.22}.p_wave_speed(), 4);
  s.set("ovalling_period", ring_ovalling_period(1, 0.22, 3.5, 1), 3);
  s.set("si_particles", si_run.particles);
  s.set("si_per_ring", si_run.per_ring);
  s.set("si_sound_speed", si.sound_speed(), 4);
  s.set("si_bulk_modulus", si.bulk_modulus, 4);
  s.set("si_shear_modulus", si.shear_modulus, 4);
  s.set("si_speed", si_run.speed, 4);
  s.set("si_dt", si_run.dt, 3);
  s.set("si_mode", si_full ? "the whole collision (--si-full)"
                           : "a timed run of " + std::to_string(si_steps) + " steps (the whole collision: --si-full)");
  s.set("threads", threads);
  s.set("skin", skin, 3);
  s.set("wall_runs", wall_runs, 3);
  s.set("cpu_runs", cpu_runs, 3);
  if (dp_spectrum > 0) {
    const auto ts = study::Clock::now();
    frozen_spectra(dp_spectrum, gap, skin, spectrum_times, out, s);
    s.set("frozen_wall", study::seconds_since(ts), 3);
  }
  s.set("wall_total", study::seconds_since(t0), 3);
  s.set("load_start", load_start);
  s.set("load_end", study::load_average());
  s.write(out);
  std::printf("gms-rings done in %.1f s\n", study::seconds_since(t0));
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "study_gms_rings: %s\n", e.what());
  return 1;
}
