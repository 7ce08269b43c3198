#include "sphstab/jacobian/linearisation.hpp"

namespace sphstab {

double relative_asymmetry(const SparseMatrix<>& a) {
  const double norm = a.norm();
  if (norm == 0.0) return 0.0;
  SparseMatrix<> at = a.transpose();
  return SparseMatrix<>(a - at).norm() / norm;
}

}  // namespace sphstab
