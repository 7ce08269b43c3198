// The reflection of a plane P wave at an SPH absorbing boundary, measured, against the plane-wave analysis of the same
// condition (spectral/plane_wave_reflection.hpp, Powell (2.49)): the toolkit's own check of the non-reflecting
// boundaries of Powell (2012) ch. 2. A strip periodic in y (period L_y = lambda / sin(theta), so that a wave of
// wavelength lambda at angle theta from the x axis fits) with absorbing particles at both ends x = 0 and x = L_x starts
// with the velocity of a P wave packet, v = v0 k g(x) sin(k . x) (k = (cos theta, sin theta), g a Gaussian envelope
// centred in the strip) and no stress. The packet splits into two halves travelling in +-k, each hitting an end at
// theta; once both have come back (the P and the slower S packets away from the ends), the energy left is the
// reflected fraction: R_E = E / E0 = 2 KE / KE0 (a travelling wave carries as much strain as kinetic energy; checked
// by the same run in a strip periodic in x too, where nothing is absorbed).
//
// Writes to --out DIR: runs.csv (condition, theta, measured and analytic R_E), series/<tag>.csv (t, 2 KE / KE0),
// summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/driver.hpp"
#include "common/nrbc.hpp"
#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/spectral/plane_wave_reflection.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

using namespace study::nrbc;  // Powell's steel and grid; the conditions: Periodic, P, M, HPowell, HHigdon, Traction

struct StripCase {
  Boundary condition = Boundary::P;
  int ny = 24;         ///< particles across the period; 0: normal incidence (a strip 6 particles across)
  int nx = 400;        ///< particles along x
  double lambda = 12;  ///< wavelength in dx
  double width = 1.5;  ///< Gaussian envelope: g = exp(-((x - L_x / 2) / (width lambda))^2)
  double cfl = 0.3;
  bool normalised = true;  ///< the absorbing particles' velocity gradient NCSPH-normalised (P, M, H)
};

struct StripRun {
  StripCase c;
  double theta = 0;  ///< the angle the period allows, asin(lambda / L_y)
  std::string status;
  int particles = 0, absorbing = 0;
  double measured = NAN, analytic = NAN, cpu = 0;
  std::vector<double> t, e;  ///< 2 KE / KE0
};

std::string label_of(const StripCase& c) {
  const bool plain = !c.normalised && c.condition != Boundary::Periodic && c.condition != Boundary::Traction;
  return boundary_name(c.condition) + (plain ? " (plain gradient)" : "");
}
std::string tag_of(const StripCase& c) {
  return boundary_name(c.condition) + (label_of(c).find("plain") != std::string::npos ? "_plain" : "") + "_ny" +
         std::to_string(c.ny) + "_lambda" + format_number(c.lambda, 3);
}

