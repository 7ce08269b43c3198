#include "sphstab/linalg/cholmod_cholesky_op.hpp"

namespace sphstab {

CholmodCholeskyOp::CholmodCholeskyOp(const ColSparseMatrix& b, CholmodVariant variant)
    : m_factor(variant, CholmodFactorKind::LLT) {
  ColSparseMatrix lower = lower_triangle(b);
  lower.makeCompressed();
  m_factor.compute(lower);
  m_tmp.resize(lower.rows());
}

void CholmodCholeskyOp::lower_triangular_solve(const double* x_in, double* y_out) const {
  m_factor.solve(CholmodSystem::P, x_in, m_tmp.data());
  m_factor.solve(CholmodSystem::L, m_tmp.data(), y_out);
}

void CholmodCholeskyOp::upper_triangular_solve(const double* x_in, double* y_out) const {
  m_factor.solve(CholmodSystem::Lt, x_in, m_tmp.data());
  m_factor.solve(CholmodSystem::Pt, m_tmp.data(), y_out);
}

}  // namespace sphstab
