#include "sphstab/linalg/symmetric_pencil.hpp"

#include <stdexcept>
#include <string>

namespace sphstab {

SymmetricPencil::SymmetricPencil(const ColSparseMatrix& a, const ColSparseMatrix& b_in) {
  const Eigen::Index n = a.rows();
  if (a.cols() != n || n == 0)
    throw std::invalid_argument("SymmetricPencil: A must be square and non-empty (got " + std::to_string(a.rows()) +
                                " x " + std::to_string(a.cols()) + ")");
  const ColSparseMatrix a_lower = lower_triangle(a);
  ColSparseMatrix b = lower_triangle(b_in);
  if (b.rows() == 0 && b.cols() == 0) {
    b.resize(n, n);
    b.setIdentity();
  }
  if (b.rows() != n || b.cols() != n)
    throw std::invalid_argument("SymmetricPencil: B must be " + std::to_string(n) + " x " + std::to_string(n) +
                                " like A (got " + std::to_string(b.rows()) + " x " + std::to_string(b.cols()) + ")");
  // Merged pattern: |A| + |B| has every structural entry of both (explicit zeros kept by the sum of patterns).
  ColSparseMatrix ones_a = a_lower, ones_b = b;
  for (Eigen::Index k = 0; k < ones_a.nonZeros(); ++k) ones_a.valuePtr()[k] = 1.0;
  for (Eigen::Index k = 0; k < ones_b.nonZeros(); ++k) ones_b.valuePtr()[k] = 1.0;
  m_matrix = ones_a + ones_b;
  m_matrix.makeCompressed();
  // Diagonal always present (CHOLMOD shifts, definiteness of the identity pencil).
  bool diag_complete = true;
  for (Eigen::Index j = 0; j < n && diag_complete; ++j) diag_complete = m_matrix.coeff(j, j) != 0.0;
  if (!diag_complete) {
    ColSparseMatrix eye(n, n);
    eye.setIdentity();
    m_matrix = m_matrix + eye;
    m_matrix.makeCompressed();
  }
  const Eigen::Index nnz = m_matrix.nonZeros();
  m_a = Eigen::VectorXd::Zero(nnz);
  m_b = Eigen::VectorXd::Zero(nnz);
  // Scatter the values of A and B into the merged pattern (both sorted within each column).
  auto scatter = [&](const ColSparseMatrix& src, Eigen::VectorXd& dst) {
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::Index k = m_matrix.outerIndexPtr()[j];
      for (ColSparseMatrix::InnerIterator it(src, j); it; ++it) {
        while (m_matrix.innerIndexPtr()[k] != it.row()) ++k;
        dst[k] = it.value();
      }
    }
  };
  scatter(a_lower, m_a);
  scatter(b, m_b);
  std::fill(m_matrix.valuePtr(), m_matrix.valuePtr() + nnz, 0.0);
}

const ColSparseMatrix& SymmetricPencil::evaluate(double sigma) {
  Eigen::Map<Eigen::VectorXd> v(m_matrix.valuePtr(), m_matrix.nonZeros());
  v = m_a - sigma * m_b;
  return m_matrix;
}

}  // namespace sphstab
