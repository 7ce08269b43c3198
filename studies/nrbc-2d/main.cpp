// Powell (2012) ch. 2 §3.2(a): 2D square compression with first-order non-reflecting boundaries. A 1 x 1 cm steel block
// (50 x 50 particles) starts with the inward velocity v0 x_mi / |x_mi| (2.73), or that field rotated by pi/8 (2.74);
// the kinetic energy of the block with absorbing boundary particles (Clayton-Engquist "P", Sochaki "M"; Powell's
// half-step timing and sphstab's whole-step one) against the same 50 x 50 particles inside a large reference block
// moving inwards everywhere (the infinite space collapsing on itself, as Powell's reference) whose boundary is too
// far to matter, and against a free block.
//
// Writes to --out DIR: runs.csv (one row per case: the largest |KE - KE_ref| / KE0 and when, KE at the end),
// series/<tag>.csv (t, KE / KE0 of the central block), summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/driver.hpp"
#include "common/nrbc.hpp"
#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/operators/boundary_particles.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

using namespace study::nrbc;  // Powell's steel, the boundaries (Reference, Free, P, M, HPowell, HHigdon, Traction)

// Powell's units (g, cm, us): common/nrbc.hpp's steel, v0 = 0.01.
constexpr double kV0 = 0.01;

/// Initial velocity: v0 x_mi / |x_mi| everywhere ((2.73), the infinite space collapsing), that field rotated by pi/8
/// (2.74), or only within 0.25 of the centre and at rest elsewhere ((2.76), Powell's central disc, at v0 = 0.01 and
/// at his second speed 0.05).
enum class Field { Centred, Skewed, Disc, FastDisc };
const char* field_name(Field f) {
  return f == Field::Centred ? "centred" : f == Field::Skewed ? "skewed" : f == Field::Disc ? "disc" : "disc_fast";
}
const char* field_label(Field f) {
  return f == Field::Centred  ? "centred (2.73)"
         : f == Field::Skewed ? "skewed (2.74)"
         : f == Field::Disc   ? "central disc (2.76)"
                              : "central disc, v0 = 0.05";
}
bool is_disc(Field f) { return f == Field::Disc || f == Field::FastDisc; }

/// One run: the boundary under an initial field. P, M, H-Powell and H-Higdon on every detected boundary particle with
/// the NCSPH gradient (H: k radial from the centre); the traction on the outer layer (depth dx) with the plain SPH
/// gradient (NCSPH's row momentum form has no traction-free surface to add a traction to). `plain`: the free block or
/// the reference with the plain gradient too (free-plain: the traction's scheme without the traction;
/// reference-plain: the reference for those two).
struct SquareCase {
  Boundary boundary = Boundary::P;
  bool plain = false;
  Field field = Field::Centred;
  bool half_step = false;  ///< Powell's algorithm 2.3 timing of the absorbing particles
  int n = 50;              ///< particles per side of the block
  int margin = 0;          ///< reference: extra particles on each side (at rest)
  double cfl = 0.3, t_end = 4, h_over_dx = 1.3;
};

struct SquareRun {
  SquareCase c;
  std::string status;
  int particles = 0, absorbing = 0, layers = 0;
  double wall = 0;
  std::vector<double> t, ke;  ///< kinetic energy of the central n x n particles over KE0
};

bool plain_gradient(const SquareCase& c) { return c.plain || c.boundary == Boundary::Traction; }
/// The boundary as runs.csv names it: free-plain and reference-plain for the plain-gradient free block and reference.
std::string boundary_label(const SquareCase& c) { return boundary_name(c.boundary) + (c.plain ? "-plain" : ""); }

std::string tag_of(const SquareCase& c) {
  return boundary_label(c) + "_" + field_name(c.field) +
         (absorbs(c.boundary) ? (c.half_step ? "_half" : "_whole") : "");
}

