#include "sphstab/linalg/dense_symmetric_eigen.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "lapack_symbols.hpp"

namespace sphstab {

namespace {

void check_square(const Eigen::MatrixXd& a, const char* who, const char* name) {
  if (a.rows() != a.cols() || a.rows() == 0)
    throw std::invalid_argument(std::string(who) + ": " + name + " must be square and non-empty (got " +
                                std::to_string(a.rows()) + " x " + std::to_string(a.cols()) + ")");
  if (!a.allFinite()) throw std::invalid_argument(std::string(who) + ": " + name + " has non-finite entries");
}

}  // namespace

DenseSymmetricEigen symmetric_eigen(const Eigen::MatrixXd& a, bool vectors) {
  check_square(a, "symmetric_eigen", "a");
  const int n = static_cast<int>(a.rows());
  Eigen::MatrixXd work_a = a;
  Eigen::VectorXd w(n);
  const char jobz = vectors ? 'V' : 'N', uplo = 'L';
  int info = 0, lwork = -1;
  double query = 0;
  dsyev_(&jobz, &uplo, &n, work_a.data(), &n, w.data(), &query, &lwork, &info, 1, 1);
  lwork = static_cast<int>(query);
  Eigen::VectorXd work(std::max(1, lwork));
  dsyev_(&jobz, &uplo, &n, work_a.data(), &n, w.data(), work.data(), &lwork, &info, 1, 1);
  DenseSymmetricEigen r;
  r.lapack_info = info;
  if (info != 0) {
    r.status = info > 0 ? Status::NotConverging : Status::NumericalIssue;
    return r;
  }
  r.values = w;
  if (vectors) r.vectors = work_a;
  r.status = Status::Successful;
  return r;
}

DenseSymmetricEigen generalized_symmetric_eigen(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, bool vectors) {
  check_square(a, "generalized_symmetric_eigen", "a");
  check_square(b, "generalized_symmetric_eigen", "b");
  if (a.rows() != b.rows())
    throw std::invalid_argument("generalized_symmetric_eigen: a and b differ in size (" + std::to_string(a.rows()) +
                                " vs " + std::to_string(b.rows()) + ")");
  const int n = static_cast<int>(a.rows()), itype = 1;
  Eigen::MatrixXd work_a = a, work_b = b;
  Eigen::VectorXd w(n);
  const char jobz = vectors ? 'V' : 'N', uplo = 'L';
  int info = 0, lwork = -1;
  double query = 0;
  dsygv_(&itype, &jobz, &uplo, &n, work_a.data(), &n, work_b.data(), &n, w.data(), &query, &lwork, &info, 1, 1);
  lwork = static_cast<int>(query);
  Eigen::VectorXd work(std::max(1, lwork));
  dsygv_(&itype, &jobz, &uplo, &n, work_a.data(), &n, work_b.data(), &n, w.data(), work.data(), &lwork, &info, 1, 1);
  DenseSymmetricEigen r;
  r.lapack_info = info;
  if (info != 0) {
    // info > n: B not positive definite; 0 < info <= n: dsyev failed to converge.
    r.status = (info > n || info < 0) ? Status::NumericalIssue : Status::NotConverging;
    return r;
  }
  r.values = w;
  if (vectors) r.vectors = work_a;
  r.status = Status::Successful;
  return r;
}

}  // namespace sphstab
