#pragma once
/// \file class_growth.hpp
/// Linear growth of u'' = -A u class by class for a Jacobian that commutes with the mirror reflections of a symmetric
/// block (growth/mirror_symmetry.hpp): eig(A) is the union of the spectra of the four projected blocks Q^T A Q, and an
/// initial condition inside one class excites only that class. Gives the growth rate over all classes, that of the
/// excited class with its fastest mode, and, with a velocity smoothing (XSPH), the growth of the leap-frog one-step
/// map restricted to the excited class (linear_growth.hpp) — the linear predictions a Swegle run is compared with.
#include <Eigen/Core>
#include <complex>
#include <limits>
#include <utility>
#include <vector>

#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {

/// The four classes (px, py) = (+,+), (+,-), (-,+), (-,-) of a mirror symmetry and the class of an initial field.
struct MirrorClasses {
  MirrorSymmetry symmetry;
  std::vector<Eigen::MatrixXd> basis;  ///< orthonormal basis Q of each class (2n x m)
  std::vector<std::pair<int, int>> parity;
  int excited = -1;  ///< class holding the initial field entirely (-1: none)
};

/// Classes of `symmetry`; `excited` is the class holding more than 1 - 1e-12 of the squared norm of `initial`.
MirrorClasses mirror_classes(const MirrorSymmetry& symmetry, const Eigen::VectorXd& initial);

struct ClassGrowth {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double gamma_all = nan;  ///< max over all classes of max Re sqrt(-mu)
  std::complex<double> mu_all{nan, nan};
  double gamma_excited = nan;  ///< the same in the excited class
  std::complex<double> mu_excited{nan, nan};
  double gamma_map = nan;    ///< log(spectral radius)/dt of the leap-frog map (excited class; dt > 0)
  double lambda_max = nan;   ///< max |mu| over all classes
  double commutation = nan;  ///< commutation_error of A with the reflections
  Eigen::VectorXd mode;      ///< fastest mode of the excited class (full DOFs, unit norm)
};

/// Class-by-class growth of A (dofs = 2n). With dt > 0, gamma_map is computed too: the leap-frog map with the
/// smoothing S (dofs x dofs, XSPH (x) I_2) as its velocity hook (Replace mode), or without one (S = I) when none is
/// given. If A does not commute with the reflections (error >= 1e-10), the whole spectrum is
/// used instead and the class information is that of the whole space. Throws std::invalid_argument for size
/// mismatches.
ClassGrowth class_growth(const SparseMatrix<>& A, const MirrorClasses& classes, const Eigen::MatrixXd& smoothing = {},
                         double dt = 0);

}  // namespace sphstab
