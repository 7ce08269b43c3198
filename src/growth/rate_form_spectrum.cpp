#include "sphstab/growth/rate_form_spectrum.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/growth/system_spectrum.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"

namespace sphstab {

namespace {

/// Rows `rows`, columns `cols` of a row-major sparse J, dense.
Eigen::MatrixXd block(const SparseMatrix<>& J, const std::vector<int>& rows, const std::vector<int>& cols) {
  std::vector<int> where(J.cols(), -1);
  for (std::size_t c = 0; c < cols.size(); ++c) where[cols[c]] = static_cast<int>(c);
  Eigen::MatrixXd b =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (SparseMatrix<>::InnerIterator it(J, rows[r]); it; ++it)
      if (where[it.col()] >= 0) b(static_cast<Eigen::Index>(r), where[it.col()]) = it.value();
  return b;
}

}  // namespace

template <int Dim>
RateFormSpectrum rate_form_spectrum(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y,
                                    const RateFormSpectrumOptions& options) {
  const bool want_mode = options.want_mode;
  if (y.size() != scheme.size())
    throw std::invalid_argument("rate_form_spectrum: state has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(scheme.size()));
  std::vector<int> ix, iv, iq;
  for (int i = 0; i < scheme.discretisation().size(); ++i) {
    for (int a = 0; a < Dim && scheme.position_offset(i) >= 0; ++a) {
      ix.push_back(scheme.position_offset(i) + a);
      iv.push_back(scheme.velocity_offset(i) + a);
      if (y[iv.back()] != 0.0)
        throw std::invalid_argument("rate_form_spectrum: the state is not at rest (particle " + std::to_string(i) +
                                    " moves): the reduction needs v = 0");
    }
    for (int c = 0; c < 1 + RateFormScheme<Dim>::kStress && scheme.density_offset(i) >= 0; ++c)
      iq.push_back(scheme.density_offset(i) + c);
  }
  const long nv = static_cast<long>(iv.size());
  require_dense_memory(nv, 8, "rate_form_spectrum");
  RateFormSpectrum out;
  out.states = scheme.size();
  const SparseMatrix<> J = jacobian(scheme, y);
  if (!J.coeffs().allFinite()) {
    out.status = Status::NumericalIssue;
    out.reason = "non-finite Jacobian";
    return out;
  }
  const double scale = std::max(J.nonZeros() ? J.coeffs().cwiseAbs().maxCoeff() : 0.0, 1e-300);
  double zero = 0;
  for (const auto& [r, c] : {std::pair{&ix, &ix}, {&ix, &iq}, {&iq, &ix}, {&iq, &iq}})
    if (!r->empty() && !c->empty()) zero = std::max(zero, block(J, *r, *c).cwiseAbs().maxCoeff());
  out.structure_residual = zero / scale;
  if (out.structure_residual > 1e-10) {
    out.status = Status::NumericalIssue;
    out.reason = "J does not have the at-rest block structure (zero blocks " + format_number(out.structure_residual) +
                 " relative)";
    return out;
  }
  const Eigen::MatrixXd Xv = block(J, ix, iv), Jvx = block(J, iv, ix);
  Eigen::MatrixXd Jvv = block(J, iv, iv);
  Eigen::MatrixXd B = Jvx * Xv;
  if (!iq.empty()) B += block(J, iv, iq) * block(J, iq, iv);
  const Eigen::MatrixXd& Q = options.basis;
  if (Q.size()) {  // restrict to the invariant subspace
    if (Q.rows() != nv)
      throw std::invalid_argument("rate_form_spectrum: basis has " + std::to_string(Q.rows()) + " rows, expected " +
                                  std::to_string(nv) + " (free velocity DOFs)");
    const Eigen::MatrixXd BQ = B * Q, Bc = Q.transpose() * BQ;
    const double norm = std::max(B.norm(), 1e-300);
    out.invariance_residual = (BQ - Q * Bc).norm() / norm;
    B = Bc;
    Jvv = Q.transpose() * Jvv * Q;
  }
  const long m = B.rows();
  const bool damped = Jvv.cwiseAbs().maxCoeff() > 0;
  Eigen::MatrixXd M;
  if (damped) {
    M = Eigen::MatrixXd::Zero(2 * m, 2 * m);
    M.topRightCorner(m, m).setIdentity();
    M.bottomLeftCorner(m, m) = B;
    M.bottomRightCorner(m, m) = Jvv;
  } else {
    M = B;
  }
  out.reduced = static_cast<int>(M.rows());
  const DenseGeneralEigen e = general_eigen(M, want_mode || options.mode_targets.size() > 0);
  if (e.status != Status::Successful) {
    out.status = e.status;
    out.reason = "dgeev failed (info " + std::to_string(e.lapack_info) + ")";
    return out;
  }
  // Eigenvalues of J: the companion's directly, or +-sqrt(mu).
  out.eigenvalues.resize(2 * m);
  for (long k = 0; k < M.rows(); ++k) {
    if (damped) {
      out.eigenvalues[k] = e.values[k];
    } else {
      const std::complex<double> s = std::sqrt(e.values[k]);
      out.eigenvalues[2 * k] = s;
      out.eigenvalues[2 * k + 1] = -s;
    }
  }
  long best = 0;
  for (long k = 1; k < out.eigenvalues.size(); ++k)
    if (out.eigenvalues[k].real() > out.eigenvalues[best].real()) best = k;
  out.lambda = out.eigenvalues[best];
  out.growth_rate = out.lambda.real();
  auto shape = [&](long k) {  // k indexes out.eigenvalues
    const long col = damped ? k : k / 2;
    Eigen::VectorXcd v = e.vectors.col(col).head(m);  // companion: the top half is v
    if (Q.size()) v = Q.cast<std::complex<double>>() * v;
    return real_mode_shape(v);
  };
  if (want_mode) out.mode = shape(best);
  const long targets = options.mode_targets.size();
  if (targets > 0) {
    out.modes.resize(Q.size() ? Q.rows() : m, targets);
    out.mode_eigenvalues.resize(targets);
    for (long t = 0; t < targets; ++t) {
      long near = 0;
      for (long k = 1; k < out.eigenvalues.size(); ++k)
        if (std::abs(out.eigenvalues[k] - options.mode_targets[t]) <
            std::abs(out.eigenvalues[near] - options.mode_targets[t]))
          near = k;
      out.mode_eigenvalues[t] = out.eigenvalues[near];
      out.modes.col(t) = shape(near);
    }
  }
  out.status = Status::Successful;
  out.reason = std::string(damped ? "companion [[0, I], [B, Jvv]]" : "lambda = +-sqrt(eig(B))") +
               (Q.size() ? " in the given class" : "") + ", " + std::to_string(out.reduced) + " x " +
               std::to_string(out.reduced) + " from " + std::to_string(out.states) + " states";
  return out;
}

template RateFormSpectrum rate_form_spectrum<1>(const RateFormScheme<1>&, const Eigen::VectorXd&,
                                                const RateFormSpectrumOptions&);
template RateFormSpectrum rate_form_spectrum<2>(const RateFormScheme<2>&, const Eigen::VectorXd&,
                                                const RateFormSpectrumOptions&);

}  // namespace sphstab
