// Study: the plastic slab in tension of Gray, Monaghan & Swift [GMS2001, §7.3] with the rate-form scheme
// (forms/rate_form.hpp: continuity -rho tr L, EOS, Jaumann rate, XSPH 1/2, viscosity 1 / 2 with the compression switch,
// artificial stress eps = 0 or 0.3, n = 4; von Mises radial return, yield 0.03; GMS predictor-corrector with a Verlet
// neighbour list). The particles within 0.2 of each end are driven at +-5e-6 along x (RateFormScheme::set_driven).
// Measures: the width profile between the driven zones (analysis/neck.hpp), the neck onset (localisation: narrowest
// width against the median), the break (the two driven ends no longer joined by bonds, analysis/fragments.hpp) with
// its time, place and the neck width just before it. Runs go in chunks from the previous chunk's state and stop once
// the slab has broken plus a margin. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, series/<tag>.csv, profiles.csv, frames.csv, vtk/<tag>/*.vtp + <tag>.pvd,
// summary.json. GMS units: rho0 = c0 = 1 (K = 1), lengths in cm, time in cm / c0.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "common/gms.hpp"
#include "common/study.hpp"
#include "sphstab/analysis/fragments.hpp"
#include "sphstab/analysis/neck.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/rate_form_vtk.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/problems/plastic_slab.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kYield = 0.03, kMu = 0.3, kAcceleration = 5e-6, kEndZone = 0.2;
constexpr double kNeckRatio = 0.95;  ///< neck onset: narrowest width < kNeckRatio x the median width

struct SlabCase {
  std::string tag;
  double dp = 0.032, eps = 0.3;
  double t_max = 650;  ///< longest run
  double margin = 40;  ///< run on at most this long after the break (1.5 dp) when the ends do not separate (2h)
  double chunk = 10;   ///< run_rate_form chunk length (the break is checked between chunks)
  double skin = 0.5;   ///< Verlet skin in dp
  int frames = 12;     ///< regular VTK frames over t_max (0: none; event frames are written too)
};

/// Per-record measures.
struct SlabRecord {
  double t = 0, ke = 0, end_displacement = 0;
  double min_width = kNaN, min_x = kNaN, median_width = kNaN;  ///< inner window (kEndZone from the driven zones)
  double min_width_all = kNaN, min_x_all = kNaN;               ///< whole profile between the driven zones
  double junction_left = kNaN, junction_right = kNaN;          ///< inner edges of the driven zones
  int fragments = 0, fragments_support = 0, largest = 0;
  bool broken = false, broken_support = false;  ///< ends separated with bonds < 1.5 dp / < 2h
};

/// One crack of a break: the midpoint of the closest pair of particles between an end's fragment and all the other
/// particles (the last bond that held that end), its distance from that end's junction (the inner edge of its driven
/// zone), its position between the junctions (0 left, 1 right) and the width of the strip there one record before.
struct Crack {
  double x = kNaN, y = kNaN, junction_distance = kNaN, position = kNaN, width_before = kNaN;
};

/// A detected break: time and the cracks bounding the left end's fragment and the right end's (the same crack when
/// the slab breaks in two; two cracks when a middle piece comes free, as the symmetric slab tends to do).
struct Break {
  double t = kNaN;
  Crack left, right;
  bool one_crack = true;                              ///< the two cracks are within 2h of each other
  double x_narrowest = kNaN, width_narrowest = kNaN;  ///< the narrowest bin of the whole profile one record before
  double junction_distance() const { return std::min(left.junction_distance, right.junction_distance); }
  double width_before() const { return std::fmin(left.width_before, right.width_before); }
  int cracks() const { return std::isnan(t) ? 0 : one_crack ? 1 : 2; }
};

struct SlabRun {
  SlabCase c;
  int particles = 0, columns = 0, rows = 0, driven = 0;
  double h = 0, dt = 0, width0 = kNaN;
  study::RunCost cost;
  int chunks = 0;
  std::string status;
  std::vector<SlabRecord> records;
  double t_neck = kNaN, x_neck = kNaN, width_neck = kNaN;  ///< localisation onset
  double t_w95 = kNaN;                                     ///< narrowest inner width < 0.95 x initial
  double t_w10 = kNaN;     ///< narrowest inner width < 10 dp (GMS: the neck fractures at "~10 particles thick")
  Break brk, brk_support;  ///< bond radius 1.5 dp and 2h
  double t_stop = 0;
};

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

