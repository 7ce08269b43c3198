#include <cmath>
#include "sphstab/growth/class_growth.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sphstab/growth/linear_growth.hpp"

namespace sphstab {

MirrorClasses mirror_classes(const MirrorSymmetry& symmetry, const Eigen::VectorXd& initial) {
  MirrorClasses c;
  c.symmetry = symmetry;
  for (int px : {1, -1})
    for (int py : {1, -1}) {
      c.basis.push_back(symmetry_basis(symmetry, px, py));
      c.parity.emplace_back(px, py);
      if (class_share(symmetry, px, py, initial) > 1 - 1e-12) c.excited = static_cast<int>(c.basis.size()) - 1;
    }
  return c;
}

ClassGrowth class_growth(const SparseMatrix<>& As, const MirrorClasses& c, const Eigen::MatrixXd& smoothing,
                         double dt) {
  const Eigen::Index n = As.rows();
  if (As.cols() != n || n != 2 * c.symmetry.size())
    throw std::invalid_argument("class_growth: A must be " + std::to_string(2 * c.symmetry.size()) + " x " +
                                std::to_string(2 * c.symmetry.size()));
  if (smoothing.size() > 0 && (smoothing.rows() != n || smoothing.cols() != n || !(dt > 0)))
    throw std::invalid_argument("class_growth: the smoothing must be dofs x dofs and dt > 0");
  if (!(dt >= 0) || !std::isfinite(dt)) throw std::invalid_argument("class_growth: dt must be finite and >= 0");
  const bool map = dt > 0;  // the leap-frog map: with the smoothing as its velocity hook, or plain (S = I)
  const Eigen::MatrixXd S = smoothing.size() > 0 ? smoothing : Eigen::MatrixXd(Eigen::MatrixXd::Identity(n, n));
  ClassGrowth g;
  g.commutation = commutation_error(c.symmetry, As);
  const Eigen::MatrixXd A(As);
  if (g.commutation < 1e-10) {
    g.gamma_all = 0;
    g.lambda_max = 0;
    for (std::size_t k = 0; k < c.basis.size(); ++k) {
      const Eigen::MatrixXd& Q = c.basis[k];
      const Eigen::MatrixXd Ak = Q.transpose() * A * Q;
      const bool exc = static_cast<int>(k) == c.excited;
      const LinearGrowth lg = matrix_growth(Ak, exc);
      if (lg.gamma > g.gamma_all || k == 0) {
        g.gamma_all = lg.gamma;
        g.mu_all = lg.mu;
      }
      g.lambda_max = std::max(g.lambda_max, lg.lambda_max);
      if (exc) {
        g.gamma_excited = lg.gamma;
        g.mu_excited = lg.mu;
        g.mode = Q * lg.mode;
        if (map) {
          const Eigen::MatrixXd Sk = Q.transpose() * S * Q;
          g.gamma_map = leapfrog_map_growth(Ak, dt, Sk, VelocityHookMode::Replace).gamma;
        }
      }
    }
  } else {  // no mirror symmetry: the whole spectrum, no class information
    const LinearGrowth lg = matrix_growth(A, true);
    g.gamma_all = g.gamma_excited = lg.gamma;
    g.mu_all = g.mu_excited = lg.mu;
    g.lambda_max = lg.lambda_max;
    g.mode = lg.mode;
    if (map) g.gamma_map = leapfrog_map_growth(A, dt, S, VelocityHookMode::Replace).gamma;
  }
  return g;
}

}  // namespace sphstab
