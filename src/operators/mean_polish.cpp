#include "sphstab/operators/mean_polish.hpp"

#include <type_traits>

#include "correction_detail.hpp"
#include "sphstab/numerics/instantiation.hpp"
#include "sphstab/operators/shepard.hpp"

namespace sphstab {

namespace {

template <class Scalar>
std::vector<int> checked_subset(const DenseMatrix<Scalar>& a, const std::vector<int>& subset, const char* who) {
  if (a.rows() != a.cols() || a.rows() == 0)
    throw std::invalid_argument(std::string(who) + ": matrix must be non-empty and square (got " +
                                std::to_string(a.rows()) + " x " + std::to_string(a.cols()) + ")");
  for (Eigen::Index k = 0; k < a.size(); ++k)
    if (!detail::finite(a.data()[k])) throw std::invalid_argument(std::string(who) + ": matrix has a non-finite entry");
  const int n = static_cast<int>(a.rows());
  if (subset.empty()) {
    std::vector<int> all(n);
    for (int i = 0; i < n; ++i) all[i] = i;
    return all;
  }
  std::vector<char> seen(n, 0);
  for (int i : subset) {
    if (i < 0 || i >= n)
      throw std::invalid_argument(std::string(who) + ": subset index " + std::to_string(i) + " outside [0, " +
                                  std::to_string(n) + ")");
    if (seen[i]) throw std::invalid_argument(std::string(who) + ": subset index " + std::to_string(i) + " repeated");
    seen[i] = 1;
  }
  return subset;
}

// Algorithm 3.1's row step: each row of the subset loses its mean over the subset's columns. A matrix expression, so
// that the column step is the row step of the transpose (the same sums in the same order).
template <class Matrix>
void row_polish_in_place(Matrix&& a, const std::vector<int>& s) {
  using Scalar = typename std::decay_t<Matrix>::Scalar;
  const double inv_n = 1.0 / static_cast<double>(s.size());
  for (int i : s) {
    Scalar mean(0);
    for (int j : s) mean += a(i, j);
    mean *= inv_n;
    for (int j : s) a(i, j) -= mean;
  }
}

template <class Scalar>
void column_polish_in_place(DenseMatrix<Scalar>& a, const std::vector<int>& s) {
  row_polish_in_place(a.transpose(), s);
}

/// Which steps of algorithm 3.1 a polish takes.
enum class PolishSteps { Rows, Columns, Both };

// A copy of A polished over the checked subset (errors name `who`): its row step, its column step or both (algorithm
// 3.1: row means first, then the column means of the new matrix).
template <class Scalar>
DenseMatrix<Scalar> polished(const DenseMatrix<Scalar>& A, const std::vector<int>& subset, const char* who,
                             PolishSteps steps) {
  const std::vector<int> s = checked_subset(A, subset, who);
  DenseMatrix<Scalar> out = A;
  if (steps != PolishSteps::Columns) row_polish_in_place(out, s);
  if (steps != PolishSteps::Rows) column_polish_in_place(out, s);
  return out;
}

}  // namespace

template <class Scalar>
DenseMatrix<Scalar> row_mean_polish(const DenseMatrix<Scalar>& A, const std::vector<int>& subset) {
  return polished(A, subset, "row_mean_polish", PolishSteps::Rows);
}

template <class Scalar>
DenseMatrix<Scalar> column_mean_polish(const DenseMatrix<Scalar>& A, const std::vector<int>& subset) {
  return polished(A, subset, "column_mean_polish", PolishSteps::Columns);
}

template <class Scalar>
DenseMatrix<Scalar> mean_polish(const DenseMatrix<Scalar>& A, const std::vector<int>& subset) {
  return polished(A, subset, "mean_polish", PolishSteps::Both);
}

template <class Scalar>
DenseMatrix<Scalar> mean_polish(const SparseMatrix<Scalar>& A, const std::vector<int>& subset) {
  detail::check_operator(A, "mean_polish", "A");
  return mean_polish<Scalar>(DenseMatrix<Scalar>(A), subset);
}

template <class Scalar>
DenseMatrix<Scalar> shepard_column_polish(const SparseMatrix<Scalar>& W, const SparseMatrix<Scalar>& G) {
  DenseMatrix<Scalar> out(shepard_gradient(W, G));
  std::vector<int> all(out.rows());
  for (int i = 0; i < static_cast<int>(all.size()); ++i) all[i] = i;
  column_polish_in_place(out, all);
  return out;
}

template <class Scalar>
PolishFill polish_fill(const SparseMatrix<Scalar>& before, const DenseMatrix<Scalar>& after) {
  if (before.rows() != after.rows() || before.cols() != after.cols())
    throw std::invalid_argument("polish_fill: matrices differ in size (" + std::to_string(before.rows()) + " x " +
                                std::to_string(before.cols()) + " vs " + std::to_string(after.rows()) + " x " +
                                std::to_string(after.cols()) + ")");
  PolishFill f;
  f.size = before.rows();
  f.stored_before = before.nonZeros();
  for (Eigen::Index k = 0; k < before.nonZeros(); ++k) f.nonzero_before += before.valuePtr()[k] != Scalar(0);
  for (Eigen::Index k = 0; k < after.size(); ++k) f.nonzero_after += after.data()[k] != Scalar(0);
  return f;
}

template <class Scalar>
SparseMatrix<Scalar> dense_to_sparse_all_entries(const DenseMatrix<Scalar>& A) {
  const Eigen::Index n = A.rows(), m = A.cols();
  SparseMatrix<Scalar> s(n, m);
  s.resizeNonZeros(n * m);
  for (Eigen::Index i = 0; i <= n; ++i) s.outerIndexPtr()[i] = static_cast<int>(i * m);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < m; ++j) {
      s.innerIndexPtr()[i * m + j] = static_cast<int>(j);
      s.valuePtr()[i * m + j] = A(i, j);
    }
  return s;
}

#define SPHSTAB_INSTANTIATE(S)                                                                      \
  template DenseMatrix<S> row_mean_polish<S>(const DenseMatrix<S>&, const std::vector<int>&);       \
  template DenseMatrix<S> column_mean_polish<S>(const DenseMatrix<S>&, const std::vector<int>&);    \
  template DenseMatrix<S> mean_polish<S>(const DenseMatrix<S>&, const std::vector<int>&);           \
  template DenseMatrix<S> mean_polish<S>(const SparseMatrix<S>&, const std::vector<int>&);          \
  template DenseMatrix<S> shepard_column_polish<S>(const SparseMatrix<S>&, const SparseMatrix<S>&); \
  template PolishFill polish_fill<S>(const SparseMatrix<S>&, const DenseMatrix<S>&);                \
  template SparseMatrix<S> dense_to_sparse_all_entries<S>(const DenseMatrix<S>&);
SPHSTAB_FOR_EACH_SCALAR(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
