#include "sphstab/growth/system_spectrum.hpp"

#include <Spectra/GenEigsSolver.h>
#include <Spectra/MatOp/SparseGenMatProd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"

namespace sphstab {

Eigen::VectorXd real_mode_shape(Eigen::VectorXcd v) {
  const std::complex<double> s = (v.array() * v.array()).sum();
  v *= std::polar(1.0, -0.5 * std::arg(s));
  Eigen::VectorXd shape = v.real();
  const double norm = shape.norm();
  if (norm > 0) shape /= norm;
  return shape;
}

SystemSpectrum system_spectrum(const SparseMatrix<>& j, const SystemSpectrumOptions& o) {
  const Eigen::Index n = j.rows();
  if (n == 0 || j.cols() != n)
    throw std::invalid_argument("system_spectrum: J must be square and non-empty (got " + std::to_string(j.rows()) +
                                " x " + std::to_string(j.cols()) + ")");
  for (Eigen::Index k = 0; k < j.nonZeros(); ++k)
    if (!std::isfinite(j.valuePtr()[k])) throw std::invalid_argument("system_spectrum: J has non-finite entries");
  if (o.nev < 1 || o.maxit < 1 || !(o.tol > 0) || o.dense_max < 0)
    throw std::invalid_argument("system_spectrum: need nev >= 1, maxit >= 1, tol > 0 and dense_max >= 0");
  SystemSpectrum out;
  Eigen::VectorXcd vectors_col;
  if (n <= o.dense_max || n < o.nev + 3) {
    out.backend = "dense";
    const DenseGeneralEigen e = general_eigen(Eigen::MatrixXd(j), o.want_mode);
    out.status = e.status;
    if (e.status != Status::Successful) return out;
    out.eigenvalues = e.values;
    Eigen::Index best = 0;
    for (Eigen::Index k = 1; k < n; ++k)
      if (e.values[k].real() > e.values[best].real()) best = k;
    out.lambda = e.values[best];
    if (o.want_mode) vectors_col = e.vectors.col(best);
  } else {
    out.backend = "spectra";
    Spectra::SparseGenMatProd<double, Eigen::RowMajor> op(j);
    const int nev = std::min<int>(o.nev, static_cast<int>(n) - 2);
    const int ncv = std::min<int>(static_cast<int>(n), o.ncv > 0 ? o.ncv : std::max(2 * nev + 1, 40));
    Spectra::GenEigsSolver<decltype(op)> eigs(op, nev, ncv);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestReal, o.maxit, o.tol, Spectra::SortRule::LargestReal);
    if (eigs.info() != Spectra::CompInfo::Successful) {
      out.status = Status::NotConverging;
      return out;
    }
    out.status = Status::Successful;
    out.eigenvalues = eigs.eigenvalues();
    out.lambda = out.eigenvalues[0];
    if (o.want_mode) vectors_col = eigs.eigenvectors().col(0);
  }
  out.growth_rate = out.lambda.real();
  if (o.want_mode) out.mode = real_mode_shape(vectors_col);
  return out;
}

SystemSpectrum system_spectrum(const SemiDiscreteSystem& system, const Eigen::VectorXd& y,
                               const SystemSpectrumOptions& options) {
  if (y.size() != system.size())
    throw std::invalid_argument("system_spectrum: y has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(system.size()));
  ComplexStepJacobian jac(system);
  const SparseMatrix<> j = jac.compute(y);
  if (jac.info() != Status::Successful) {
    SystemSpectrum out;
    out.status = Status::NumericalIssue;
    return out;
  }
  return system_spectrum(j, options);
}

}  // namespace sphstab
