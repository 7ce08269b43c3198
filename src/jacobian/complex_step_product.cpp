#include "sphstab/jacobian/complex_step_product.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

ComplexStepProduct::ComplexStepProduct(const SemiDiscreteSystem& system, const Eigen::VectorXd& y0, double step)
    : m_system(system), m_y0(y0), m_step(step) {
  if (y0.size() != system.size())
    throw std::invalid_argument("ComplexStepProduct: the state has " + std::to_string(y0.size()) + " entries, " +
                                system.name() + " needs " + std::to_string(system.size()));
  if (!y0.allFinite()) throw std::invalid_argument("ComplexStepProduct: the state y0 is not finite");
  if (!(step > 0) || !std::isfinite(step))
    throw std::invalid_argument("ComplexStepProduct: step must be finite and > 0 (got " + format_number(step) + ")");
}

void ComplexStepProduct::apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const {
  if (x.size() != rows() || y.size() != rows())
    throw std::invalid_argument("ComplexStepProduct::apply: x has " + std::to_string(x.size()) + " and y " +
                                std::to_string(y.size()) + " entries, need " + std::to_string(rows()));
  const double scale = x.cwiseAbs().maxCoeff();
  if (scale == 0) {
    y.setZero();
    return;
  }
  // Step relative to x, so that h x stays far below the real part whatever the scale of x.
  const double h = m_step / scale;
  m_y.resize(rows());
  m_y.real() = m_y0;
  m_y.imag() = h * x;
  m_system.rate(m_y, m_f);
  ++m_products;
  if (!m_f.allFinite())
    throw std::runtime_error("ComplexStepProduct: " + m_system.name() + " is not finite at y0 + i h x");
  y = m_f.imag() / h;
}

}  // namespace sphstab
