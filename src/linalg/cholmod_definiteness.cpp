#include "sphstab/linalg/cholmod_definiteness.hpp"

namespace sphstab {

bool is_positive_definite(const ColSparseMatrix& a, CholmodVariant variant) {
  ColSparseMatrix lower = lower_triangle(a);
  lower.makeCompressed();
  CholmodDefiniteness check(variant);
  check.analyze_pattern(lower);
  return check.is_positive_definite(lower);
}

}  // namespace sphstab