/// The fragment holding most of `particles` (an end zone may shed a corner particle).
int majority_label(const Fragments& f, const std::vector<int>& particles) {
  std::vector<int> votes(f.count(), 0);
  for (int i : particles) ++votes[f.label[i]];
  return static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
}

/// The last bond that held fragment `label` to the rest: the midpoint of the closest pair of particles between the
/// fragment and all the other particles.
Eigen::Vector2d closest_to_rest(const Eigen::Matrix2Xd& x, const Fragments& f, int label) {
  std::vector<int> in, out;
  for (int i = 0; i < static_cast<int>(f.label.size()); ++i) (f.label[i] == label ? in : out).push_back(i);
  double best = kInf;
  Eigen::Vector2d mid(kNaN, kNaN);
  for (int i : in)
    for (int j : out) {
      const double d = (x.col(i) - x.col(j)).squaredNorm();
      if (d < best) best = d, mid = 0.5 * (x.col(i) + x.col(j));
    }
  return mid;
}

struct FrameInfo {
  std::string tag, kind, file;
  double t;
};

SlabRun run_slab(const SlabCase& c, const std::string& out, std::vector<FrameInfo>& frame_log,
                 std::vector<std::string>& profile_rows) {
  SlabRun r{.c = c};
  const PlasticSlab slab = make_plastic_slab({.spacing = c.dp, .end_zone = kEndZone, .acceleration = kAcceleration});
  r.particles = slab.size();
  r.columns = slab.columns;
  r.rows = slab.rows;
  r.driven = static_cast<int>(slab.driven.size());
  r.h = 1.5 * c.dp;
  const Kernel<2> kernel(KernelType::CubicSpline);
  const RateFormMaterial mat{.density = 1, .bulk_modulus = 1, .shear_modulus = kMu};
  const Scene<2> scene = gms_slab_scene({.spacing = c.dp, .end_zone = kEndZone, .acceleration = kAcceleration}, kYield,
                                        {.material = mat, .scheme = gms_scheme_options(c.eps)});
  const RateFormScheme<2>& scheme = *scene.scheme;
  Eigen::VectorXd y = scene.y0;
  double right0 = 0;
  for (int i : slab.right_end) right0 += slab.particles.x(i, 0) / slab.right_end.size();

  const double bond = 1.5 * c.dp, support = kernel.support_radius(r.h);
  const SlabNeckOptions neck_options{.bin_width = 2 * c.dp, .particle_size = c.dp, .bond_radius = bond};
  // Steps: a record every ~1 time unit, a chunk of whole records, dt = 0.5 h / c_P rounded down to fit.
  const double dt0 = 0.5 * r.h / mat.p_wave_speed();
  const int record_every = std::max(1, static_cast<int>(std::ceil(1.0 / dt0)));
  r.dt = 1.0 / record_every;  // <= dt0
  const int records_per_chunk = std::max(1, static_cast<int>(std::lround(c.chunk)));
  const long chunk_steps = static_cast<long>(record_every) * records_per_chunk;
  const double chunk_time = chunk_steps * r.dt;

  const std::string vtk_dir = out + "/vtk/" + c.tag;
  if (c.frames > 0) fs::create_directories(vtk_dir);
  std::vector<std::pair<double, std::string>> pvd;
  const double frame_every = c.t_max / std::max(c.frames, 1);
  int regular_frames = 0;
  auto frame = [&](const Eigen::VectorXd& ys, double t, const std::string& kind) {
    if (c.frames <= 0) return;
    char name[96];
    std::snprintf(name, sizeof name, "%s_t%07.2f_%s.vtp", c.tag.c_str(), t, kind.c_str());
    write_rate_form_vtp(vtk_dir + "/" + name, scheme, ys);
    pvd.emplace_back(t, name);
    frame_log.push_back({c.tag, kind, std::string("vtk/") + c.tag + "/" + name, t});
  };
  auto log_profile = [&](const NeckProfile& p, double t, const std::string& kind) {
    for (std::size_t k = 0; k < p.width.size(); ++k)
      profile_rows.push_back(csv_line({c.tag, format_number(t, 6), kind, format_number(p.centre[k], 8),
                                       format_number(p.width[k], 8), std::to_string(p.count[k])}));
  };

  NeckProfile previous;
  double t0 = 0;
  auto observe = [&](long step, double t_chunk, const Eigen::VectorXd& ys) {
    if (step == 0 && r.chunks > 0) return;  // the previous chunk's last record
    const double t = t0 + t_chunk;
    const Eigen::Matrix2Xd x = rate_form_positions(scheme, ys);
    const SlabNeck neck = slab_neck(x, slab.left_end, slab.right_end, neck_options);
    const Fragments fs2h = find_fragments(x, support);
    SlabRecord rec{.t = t, .ke = scheme.kinetic_energy(ys)};
    double right = 0;
    for (int i : slab.right_end) right += x(0, i) / slab.right_end.size();
    rec.end_displacement = right - right0;
    const NeckProfile& p = neck.profile;
    rec.junction_left = p.x_lo - c.dp;  // slab_neck's range starts w/2 = dp inside the driven zone's edge
    rec.junction_right = p.x_hi + c.dp;
    std::vector<double> inner;
    for (std::size_t k = 0; k < p.width.size(); ++k) {
      if (std::isnan(p.width[k])) continue;
      if (!(rec.min_width_all <= p.width[k])) rec.min_width_all = p.width[k], rec.min_x_all = p.centre[k];
      if (p.centre[k] < p.x_lo + kEndZone || p.centre[k] > p.x_hi - kEndZone) continue;
      inner.push_back(p.width[k]);
      if (!(rec.min_width <= p.width[k])) rec.min_width = p.width[k], rec.min_x = p.centre[k];
    }
    rec.median_width = median(inner);
    rec.fragments = neck.fragments.count();
    rec.largest = neck.fragments.largest();
    rec.fragments_support = fs2h.count();
    rec.broken = neck.broken;
    rec.broken_support = ends_separated(fs2h, slab.left_end, slab.right_end);
    if (r.records.empty()) r.width0 = rec.min_width;
    bool event = false;
    if (std::isnan(r.t_neck) && std::isnan(r.brk.t) && rec.min_width < kNeckRatio * rec.median_width) {
      r.t_neck = t, r.x_neck = rec.min_x, r.width_neck = rec.min_width;
      frame(ys, t, "neck");
      log_profile(p, t, "neck");
      event = true;
    }
    if (std::isnan(r.t_w95) && rec.min_width < 0.95 * r.width0) r.t_w95 = t;
    if (std::isnan(r.t_w10) && std::isnan(r.brk.t) && rec.min_width < 10 * c.dp) r.t_w10 = t;
    auto detect = [&](bool broken, const Fragments& f, Break& b, const char* kind) {
      if (!broken || !std::isnan(b.t)) return;
      b.t = t;
      auto crack = [&](const std::vector<int>& end, bool left) {
        Crack c;
        const Eigen::Vector2d m = closest_to_rest(x, f, majority_label(f, end));
        c.x = m[0], c.y = m[1];
        c.junction_distance = std::abs(left ? c.x - rec.junction_left : rec.junction_right - c.x);
        c.position = (c.x - rec.junction_left) / (rec.junction_right - rec.junction_left);
        // The width at that place one record earlier (the neck the break went through).
        for (std::size_t k = 0; k < previous.width.size(); ++k)
          if (std::abs(previous.centre[k] - c.x) <= 0.5 * previous.bin_width + 1e-12)
            c.width_before = previous.width[k];
        return c;
      };
      b.left = crack(slab.left_end, true);
      b.right = crack(slab.right_end, false);
      b.one_crack = std::abs(b.left.x - b.right.x) <= support;
      b.x_narrowest = previous.min_x, b.width_narrowest = previous.min_width;
      frame(ys, t, kind);
      log_profile(previous, previous.centre.empty() ? t : r.records.back().t, std::string(kind) + "-before");
      event = true;
    };
    detect(rec.broken, neck.fragments, r.brk, "break");
    detect(rec.broken_support, fs2h, r.brk_support, "separation");
    if (!event && t >= regular_frames * frame_every - 0.5 * r.dt) {
      frame(ys, t, "regular");
      log_profile(p, t, "regular");
      ++regular_frames;
    }
    previous = p;
    r.records.push_back(rec);
  };

  r.status = "completed to t_max";
  while (t0 < c.t_max - 0.5 * r.dt) {
    const double len = std::min(chunk_time, c.t_max - t0);
    const RateFormRunResult run = study::timed_run(scheme, y,
                                                   {.dt = r.dt,
                                                    .t_end = len,
                                                    .record_every = record_every,
                                                    .observer = observe,
                                                    .yield_stress = kYield,
                                                    .neighbour_skin = c.skin * c.dp},
                                                   r.cost);
    ++r.chunks;
    t0 += run.steps * run.dt;
    y = run.y;
    if (!run.completed()) {
      r.status = run.message;
      break;
    }
    // Stop one chunk after the separation (bonds < 2h), or `margin` after the break (bonds < 1.5 dp).
    if (!std::isnan(r.brk_support.t) || (!std::isnan(r.brk.t) && t0 >= r.brk.t + c.margin - 0.5 * r.dt)) {
      r.status = !std::isnan(r.brk_support.t) ? "stopped after the separation"
                                              : "stopped " + format_number(c.margin) + " after the break";
      break;
    }
  }
  r.t_stop = t0;
  if (c.frames > 0) {
    if (pvd.empty() || pvd.back().first < t0 - 0.5 * r.dt) frame(y, t0, "final");
    log_profile(slab_neck(rate_form_positions(scheme, y), slab.left_end, slab.right_end, neck_options).profile, t0,
                "final");
    write_pvd(vtk_dir + "/" + c.tag + ".pvd", pvd);
  }

  std::ofstream csv(out + "/series/" + c.tag + ".csv");
  csv << "t,kinetic,end_displacement,min_width,min_x,median_width,min_width_all,min_x_all,junction_left,"
         "junction_right,fragments,largest,fragments_support,broken,broken_support\n";
  for (const SlabRecord& s : r.records)
    csv << csv_line({format_number(s.t, 8), format_number(s.ke, 8), format_number(s.end_displacement, 8),
                     format_number(s.min_width, 8), format_number(s.min_x, 8), format_number(s.median_width, 8),
                     format_number(s.min_width_all, 8), format_number(s.min_x_all, 8),
                     format_number(s.junction_left, 8), format_number(s.junction_right, 8), std::to_string(s.fragments),
                     std::to_string(s.largest), std::to_string(s.fragments_support), s.broken ? "1" : "0",
                     s.broken_support ? "1" : "0"});
  return r;
}

