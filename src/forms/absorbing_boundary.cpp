#include "sphstab/forms/absorbing_boundary.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> absorbing_acceleration(AbsorbingCondition condition, double c_p, double c_s,
                                                   const Eigen::Vector2d& n, const Eigen::Matrix<Scalar, 2, 2>& L,
                                                   const Eigen::Matrix<Scalar, 2, 1>& v, bool convective) {
  using Vec = Eigen::Matrix<Scalar, 2, 1>;
  if (!(std::abs(n.norm() - 1) <= 1e-12))
    throw std::invalid_argument("absorbing_acceleration: the normal must have unit length (got " +
                                format_number(n.norm()) + ")");
  const Eigen::Vector2d t(n[1], -n[0]);  // (2.55)-(2.58): t = (n_2, -n_1)
  const Vec nn = n.cast<Scalar>(), tt = t.cast<Scalar>();
  const Vec Ln = L * nn, Lt = L * tt;
  // Eigen's dot() conjugates its first argument: a complex step needs the bilinear product.
  const auto dot = [](const Vec& a, const Vec& b) { return (a.array() * b.array()).sum(); };
  Vec a;
  switch (condition) {
    case AbsorbingCondition::ClaytonEngquist:
      a = -c_p * dot(Ln, nn) * nn - c_s * dot(Ln, tt) * tt;
      break;
    case AbsorbingCondition::Sochaki:
      a = -(c_p * dot(Ln, nn) + (c_p - c_s) * dot(Lt, tt)) * nn - (c_s * dot(Ln, tt) + (c_p - c_s) * dot(Lt, nn)) * tt;
      break;
    case AbsorbingCondition::Higdon:
      throw std::invalid_argument(
          "absorbing_acceleration: Higdon's condition is second order in time (no velocity form)");
    case AbsorbingCondition::ViscousTraction:
      throw std::invalid_argument(
          "absorbing_acceleration: the viscous traction adds to the momentum equation "
          "(viscous_traction_acceleration)");
  }
  if (convective) a += L * v;
  return a;
}

template Eigen::Vector2d absorbing_acceleration(AbsorbingCondition, double, double, const Eigen::Vector2d&,
                                                const Eigen::Matrix2d&, const Eigen::Vector2d&, bool);
template Eigen::Vector2cd absorbing_acceleration(AbsorbingCondition, double, double, const Eigen::Vector2d&,
                                                 const Eigen::Matrix2cd&, const Eigen::Vector2cd&, bool);

}  // namespace sphstab
