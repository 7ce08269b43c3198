#include "sphstab/problems/cantilever_plate.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

double cantilever_fundamental_kl() {
  // f(z) = cos z cosh z + 1 changes sign once on [1.5, 2.2] (f(1.5) > 0 > f(2.2)); bisection to rounding.
  auto f = [](double z) { return std::cos(z) * std::cosh(z) + 1; };
  double lo = 1.5, hi = 2.2;
  for (int it = 0; it < 200 && hi - lo > 4 * std::numeric_limits<double>::epsilon() * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

IsotropicModuli isotropic_moduli(double bulk_modulus, double shear_modulus) {
  if (!(bulk_modulus > 0) || !(shear_modulus > 0) || !std::isfinite(bulk_modulus) || !std::isfinite(shear_modulus))
    throw std::invalid_argument("isotropic_moduli: K and mu must be finite and > 0 (got K " +
                                format_number(bulk_modulus) + ", mu " + format_number(shear_modulus) + ")");
  const double K = bulk_modulus, mu = shear_modulus;
  return {.youngs = 9 * K * mu / (3 * K + mu), .poisson = (3 * K - 2 * mu) / (2 * (3 * K + mu))};
}

double thin_plate_period(double youngs, double poisson, double density, double thickness, double length) {
  if (!(youngs > 0) || !(density > 0) || !(thickness > 0) || !(length > 0) || !(poisson > -1 && poisson < 0.5))
    throw std::invalid_argument("thin_plate_period: need E, rho, H, L > 0 and -1 < nu < 1/2 (got E " +
                                format_number(youngs) + ", nu " + format_number(poisson) + ", rho " +
                                format_number(density) + ", H " + format_number(thickness) + ", L " +
                                format_number(length) + ")");
  const double k = cantilever_fundamental_kl() / length;
  const double omega2 = youngs * thickness * thickness * std::pow(k, 4) / (12 * density * (1 - poisson * poisson));
  return 2 * M_PI / std::sqrt(omega2);
}

namespace {

/// The clamped-free boundary determinant of the Timoshenko beam at omega (its sign changes at a natural frequency).
/// Harmonic w = W e^{i omega t}, phi = Phi e^{i omega t}; e^{s x} solves the pair when
///   D I kGA s^4 + rho omega^2 (kGA I + A D I) s^2 + rho A omega^2 (rho I omega^2 - kGA) = 0   (kGA = kappa G A),
/// with Phi = (s^2 + q) / s W, q = rho omega^2 / (kappa G). Below the cutoff the constant term is negative: one root
/// s^2 = alpha^2 > 0, one s^2 = -beta^2 < 0, so W = A1 cosh ax + A2 sinh ax + A3 cos bx + A4 sin bx and
/// Phi = pa (A1 sinh ax + A2 cosh ax) + pb (A3 sin bx - A4 cos bx), pa = (a^2 + q) / a, pb = (q - b^2) / b.
double timoshenko_determinant(double omega, double D, double kG, double rho, double H, double L) {
  const double A = H, I = H * H * H / 12, kGA = kG * A, w2 = omega * omega;
  const double a4 = D * I * kGA, a2 = rho * w2 * (kGA * I + A * D * I), a0 = rho * A * w2 * (rho * I * w2 - kGA);
  const double disc = std::sqrt(a2 * a2 - 4 * a4 * a0);
  const double alpha = std::sqrt((-a2 + disc) / (2 * a4)), beta = std::sqrt((a2 + disc) / (2 * a4));
  const double q = rho * w2 / kG, pa = (alpha * alpha + q) / alpha, pb = (q - beta * beta) / beta;
  const double ch = std::cosh(alpha * L), sh = std::sinh(alpha * L), c = std::cos(beta * L), s = std::sin(beta * L);
  Eigen::Matrix4d m;
  m << 1, 0, 1, 0,                                                              // w(0) = 0
      0, pa, 0, -pb,                                                            // phi(0) = 0
      pa * alpha * ch, pa * alpha * sh, pb * beta * c, pb * beta * s,           // phi'(L) = 0 (moment)
      (alpha - pa) * sh, (alpha - pa) * ch, -(beta + pb) * s, (beta + pb) * c;  // w'(L) - phi(L) = 0 (shear)
  return m.determinant();
}

}  // namespace

double timoshenko_cantilever_period(double bending_modulus, double shear_modulus, double shear_coefficient,
                                    double density, double thickness, double length) {
  const double D = bending_modulus, G = shear_modulus, kappa = shear_coefficient, rho = density, H = thickness,
               L = length;
  for (double v : {D, G, kappa, rho, H, L})
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument("timoshenko_cantilever_period: every argument must be finite and > 0 (got D " +
                                  format_number(D) + ", G " + format_number(G) + ", kappa " + format_number(kappa) +
                                  ", rho " + format_number(rho) + ", H " + format_number(H) + ", L " +
                                  format_number(L) + ")");
  const double k = cantilever_fundamental_kl() / L;
  const double omega_eb = std::sqrt(D * H * H * std::pow(k, 4) / (12 * rho));  // (7.1) with D for E / (1 - nu^2)
  const double cutoff = std::sqrt(kappa * G * 12 / (rho * H * H));
  if (!(omega_eb < cutoff))
    throw std::invalid_argument("timoshenko_cantilever_period: H / L = " + format_number(H / L) +
                                " is too thick (thin-plate frequency above the shear cutoff)");
  // Shear and rotary inertia only soften the beam: the fundamental lies in (0, omega_eb]. Scan up for the first
  // sign change of the determinant, then bisect to rounding.
  auto f = [&](double w) { return timoshenko_determinant(w, D, kappa * G, rho, H, L); };
  const int n = 400;
  double lo = 1e-3 * omega_eb, flo = f(lo), hi = lo;
  bool bracketed = false;
  for (int i = 1; i <= n && !bracketed; ++i) {
    hi = std::min(omega_eb * (1 + 1e-9), cutoff * (1 - 1e-12)) * i / n;
    if (hi <= lo) continue;
    const double fhi = f(hi);
    if ((flo > 0) != (fhi > 0))
      bracketed = true;
    else
      lo = hi, flo = fhi;
  }
  if (!bracketed) throw std::runtime_error("timoshenko_cantilever_period: no root below the thin-plate frequency");
  for (int it = 0; it < 200 && hi - lo > 4 * std::numeric_limits<double>::epsilon() * hi; ++it) {
    const double mid = 0.5 * (lo + hi), fm = f(mid);
    if ((fm > 0) == (flo > 0))
      lo = mid, flo = fm;
    else
      hi = mid;
  }
  return 2 * M_PI / (0.5 * (lo + hi));
}

double cantilever_mode_velocity(double x, double length, double tip_speed) {
  const double kl = cantilever_fundamental_kl(), k = kl / length, kx = k * x;
  const double M = std::sin(kl) + std::sinh(kl), N = std::cos(kl) + std::cosh(kl);
  const double Q = 2 * (std::cos(kl) * std::sinh(kl) - std::sin(kl) * std::cosh(kl));
  return tip_speed * (M * (std::cos(kx) - std::cosh(kx)) - N * (std::sin(kx) - std::sinh(kx))) / Q;
}

ParticleSet<2> make_cantilever_plate(const CantileverPlateOptions& o) {
  if (!(o.length > 0) || !(o.thickness > 0) || !std::isfinite(o.length) || !std::isfinite(o.thickness) ||
      o.across < 2 || o.clamp_layers < 1)
    throw std::invalid_argument("make_cantilever_plate: need L, H > 0, across >= 2, clamp_layers >= 1 (got L " +
                                format_number(o.length) + ", H " + format_number(o.thickness) + ", across " +
                                std::to_string(o.across) + ", clamp_layers " + std::to_string(o.clamp_layers) + ")");
  const double dp = o.thickness / o.across;
  const double columns = o.length / dp;
  const long along = std::lround(columns);
  if (std::abs(columns - static_cast<double>(along)) > 1e-9 * columns || along < 1)
    throw std::invalid_argument("make_cantilever_plate: L = " + format_number(o.length) +
                                " is not a whole number of spacings dp = H / across = " + format_number(dp));
  const long total_columns = along + o.clamp_layers, n = total_columns * o.across;
  ParticleSet<2> set;
  set.x.resize(n, 2);
  set.volume = Eigen::VectorXd::Constant(n, dp * dp);
  set.role.resize(n);
  set.depth.resize(n);
  set.spacing = dp;
  long p = 0;
  for (long c = 0; c < total_columns; ++c)
    for (int r = 0; r < o.across; ++r, ++p) {
      set.x(p, 0) = (static_cast<double>(c - o.clamp_layers) + 0.5) * dp;
      set.x(p, 1) = (r + 0.5) * dp - 0.5 * o.thickness;
      set.role[p] = c < o.clamp_layers ? Role::Fixed : Role::Free;
      set.depth[p] = static_cast<int>(std::min<long>({c, total_columns - 1 - c, r, o.across - 1 - r}));
    }
  set.validate("make_cantilever_plate");
  return set;
}

}  // namespace sphstab
