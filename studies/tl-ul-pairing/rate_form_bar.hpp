#pragma once
// The rate-form bar of the TL-vs-UL pairing study (1D): the Gray-Monaghan-Swift / Powell rate-form SPH scheme
// (forms/rate_form.hpp; continuity, linear equation of state, Jaumann stress rate, predictor-corrector) on the same
// bar, kernel and h as the TL and UL runs of main.cpp. Header-only and built on the library alone, so that
// tests/stability/tl_ul_rate_form_pairing_test.cpp checks exactly what the study runs.
//
// - Material: the bar's 1D modulus is the P-wave modulus M = K + 4 mu / 3 of the rate form (1D = uniaxial STRAIN,
//   dS/dt = (4 mu / 3) L); material_with_modulus() gives M = E_bar (= 1 in the study) with K and mu split by Poisson's
//   ratio, so that c = sqrt(M / rho0) and the small-strain bar are those of the TL (1D stress, P = E (F - 1)) and UL
//   (s = <u_x> + T) forms, and T = sigma0 / E_bar = sigma0 / M.
// - Pre-stretched state (docs/conventions.md §7: a state, not an added stress): the lattice of the discretisation is
//   the stretched one; a homogeneous uniaxial stretch xi from rest gives rho = rho0 / xi, p = K (1/xi - 1) and, from
//   the exact integral of the 1D Jaumann rate (no spin, L = d ln xi / dt), S = (4 mu / 3) ln xi; stretched_state()
//   solves sigma(xi) = K (1 - 1/xi) + (4 mu / 3) ln xi = sigma0 for xi.
// - Perturbation: the centre particle displaced by delta QUASI-STATICALLY (perturbed_state()): its position moves
//   along the straight path at unit speed over unit time while the density and stress of every particle follow the
//   scheme's own continuity and stress-rate equations (RK4), then the velocity is reset to 0. Density and stress of
//   the perturbed state are thus those the scheme gives the displaced configuration, as the TL and UL forms' stresses
//   are functions of their displacements.
// - Run: run_pairing() steps the predictor-corrector one step per run_rate_form call (a one-step method, so the
//   chunked run is the continuous one) and measures, at every step, the gaps x_{i+1} - x_i of the free particles over
//   the lattice spacing, exactly like the TL/UL loop of main.cpp; each call builds its neighbour list at the current
//   positions (a Verlet skin), so the list stays complete while the particles pair.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace pairing_rf {

/// Linear EOS + hypoelastic shear with P-wave modulus `modulus` (the 1D bar's modulus in uniaxial strain), Poisson's
/// ratio nu in (-1, 1/2) and zero-pressure density rho0: E_young = M (1 + nu)(1 - 2 nu) / (1 - nu).
inline sphstab::ElasticMaterial material_with_modulus(double modulus, double nu, double rho0) {
  return sphstab::ElasticMaterial::from_young_poisson(modulus * (1 + nu) * (1 - 2 * nu) / (1 - nu), nu, rho0);
}

/// P-wave modulus M = K + 4 mu / 3.
inline double p_wave_modulus(const sphstab::ElasticMaterial& m) { return m.bulk_modulus() + 4 * m.mu() / 3; }

/// A homogeneous uniaxial-strain stretch xi = V / V0 of the rate-form material from rest (see the file comment).
struct StretchedState {
  double xi = 1;        ///< stretch = volume ratio (1D)
  double density = 1;   ///< rho0 / xi
  double pressure = 0;  ///< K (1/xi - 1)
  double deviator = 0;  ///< S_xx = (4 mu / 3) ln xi
  double stress = 0;    ///< sigma_xx = -p + S (tension positive)
};

inline StretchedState stretched_state_at(const sphstab::ElasticMaterial& m, double xi) {
  StretchedState s;
  s.xi = xi;
  s.density = m.density() / xi;
  s.pressure = m.bulk_modulus() * (1 / xi - 1);
  s.deviator = 4 * m.mu() / 3 * std::log(xi);
  s.stress = -s.pressure + s.deviator;
  return s;
}

/// The stretched state with sigma_xx = stress (Newton on the monotone sigma(xi), d sigma / d xi = K / xi^2 +
/// (4 mu / 3) / xi > 0, from xi = 1 + stress / M). Throws std::invalid_argument for a non-finite stress or when Newton
/// does not converge in 100 steps.
inline StretchedState stretched_state(const sphstab::ElasticMaterial& m, double stress) {
  if (!std::isfinite(stress)) throw std::invalid_argument("stretched_state: stress must be finite");
  const double K = m.bulk_modulus(), g = 4 * m.mu() / 3;
  double xi = 1 + stress / (K + g);
  for (int it = 0; it < 100; ++it) {
    if (!(xi > 0)) break;
    const double f = K * (1 - 1 / xi) + g * std::log(xi) - stress;
    const double step = f / (K / (xi * xi) + g / xi);
    xi -= step;
    if (std::abs(step) <= 1e-15 * xi) return stretched_state_at(m, xi);
  }
  throw std::invalid_argument("stretched_state: no stretch reaches sigma = " + std::to_string(stress));
}

/// Largest |F| entry of the free particles' accelerations at y (0 iff y is an equilibrium of the free motion).
inline double equilibrium_residual(const sphstab::RateFormScheme<1>& scheme, const Eigen::VectorXd& y) {
  Eigen::VectorXd f;
  scheme.rate(y, f);
  double r = 0;
  for (int i = 0; i < scheme.discretisation().size(); ++i)
    if (scheme.velocity_offset(i) >= 0) r = std::max(r, std::abs(f[scheme.velocity_offset(i)]));
  return r;
}

