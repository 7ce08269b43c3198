#pragma once
// The bar of the 1D non-reflecting boundary study [Powell2012, ch. 2 §3.1]: problem (2.68) in Powell's units with its
// exact d'Alembert velocity, the four formulations of Table 2.1 (SPH, XSPH, NCSPH, NCXSPH), one case (particles, free
// or mirrored end, absorbing particles (2.69)-(2.70) or upwind (2.67), half- or whole-step timing, h, CFL, viscosity),
// its tag, and its scheme, initial state and leap-frog options (XSPH (2.71), algorithm 2.3).
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/nrbc.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace nrbc1d {

using namespace sphstab;

// Powell's units: g, cm, us (stress in Mbar). Steel: the thesis gives neither E nor rho for this test; the 2D tests'
// values give c = sqrt(E / rho) = 0.51887 cm/us.
constexpr double kRho = 7.8, kE = 2.1, kDx = 0.01, kV = 0.01, kSplit = 0.35;
constexpr int kProbe = 79;  // particle 80 (1-based), x = 0.795

inline double bar_speed() { return std::sqrt(kE / kRho); }

/// The exact velocity of (2.68) at x: d'Alembert with the even extension of the initial velocity (free end u_x = 0)
/// and zero initial stress, v = (v0(x - ct) + v0(x + ct)) / 2, v0(s) = +V for |s| < 0.35, -V otherwise.
inline double exact_velocity(double x, double t) {
  const auto v0 = [](double s) { return std::abs(s) < kSplit ? kV : -kV; };
  const double c = bar_speed();
  return 0.5 * (v0(x - c * t) + v0(x + c * t));
}

enum class Form { Sph, Xsph, Ncsph, Ncxsph };
constexpr NamedValue<Form> kFormNames[] = {
    {Form::Sph, "SPH"}, {Form::Xsph, "XSPH"}, {Form::Ncsph, "NCSPH"}, {Form::Ncxsph, "NCXSPH"}};
inline std::string form_name(Form f) { return name_of(f, kFormNames); }
inline bool normalised(Form f) { return f == Form::Ncsph || f == Form::Ncxsph; }
inline bool smoothed(Form f) { return f == Form::Xsph || f == Form::Ncxsph; }
/// The four formulations of Table 2.1, in its column order.
inline const std::vector<Form> kForms = {Form::Sph, Form::Xsph, Form::Ncsph, Form::Ncxsph};

struct BarCase {
  Form form = Form::Sph;
  int particles = 100;  ///< per side: 100 (truncated, 1 cm) or 800 (the 8 cm reference)
  /// The free end u_x(0) = 0 by symmetry: the bar on (-L, L) with the even initial velocity and absorbing particles at
  /// both ends (exact for every gradient); false: Powell's free end, particle 1 at x = 0.005 with nothing beyond.
  bool mirror = true;
  int layers = 0;          ///< absorbing particles at the right end (0: free end)
  bool upwind = false;     ///< Powell (2.67)
  bool half_step = true;   ///< Powell's algorithm 2.3 (forward Euler (2.66)); false: sphstab's whole-step a
  double h_over_dx = 1.3;  ///< Powell 1.3
  double cfl = 0.5;        ///< dt = cfl dx / c
  /// MCM's bulk viscosity (linear 0.06, quadratic 1.5; thesis App. B): Compression as MCM runs it; Always only for
  /// the damped linearisation (its linear term acts on every pair; the quadratic one vanishes at rest).
  ViscositySwitch viscosity = ViscositySwitch::Compression;
  double t_from = 3, t_to = 20;
  bool keep_series = false;
};

inline std::string tag_of(const BarCase& c) {
  std::string s = std::string(form_name(c.form)) + "_n" + std::to_string(c.particles) + "_";
  s += c.upwind ? "upwind" + std::to_string(c.layers) : "layers" + std::to_string(c.layers);
  s += std::string(c.half_step ? "_half" : "_whole") + "_h" + format_number(c.h_over_dx) + "_cfl" +
       format_number(c.cfl) +
       (c.viscosity == ViscositySwitch::Compression ? ""
        : c.viscosity == ViscositySwitch::Off       ? "_novisc"
                                                    : "_always") +
       (c.mirror ? "" : "_free");
  return s;
}

/// The bar's scheme and initial state (2.68).
struct BarScene {
  std::unique_ptr<RateFormScheme<1>> scheme;
  Eigen::VectorXd y0;
  int probe = kProbe;  ///< particle 80's index
  double x80 = 0;
};

inline BarScene make_bar(const BarCase& c) {
  const int n = c.mirror ? 2 * c.particles : c.particles, first = c.mirror ? c.particles : 0;  // x = 0.005: first
  ParticleSet<1> p;
  p.x.resize(n, 1);
  p.volume = Eigen::VectorXd::Constant(n, kDx);
  p.role.assign(n, Role::Free);
  p.spacing = kDx;
  for (int i = 0; i < n; ++i) p.x(i, 0) = (i - first + 0.5) * kDx;
  const double h = c.h_over_dx * kDx;
  auto disc = make_discretisation(p, Kernel<1>(KernelType::CubicSpline), h);
  // Uniaxial modulus E: K = E, mu = 0 (the 1D scheme's longitudinal modulus is K + 4 mu / 3).
  RateFormScheme<1> scheme(disc, ElasticMaterial::from_bulk_shear(kE, 0, kRho),
                           {.continuity = ContinuityForm::Divergence,
                            .viscosity = c.viscosity,
                            .gradient = normalised(c.form) ? RateFormGradient::Ncsph : RateFormGradient::Plain});
  AbsorbingParticles<1> b{.upwind = c.upwind};
  for (int i = n - c.layers; i < n; ++i)
    b.particles.push_back(i), b.normals.emplace_back(Eigen::Matrix<double, 1, 1>(1.0));
  if (c.mirror)
    for (int i = 0; i < c.layers; ++i)
      b.particles.push_back(i), b.normals.emplace_back(Eigen::Matrix<double, 1, 1>(-1.0));
  scheme.set_absorbing(b);
  BarScene scene{.scheme = std::make_unique<RateFormScheme<1>>(std::move(scheme)),
                 .probe = first + kProbe,
                 .x80 = p.x(first + kProbe, 0)};
  scene.y0 = scene.scheme->uniform_state();
  for (int i = 0; i < n; ++i)  // (2.68), evenly extended
    scene.y0[scene.scheme->velocity_offset(i)] = std::abs(p.x(i, 0)) < kSplit ? kV : -kV;
  return scene;
}

/// The run options of a case: Powell's leap-frog (common/nrbc.hpp) at dt = cfl dx / c, with XSPH in the smoothed forms.
inline RateFormRunOptions run_options(const BarCase& c) {
  RateFormRunOptions o = study::nrbc::powell_leapfrog(c.cfl * kDx / bar_speed(), c.t_to, smoothed(c.form) ? 0.1 : 0.0);
  o.absorbing_half_step = c.half_step && c.layers > 0;
  return o;
}

}  // namespace nrbc1d
