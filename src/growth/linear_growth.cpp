#include "sphstab/growth/linear_growth.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/growth/system_spectrum.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"

namespace sphstab {

LinearGrowth matrix_growth(const Eigen::MatrixXd& A, bool mode) {
  const auto t0 = std::chrono::steady_clock::now();
  LinearGrowth out;
  const DenseGeneralEigen eig = general_eigen(A, mode);  // validates A
  out.status = eig.status;
  if (eig.status == Status::Successful) {
    out.gamma = 0;
    out.lambda_max = 0;
    out.min_real = std::numeric_limits<double>::infinity();
    Eigen::Index best = 0;
    for (Eigen::Index k = 0; k < eig.values.size(); ++k) {
      const double g = mode_growth(eig.values[k]);
      out.lambda_max = std::max(out.lambda_max, std::abs(eig.values[k]));
      out.min_real = std::min(out.min_real, eig.values[k].real());
      if (k == 0 || g > out.gamma) {
        out.gamma = g;
        out.mu = eig.values[k];
        best = k;
      }
    }
    if (mode) out.mode = real_mode_shape(eig.vectors.col(best));
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

LinearGrowth linear_growth(const ForceFunction& force, const Eigen::VectorXd& u, bool mode) {
  if (u.size() != force.dofs())
    throw std::invalid_argument("linear_growth: u has " + std::to_string(u.size()) + " entries, expected " +
                                std::to_string(force.dofs()));
  const auto t0 = std::chrono::steady_clock::now();
  ComplexStepJacobian jac(force);
  const SparseMatrix<> A = jac.compute(u);
  LinearGrowth out;
  if (jac.info() != Status::Successful) {
    out.status = Status::NumericalIssue;
  } else {
    out = matrix_growth(Eigen::MatrixXd(A), mode);
    out.asymmetry = relative_asymmetry(A);
  }
  out.colours = jac.colours();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

MapGrowth leapfrog_map_growth(const Eigen::MatrixXd& A, double dt, const Eigen::MatrixXd& S, VelocityHookMode mode) {
  const char* who = "leapfrog_map_growth";
  const Eigen::Index n = A.rows();
  if (A.cols() != n || n == 0) throw std::invalid_argument(std::string(who) + ": A must be square and non-empty");
  if (!(dt > 0) || !std::isfinite(dt)) throw std::invalid_argument(std::string(who) + ": dt must be finite and > 0");
  const bool hook = S.size() > 0;
  if (hook && (S.rows() != n || S.cols() != n))
    throw std::invalid_argument(std::string(who) + ": S must be " + std::to_string(n) + " x " + std::to_string(n) +
                                " (got " + std::to_string(S.rows()) + " x " + std::to_string(S.cols()) + ")");
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  // v_h = Vu u + v;  w = Wu u + Wv v;  u' = Uu u + Uv v;  v' = Bu u + Bv v - dt/2 A u'
  const Eigen::MatrixXd Vu = -0.5 * dt * A;
  const Eigen::MatrixXd Wu = hook ? Eigen::MatrixXd(S * Vu) : Vu, Wv = hook ? S : I;
  const Eigen::MatrixXd Uu = I + dt * Wu, Uv = dt * Wv;
  const bool replace = hook && mode == VelocityHookMode::Replace;
  Eigen::MatrixXd M(2 * n, 2 * n);
  M.topLeftCorner(n, n) = Uu;
  M.topRightCorner(n, n) = Uv;
  M.bottomLeftCorner(n, n) = (replace ? Wu : Vu) - 0.5 * dt * A * Uu;
  M.bottomRightCorner(n, n) = (replace ? Wv : I) - 0.5 * dt * A * Uv;
  MapGrowth out;
  const DenseGeneralEigen eig = general_eigen(M, false);
  out.status = eig.status;
  if (eig.status != Status::Successful) return out;
  out.spectral_radius = eig.values.cwiseAbs().maxCoeff();
  out.gamma = std::log(out.spectral_radius) / dt;
  return out;
}

}  // namespace sphstab