/// y (at rest) with free particle `particle` displaced by delta quasi-statically (file comment): RK4 over `substeps`
/// steps of the path x_p(s) = x_p + s delta, s in [0, 1], the densities and stresses following the scheme's rates.
/// Throws std::invalid_argument for a fixed particle or a scheme with XSPH (the path would then not be straight).
inline Eigen::VectorXd perturbed_state(const sphstab::RateFormScheme<1>& scheme, Eigen::VectorXd y, int particle,
                                       double delta, int substeps = 64) {
  if (scheme.position_offset(particle) < 0) throw std::invalid_argument("perturbed_state: not a free particle");
  if (scheme.options().xsph != 0) throw std::invalid_argument("perturbed_state: needs a scheme without XSPH");
  const auto& d = scheme.discretisation();
  y[scheme.velocity_offset(particle)] = delta;
  auto rate = [&](const Eigen::VectorXd& s, Eigen::VectorXd& f) {
    scheme.rate(s, f);
    for (int i = 0; i < d.size(); ++i)
      if (scheme.velocity_offset(i) >= 0) f[scheme.velocity_offset(i)] = 0;  // the prescribed motion: v constant
  };
  const double ds = 1.0 / substeps;
  Eigen::VectorXd k1, k2, k3, k4;
  for (int k = 0; k < substeps; ++k) {
    rate(y, k1);
    rate(y + 0.5 * ds * k1, k2);
    rate(y + 0.5 * ds * k2, k3);
    rate(y + ds * k3, k4);
    y += ds / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  y[scheme.velocity_offset(particle)] = 0;
  return y;
}

/// Free particles' positions in free order (ascending along the bar).
inline Eigen::VectorXd free_positions(const sphstab::RateFormScheme<1>& scheme, const Eigen::VectorXd& y) {
  const auto& d = scheme.discretisation();
  Eigen::VectorXd x(d.free_count());
  for (int f = 0; f < d.free_count(); ++f) x[f] = y[scheme.position_offset(d.free[f])];
  return x;
}

struct PairingOptions {
  double delta = 0;          ///< the perturbation (gap deviation unit: delta / spacing), > 0
  double spacing = 1;        ///< equilibrium gap
  double dt = 0.05;          ///< predictor-corrector step
  double t_end = 100;        ///< run length
  double t_arrival = 0;      ///< time of "gap deviation at arrival"
  double pairing_gap = 0.5;  ///< pairing: min gap / spacing below this
  double stop_gap = 0.05;    ///< the run stops below this
  /// run_rate_form's Verlet skin (> 0): every step (one run_rate_form call) builds its list at the current positions,
  /// with radius support + skin, so every pair within the support is found however far the particles move (kernel
  /// sums do not depend on the list radius: the run is that of an all-pairs search).
  double neighbour_skin = 1;
};

struct PairingResult {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double t_pair = nan;       ///< first time min gap / spacing < pairing_gap (NaN: never)
  double amp_arrival = nan;  ///< gap deviation / initial at the first step with t >= t_arrival
  double amp_max = 0;        ///< largest gap deviation / initial
  double gap_min = 1e300;    ///< smallest min gap / spacing
  double time = 0;           ///< end time
  long steps = 0;
  std::string status = "completed";
};

/// Called at every step (step 0 included) with the measures and the state.
using PairingSample =
    std::function<void(long step, double t, double gap_min, double gap_max, double amp, const Eigen::VectorXd& y)>;

/// The pairing run from y0 (see the file comment); the measures as in main.cpp's TL/UL loop.
inline PairingResult run_pairing(const sphstab::RateFormScheme<1>& scheme, Eigen::VectorXd y, const PairingOptions& o,
                                 const PairingSample& sample = {}) {
  if (!(o.delta > 0) || !(o.dt > 0) || !(o.t_end > 0) || !(o.neighbour_skin > 0))
    throw std::invalid_argument("run_pairing: need delta, dt, t_end, neighbour_skin > 0");
  PairingResult r;
  const sphstab::RateFormRunOptions ro{.dt = o.dt, .t_end = o.dt, .neighbour_skin = o.neighbour_skin};
  for (long step = 0;; ++step) {
    const double t = step * o.dt;
    r.time = t;
    r.steps = step;
    const Eigen::VectorXd x = free_positions(scheme, y);
    double gmin = 1e300, gmax = 0;
    for (int i = 0; i + 1 < x.size(); ++i) {
      const double g = (x[i + 1] - x[i]) / o.spacing;
      gmin = std::min(gmin, g);
      gmax = std::max(gmax, g);
    }
    r.gap_min = std::min(r.gap_min, gmin);
    const double amp = std::max(1 - gmin, gmax - 1) / (o.delta / o.spacing);
    r.amp_max = std::max(r.amp_max, amp);
    if (std::isnan(r.amp_arrival) && t >= o.t_arrival) r.amp_arrival = amp;
    if (std::isnan(r.t_pair) && gmin < o.pairing_gap) r.t_pair = t;
    if (sample) sample(step, t, gmin, gmax, amp, y);
    if (gmin < o.stop_gap) {
      r.status = "particles within " + sphstab::format_number(o.stop_gap) + " spacing (stopped)";
      break;
    }
    if (!y.allFinite()) {
      r.status = "non-finite";
      break;
    }
    if (t >= o.t_end) break;
    const sphstab::RateFormRunResult s = sphstab::run_rate_form(scheme, y, ro);
    if (!s.completed()) {
      r.status = s.message;
      break;
    }
    y = s.y;
  }
  return r;
}

}  // namespace pairing_rf
