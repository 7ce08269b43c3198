#pragma once
// One run of the gms-rings study [GMS2001, §7.2]: the two rings of a case (colliding_rings.hpp) with the rate-form
// scheme in the GMS configuration (gms_rings_scene: XSPH, viscosity with the compression switch, artificial stress
// eps, predictor-corrector, Verlet neighbour list). At every record: the fragments (bond graph, bonds < 1.5 dp) of the
// scene and of each ring, the closest distance between the rings and between their bodies (largest fragments), the
// rings' centre-of-mass velocities, the largest sigma_xx and the kinetic energy. Writes the run's VTK frames; its
// series is written by ring_tables.hpp.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "common/gms.hpp"
#include "common/study.hpp"
#include "ring_case.hpp"
#include "sphstab/analysis/fragments.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/rate_form_vtk.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/problems/colliding_rings.hpp"

namespace grings {

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
  /// The length of the run in GMS time units (cm / c0).
  double t_run() const { return cost.steps * dt / u.time(); }
};

/// Smallest distance between a particle of ring 0 (indices [0, n)) and one of ring 1 ([n, 2n)), exact when below
/// `band`; otherwise some value >= band (the candidates are the particles within `band` in x of the other ring's
/// extent).
inline double ring_distance(const Eigen::Matrix2Xd& x, const std::vector<int>& left, const std::vector<int>& right,
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
inline std::vector<int> body(const Fragments& f, int first) {
  const int big = static_cast<int>(std::max_element(f.sizes.begin(), f.sizes.end()) - f.sizes.begin());
  std::vector<int> idx;
  for (int i = 0; i < static_cast<int>(f.label.size()); ++i)
    if (f.label[i] == big) idx.push_back(first + i);
  return idx;
}

/// Runs case c, writing its VTK frames to out/vtk/<tag>/ (with <tag>.pvd).
inline RingRun run_rings(const RingCase& c, const std::string& out) {
  RingRun r{.c = c};
  const ElasticMaterial mat = c.si ? si_material() : gms_material();
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
  if (c.frames > 0) std::filesystem::create_directories(vtk_dir);
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
      const double p = mat.bulk_modulus() * (y[scheme.density_offset(i)] / mat.density() - 1);
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
    r.sxx_max.push_back(smax / (mat.density() * r.u.speed * r.u.speed));
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
  return r;
}

}  // namespace grings
