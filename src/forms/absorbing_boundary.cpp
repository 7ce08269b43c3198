#include "sphstab/forms/absorbing_boundary.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

Eigen::Vector2d absorbing_acceleration(AbsorbingCondition condition, double c_p, double c_s, const Eigen::Vector2d& n,
                                       const Eigen::Matrix2d& L, const Eigen::Vector2d& v, bool convective) {
  if (!(std::abs(n.norm() - 1) <= 1e-12))
    throw std::invalid_argument("absorbing_acceleration: the normal must have unit length (got " +
                                format_number(n.norm()) + ")");
  const Eigen::Vector2d t(n[1], -n[0]);  // (2.55)-(2.58): t = (n_2, -n_1)
  const Eigen::Vector2d Ln = L * n, Lt = L * t;
  Eigen::Vector2d a;
  switch (condition) {
    case AbsorbingCondition::ClaytonEngquist:
      a = -c_p * Ln.dot(n) * n - c_s * Ln.dot(t) * t;
      break;
    case AbsorbingCondition::Sochaki:
      a = -(c_p * Ln.dot(n) + (c_p - c_s) * Lt.dot(t)) * n - (c_s * Ln.dot(t) + (c_p - c_s) * Lt.dot(n)) * t;
      break;
    case AbsorbingCondition::Higdon:
      throw std::invalid_argument(
          "absorbing_acceleration: Higdon's condition is second order in time (no velocity form)");
  }
  if (convective) a += L * v;
  return a;
}

double absorbing_acceleration_1d(double c, double n, double dvdx, double v, bool convective) {
  return -c * n * dvdx + (convective ? v * dvdx : 0.0);
}

}  // namespace sphstab
