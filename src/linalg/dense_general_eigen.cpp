#include "sphstab/linalg/dense_general_eigen.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "lapack_symbols.hpp"

namespace sphstab {

DenseGeneralEigen general_eigen(const Eigen::MatrixXd& a, bool vectors) {
  if (a.rows() != a.cols() || a.rows() == 0)
    throw std::invalid_argument("general_eigen: matrix must be square and non-empty (got " + std::to_string(a.rows()) +
                                " x " + std::to_string(a.cols()) + ")");
  if (!a.allFinite()) throw std::invalid_argument("general_eigen: matrix has non-finite entries");
  const int n = static_cast<int>(a.rows()), one = 1;
  Eigen::MatrixXd work_a = a;
  Eigen::VectorXd wr(n), wi(n);
  Eigen::MatrixXd vr(vectors ? n : 1, vectors ? n : 1);
  double vl = 0;
  const char jobvl = 'N', jobvr = vectors ? 'V' : 'N';
  const int ldvr = vectors ? n : 1;
  int info = 0, lwork = -1;
  double query = 0;
  dgeev_(&jobvl, &jobvr, &n, work_a.data(), &n, wr.data(), wi.data(), &vl, &one, vr.data(), &ldvr, &query, &lwork,
         &info, 1, 1);
  lwork = static_cast<int>(query);
  Eigen::VectorXd work(std::max(1, lwork));
  dgeev_(&jobvl, &jobvr, &n, work_a.data(), &n, wr.data(), wi.data(), &vl, &one, vr.data(), &ldvr, work.data(), &lwork,
         &info, 1, 1);
  DenseGeneralEigen r;
  r.lapack_info = info;
  if (info != 0) {
    r.status = info > 0 ? Status::NotConverging : Status::NumericalIssue;
    return r;
  }
  r.values.resize(n);
  for (int k = 0; k < n; ++k) r.values[k] = {wr[k], wi[k]};
  if (vectors) {
    // LAPACK packs a complex pair (wi[k] > 0) as columns k (real part) and k+1 (imaginary part).
    r.vectors.resize(n, n);
    for (int k = 0; k < n; ++k) {
      if (wi[k] == 0.0) {
        r.vectors.col(k) = vr.col(k).cast<std::complex<double>>();
      } else if (wi[k] > 0.0 && k + 1 < n) {
        for (int i = 0; i < n; ++i) {
          r.vectors(i, k) = {vr(i, k), vr(i, k + 1)};
          r.vectors(i, k + 1) = {vr(i, k), -vr(i, k + 1)};
        }
        ++k;
      }
    }
  }
  r.status = Status::Successful;
  return r;
}

}  // namespace sphstab
