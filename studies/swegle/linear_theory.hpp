#pragma once
// Linear theory of a Swegle run: A = -da/du of the same force function by the coloured complex-step Jacobian
// ([SquireTrapp1998], [CurtisPowellReid1974]), its eigenvalues per mirror-symmetry class of the block (the kick
// excites one class), gamma = max Re sqrt(-mu), and with XSPH the spectral radius of the leap-frog map including the
// smoothing (growth/class_growth.hpp); the linear verdict of a predicted rate against the detection limit.

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <string>

#include "common/study.hpp"
#include "sphstab/growth/class_growth.hpp"
#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/integrate/xsph.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/problems/swegle.hpp"
#include "swegle_options.hpp"

namespace swegle_study {

using namespace sphstab;

/// The four mirror classes of the Swegle block (the same for every xi) and the XSPH smoothing on the DOFs.
struct Classes {
  MirrorClasses mirror;
  Eigen::MatrixXd S_dof;  ///< XSPH smoothing (x) I_2 at x0
};

inline Classes make_classes(const SwegleScene& s) {
  Classes c;
  const double mid = 0.5 * s.options.n * s.options.spacing;
  c.mirror =
      mirror_classes(mirror_symmetry(s.free_positions(), Eigen::Vector2d(mid, mid), 1e-6 * s.options.spacing), s.v0);
  const SparseMatrix<> S = xsph_smoothing_matrix(*s.discretisation, {});
  const int n = s.discretisation->dofs();
  c.S_dof = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < S.outerSize(); ++i)
    for (SparseMatrix<>::InnerIterator it(S, i); it; ++it)
      for (int a = 0; a < 2; ++a) c.S_dof(2 * i + a, 2 * it.col() + a) = it.value();
  return c;
}

/// Linear theory of one force function at u: all four classes, the excited one, the leap-frog map with XSPH.
struct Linear {
  double gamma_all = kNaN, gamma_exc = kNaN, gamma_map = kNaN, lambda_max = kNaN;
  std::complex<double> mu_all{kNaN, kNaN}, mu_exc{kNaN, kNaN};
  double commutation = kNaN, asymmetry = kNaN;
  Eigen::VectorXd mode;  ///< fastest mode of the excited class (full DOFs, unit norm)
  int colours = 0;
  double seconds = 0;
};

inline Linear analyse(const ForceFunction& f, const Eigen::VectorXd& u, const Classes& c, bool xsph, double dt) {
  const auto t0 = study::Clock::now();
  Linear L;
  ComplexStepJacobian jac(f);
  const SparseMatrix<> As = jac.compute(u);
  L.colours = jac.colours();
  if (jac.info() != Status::Successful) return L;
  L.asymmetry = relative_asymmetry(As);
  // gamma_map: the leap-frog's one-step map at dt, with XSPH as its velocity hook when the formulation smooths.
  const ClassGrowth g = class_growth(As, c.mirror, xsph ? c.S_dof : Eigen::MatrixXd(), dt);
  L.commutation = g.commutation;
  L.gamma_all = g.gamma_all;
  L.mu_all = g.mu_all;
  L.gamma_exc = g.gamma_excited;
  L.mu_exc = g.mu_excited;
  L.gamma_map = g.gamma_map;
  L.lambda_max = g.lambda_max;
  L.mode = g.mode;
  L.seconds = study::seconds_since(t0);
  return L;
}

/// The linear verdict of a predicted growth rate against the run's detection limit (Config::detect).
inline std::string linear_verdict(double gamma, double detect) {
  if (std::isnan(gamma)) return "n/a";
  if (gamma > detect) return "unstable";
  if (gamma > 1e-3) return "weakly unstable";
  return "stable";
}

}  // namespace swegle_study
