#pragma once
// One run of an impact case (impact_cases.hpp): the lattice, the absorbing particles with Powell's manual normals,
// the patch's velocity, and Powell's leap-frog with XSPH to t_end, recording v_x, v_y at the probes; and the runs of
// the study, largest first on the threads.
#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "common/driver.hpp"
#include "common/nrbc.hpp"
#include "common/study.hpp"
#include "impact_cases.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace nrbc_impact {

struct ImpactRun {
  ImpactCase c;
  std::string status;
  int particles = 0, absorbing = 0;
  double wall = 0, cpu = 0;
  std::vector<double> t;
  std::vector<std::vector<Eigen::Vector2d>> v;  ///< per record, per probe
};

inline ImpactRun run_impact(const ImpactCase& c) {
  // Particle (i, j) at ((i + 1/2 - nx/2) dx, -(j + 1/2) dx): every domain is a subset of the same lattice.
  const int n = c.nx * c.ny;
  ParticleSet<2> p;
  p.x.resize(n, 2);
  p.volume = Eigen::VectorXd::Constant(n, kDx * kDx);
  p.role.assign(n, Role::Free);
  p.spacing = kDx;
  for (int j = 0; j < c.ny; ++j)
    for (int i = 0; i < c.nx; ++i) p.x.row(j * c.nx + i) << (i + 0.5 - 0.5 * c.nx) * kDx, -(j + 0.5) * kDx;
  auto disc = make_discretisation(p, Kernel<2>(KernelType::CubicSpline), 1.3 * kDx);
  RateFormScheme<2> scheme(
      disc, kSteel,
      {.continuity = ContinuityForm::Divergence, .viscosity = ViscositySwitch::Compression, .gradient = c.gradient});
  ImpactRun r{.c = c, .particles = n};
  if (absorbs(c.boundary)) {
    // Powell's manual normals on floor(2h/dx) + 1 = 3 layers (the viscous traction: the outer layer only), with the
    // NCSPH-normalised velocity gradient at the absorbing particles (nrbc-plane-wave: the plain one reflects 2.4x more
    // energy at normal incidence, lambda = 12 dx).
    const int layers = c.boundary == Boundary::Traction ? 1 : 3;
    AbsorbingParticles<2> a = absorbing_particles(c.boundary, kDx, true);
    for (int j = 0; j < c.ny; ++j)
      for (int i = 0; i < c.nx; ++i) {
        Eigen::Vector2d normal = Eigen::Vector2d::Zero();
        if (c.side == Side::Sides && i < layers) normal = {-1, 0};
        if (c.side == Side::Sides && i >= c.nx - layers) normal = {1, 0};
        if (c.side == Side::Bottom && j >= c.ny - layers) normal = {0, -1};
        if (normal.squaredNorm() == 0) continue;
        add_absorbing(a, c.boundary, j * c.nx + i, normal);
      }
    r.absorbing = static_cast<int>(a.particles.size());
    scheme.set_absorbing(a);
  }
  Eigen::VectorXd y0 = scheme.uniform_state();
  for (int k = 0; k < n; ++k)
    if (std::abs(p.x(k, 0)) < 0.3 && p.x(k, 1) > -2 * kDx) scheme.set_velocity(y0, k, Eigen::Vector2d(0, -c.v_patch));
  std::vector<int> at;
  for (const Probe& q : probes()) {
    int best = -1;
    double d = 1e300;
    for (int k = 0; k < n; ++k) {
      const double e = (p.x.row(k).transpose() - Eigen::Vector2d(q.x, q.y)).norm();
      if (e < d) d = e, best = k;
    }
    at.push_back(d < 1e-9 ? best : -1);  // -1: outside this domain (recorded as NaN)
  }
  RateFormRunOptions o = powell_leapfrog(c.cfl * kDx / kSteel.p_wave_speed(), c.t_end);
  o.observer = [&](long, double t, const Eigen::VectorXd& y) {
    r.t.push_back(t);
    std::vector<Eigen::Vector2d> v;
    for (int k : at)
      v.push_back(k < 0 ? Eigen::Vector2d(NAN, NAN) : Eigen::Vector2d(y.segment<2>(scheme.velocity_offset(k))));
    r.v.push_back(std::move(v));
  };
  o.neighbour_skin = 0.5 * kDx;
  const auto t0 = study::Clock::now();
  const double c0 = study::thread_cpu_seconds();
  const RateFormRunResult res = run_rate_form(scheme, y0, o);
  r.wall = study::seconds_since(t0);
  r.cpu = study::thread_cpu_seconds() - c0;
  r.status = run_status_name(res.status);
  return r;
}

/// Every case, the largest domains first on the threads; the runs stay in case order.
inline std::vector<ImpactRun> run_all(const std::vector<ImpactCase>& cases, int threads) {
  return study::run_costliest_first(
      cases, threads, [](const ImpactCase& c) { return c.nx * c.ny; }, run_impact);
}

}  // namespace nrbc_impact
