#pragma once
// One run of the gms-slab study [GMS2001, §7.3]: the slab at spacing dp driven at both ends, with the rate-form
// scheme in the GMS configuration (gms_slab_scene) and the von Mises return, run in chunks from the previous chunk's
// state until it has broken plus a margin. At every time unit: the width profile between the driven zones
// (analysis/neck.hpp), the neck onset (narrowest width against the median of the inner window), the break (bonds
// < 1.5 dp) and the separation (< 2h) with their cracks (slab_break.hpp). Writes the VTK frames (regular and at the
// events) and logs them and the width profiles for frames.csv and profiles.csv (written by slab_tables.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/gms.hpp"
#include "common/study.hpp"
#include "slab_break.hpp"
#include "slab_case.hpp"
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

namespace gslab {

namespace fs = std::filesystem;

/// Per-record measures.
struct SlabRecord {
  double t = 0, ke = 0, end_displacement = 0;
  double min_width = kNaN, min_x = kNaN, median_width = kNaN;  ///< inner window (kEndZone from the driven zones)
  double min_width_all = kNaN, min_x_all = kNaN;               ///< whole profile between the driven zones
  double junction_left = kNaN, junction_right = kNaN;          ///< inner edges of the driven zones
  int fragments = 0, fragments_support = 0, largest = 0;
  bool broken = false, broken_support = false;  ///< ends separated with bonds < 1.5 dp / < 2h
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

inline double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

struct FrameInfo {
  std::string tag, kind, file;
  double t;
};

inline SlabRun run_slab(const SlabCase& c, const std::string& out, std::vector<FrameInfo>& frame_log,
                        std::vector<std::string>& profile_rows) {
  SlabRun r{.c = c};
  const PlasticSlab slab = make_plastic_slab({.spacing = c.dp, .end_zone = kEndZone, .acceleration = kAcceleration});
  r.particles = slab.size();
  r.columns = slab.columns;
  r.rows = slab.rows;
  r.driven = static_cast<int>(slab.driven.size());
  r.h = 1.5 * c.dp;
  const Kernel<2> kernel(KernelType::CubicSpline);
  const ElasticMaterial mat = ElasticMaterial::from_bulk_shear(1, kMu, 1);
  const Scene<2> scene = gms_slab_scene(
      {.spacing = c.dp, .end_zone = kEndZone, .acceleration = kAcceleration}, kYield,
      {.material = mat, .scheme = c.pair_loop ? gms_scheme_options(c.eps) : row_loop(gms_scheme_options(c.eps))});
  const RateFormScheme<2>& scheme = *scene.scheme;
  Eigen::VectorXd y = scene.y0;
  if (c.perturbation > 0) {  // the free particles only: the driven ends keep their prescribed motion
    std::mt19937_64 rng(c.seed);
    std::uniform_real_distribution<double> u(-c.perturbation * c.dp, c.perturbation * c.dp);
    std::vector<char> driven(scheme.discretisation().size(), 0);
    for (int i : slab.driven) driven[i] = 1;
    for (int i = 0; i < scheme.discretisation().size(); ++i) {
      const int xo = scheme.position_offset(i);
      if (xo < 0 || driven[i]) continue;
      for (int a = 0; a < 2; ++a) y[xo + a] += u(rng);
    }
  }
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
  return r;
}

}  // namespace gslab