SquareRun run_square(const SquareCase& c) {
  const double dx = 1.0 / c.n;
  const int side = c.n + 2 * c.margin;
  ParticleSet<2> p;
  p.x.resize(side * side, 2);
  p.volume = Eigen::VectorXd::Constant(side * side, dx * dx);
  p.role.assign(side * side, Role::Free);
  p.spacing = dx;
  std::vector<int> central;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const int k = j * side + i;
      p.x.row(k) << (i - c.margin + 0.5) * dx, (j - c.margin + 0.5) * dx;
      if (i >= c.margin && i < c.margin + c.n && j >= c.margin && j < c.margin + c.n) central.push_back(k);
    }
  auto disc = make_discretisation(p, Kernel<2>(KernelType::CubicSpline), c.h_over_dx * dx);
  RateFormScheme<2> scheme(disc, kSteel,
                           {.continuity = ContinuityForm::Divergence,
                            .viscosity = ViscositySwitch::Compression,
                            .gradient = plain_gradient(c) ? RateFormGradient::Plain : RateFormGradient::Ncsph});
  SquareRun r{.c = c, .particles = side * side};
  if (absorbs(c.boundary)) {
    const BoundaryParticles<2> b = boundary_particles(disc->particles, disc->kernel, disc->h, disc->neighbours);
    AbsorbingParticles<2> a = absorbing_particles(c.boundary, dx, false);
    for (int i : b.particles) {
      if (c.boundary == Boundary::Traction && b.layer[i] != 0) continue;  // the outer face only
      const Eigen::Vector2d n = b.normal.row(i).transpose();
      // H: the waves come from the centre, k = (x_i - x_m) / |x_i - x_m|.
      add_absorbing(a, c.boundary, i, n, (p.x.row(i).transpose() - Eigen::Vector2d(0.5, 0.5)).normalized().dot(n));
    }
    r.absorbing = static_cast<int>(a.particles.size());
    r.layers = c.boundary == Boundary::Traction ? 1 : b.layers;
    scheme.set_absorbing(a);
  }
  Eigen::VectorXd y0 = scheme.uniform_state();
  const double ang = c.field == Field::Skewed ? M_PI / 8 : 0.0;
  const Eigen::Matrix2d R{{std::cos(ang), -std::sin(ang)}, {std::sin(ang), std::cos(ang)}};
  // Powell: "the hypothetical infinite space surrounding the problem domain is supposed to be collapsing in on
  // itself", so the reference block moves inwards everywhere, not only in its central n x n.
  const double v0 = c.field == Field::FastDisc ? 5 * kV0 : kV0;
  for (int k = 0; k < side * side; ++k) {
    const Eigen::Vector2d to_centre = Eigen::Vector2d(0.5, 0.5) - p.x.row(k).transpose();  // x_mi = x_m - x_i
    if (!is_disc(c.field) || to_centre.norm() < 0.25) scheme.set_velocity(y0, k, v0 * R * to_centre.normalized());
  }
  const auto central_ke = [&](const Eigen::VectorXd& y) {
    double e = 0;
    for (int k : central) e += 0.5 * scheme.mass()[k] * y.segment<2>(scheme.velocity_offset(k)).squaredNorm();
    return e;
  };
  const double ke0 = central_ke(y0);
  RateFormRunOptions o = powell_leapfrog(c.cfl * dx / kSteel.p_wave_speed(), c.t_end);
  o.observer = [&](long, double t, const Eigen::VectorXd& y) {
    r.t.push_back(t);
    r.ke.push_back(central_ke(y) / ke0);
  };
  o.absorbing_half_step = c.half_step && r.absorbing > 0;
  o.neighbour_skin = c.field == Field::FastDisc ? 0.5 * dx : 0.0;  // the fast disc's particles move by about dx
  const auto t0 = study::Clock::now();
  const RateFormRunResult res = run_rate_form(scheme, y0, o);
  r.wall = study::seconds_since(t0);
  r.status = run_status_name(res.status);
  return r;
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"Powell 2012 ch. 2 §3.2(a): square compression with non-reflecting boundaries"};
  std::string out = "results/nrbc-2d";
  int threads = 2, n = 50, margin = 124;
  double cfl = 0.3, t_end = 4;
  bool quick = false;
  app.add_option("--out", out, "output directory");
  app.add_option("--threads", threads, "concurrent runs")->check(CLI::Range(1, 64));
  app.add_option("--n", n, "particles per side of the block (Powell 50)")->check(CLI::Range(8, 400));
  app.add_option("--margin", margin, "reference: particles added on each side")->check(CLI::Range(0, 1000));
  app.add_option("--cfl", cfl, "dt = cfl dx / c_p")->check(CLI::Range(0.01, 2.0));
  app.add_option("--t-end", t_end, "run length (us)")->check(CLI::Range(0.1, 100.0));
  app.add_flag("--quick", quick,
               "pipeline check: every case on a 20 x 20 block to 1 us (the waves from the disc have reached the "
               "boundary), the reference 13 particles wider on each side");
  CLI11_PARSE(app, argc, argv);
  if (quick) n = 20, margin = 13, t_end = std::min(t_end, 1.0);
  const auto t0 = study::Clock::now();
  fs::create_directories(out + "/series");
  // The reference's own (moving, free) boundary must not be heard in the block before t_end: margin dx > c_p t_end.
  const double cp = kSteel.p_wave_speed();
  if (margin / static_cast<double>(n) <= cp * t_end)
    throw std::invalid_argument("margin " + std::to_string(margin) +
                                " too small: the reference's boundary is heard at t = " +
                                format_number(margin / static_cast<double>(n) / cp) + " < t_end");
  std::vector<SquareCase> cases;
  for (Field field : {Field::Centred, Field::Skewed, Field::Disc, Field::FastDisc}) {
    const SquareCase reference_case{
        .boundary = Boundary::Reference, .field = field, .n = n, .margin = margin, .cfl = cfl, .t_end = t_end};
    cases.push_back(reference_case);
    if (field == Field::Disc) {  // and with the plain gradient (reference-plain)
      cases.push_back(reference_case);
      cases.back().plain = true;
    }
    cases.push_back({.boundary = Boundary::Free, .field = field, .n = n, .cfl = cfl, .t_end = t_end});
    for (Boundary b : {Boundary::P, Boundary::M})
      for (bool half : {false, true})
        if (!half || field != Field::FastDisc)
          cases.push_back({.boundary = b, .field = field, .half_step = half, .n = n, .cfl = cfl, .t_end = t_end});
    // The free block last again, with the plain gradient (free-plain).
    for (Boundary b : {Boundary::HPowell, Boundary::HHigdon, Boundary::Traction, Boundary::Free})
      if (field != Field::Skewed)  // H's a-priori direction is the radial one: not the skewed field's
        cases.push_back(
            {.boundary = b, .plain = b == Boundary::Free, .field = field, .n = n, .cfl = cfl, .t_end = t_end});
  }
  // Most expensive (the references) first; rows stay in case order.
  const std::vector<SquareRun> runs = study::run_costliest_first(
      cases, threads, [](const SquareCase& c) { return c.margin; }, run_square);

  study::Summary sum;
  CsvWriter w(out + "/runs.csv", {"boundary", "field", "timing", "particles", "absorbing", "layers", "status",
                                  "max_deviation", "t_max_deviation", "ke_end", "ke_ref_end", "wall_seconds"});
  std::string md;
  for (const SquareRun& r : runs) {
    // The plain-gradient runs against the plain reference where there is one.
    const auto reference = [&](bool plain) {
      return std::find_if(runs.begin(), runs.end(), [&](const SquareRun& q) {
        return q.c.boundary == Boundary::Reference && q.c.plain == plain && q.c.field == r.c.field;
      });
    };
    auto it = plain_gradient(r.c) ? reference(true) : runs.end();
    if (it == runs.end()) it = reference(false);
    const SquareRun& ref = *it;
    double dev = 0, t_dev = NAN;
    const std::size_t m = std::min(r.ke.size(), ref.ke.size());
    for (std::size_t k = 0; k < m; ++k)
      if (std::abs(r.ke[k] - ref.ke[k]) > dev) dev = std::abs(r.ke[k] - ref.ke[k]), t_dev = r.t[k];
    const std::string timing = r.absorbing > 0 ? (r.c.half_step ? "half" : "whole") : "-";
    w.row({boundary_label(r.c), field_name(r.c.field), timing, r.particles, r.absorbing, r.layers, r.status, dev, t_dev,
           r.ke.back(), ref.ke.back(), r.wall});
    CsvWriter s(out + "/series/" + tag_of(r.c) + ".csv", {"t", "ke_over_ke0", "ke_ref_over_ke0"});
    for (std::size_t k = 0; k < m; ++k) s.row({r.t[k], r.ke[k], ref.ke[k]});
    if (r.c.boundary == Boundary::Reference && !r.c.plain) continue;
    study::md_row(md, {field_label(r.c.field), boundary_label(r.c) + (&ref != &*reference(false) ? " †" : ""), timing,
                       std::to_string(r.absorbing) + " (" + std::to_string(r.layers) + " layers)", r.status,
                       study::sig(100 * dev, 3) + " % at t = " + study::sig(t_dev, 3),
                       study::sig(100 * r.ke.back(), 3) + " % (" + study::sig(100 * ref.ke.back(), 3) + " %)",
                       study::sig(r.wall, 3)});
  }
  sum.set("table", md);
  sum.set("n", n);
  sum.set("reference_side", n + 2 * margin);
  sum.set("cfl", cfl, 3);
  sum.set("t_end", t_end, 3);
  study::write_summary(sum, out, t0);
  return 0;
} catch (const std::exception& e) {
  return study::exit_on_error("nrbc-2d", e);
}
