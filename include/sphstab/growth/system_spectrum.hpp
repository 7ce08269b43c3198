#pragma once
/// \file system_spectrum.hpp
/// The rightmost spectrum of a linearised first-order system y' = J y (J = dF/dy of a SemiDiscreteSystem,
/// system/semi_discrete_system.hpp): the growth rate max Re lambda(J) and its mode. The one growth routine for
/// first-order schemes: dense LAPACK dgeev up to dense_max unknowns, Spectra's GenEigsSolver (largest real part)
/// above. For y = (u, v) of u'' = -A u the eigenvalues are +-sqrt(-mu), mu in eig(A), so the growth rate equals
/// growth_rate()'s gamma = max Re sqrt(-mu) (checked in tests/growth/system_spectrum_test.cpp).
///
/// \code{.cpp}
/// sphstab::SecondOrderForm system(force);                         // y = (u, v)
/// auto s = sphstab::system_spectrum(system, Eigen::VectorXd::Zero(system.size()));
/// if (s.info() == sphstab::Status::Successful && s.growth_rate > 0) { /* unstable: e^{growth_rate t} */ }
/// \endcode
#include <Eigen/Core>
#include <complex>
#include <limits>
#include <string>

#include "sphstab/core/status.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/system/semi_discrete_system.hpp"

namespace sphstab {

struct SystemSpectrumOptions {
  int dense_max = 2000;  ///< dense dgeev up to this many unknowns, Spectra above
  int nev = 6;           ///< Spectra: eigenvalues of largest real part wanted (>= 1)
  int ncv = 0;           ///< Spectra: Krylov dimension (0: max(2 nev + 1, 40), capped at the size)
  double tol = 1e-10;    ///< Spectra: relative tolerance
  int maxit = 3000;      ///< Spectra: restarts
  bool want_mode = false;
};

struct SystemSpectrum {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double growth_rate = nan;      ///< max Re lambda(J)
  std::complex<double> lambda;   ///< the eigenvalue attaining it
  Eigen::VectorXcd eigenvalues;  ///< dense: all; Spectra: the nev of largest real part
  Eigen::VectorXd mode;          ///< real shape of lambda's eigenvector, unit norm (want_mode)
  std::string backend;           ///< "dense" or "spectra"
  Status status = Status::NotComputed;
  Status info() const { return status; }
};

/// Spectrum of a square sparse J. Throws std::invalid_argument for an empty, non-square or non-finite J, or invalid
/// options; a solver that does not converge is reported as NotConverging.
SystemSpectrum system_spectrum(const SparseMatrix<>& jacobian, const SystemSpectrumOptions& options = {});

/// J = dF/dy of `system` at y by coloured complex step, then the spectrum. A non-finite rate at y is reported as
/// NumericalIssue.
SystemSpectrum system_spectrum(const SemiDiscreteSystem& system, const Eigen::VectorXd& y,
                               const SystemSpectrumOptions& options = {});

/// Real shape of a complex eigenvector: rotated by the phase that puts the largest share into the real part
/// (phi = arg(sum v_i^2) / 2), real part, unit 2-norm.
Eigen::VectorXd real_mode_shape(Eigen::VectorXcd v);

}  // namespace sphstab
