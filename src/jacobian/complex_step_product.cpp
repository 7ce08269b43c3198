#include "sphstab/jacobian/complex_step_product.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace sphstab {

ComplexStepProduct::ComplexStepProduct(const SemiDiscreteSystem& system, const Eigen::VectorXd& y0, double step)
    : m_system(system), m_y0(y0), m_step(step) {
  if (y0.size() != system.size())
    throw std::invalid_argument("ComplexStepProduct: the state has " + std::to_string(y0.size()) + " entries, " +
                                system.name() + " needs " + std::to_string(system.size()));
  if (!y0.allFinite()) throw std::invalid_argument("ComplexStepProduct: the state y0 is not finite");
  if (!(step > 0) || !std::isfinite(step))
    throw std::invalid_argument("ComplexStepProduct: step must be finite and > 0 (got " + format_number(step) + ")");
  // The step of each variable as the assembled J takes it (complex_step_size of the system's variable scale): 1 inside
  // the band [1e-12, 1e12], the variable's scale / band beyond it (positions of a lattice at dx = 1e-40).
  const Eigen::VectorXd scale = system.variable_scale();
  if (scale.size() != y0.size())
    throw std::invalid_argument("ComplexStepProduct: variable_scale() of " + system.name() + " has " +
                                std::to_string(scale.size()) + " entries, expected " + std::to_string(y0.size()));
  m_inverse_band.resize(scale.size());
  for (Eigen::Index k = 0; k < scale.size(); ++k) m_inverse_band[k] = 1.0 / complex_step_size(1.0, scale[k]);
}

void ComplexStepProduct::apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const {
  if (x.size() != rows() || y.size() != rows())
    throw std::invalid_argument("ComplexStepProduct::apply: x has " + std::to_string(x.size()) + " and y " +
                                std::to_string(y.size()) + " entries, need " + std::to_string(rows()));
  // One step h for the whole product (J x = Im F(y0 + i h x) / h needs a common h) with |h x_k| <= the assembled J's
  // step of variable k (complex_step_jacobian.hpp), so that h x stays far below every variable's real part whatever the
  // scale of x and of the variables: h = step / max_k |x_k| / c_k, c_k = complex_step_size(1, scale_k).
  const double scale = x.cwiseAbs().cwiseProduct(m_inverse_band).maxCoeff();
  if (scale == 0) {
    y.setZero();
    return;
  }
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
