#include "sphstab/operators/column_shepard.hpp"

#include "correction_detail.hpp"

namespace sphstab {

template <class Scalar>
SparseMatrix<Scalar> column_shepard_gradient(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G) {
  const char* who = "column_shepard_gradient";
  detail::check_operator(W, who, "W");
  detail::check_operator(G, who, "G");
  detail::check_same_size(W, G, who, "W", "G");
  detail::Vector<Scalar> r = detail::row_sums(W);  // (sum_l W_jl), the printed denominator
  detail::check_divisor(r, who, "kernel row sum");
  detail::Vector<Scalar> r2 = r.cwiseProduct(r);
  detail::Vector<Scalar> a = detail::column_sums(W).cwiseQuotient(r2);
  detail::Vector<Scalar> b = detail::column_sums(G).cwiseQuotient(r2);
  return SparseMatrix<Scalar>(G * a.asDiagonal() - W * b.asDiagonal());
}

template SparseMatrix<double> column_shepard_gradient<double>(const SparseMatrix<double>&, const SparseMatrix<double>&);
template SparseMatrix<std::complex<double>> column_shepard_gradient<std::complex<double>>(
    const SparseMatrix<std::complex<double>>&, const SparseMatrix<std::complex<double>>&);
template SparseMatrix<Dual<double>> column_shepard_gradient<Dual<double>>(const SparseMatrix<Dual<double>>&,
                                                                          const SparseMatrix<Dual<double>>&);
template SparseMatrix<Dual<std::complex<double>>> column_shepard_gradient<Dual<std::complex<double>>>(
    const SparseMatrix<Dual<std::complex<double>>>&, const SparseMatrix<Dual<std::complex<double>>>&);

}  // namespace sphstab
