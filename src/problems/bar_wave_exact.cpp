#include "sphstab/problems/bar_wave_exact.hpp"

#include <stdexcept>
#include <string>

namespace sphstab {

BarJumpExact::BarJumpExact(const BarJumpProblem& p) : m_p(p) {
  auto pos = [](double x) { return x > 0 && std::isfinite(x); };
  if (!pos(p.length) || !pos(p.density) || !pos(p.youngs_modulus))
    throw std::invalid_argument("BarJumpExact: length, density and Young's modulus must be finite and > 0");
  if (!(p.jump_position > 0 && p.jump_position < p.length))
    throw std::invalid_argument("BarJumpExact: jump_position must lie in (0, L) (got " +
                                std::to_string(p.jump_position) + ")");
  m_c = p.wave_speed();
  m_s0 = p.left == BarEnd::Free ? 1.0 : -1.0;
  m_sL = p.right == BarEnd::Free ? 1.0 : -1.0;
}

double BarJumpExact::period() const { return (m_s0 * m_sL > 0 ? 2.0 : 4.0) * m_p.length / m_c; }

double BarJumpExact::initial_velocity(double x) const {
  if (x < m_p.jump_position) return m_p.velocity_left;
  if (x > m_p.jump_position) return m_p.velocity_right;
  return 0.5 * (m_p.velocity_left + m_p.velocity_right);
}

double BarJumpExact::extended_velocity(double y) const {
  const double L = m_p.length, P = 2.0 * L;
  const double k = std::floor(y / P);
  double r = y - k * P;  // in [0, 2L)
  if (r < 0) r = 0;
  if (r >= P) r = 0;
  const double sign = (m_s0 * m_sL < 0 && std::fmod(std::abs(k), 2.0) == 1.0) ? -1.0 : 1.0;
  if (r <= L) return sign * initial_velocity(r);
  return sign * m_sL * initial_velocity(P - r);
}

double BarJumpExact::base_integral(double r) const {
  const double xj = m_p.jump_position;
  return m_p.velocity_left * std::min(r, xj) + m_p.velocity_right * std::max(0.0, r - xj);
}

double BarJumpExact::extended_integral(double y) const {
  const double L = m_p.length, P = 2.0 * L;
  const double k = std::floor(y / P);
  double r = y - k * P;
  if (r < 0) r = 0;
  if (r > P) r = P;
  // F(r) = ∫_0^r ĝ for r in [0, 2L]; on (L, 2L]: ĝ(s) = sL g(2L - s).
  const double IL = base_integral(L);
  const double F = r <= L ? base_integral(r) : IL + m_sL * (IL - base_integral(P - r));
  const double IP = IL * (1.0 + m_sL);  // ∫ over one 2L period
  // Ĝ(y + 2L) = IP + s0 sL Ĝ(y).
  if (m_s0 * m_sL > 0) return k * IP + F;
  return std::fmod(std::abs(k), 2.0) == 1.0 ? IP - F : F;
}

double BarJumpExact::velocity(double x, double t) const {
  return 0.5 * (extended_velocity(x + m_c * t) + extended_velocity(x - m_c * t));
}

double BarJumpExact::stress(double x, double t) const {
  return 0.5 * m_p.density * m_c * (extended_velocity(x + m_c * t) - extended_velocity(x - m_c * t));
}

double BarJumpExact::displacement(double x, double t) const {
  return (extended_integral(x + m_c * t) - extended_integral(x - m_c * t)) / (2.0 * m_c);
}

double BarJumpExact::momentum(double t) const {
  const double L = m_p.length, ct = m_c * t;
  // ∫_0^L v dx = ½ [Ĝ(L + ct) - Ĝ(ct) + Ĝ(L - ct) - Ĝ(-ct)].
  return m_p.density * 0.5 *
         (extended_integral(L + ct) - extended_integral(ct) + extended_integral(L - ct) - extended_integral(-ct));
}

}  // namespace sphstab
