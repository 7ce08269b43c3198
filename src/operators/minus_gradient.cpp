#include "sphstab/operators/minus_gradient.hpp"

#include "correction_detail.hpp"

namespace sphstab {

template <class Scalar>
SparseMatrix<Scalar> minus_gradient(const SparseMatrix<Scalar>& G) {
  detail::check_operator(G, "minus_gradient", "G");
  detail::Vector<Scalar> s = detail::row_sums(G);
  return detail::add_to_diagonal<Scalar>(G, -s);
}

template SparseMatrix<double> minus_gradient<double>(const SparseMatrix<double>&);
template SparseMatrix<std::complex<double>> minus_gradient<std::complex<double>>(
    const SparseMatrix<std::complex<double>>&);
template SparseMatrix<Dual<double>> minus_gradient<Dual<double>>(const SparseMatrix<Dual<double>>&);
template SparseMatrix<Dual<std::complex<double>>> minus_gradient<Dual<std::complex<double>>>(
    const SparseMatrix<Dual<std::complex<double>>>&);

}  // namespace sphstab
