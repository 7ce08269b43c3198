#include "sphstab/problems/cantilever_plate.hpp"

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
