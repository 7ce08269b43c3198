#include "sphstab/operators/shepard.hpp"

#include "correction_detail.hpp"
#include "sphstab/numerics/instantiation.hpp"

namespace sphstab {

template <class Scalar>
SparseMatrix<Scalar> shepard_kernel(const SparseMatrix<Scalar>& W) {
  detail::check_operator(W, "shepard_kernel", "W");
  detail::Vector<Scalar> s = detail::row_sums(W);
  detail::check_divisor(s, "shepard_kernel", "kernel row sum");
  detail::Vector<Scalar> inv = s.cwiseInverse();
  return SparseMatrix<Scalar>(inv.asDiagonal() * W);
}

namespace {

// (G_ij S_i - W_ij g_i) / S_i^2 = G_ij / S_i - W_ij g_i / S_i^2 for given S, g.
template <class Scalar>
SparseMatrix<Scalar> normalised_gradient(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G,
                                         const detail::Vector<Scalar>& s, const detail::Vector<Scalar>& g) {
  detail::Vector<Scalar> a = s.cwiseInverse();
  detail::Vector<Scalar> b = g.cwiseQuotient(s.cwiseProduct(s));
  return SparseMatrix<Scalar>(a.asDiagonal() * G - b.asDiagonal() * W);
}

}  // namespace

template <class Scalar>
SparseMatrix<Scalar> shepard_gradient(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G) {
  detail::check_operator(W, "shepard_gradient", "W");
  detail::check_operator(G, "shepard_gradient", "G");
  detail::check_same_size(W, G, "shepard_gradient", "W", "G");
  detail::Vector<Scalar> s = detail::row_sums(W);
  detail::check_divisor(s, "shepard_gradient", "kernel row sum");
  return normalised_gradient(W, G, s, detail::row_sums(G));
}

ShepardReference shepard_reference(const SparseMatrix<double>& W0, const SparseMatrix<double>& G0) {
  detail::check_operator(W0, "shepard_reference", "W0");
  detail::check_operator(G0, "shepard_reference", "G0");
  detail::check_same_size(W0, G0, "shepard_reference", "W0", "G0");
  ShepardReference ref{detail::row_sums(W0), detail::row_sums(G0)};
  detail::check_divisor<double>(ref.kernel_sum, "shepard_reference", "kernel row sum");
  return ref;
}

template <class Scalar>
SparseMatrix<Scalar> reference_shepard_gradient(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G,
                                                const ShepardReference& ref) {
  detail::check_operator(W, "reference_shepard_gradient", "W");
  detail::check_operator(G, "reference_shepard_gradient", "G");
  detail::check_same_size(W, G, "reference_shepard_gradient", "W", "G");
  if (ref.kernel_sum.size() != W.rows() || ref.gradient_sum.size() != W.rows())
    throw std::invalid_argument("reference_shepard_gradient: reference sums have " +
                                std::to_string(ref.kernel_sum.size()) + " and " +
                                std::to_string(ref.gradient_sum.size()) + " entries but the matrices are " +
                                std::to_string(W.rows()) + " x " + std::to_string(W.rows()));
  detail::check_divisor<double>(ref.kernel_sum, "reference_shepard_gradient", "reference kernel row sum");
  if (!ref.gradient_sum.allFinite())
    throw std::invalid_argument("reference_shepard_gradient: reference gradient sums must be finite");
  return normalised_gradient<Scalar>(W, G, ref.kernel_sum.cast<Scalar>(), ref.gradient_sum.cast<Scalar>());
}

#define SPHSTAB_INSTANTIATE(S)                                                                           \
  template SparseMatrix<S> shepard_kernel<S>(const SparseMatrix<S>&);                                    \
  template SparseMatrix<S> shepard_gradient<S>(const SparseMatrix<S>&, const SparseMatrix<S>&);          \
  template SparseMatrix<S> reference_shepard_gradient<S>(const SparseMatrix<S>&, const SparseMatrix<S>&, \
                                                         const ShepardReference&);
SPHSTAB_FOR_EACH_SCALAR(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
