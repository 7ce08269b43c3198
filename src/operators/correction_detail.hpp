#pragma once
// Private helpers shared by the kernel corrections (src/operators/*.cpp): validation and row/column sums of
// sparse matrices templated on the scalar. Branching uses the real part only (complex-step safety).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/numerics/dual.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab::detail {

inline bool finite(double x) { return std::isfinite(x); }
inline bool finite(const std::complex<double>& x) { return std::isfinite(x.real()) && std::isfinite(x.imag()); }
template <class S>
bool finite(const Dual<S>& x) {
  return finite(x.v) && finite(x.d);
}

template <class Scalar>
using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

/// Throws unless A is square, non-empty and has finite entries.
template <class Scalar>
void check_operator(const SparseMatrix<Scalar>& a, const char* who, const char* name) {
  if (a.rows() != a.cols() || a.rows() == 0)
    throw std::invalid_argument(std::string(who) + ": " + name + " must be a non-empty square matrix (got " +
                                std::to_string(a.rows()) + " x " + std::to_string(a.cols()) + ")");
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k)
    if (!finite(a.valuePtr()[k]))
      throw std::invalid_argument(std::string(who) + ": " + name + " has a non-finite entry");
}

template <class Scalar>
void check_same_size(const SparseMatrix<Scalar>& a, const SparseMatrix<Scalar>& b, const char* who, const char* na,
                     const char* nb) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    throw std::invalid_argument(std::string(who) + ": " + na + " is " + std::to_string(a.rows()) + " x " +
                                std::to_string(a.cols()) + " but " + nb + " is " + std::to_string(b.rows()) + " x " +
                                std::to_string(b.cols()));
}

/// True when a and b store exactly the same (compressed) pattern.
template <class Scalar>
bool same_pattern(const SparseMatrix<Scalar>& a, const SparseMatrix<Scalar>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  if (!a.isCompressed() || !b.isCompressed()) return false;
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

template <class Scalar>
Vector<Scalar> row_sums(const SparseMatrix<Scalar>& a) {
  Vector<Scalar> s = Vector<Scalar>::Zero(a.rows());
  for (int i = 0; i < a.outerSize(); ++i)
    for (typename SparseMatrix<Scalar>::InnerIterator it(a, i); it; ++it) s[i] += it.value();
  return s;
}

template <class Scalar>
Vector<Scalar> column_sums(const SparseMatrix<Scalar>& a) {
  Vector<Scalar> s = Vector<Scalar>::Zero(a.cols());
  for (int i = 0; i < a.outerSize(); ++i)
    for (typename SparseMatrix<Scalar>::InnerIterator it(a, i); it; ++it) s[it.col()] += it.value();
  return s;
}

/// Throws unless every entry of a normalising sum has a non-zero, finite real part.
template <class Scalar>
void check_divisor(const Vector<Scalar>& s, const char* who, const char* what) {
  for (Eigen::Index i = 0; i < s.size(); ++i)
    if (!(re(s[i]) != 0.0) || !finite(s[i]))
      throw std::invalid_argument(std::string(who) + ": " + what + " of particle " + std::to_string(i) +
                                  " is zero or non-finite (got " + format_number(re(s[i])) + ")");
}

/// A + diag(d); the diagonal is added in place where stored, inserted where missing.
template <class Scalar>
SparseMatrix<Scalar> add_to_diagonal(const SparseMatrix<Scalar>& a, const Vector<Scalar>& d) {
  SparseMatrix<Scalar> out = a;
  out.makeCompressed();
  bool all_stored = true;
  for (int i = 0; i < out.outerSize() && all_stored; ++i) {
    bool found = false;
    for (typename SparseMatrix<Scalar>::InnerIterator it(out, i); it; ++it)
      if (it.col() == i) {
        it.valueRef() += d[i];
        found = true;
        break;
      }
    all_stored = found;
  }
  if (all_stored) return out;
  // Some diagonal entries are not stored: rebuild as A + D (the rows already updated are recomputed).
  SparseMatrix<Scalar> diag(a.rows(), a.cols());
  diag.reserve(Eigen::VectorXi::Constant(a.rows(), 1));
  for (int i = 0; i < a.rows(); ++i) diag.insert(i, i) = d[i];
  return SparseMatrix<Scalar>(a + diag);
}

}  // namespace sphstab::detail