/// Where a crack is, in words: at a junction (within 2h = 3 dp of a driven zone's inner edge), in the middle (the
/// middle fifth between the junctions) or between the two.
std::string place(const Crack& c, double dp) {
  char buf[160];
  const char* what = c.junction_distance <= 3 * dp       ? "at the forced/free junction"
                     : std::abs(c.position - 0.5) <= 0.1 ? "in the middle"
                                                         : "between the middle and a junction";
  std::snprintf(buf, sizeof buf, "%s (x = %.3f, %.3g = %.3g dp from its end's junction)", what, c.x,
                c.junction_distance, c.junction_distance / dp);
  return buf;
}

/// Where a break is, in words: its crack, or its two cracks.
std::string where(const Break& b, double dp) {
  if (std::isnan(b.t)) return "no break";
  if (b.one_crack) return "one crack " + place(b.left, dp);
  return "two cracks, one " + place(b.left, dp) + " and one " + place(b.right, dp);
}

/// The x of the crack(s): "x" or "x_left / x_right".
std::string crack_x(const Break& b) {
  if (std::isnan(b.t)) return "-";
  return b.one_crack ? study::fixed(b.left.x, 3) : study::fixed(b.left.x, 3) + " / " + study::fixed(b.right.x, 3);
}

/// Frozen-state spectra (common/gms.hpp) along the eps = 0 run at a coarser grid (dp_spectrum): the start (stress
/// free) and `times` before the break, under eps = 0 and 0.3, the last time also with the viscosity on. Elastic
/// linearisations: the von Mises return is not part of the rate (the run has it).
void frozen_spectra(double dp_spectrum, double skin, const std::vector<double>& times, const std::string& out,
                    study::Summary& sum) {
  const RateFormMaterial mat{.density = 1, .bulk_modulus = 1, .shear_modulus = kMu};
  const Scene<2> scene = gms_slab_scene({.spacing = dp_spectrum, .end_zone = kEndZone, .acceleration = kAcceleration},
                                        kYield, {.material = mat, .scheme = gms_scheme_options(0)});
  const double h = scene.scheme->discretisation().h;
  study::frozen_spectra_along_run(
      *scene.scheme, scene.y0,
      {.dt = 0.5 * h / mat.p_wave_speed(), .yield_stress = kYield, .neighbour_skin = skin * dp_spectrum}, times,
      times.back(), out, sum);
  sum.set("frozen_dp", dp_spectrum, 3);
  sum.set("frozen_particles", scene.scheme->discretisation().size());
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"GMS 2001 §7.3: plastic slab in tension with and without the artificial stress"};
  std::string out = "results/gms-slab";
  std::vector<double> dps = {0.04, 0.05};
  double t_max0 = 200, t_max3 = 650, margin = 40, chunk = 10, skin = 0.5;
  int threads = 2, frames = 12;
  bool quick = false;
  double dp_spectrum = 0.0625;
  std::vector<double> spectrum_times = {60, 100};
  app.add_option("--out", out, "output directory");
  app.add_option("--dp", dps, "particle spacings, comma list (GMS 0.016: about 30 CPU minutes for eps = 0.3)")
      ->delimiter(',')
      ->check(CLI::Range(0.004, 0.2));
  app.add_option("--t-max-eps0", t_max0, "longest eps = 0 run (GMS break 119)")->check(CLI::Range(1.0, 1e5));
  app.add_option("--t-max-eps03", t_max3, "longest eps = 0.3 run (GMS break 542)")->check(CLI::Range(1.0, 1e5));
  app.add_option("--margin", margin,
                 "run on at most this long after the break (1.5 dp bonds) when the ends have not "
                 "separated (2h)")
      ->check(CLI::Range(0.0, 1e5));
  app.add_option("--chunk", chunk, "chunk length between break checks (whole time units)")
      ->check(CLI::Range(1.0, 1000.0));
  app.add_option("--skin", skin, "Verlet skin of the neighbour list in dp")->check(CLI::Range(0.05, 10.0));
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--frames", frames, "regular VTK frames per run (0: none)")->check(CLI::Range(0, 1000));
  app.add_option("--dp-spectrum", dp_spectrum, "grid spacing of the frozen-state spectra (0: none)")
      ->check(CLI::Range(0.0, 0.2));
  app.add_option("--spectrum-times", spectrum_times,
                 "times of the frozen spectra (the last also with the viscosity on)")
      ->delimiter(',')
      ->check(CLI::Range(0.01, 1e4));
  app.add_flag("--quick", quick, "pipeline check: dp 0.08, both runs to t = 40");
  CLI11_PARSE(app, argc, argv);
  if (quick)
    dps = {0.08}, t_max0 = t_max3 = 40, frames = std::min(frames, 4), dp_spectrum = 0.125, spectrum_times = {20};
  std::sort(spectrum_times.begin(), spectrum_times.end());
  std::sort(dps.begin(), dps.end());
  dps.erase(std::unique(dps.begin(), dps.end()), dps.end());
  const auto t0 = study::Clock::now();
  const std::string load_start = study::load_average();
  fs::create_directories(out + "/series");

  std::vector<SlabCase> cases;
  for (double dp : dps)
    for (double eps : {0.3, 0.0})
      cases.push_back({.tag = "dp" + format_number(dp) + "_eps" + format_number(eps),
                       .dp = dp,
                       .eps = eps,
                       .t_max = eps > 0 ? t_max3 : t_max0,
                       .margin = margin,
                       .chunk = chunk,
                       .skin = skin,
                       .frames = frames});
  // Longest first (particles x steps ~ t_max / dp^3), so that two threads finish together.
  std::vector<std::size_t> order(cases.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  auto cost = [&](const SlabCase& c) { return c.t_max / std::pow(c.dp, 3); };
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return cost(cases[a]) > cost(cases[b]); });
  std::fprintf(stderr, "gms-slab: %zu runs on %d threads\n", cases.size(), threads);

  std::vector<SlabRun> runs(cases.size());
  std::vector<std::vector<FrameInfo>> frame_logs(cases.size());
  std::vector<std::vector<std::string>> profile_logs(cases.size());
  std::mutex m;
  study::parallel_for(order.size(), threads, [&](std::size_t q) {
    const std::size_t k = order[q];
    runs[k] = run_slab(cases[k], out, frame_logs[k], profile_logs[k]);
    std::lock_guard<std::mutex> lock(m);
    const SlabRun& r = runs[k];
    std::printf(
        "%-16s %5d particles, %6ld steps to t = %.0f, %7.1f s wall (%.1f s CPU), %.3g us per particle-step "
        "(%.3g CPU), %ld builds: %s; "
        "neck %.4g, break %.4g (1.5 dp) / %.4g (2h) at x = %.3g, width before %.3g = %.3g dp\n",
        r.c.tag.c_str(), r.particles, r.cost.steps, r.t_stop, r.cost.wall, r.cost.cpu, r.cost.us_per_particle_step(),
        r.cost.us_cpu(), r.cost.neighbour_builds, r.status.c_str(), r.t_neck, r.brk.t, r.brk_support.t, r.brk.left.x,
        r.brk.width_before(), r.brk.width_before() / r.c.dp);
    std::fflush(stdout);
  });

  std::ofstream frames_csv(out + "/frames.csv"), profiles_csv(out + "/profiles.csv");
  frames_csv << "tag,kind,t,file\n";
  profiles_csv << "tag,t,kind,x,width,count\n";
  for (std::size_t k = 0; k < cases.size(); ++k) {
    for (const FrameInfo& f : frame_logs[k]) frames_csv << csv_line({f.tag, f.kind, format_number(f.t, 8), f.file});
    for (const std::string& line : profile_logs[k]) profiles_csv << line;
  }

  std::ofstream runs_csv(out + "/runs.csv");
  runs_csv
      << "tag,dp,eps,columns,rows,particles,driven,h,dt,steps,chunks,t_stop,status,wall,cpu,us_per_particle_step,"
         "us_cpu,"
         "neighbour_builds,width0,t_neck,x_neck,width_neck,t_w95,t_w10,t_break,cracks,x_crack_left,y_crack_left,"
         "x_crack_right,y_crack_right,junction_distance_left,junction_distance_right,position_left,position_right,"
         "width_before_left,width_before_right,t_separation,separation_cracks,x_separation_left,x_separation_right,"
         "separation_junction_distance,end_displacement_at_break,x_narrowest_before_break,"
         "width_narrowest_before_break\n";
  study::Summary s;
  std::string table, cost_table;
  double wall_runs = 0, wall_max = 0, cpu_runs = 0;
  auto end_disp = [](double t) { return std::isnan(t) ? kNaN : slab_end_displacement(t, kAcceleration); };
  for (const SlabRun& r : runs) {
    wall_runs += r.cost.wall;
    cpu_runs += r.cost.cpu;
    wall_max = std::max(wall_max, r.cost.wall);
    runs_csv << csv_line({r.c.tag,
                          format_number(r.c.dp),
                          format_number(r.c.eps),
                          std::to_string(r.columns),
                          std::to_string(r.rows),
                          std::to_string(r.particles),
                          std::to_string(r.driven),
                          format_number(r.h),
                          format_number(r.dt, 8),
                          std::to_string(r.cost.steps),
                          std::to_string(r.chunks),
                          format_number(r.t_stop),
                          r.status,
                          format_number(r.cost.wall, 4),
                          format_number(r.cost.cpu, 4),
                          format_number(r.cost.us_per_particle_step(), 4),
                          format_number(r.cost.us_cpu(), 4),
                          std::to_string(r.cost.neighbour_builds),
                          format_number(r.width0),
                          format_number(r.t_neck),
                          format_number(r.x_neck),
                          format_number(r.width_neck),
                          format_number(r.t_w95),
                          format_number(r.t_w10),
                          format_number(r.brk.t),
                          std::to_string(r.brk.cracks()),
                          format_number(r.brk.left.x),
                          format_number(r.brk.left.y),
                          format_number(r.brk.right.x),
                          format_number(r.brk.right.y),
                          format_number(r.brk.left.junction_distance),
                          format_number(r.brk.right.junction_distance),
                          format_number(r.brk.left.position),
                          format_number(r.brk.right.position),
                          format_number(r.brk.left.width_before),
                          format_number(r.brk.right.width_before),
                          format_number(r.brk_support.t),
                          std::to_string(r.brk_support.cracks()),
                          format_number(r.brk_support.left.x),
                          format_number(r.brk_support.right.x),
                          format_number(r.brk_support.junction_distance()),
                          format_number(end_disp(r.brk.t)),
                          format_number(r.brk.x_narrowest),
                          format_number(r.brk.width_narrowest)});
    const std::string paper_break = r.c.eps > 0 ? "542" : "119";
    study::md_row(table, {study::fixed(r.c.dp, 3), std::to_string(r.columns) + " × " + std::to_string(r.rows),
                          study::fixed(r.c.eps, 1), study::sig(r.t_neck, 4), study::sig(r.x_neck, 3),
                          study::sig(r.t_w95, 4), study::sig(r.t_w10, 4),
                          study::sig(r.brk.t, 4) + " (" + paper_break + ")", study::sig(r.brk_support.t, 4),
                          std::to_string(r.brk.cracks()), crack_x(r.brk), study::fixed(r.brk.junction_distance(), 3),
                          study::sig(r.brk.width_before() / r.c.dp, 3), study::sig(r.t_stop, 4)});
    study::md_row(cost_table, {r.c.tag, std::to_string(r.particles), study::sig(r.dt, 4), std::to_string(r.cost.steps),
                               study::sig(r.t_stop, 4), study::fixed(r.cost.wall, 1), study::fixed(r.cost.cpu, 1),
                               study::sig(r.cost.us_per_particle_step(), 3), study::sig(r.cost.us_cpu(), 3),
                               std::to_string(r.cost.neighbour_builds), r.status});
    if (r.c.dp != dps.front()) continue;  // the key numbers of the prose: the finest resolution run
    const std::string k = r.c.eps > 0 ? "eps03" : "eps0";
    s.set(k + "_t_neck", r.t_neck, 4);
    s.set(k + "_x_neck", r.x_neck, 3);
    s.set(k + "_t_w95", r.t_w95, 4);
    s.set(k + "_t_w10", r.t_w10, 4);
    s.set(k + "_t_break", r.brk.t, 4);
    s.set(k + "_cracks", r.brk.cracks());
    s.set(k + "_x_break", crack_x(r.brk));
    s.set(k + "_break_junction", r.brk.junction_distance(), 3);
    s.set(k + "_width_before", r.brk.width_before() / r.c.dp, 3);
    s.set(k + "_x_narrowest", r.brk.x_narrowest, 3);
    s.set(k + "_width_narrowest", r.brk.width_narrowest / r.c.dp, 3);
    s.set(k + "_t_separation", r.brk_support.t, 4);
    s.set(k + "_t_stop", r.t_stop, 4);
    s.set(k + "_wall", r.cost.wall, 3);
    s.set(k + "_cpu", r.cost.cpu, 3);
    s.set(k + "_end_displacement", end_disp(r.brk.t), 3);
    s.set(k + "_where", where(r.brk, r.c.dp));
    // GMS's "strain": one end's displacement over the length 3 (0.13 at t = 394).
    s.set(k + "_neck_strain", end_disp(r.t_neck) / 3, 3);
    s.set(k + "_break_strain", end_disp(r.brk.t) / 3, 3);
    s.set(k + "_where_separation", where(r.brk_support, r.c.dp));
    s.set("fine_particles", r.particles);
    s.set("fine_grid", std::to_string(r.columns) + " × " + std::to_string(r.rows));
    s.set("fine_dt", r.dt, 4);
  }
  s.set("fine_dp", dps.front(), 3);
  std::string dp_list;
  for (double dp : dps) dp_list += (dp_list.empty() ? "" : ", ") + format_number(dp);
  s.set("dp_list", dp_list);
  s.set("results_table", table);
  s.set("cost_table", cost_table);
  s.set("t_max_eps0", t_max0, 4);
  s.set("t_max_eps03", t_max3, 4);
  s.set("margin", margin, 3);
  s.set("chunk", chunk, 3);
  s.set("skin", skin, 3);
  s.set("neck_ratio", kNeckRatio, 3);
  s.set("c_p", RateFormMaterial{.density = 1, .bulk_modulus = 1, .shear_modulus = kMu}.p_wave_speed(), 4);
  s.set("threads", threads);
  s.set("wall_runs", wall_runs, 3);
  s.set("cpu_runs", cpu_runs, 3);
  s.set("load_start", load_start);
  s.set("load_end", study::load_average());
  s.set("wall_max", wall_max, 3);
  if (dp_spectrum > 0) {
    const auto ts = study::Clock::now();
    frozen_spectra(dp_spectrum, skin, spectrum_times, out, s);
    s.set("frozen_wall", study::seconds_since(ts), 3);
  }
  s.set("wall_total", study::seconds_since(t0), 3);
  s.write(out);
  std::printf("gms-slab done in %.1f s\n", study::seconds_since(t0));
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "study_gms_slab: %s\n", e.what());
  return 1;
}
