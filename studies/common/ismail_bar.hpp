#pragma once
/// \file ismail_bar.hpp
/// Ismail's 1D validation bar [Ismail2009, §4.6.3, §5.3.1] shared by the study drivers studies/tl-bar-wave-1d (the bar
/// itself) and studies/tl-hourglass (the accuracy cost of the hourglass control on it): L = 0.15 m, rho = 8000,
/// E = 200 GPa, nu = 0.3, a -100 kPa compressive pulse entering at the left end, probes at x = 0.05, 0.10, 0.15 m.
/// - the pulse: a smoothed square pulse (sin^2 ramps of kRise, total kDuration) and its time integral;
/// - the discretised bar: modified mollifier, h = 2.75 dx, fixed layers two supports deep at each end, the free
///   particles nearest the probes;
/// - the source: the left fixed layers carry the exact incoming wave u(x, t) = f(t - x / c) of the material's
///   small-strain speed c (as if the bar continued to the left), f' = v(t) = -sigma(t) / (rho c);
/// - the exact linear solution before the reflection reaches the left end:
///   sigma(x, t) = sigma_in(t - x / c) + sigma_in(t - (2L - x) / c) (full, same-sign reflection at the fixed end).
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab::study::ismail_bar {

constexpr double kE = 200e9, kRho = 8000, kNu = 0.3, kLength = 0.15, kStress = -100e3;
constexpr double kHOverDx = 2.75;  // Ismail's h = 5.5 dx (mollifier support h) in sphstab's support-2h convention
constexpr double kRise = 2e-6, kDuration = 10e-6;  // smoothed square pulse: sin^2 ramps of kRise, total kDuration
inline const std::vector<double> kProbes{0.05, 0.10, 0.15};

/// The pulse shape in [0, 1]: sin^2 rise over kRise, plateau, sin^2 fall, zero outside [0, kDuration].
inline double shape(double t) {
  if (t <= 0 || t >= kDuration) return 0;
  auto s2 = [](double x) { return std::pow(std::sin(0.5 * std::numbers::pi * x), 2); };
  if (t < kRise) return s2(t / kRise);
  if (t > kDuration - kRise) return s2((kDuration - t) / kRise);
  return 1;
}

/// Integral of shape from 0 to t (for the displacement f(t) = int v).
inline double shape_integral(double t) {
  if (t <= 0) return 0;
  const double r = kRise;
  auto ramp_int = [r](double x) { return 0.5 * x - r / (2 * std::numbers::pi) * std::sin(std::numbers::pi * x / r); };
  if (t < r) return ramp_int(t);
  const double rise = ramp_int(r);  // = r / 2
  if (t < kDuration - r) return rise + (t - r);
  const double plateau = kDuration - 2 * r;
  if (t < kDuration) return rise + plateau + (rise - ramp_int(kDuration - t));
  return 2 * rise + plateau;
}

/// Particle velocity of the incoming compressive wave at speed c.
inline double source_velocity(double c) { return -kStress / (kRho * c); }

/// Displacement of a fixed particle at x at time t: on the left (x < 0) the incoming wave v0 f(t - x / c)
/// (v0 = source_velocity(c)), 0 elsewhere (the clamped right end).
inline double source_displacement(double x, double t, double c, double v0) {
  return x < 0 ? v0 * shape_integral(t - x / c) : 0.0;
}

/// The exact linear stress at x, t for the speed c: incident plus fixed-end reflection.
inline double exact_stress(double x, double t, double c) {
  return kStress * (shape(t - x / c) + shape(t - (2 * kLength - x) / c));
}

/// The time at which a probe signal crosses `threshold` between two samples (t0, s0) and (t1, s1), linear in time.
inline double crossing_time(double t0, double s0, double t1, double s1, double threshold) {
  return t0 + (t1 - t0) * (threshold - s0) / (s1 - s0);
}

/// The bar with n free particles of spacing dx = L / n.
struct Bar {
  int n = 0;  ///< free particles
  double dx = 0, h = 0;
  Kernel<1> kernel{KernelType::ModifiedMollifier};
  std::shared_ptr<const Discretisation<1>> disc;
  std::vector<double> x_fixed;  ///< reference positions of the fixed particles, in particle order
  std::vector<int> probe_slot;  ///< per probe of kProbes: the free slot of the nearest free particle

  /// Reference position of free slot f.
  double free_x(int f) const { return disc->particles.x(disc->free[f], 0); }
  /// Reference position of the particle of probe p.
  double probe_x(std::size_t p) const { return free_x(probe_slot[p]); }
};

/// Builds the bar: modified mollifier, h = kHOverDx dx, fixed layers two supports deep at each end.
inline Bar make_bar(int n) {
  Bar bar;
  bar.n = n;
  bar.dx = kLength / n;
  bar.h = kHOverDx * bar.dx;
  const ParticleSet<1> set = make_lattice<1>(
      LatticeType::Line, n, {.spacing = bar.dx, .support_radius = 2 * bar.kernel.support_radius(bar.h)});
  bar.disc = make_discretisation(set, bar.kernel, bar.h);
  const Discretisation<1>& d = *bar.disc;
  for (int i = 0; i < d.size(); ++i)
    if (d.free_slot[i] < 0) bar.x_fixed.push_back(d.particles.x(i, 0));
  for (double xp : kProbes) {
    int best = 0;
    for (int f = 0; f < d.free_count(); ++f)
      if (std::abs(d.particles.x(d.free[f], 0) - xp) < std::abs(d.particles.x(d.free[best], 0) - xp)) best = f;
    bar.probe_slot.push_back(best);
  }
  return bar;
}

}  // namespace sphstab::study::ismail_bar
