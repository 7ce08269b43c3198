#include "sphstab/linalg/cholmod_shift_invert.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sphstab {

CholmodShiftInvert::CholmodShiftInvert(const ColSparseMatrix& a, const ColSparseMatrix& b, CholmodFactorKind kind,
                                       CholmodVariant variant)
    : m_pencil(a, b), m_factor(variant, kind) {}

void CholmodShiftInvert::set_shift(double sigma) {
  if (!std::isfinite(sigma)) throw std::invalid_argument("CholmodShiftInvert::set_shift: shift must be finite");
  if (!m_analysed) {
    m_factor.analyze_pattern(m_pencil.pattern());
    m_analysed = true;
  }
  m_sigma = sigma;
  const ColSparseMatrix& m = m_pencil.evaluate(sigma);
  ++m_count;
  if (m_factor.factorize(m)) {
    m_sign = 1;
    return;
  }
  if (m_factor.kind() == CholmodFactorKind::LLT) {
    m_work = m;
    m_work *= -1.0;
    ++m_count;
    if (m_factor.factorize(m_work)) {
      m_sign = -1;
      return;
    }
  }
  std::ostringstream msg;
  msg << "CholmodShiftInvert::set_shift: A - sigma B is "
      << (m_factor.kind() == CholmodFactorKind::LLT ? "neither positive nor negative definite"
                                                    : "singular (zero pivot)")
      << " at sigma = " << sigma << "; choose another shift"
      << (m_factor.kind() == CholmodFactorKind::LLT ? " or CholmodFactorKind::LDLT" : "");
  throw std::invalid_argument(msg.str());
}

void CholmodShiftInvert::perform_op(const double* x_in, double* y_out) const {
  m_factor.solve(CholmodSystem::A, x_in, y_out);
  if (m_sign < 0)
    for (Eigen::Index i = 0; i < rows(); ++i) y_out[i] = -y_out[i];
}

}  // namespace sphstab
