// Powell (2012) ch. 2 §3.2(c): surface impact on a half-space with non-reflecting boundaries, and the cost of a
// non-reflecting boundary against a larger domain. A patch of the surface (|x| < 0.3 cm, the top two rows) starts
// moving into a steel half-space (rho 7.8, E 2.1, nu 0.3; g, cm, us) at v_patch; the P, S and Rayleigh waves spread.
// Truncations, full width (Powell's half-models mirrored at x = 0): "narrow", 2 cm wide and 2 cm deep with absorbing
// particles on both sides (normal (+-1, 0)); "shallow", 4 cm wide and 0.6 cm deep with absorbing particles at the
// bottom (normal (0, -1)); each against the same particles in a reference 6 cm wide and 2 cm deep whose own
// boundaries are not heard at the probes before t_end. Measures: v_x, v_y at surface probes every 0.1 cm and at depth;
// the Rayleigh speed of the incident surface wave (reference) and of the wave the narrow truncation's sides send back
// (the difference narrow - reference), against rayleigh_speed() (A.35); the error at the probes against wall time for
// the absorbing truncations and for free truncations of growing width (the cost of a non-reflecting boundary).
//
// Writes to --out DIR: runs.csv (one row per run: the error at the probes, wall time), speeds.csv (arrival fits),
// series/<tag>.csv (t and v_x, v_y at each probe), summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/spectral/plane_wave_reflection.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kDx = 0.02;  // Powell's grid (cm)
const RateFormMaterial kSteel = RateFormMaterial::from_youngs(2.1, 0.3, 7.8);

enum class Side { None, Sides, Bottom };  ///< where the absorbing particles are
enum class Boundary { Free, P, M, Traction };
const char* boundary_name(Boundary b) {
  return b == Boundary::Free ? "free" : b == Boundary::P ? "P" : b == Boundary::M ? "M" : "traction";
}

struct ImpactCase {
  std::string name;  ///< narrow, shallow, reference, free-W
  int nx = 100, ny = 100;
  Side side = Side::None;
  Boundary boundary = Boundary::Free;
  double v_patch = 0.1, cfl = 0.3, t_end = 4;
  RateFormGradient gradient = RateFormGradient::Plain;
};

/// Probes: surface particles (top row) at x = 0.11, 0.21, ..., 0.91 and two at depth below the centre (y = -0.31,
/// -0.51).
struct Probe {
  std::string name;
  double x, y;
};
std::vector<Probe> probes() {
  std::vector<Probe> p;
  for (int k = 1; k <= 9; ++k) p.push_back({"s" + std::to_string(k), 0.1 * k + 0.5 * kDx, -0.5 * kDx});
  p.push_back({"d3", 0.5 * kDx, -0.3 - 0.5 * kDx});
  p.push_back({"d5", 0.5 * kDx, -0.5 - 0.5 * kDx});
  return p;
}

struct ImpactRun {
  ImpactCase c;
  std::string status;
  int particles = 0, absorbing = 0;
  double wall = 0, cpu = 0;
  std::vector<double> t;
  std::vector<std::vector<Eigen::Vector2d>> v;  ///< per record, per probe
};

std::string tag_of(const ImpactCase& c) {
  return c.name + "_" + boundary_name(c.boundary) + "_v" + format_number(c.v_patch, 3);
}