StripRun run_strip(const StripCase& c) {
  const int ny = c.ny > 0 ? c.ny : 6, n = c.nx * ny;
  const double lambda = c.lambda * kDx, Lx = c.nx * kDx, Ly = ny * kDx;
  StripRun r{.c = c, .theta = c.ny > 0 ? std::asin(lambda / Ly) : 0.0, .particles = n};
  ParticleSet<2> p;
  p.x.resize(n, 2);
  p.volume = Eigen::VectorXd::Constant(n, kDx * kDx);
  p.role.assign(n, Role::Free);
  p.spacing = kDx;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < c.nx; ++i) p.x.row(j * c.nx + i) << (i + 0.5) * kDx, (j + 0.5) * kDx;
  p.periodic = {c.condition == Boundary::Periodic, true};
  p.box_lo = Eigen::Vector2d::Zero();
  p.box_hi = Eigen::Vector2d(Lx, Ly);
  auto disc = make_discretisation(p, Kernel<2>(KernelType::CubicSpline), 1.3 * kDx);
  // No viscosity, no XSPH: the interior conserves energy, so what is lost went out through the ends.
  RateFormScheme<2> scheme(disc, kSteel,
                           {.continuity = ContinuityForm::Divergence,
                            .viscosity = ViscositySwitch::Off,
                            .gradient = RateFormGradient::Plain});
  const double kn = std::cos(r.theta);
  if (c.condition != Boundary::Periodic) {
    const int layers = c.condition == Boundary::Traction ? 1 : 3;  // floor(2h/dx) + 1 = 3
    AbsorbingParticles<2> a = absorbing_particles(c.condition, kDx, c.normalised);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < c.nx; ++i) {
        if (i >= layers && i < c.nx - layers) continue;
        add_absorbing(a, c.condition, j * c.nx + i, Eigen::Vector2d(i < layers ? -1.0 : 1.0, 0.0), kn);
      }
    r.absorbing = static_cast<int>(a.particles.size());
    scheme.set_absorbing(a);
    r.analytic =
        reflected_energy(absorbing_condition(c.condition), kSteel.p_wave_speed(),
                         std::sqrt(kSteel.mu() / kSteel.density()), r.theta, WaveKind::P, speed_scale(c.condition, kn));
  } else {
    r.analytic = 1;
  }
  // The packet: k = 2 pi / lambda (cos, sin), v = v0 k_hat g(x) sin(k . x).
  const Eigen::Vector2d khat(std::cos(r.theta), std::sin(r.theta));
  const Eigen::Vector2d kvec = 2 * M_PI / lambda * khat;
  const double v0 = 1e-4, w = c.width * lambda;
  Eigen::VectorXd y0 = scheme.uniform_state();
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d x = p.x.row(k).transpose();
    const double g = std::exp(-std::pow((x[0] - 0.5 * Lx) / w, 2));
    scheme.set_velocity(y0, k, v0 * g * std::sin(kvec.dot(x)) * khat);
  }
  const double ke0 = scheme.kinetic_energy(y0);
  // The halves reach the ends at t_b = (L_x / 2) / (c_p cos theta); measured over [1.4, 1.5] t_b, when the reflected
  // P packets are about L_x / 4 from the ends (and L_x / 2 apart: no overlap) and the reflected S ones (x speed
  // c_s cos(phi_s) >= 0.54 c_p cos theta here) about 0.13 L_x, clear of the absorbing layers by several envelope
  // widths.
  const double t_b = 0.5 * Lx / (kSteel.p_wave_speed() * kn), t_end = 1.5 * t_b;
  const double c0 = study::thread_cpu_seconds();
  const RateFormRunResult res = run_rate_form(scheme, y0,
                                              {.dt = c.cfl * kDx / kSteel.p_wave_speed(),
                                               .t_end = t_end,
                                               .record_every = 5,
                                               .energy_growth = 10,
                                               .observer =
                                                   [&](long, double t, const Eigen::VectorXd& y) {
                                                     r.t.push_back(t);
                                                     r.e.push_back(2 * scheme.kinetic_energy(y) / ke0);
                                                   },
                                               .integrator = RateFormIntegrator::Leapfrog});
  r.cpu = study::thread_cpu_seconds() - c0;
  r.status = run_status_name(res.status);
  if (res.completed()) {
    double sum = 0;
    int count = 0;
    for (std::size_t k = 0; k < r.t.size(); ++k)
      if (r.t[k] >= 1.4 * t_b) sum += r.e[k], ++count;
    r.measured = sum / count;
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) try {
  study::DriverCli cli{"Plane P-wave reflection at SPH absorbing boundaries, measured against the plane-wave analysis",
                       "results/nrbc-plane-wave",
                       "pipeline check: a strip of 50 particles, wavelength 6 dx, theta 0 and 45 degrees only"};
  int threads = 2, nx = 400;
  double lambda = 12;
  std::vector<double> degrees{15, 30, 45, 60};  // the oblique angles of the tables
  cli.add_threads(threads);
  cli.app.add_option("--nx", nx, "particles along the strip")->check(CLI::Range(100, 5000));
  cli.app.add_option("--lambda", lambda, "wavelength in particle spacings")->check(CLI::Range(4.0, 100.0));
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  if (cli.quick) nx = 50, lambda = 6, degrees = {45};
  const auto t0 = study::Clock::now();
  fs::create_directories(cli.out + "/series");
  // Angle tables at lambda and 2 lambda (the strip's length in proportion): periods across the strip for theta = 0
  // and about 15, 30, 45 and 60 degrees (--quick: 45); then normal incidence at 4 lambda.
  std::vector<StripCase> cases;
  for (double l : {lambda, 2 * lambda}) {
    const int n = static_cast<int>(std::lround(nx * l / lambda));
    std::vector<int> periods{0};
    for (double deg : degrees) periods.push_back(static_cast<int>(std::lround(l / std::sin(deg * M_PI / 180))));
    for (int ny : periods) {
      for (Boundary cond :
           {Boundary::Periodic, Boundary::P, Boundary::M, Boundary::HPowell, Boundary::HHigdon, Boundary::Traction})
        cases.push_back({.condition = cond, .ny = ny, .nx = n, .lambda = l});
      cases.push_back({.condition = Boundary::P, .ny = ny, .nx = n, .lambda = l, .normalised = false});
    }
  }
  for (Boundary cond : {Boundary::Periodic, Boundary::P, Boundary::Traction})
    for (bool normalised : {true, false})
      if (normalised || cond == Boundary::P)
        cases.push_back({.condition = cond, .ny = 0, .nx = 4 * nx, .lambda = 4 * lambda, .normalised = normalised});
  // The largest strips (particles: a normal-incidence strip is 6 across) first; rows stay in case order.
  const std::vector<StripRun> runs = study::run_costliest_first(
      cases, threads, [](const StripCase& c) { return std::max(c.ny, 6) * c.nx; }, run_strip);

  CsvWriter w(cli.out + "/runs.csv", {"condition", "gradient", "ny", "lambda", "theta_deg", "particles", "absorbing",
                                      "status", "measured", "analytic", "periodic_check", "cpu_seconds"});
  std::string md_lambda;
  std::string md;
  double worst_periodic = 0;
  for (const StripRun& r : runs) {
    const StripRun& per = *std::find_if(runs.begin(), runs.end(), [&](const StripRun& q) {
      return q.c.condition == Boundary::Periodic && q.c.ny == r.c.ny && q.c.lambda == r.c.lambda;
    });
    const bool plain = label_of(r.c).find("plain") != std::string::npos;
    w.row({boundary_name(r.c.condition), plain ? "plain" : "normalised", r.c.ny, r.c.lambda, r.theta * 180 / M_PI,
           r.particles, r.absorbing, r.status, r.measured, r.analytic, per.measured, r.cpu});
    CsvWriter s(cli.out + "/series/" + tag_of(r.c) + ".csv", {"t", "two_ke_over_ke0"}, false);
    for (std::size_t k = 0; k < r.t.size(); ++k) s.row({r.t[k], r.e[k]});
    if (r.c.condition == Boundary::Periodic) {
      worst_periodic = std::max(worst_periodic, std::abs(r.measured - 1));
      continue;
    }
    if (r.c.ny == 0)
      study::md_row(md_lambda,
                    {label_of(r.c), study::sig(r.c.lambda, 3), r.status, study::sig(100 * r.measured, 3) + " %",
                     study::sig(100 * per.measured - 100, 2) + " %"});
    if (r.c.lambda > 2 * lambda) continue;
    study::md_row(md, {label_of(r.c), study::sig(r.c.lambda, 3), study::fixed(r.theta * 180 / M_PI, 1), r.status,
                       study::sig(100 * r.measured, 3) + " %", study::sig(100 * r.analytic, 3) + " %",
                       study::sig(100 * (r.measured - r.analytic), 2) + " %"});
  }
  study::Summary sum;
  sum.set("table", md);
  sum.set("table_lambda", md_lambda);
  sum.set("nx", nx);
  sum.set("lambda", lambda, 3);
  sum.set("periodic_worst", 100 * worst_periodic, 2);
  study::write_summary(sum, cli.out, t0);
  return 0;
} catch (const std::exception& e) {
  return study::exit_on_error("nrbc-plane-wave", e);
}
