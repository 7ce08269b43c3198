#include "sphstab/spectral/plane_wave_reflection.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

namespace {

using cd = std::complex<double>;
const cd I(0, 1);

void check_speeds(double c_p, double c_s, const char* who) {
  if (!(std::isfinite(c_p) && std::isfinite(c_s) && c_s > 0 && c_s < c_p))
    throw std::invalid_argument(std::string(who) + ": need 0 < c_s < c_p, finite (got c_p " + format_number(c_p) +
                                ", c_s " + format_number(c_s) + ")");
}

void check_angle(double theta, const char* who) {
  if (!(theta >= 0 && theta < M_PI / 2))
    throw std::invalid_argument(std::string(who) + ": angle must be in [0, pi/2) (got " + format_number(theta) + ")");
}

/// B applied to a unit-frequency plane wave with unit direction k (complex for an evanescent wave), speed c and
/// polarisation d: the 2-vector B(-i, i k_x / c, i k_y / c) d.
Eigen::Vector2cd apply(AbsorbingCondition b, double c_p, double c_s, const Eigen::Vector2cd& k, double c,
                       const Eigen::Vector2cd& d) {
  const cd dt = -I, dx = I * k[0] / c, dy = I * k[1] / c;
  switch (b) {
    case AbsorbingCondition::ClaytonEngquist:
      return {(dt + c_p * dx) * d[0], (dt + c_s * dx) * d[1]};
    case AbsorbingCondition::Sochaki:
      return {(dt + c_p * dx) * d[0] + (c_p - c_s) * dy * d[1], (dt + c_s * dx) * d[1] + (c_p - c_s) * dy * d[0]};
    case AbsorbingCondition::Higdon:
      return (dt + c_p * dx) * (dt + c_s * dx) * d;
    case AbsorbingCondition::ViscousTraction:  // the traction (2.75) divided by rho c_p and rho c_s
      return {(dt + c_p * dx) * d[0] + (c_p - 2 * c_s * c_s / c_p) * dy * d[1],
              (dt + c_s * dx) * d[1] + c_s * dy * d[0]};
  }
  throw std::invalid_argument("elastic_reflection: unknown condition");
}

}  // namespace

Reflection elastic_reflection(AbsorbingCondition condition, double c_p, double c_s, double theta, WaveKind incident,
                              double speed_scale) {
  check_speeds(c_p, c_s, "elastic_reflection");
  check_angle(theta, "elastic_reflection");
  if (!(speed_scale > 0) || !std::isfinite(speed_scale))
    throw std::invalid_argument("elastic_reflection: speed_scale must be finite and > 0 (got " +
                                format_number(speed_scale) + ")");
  const double b_p = speed_scale * c_p, b_s = speed_scale * c_s;  // the condition's speeds
  const double a = std::cos(theta), b = std::sin(theta);
  // Directions (outgoing waves travel towards -x) and polarisations: P along k, S along (-k_y, k_x); an evanescent
  // P keeps k . k = 1, so its polarisation k is still of unit (complex-bilinear) length.
  auto p_pol = [](const Eigen::Vector2cd& k) { return k; };
  auto s_pol = [](const Eigen::Vector2cd& k) { return Eigen::Vector2cd(-k[1], k[0]); };
  Eigen::Vector2cd k_in(a, b), k_p, k_s;
  Reflection r;
  if (incident == WaveKind::P) {
    k_p = {-a, b};
    const double eta = c_s / c_p * b;
    k_s = {-std::sqrt(1 - eta * eta), eta};
  } else {
    k_s = {-a, b};
    const double xi = c_p / c_s * b;
    // Beyond the critical angle the P wave decays into x < 0: exp(i k_x x / c_p) with k_x = -i sqrt(xi^2 - 1).
    r.p_evanescent = xi > 1;
    k_p = {r.p_evanescent ? cd(0, -std::sqrt(xi * xi - 1)) : cd(-std::sqrt(1 - xi * xi)), xi};
  }
  const Eigen::Vector2cd f_in = incident == WaveKind::P ? apply(condition, b_p, b_s, k_in, c_p, p_pol(k_in))
                                                        : apply(condition, b_p, b_s, k_in, c_s, s_pol(k_in));
  Eigen::Matrix2cd m;
  m.col(0) = apply(condition, b_p, b_s, k_p, c_p, p_pol(k_p));
  m.col(1) = apply(condition, b_p, b_s, k_s, c_s, s_pol(k_s));
  const cd det = m.determinant();
  if (std::abs(det) <= 1e-14 * m.cwiseAbs().maxCoeff() * m.cwiseAbs().maxCoeff())
    throw std::domain_error("elastic_reflection: singular system at theta = " + format_number(theta) +
                            " (the condition admits a boundary wave there)");
  const Eigen::Vector2cd amp = m.partialPivLu().solve(-f_in);
  r.to_p = amp[0];
  r.to_s = amp[1];
  return r;
}

double reflected_energy(AbsorbingCondition condition, double c_p, double c_s, double theta, WaveKind incident,
                        double speed_scale) {
  const Reflection r = elastic_reflection(condition, c_p, c_s, theta, incident, speed_scale);
  const double b = std::sin(theta), c_in = incident == WaveKind::P ? c_p : c_s;
  const double flux_in = c_in * std::cos(theta);
  // Reflected directions (elastic_reflection): the same-kind wave at -theta, the converted one by Snell's law.
  const double sin_p = incident == WaveKind::P ? b : c_p / c_s * b, sin_s = incident == WaveKind::P ? c_s / c_p * b : b;
  double e = std::norm(r.to_s) * c_s * std::sqrt(1 - sin_s * sin_s) / flux_in;
  if (!r.p_evanescent) e += std::norm(r.to_p) * c_p * std::sqrt(std::max(0.0, 1 - sin_p * sin_p)) / flux_in;
  return e;
}

double scalar_reflection(double theta, const std::vector<double>& absorbing_angles) {
  check_angle(theta, "scalar_reflection");
  double r = 1;
  const double c = std::cos(theta);
  for (double a : absorbing_angles) {
    check_angle(a, "scalar_reflection (absorbing angle)");
    r *= std::abs(c - std::cos(a)) / (c + std::cos(a));
  }
  return r;
}

double rayleigh_speed(double c_p, double c_s) {
  check_speeds(c_p, c_s, "rayleigh_speed");
  // f(x) = (2 - x)^2 - 4 sqrt(1 - x s) sqrt(1 - x), x = (c_r / c_s)^2 in (0, 1), s = (c_s / c_p)^2: f(0) = 0 (a
  // spurious root), f < 0 just above 0 and f(1) = 1 > 0, so bisection on (x0, 1) with f(x0) < 0 finds the root.
  const double s = (c_s / c_p) * (c_s / c_p);
  auto f = [s](double x) { return (2 - x) * (2 - x) - 4 * std::sqrt(1 - x * s) * std::sqrt(1 - x); };
  double lo = 1e-3, hi = 1;
  while (f(lo) >= 0 && lo > 1e-12) lo *= 0.1;
  if (!(f(lo) < 0)) throw std::domain_error("rayleigh_speed: no sign change near 0");
  for (int it = 0; it < 200 && hi - lo > 4e-16; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return c_s * std::sqrt(0.5 * (lo + hi));
}

}  // namespace sphstab