ImpactRun run_impact(const ImpactCase& c) {
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
  if (c.boundary != Boundary::Free) {
    // Powell's manual normals on floor(2h/dx) + 1 = 3 layers (the viscous traction: the outer layer only).
    const int layers = c.boundary == Boundary::Traction ? 1 : 3;
    AbsorbingParticles<2> a{.condition = c.boundary == Boundary::M          ? AbsorbingCondition::Sochaki
                                         : c.boundary == Boundary::Traction ? AbsorbingCondition::ViscousTraction
                                                                            : AbsorbingCondition::ClaytonEngquist,
                            .traction_depth = kDx,
                            // NCSPH-normalised velocity gradient at the absorbing particles (nrbc-plane-wave: the
                            // plain one reflects 2.4x more energy at normal incidence, lambda = 12 dx)
                            .normalised = c.boundary != Boundary::Traction};
    for (int j = 0; j < c.ny; ++j)
      for (int i = 0; i < c.nx; ++i) {
        Eigen::Vector2d normal = Eigen::Vector2d::Zero();
        if (c.side == Side::Sides && i < layers) normal = {-1, 0};
        if (c.side == Side::Sides && i >= c.nx - layers) normal = {1, 0};
        if (c.side == Side::Bottom && j >= c.ny - layers) normal = {0, -1};
        if (normal.squaredNorm() == 0) continue;
        a.particles.push_back(j * c.nx + i), a.normals.push_back(normal);
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
  const auto t0 = study::Clock::now();
  const double c0 = study::thread_cpu_seconds();
  const RateFormRunResult res =
      run_rate_form(scheme, y0,
                    {.dt = c.cfl * kDx / kSteel.p_wave_speed(),
                     .t_end = c.t_end,
                     .energy_growth = 100,
                     .observer =
                         [&](long, double t, const Eigen::VectorXd& y) {
                           r.t.push_back(t);
                           std::vector<Eigen::Vector2d> v;
                           for (int k : at)
                             v.push_back(k < 0 ? Eigen::Vector2d(NAN, NAN)
                                               : Eigen::Vector2d(y.segment<2>(scheme.velocity_offset(k))));
                           r.v.push_back(std::move(v));
                         },
                     .integrator = RateFormIntegrator::Leapfrog,
                     .leapfrog_xsph = 0.1,
                     .neighbour_skin = 0.5 * kDx});
  r.wall = study::seconds_since(t0);
  r.cpu = study::thread_cpu_seconds() - c0;
  r.status = run_status_name(res.status);
  return r;
}

/// Time of the largest |s| over records with t >= t_from, and that largest value.
std::pair<double, double> peak(const std::vector<double>& t, const std::vector<double>& s, double t_from = 0) {
  double best = 0, when = NAN;
  for (std::size_t k = 0; k < s.size(); ++k)
    if (t[k] >= t_from && std::abs(s[k]) > best) best = std::abs(s[k]), when = t[k];
  return {when, best};
}

/// Least-squares slope dx/dt of points (t_k, x_k) and its standard error.
std::pair<double, double> speed_fit(const std::vector<double>& t, const std::vector<double>& x) {
  const double m = static_cast<double>(t.size());
  double st = 0, sx = 0;
  for (std::size_t k = 0; k < t.size(); ++k) st += t[k], sx += x[k];
  st /= m, sx /= m;
  double stt = 0, stx = 0, sxx = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    stt += (t[k] - st) * (t[k] - st), stx += (t[k] - st) * (x[k] - sx), sxx += (x[k] - sx) * (x[k] - sx);
  const double slope = stx / stt;
  const double resid = std::max(0.0, sxx - slope * stx);
  return {slope, m > 2 ? std::sqrt(resid / (m - 2) / stt) : NAN};
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"Powell 2012 ch. 2 §3.2(c): surface impact with non-reflecting boundaries, and their cost"};
  std::string out = "results/nrbc-impact";
  int threads = 2;
  double t_end = 6, cfl = 0.3;
  std::string gradient = "plain";
  app.add_option("--out", out, "output directory");
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--t-end", t_end, "run length (us)")->check(CLI::Range(0.1, 100.0));
  app.add_option("--cfl", cfl, "dt = cfl dx / c_p")->check(CLI::Range(0.01, 2.0));
  app.add_option("--gradient", gradient, "plain or ncsph")->check(CLI::IsMember({"plain", "ncsph"}));
  CLI11_PARSE(app, argc, argv);
  const auto t0 = study::Clock::now();
  fs::create_directories(out + "/series");
  const RateFormGradient grad = gradient == "ncsph" ? RateFormGradient::Ncsph : RateFormGradient::Plain;
  const double c_p = kSteel.p_wave_speed(), c_s = std::sqrt(kSteel.shear_modulus / kSteel.density);
  const double c_r = rayleigh_speed(c_p, c_s);
  // The reference's sides (3 cm from the centre) and bottom (2 cm) are heard at the probes only after
  // (3 - 0.3 + 3 - 0.91) / c_p = 8 us and 4 / c_p = 6.6 us.
  if (t_end > 6.5)
    throw std::invalid_argument("t_end " + format_number(t_end) +
                                " us: the reference's boundaries are heard at the probes after 6.6 us");
  std::vector<ImpactCase> cases;
  const ImpactCase base{.cfl = cfl, .t_end = t_end, .gradient = grad};
  const auto with = [&](std::string name, int nx, int ny, Side side, Boundary b) {
    ImpactCase c = base;
    c.name = std::move(name), c.nx = nx, c.ny = ny, c.side = side, c.boundary = b;
    cases.push_back(c);
  };
  with("reference", 300, 100, Side::None, Boundary::Free);
  for (Boundary b : {Boundary::P, Boundary::M, Boundary::Traction}) {
    with("narrow", 100, 100, Side::Sides, b);
    with("shallow", 200, 30, Side::Bottom, b);
  }
  // The cost of a non-reflecting boundary: absorbing truncations of growing width against free truncations of
  // growing width (the domain the absorbing boundary is to replace), all 2 cm deep.
  for (int nx : {60, 140}) with("narrow-" + std::to_string(nx), nx, 100, Side::Sides, Boundary::P);
  for (int nx : {100, 140, 200, 240}) with("free-" + std::to_string(nx), nx, 100, Side::None, Boundary::Free);
  with("free-shallow", 200, 30, Side::None, Boundary::Free);
  // Powell's fast impact (0.5 cm/us, 83 % of c_p: strongly non-linear).
  for (Boundary b : {Boundary::Free, Boundary::P, Boundary::M}) {
    with(b == Boundary::Free ? "reference" : "narrow", b == Boundary::Free ? 300 : 100, 100,
         b == Boundary::Free ? Side::None : Side::Sides, b);
    cases.back().v_patch = 0.5;
  }
  std::vector<std::size_t> order(cases.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cases[a].nx * cases[a].ny > cases[b].nx * cases[b].ny; });
  std::vector<ImpactRun> runs(cases.size());
  study::parallel_for(cases.size(), threads, [&](std::size_t k) { runs[order[k]] = run_impact(cases[order[k]]); });
  const std::vector<Probe> pr = probes();
  const std::size_t np = pr.size();
  const auto reference_of = [&](const ImpactRun& r) -> const ImpactRun& {
    return *std::find_if(runs.begin(), runs.end(),
                         [&](const ImpactRun& q) { return q.c.name == "reference" && q.c.v_patch == r.c.v_patch; });
  };
  const auto vy_of = [&](const ImpactRun& r, std::size_t q) {
    std::vector<double> v;
    for (const auto& rec : r.v) v.push_back(rec[q][1]);
    return v;
  };

  // The incident Rayleigh wave: the peak of |v_y| at the surface probes beyond the patch (s5..s9, x >= 0.51) in the
  // slow reference, fitted as x(t).
  study::Summary sum;
  CsvWriter sp(out + "/speeds.csv", {"run", "wave", "probe", "x", "t_peak", "peak"});
  const ImpactRun& ref = runs[0];
  std::vector<double> t_in(np, NAN), ti, xi;
  for (std::size_t q = 0; q < 9; ++q) {
    const auto [when, top] = peak(ref.t, vy_of(ref, q));
    t_in[q] = when;
    if (q < 4) continue;
    ti.push_back(when), xi.push_back(pr[q].x);
    sp.row({"reference", "incident", pr[q].name, pr[q].x, when, top});
  }
  const auto [cr_in, cr_in_err] = speed_fit(ti, xi);

  CsvWriter w(out + "/runs.csv",
              {"run", "boundary", "particles", "absorbing", "status", "v_patch", "error_surface", "error_depth",
               "reflected_speed", "reflected_speed_stderr", "wall_seconds", "cpu_seconds"});
  std::string md;
  for (const ImpactRun& r : runs) {
    const ImpactRun& rf = reference_of(r);
    CsvWriter s(
        out + "/series/" + tag_of(r.c) + ".csv",
        [&] {
          std::vector<std::string> h{"t"};
          for (const Probe& q : pr) h.push_back("vx_" + q.name), h.push_back("vy_" + q.name);
          return h;
        }(),
        false);
    for (std::size_t k = 0; k < r.t.size(); ++k) {
      std::vector<CsvCell> row{r.t[k]};
      for (std::size_t q = 0; q < np; ++q) row.emplace_back(r.v[k][q][0]), row.emplace_back(r.v[k][q][1]);
      s.row(row);
    }
    // Error: per probe, the largest |v - v_ref| over time over the largest |v_ref|; the largest of these over the
    // surface probes beyond the patch (s4..s9) and over the two at depth.
    const std::size_t m = std::min(r.t.size(), rf.t.size());
    double e_surf = 0, e_depth = 0;
    for (std::size_t q = 3; q < np; ++q) {
      double e = 0, s0 = 0;
      for (std::size_t k = 0; k < m; ++k)
        e = std::max(e, (r.v[k][q] - rf.v[k][q]).norm()), s0 = std::max(s0, rf.v[k][q].norm());
      if (std::isnan(rf.v[0][q][0]) || std::isnan(r.v[0][q][0])) continue;  // a probe outside this domain
      double& into = q < 9 ? e_surf : e_depth;
      into = std::max(into, e / s0);
    }
    if (m < rf.t.size()) e_surf = e_depth = INFINITY;  // stopped early
    // The surface wave sent back by an absorbing side at x = X: at the surface probes beyond the patch (s4.., x <
    // X - 0.1), the peak of |v_y - v_y,ref| in the window of arrival times of a wave going to the side and back at a
    // speed between 0.6 c_s and c_s, t_in(x) + 2 (X - x) / [c_s, 0.6 c_s] (this excludes the reflected P; S and
    // Rayleigh are not separated, Powell's "Rayleigh/S"), fitted as x(t).
    double cr_back = NAN, cr_back_err = NAN;
    const double side_x = 0.5 * r.c.nx * kDx;
    if (r.c.side == Side::Sides && r.c.v_patch == ref.c.v_patch && m == rf.t.size()) {
      std::vector<double> tb, xb;
      for (std::size_t q = 3; q < 9 && pr[q].x < side_x - 0.1; ++q) {
        std::vector<double> d, a = vy_of(r, q), b = vy_of(rf, q);
        for (std::size_t k = 0; k < m; ++k) d.push_back(a[k] - b[k]);
        const double from = t_in[q] + 2 * (side_x - pr[q].x) / c_s, to = t_in[q] + 2 * (side_x - pr[q].x) / (0.6 * c_s);
        for (std::size_t k = 0; k < m; ++k)
          if (r.t[k] > to) d[k] = 0;
        const auto [when, top] = peak(r.t, d, from);
        if (std::isnan(when)) continue;
        tb.push_back(when), xb.push_back(pr[q].x);
        sp.row({tag_of(r.c), "reflected", pr[q].name, pr[q].x, when, top});
      }
      if (tb.size() >= 3) std::tie(cr_back, cr_back_err) = speed_fit(tb, xb), cr_back = -cr_back;
      if (r.c.name == "narrow") {
        const std::string key = std::string("c_r_reflected_") + boundary_name(r.c.boundary);
        sum.set(key, cr_back, 4);
        sum.set(key + "_err", cr_back_err, 2);
        sum.set(key + "_rel", 100 * (cr_back / c_r - 1), 2);
      }
    }
    w.row({r.c.name, boundary_name(r.c.boundary), r.particles, r.absorbing, r.status, r.c.v_patch, e_surf, e_depth,
           cr_back, cr_back_err, r.wall, r.cpu});
    if (&r == &rf) continue;
    study::md_row(md, {r.c.name, boundary_name(r.c.boundary), study::sig(r.c.v_patch, 2), std::to_string(r.particles),
                       std::to_string(r.absorbing), r.status, study::sig(100 * e_surf, 3) + " %",
                       study::sig(100 * e_depth, 3) + " %",
                       std::isnan(cr_back) ? "-" : study::sig(cr_back, 4) + " ± " + study::sig(cr_back_err, 2),
                       study::sig(r.cpu, 3), study::sig(r.cpu / rf.cpu, 3)});
  }
  sum.set("table", md);
  sum.set("c_p", c_p, 5);
  sum.set("c_s", c_s, 5);
  sum.set("c_r", c_r, 5);
  sum.set("c_r_incident", cr_in, 4);
  sum.set("c_r_incident_err", cr_in_err, 2);
  sum.set("c_r_incident_rel", 100 * (cr_in / c_r - 1), 2);
  sum.set("reference_particles", ref.particles);
  sum.set("reference_cpu", ref.cpu, 3);
  sum.set("gradient", gradient);
  sum.set("cfl", cfl, 3);
  sum.set("t_end", t_end, 3);
  sum.set("wall_seconds", study::seconds_since(t0), 3);
  sum.write(out);
  return 0;
} catch (const std::exception& e) {
  std::cerr << "nrbc-impact: " << e.what() << "\n";
  return 1;
}
