#pragma once
/// \file rate_form_symbol.hpp
/// The Fourier (Bloch) symbol of the whole rate-form scheme (forms/rate_form.hpp) on a periodic lattice: every
/// dispersion branch omega(k) of the state (x, v, rho, S), at any real wavevector, from one exact Jacobian.
///
/// On a periodic Bravais lattice (one particle per cell, every particle free) J = dF/dy is block-circulant: the
/// s x s block J_ij (s = 2 Dim + 1 + kStress states per particle) depends only on x_j - x_i. A Bloch perturbation
/// dy_j = yhat exp(i k . x_j) then satisfies lambda yhat = Jhat(k) yhat with
///     Jhat(k) = sum_j J_0j exp(i k . (x_j - x_0)),
/// and omega = i lambda (a wave exp(i (k . x - omega t)); Re lambda > 0 grows). J_0j is taken from the coloured
/// complex-step Jacobian (exact to rounding), so nothing of the scheme is re-derived here: density, stress-rate,
/// XSPH, viscosity, artificial-stress and kernel-correction couplings all enter as the scheme evaluates them.
///
/// At rest the symbol has the block structure of growth/rate_form_spectrum.hpp,
///     Jhat = [[0, Xhat, 0], [Jvx, Jvv, Jvq], [0, Jqv, 0]],
/// so its 2 Dim acoustic eigenvalues solve lambda^2 v = lambda Jvv v + Bhat v, Bhat = Jvx Xhat + Jvq Jqv (a Dim x Dim
/// problem: rho omega^2 = -rho eig(Bhat) when Jvv = 0), and the 1 + kStress density and stress branches have
/// lambda = 0: at rest their perturbations are slaved to the motion (no sound, no growth of their own).
///
/// Checks (tests/spectral/rate_form_symbol_test.cpp): the symbols at the box's wavevectors reproduce the dense
/// spectrum of the whole periodic J; two box sizes give the same symbol at any k; with GMS's terms (XSPH 1/2,
/// summation continuity, artificial stress) the 2 x 2 problem equals GMS (5.8)/(5.9) with the perturbed artificial
/// stress (spectral/lattice_dispersion.hpp); in 1D, plain SPH gives rho omega^2 = (M + sigma0)|g|^2 - 2 sigma0 L
/// (fourier_symbol.hpp); long waves tend to the continuum GMS (4.9)/(4.10).
#include <Eigen/Core>
#include <complex>
#include <limits>
#include <vector>

#include "sphstab/forms/rate_form.hpp"

namespace sphstab {

/// The block row of J at a reference particle: Jhat(k) = sum_j blocks[j] exp(i k . offsets[j]).
template <int Dim>
struct RateFormSymbol {
  using Wavevector = Eigen::Matrix<double, Dim, 1>;
  int states = 0;                       ///< s = 2 Dim + 1 + kStress (4 in 1D, 8 in 2D)
  std::vector<Wavevector> offsets;      ///< x_j - x_0 (minimum image) of each particle coupled to particle 0
  std::vector<Eigen::MatrixXd> blocks;  ///< J_0j, s x s, in the per-particle order (x, v, rho, S)
  /// max over particles i and couplings of |J_ij - J_0j'| / max |J| (j' at the same offset from 0 as j from i):
  /// ~1e-16 on a Bravais lattice; large when the lattice is not translation invariant (e.g. not one particle per cell).
  double invariance_residual = std::numeric_limits<double>::quiet_NaN();
  /// The stencil's largest |x_j - x_0| per axis against the box: the symbol is exact at every k only if no particle
  /// is coupled through two periodic images, which rate_form_symbol ensures (box > 2 x stencil + a row).
  Wavevector stencil_extent = Wavevector::Zero();

  /// Jhat(k), s x s. k in 1/length; any real k (not only the box's wavevectors).
  Eigen::MatrixXcd at(const Wavevector& k) const;
};

/// Symbol of `scheme` at state y (a uniform state on a periodic lattice: every particle free and periodic in every
/// axis). Throws std::invalid_argument for a state of the wrong size, a non-periodic axis, fixed particles, a box
/// too small for the stencil (with the sizes: "box 12 dx, stencil reaches 6 dx: use a box of at least 14") or an
/// invariance residual above 1e-9 (not a Bravais lattice or not a uniform state).
template <int Dim>
RateFormSymbol<Dim> rate_form_symbol(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y);

/// The dispersion at one wavevector.
struct RateFormDispersion {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXcd lambda;  ///< all s eigenvalues of Jhat(k), sorted by decreasing |lambda|
  /// omega^2 of the acoustic branches from the reduced problem (at rest): -eig(Bhat) when Jvv = 0, else
  /// -lambda^2 of the companion problem's eigenvalue with the largest real part per pair; sorted by Re, descending.
  Eigen::VectorXcd omega2;
  /// Velocity polarisation of each omega2 (columns, unit); in 2D |v . k| / |k| says longitudinal (1) or transverse (0).
  Eigen::MatrixXcd polarisation;
  /// max Re lambda. At rest from the acoustic roots (max Re sqrt(-omega2), or the companion's): the full
  /// eigenvalues scatter by ~sqrt(eps) |lambda| about the slaved zeros' Jordan blocks. A neutral branch still reads
  /// sqrt(rounding of omega2) ~ 1e-8 |omega|: judge instability by -omega2 against |omega2|, not by this alone.
  double growth_rate = nan;
  double slaved_lambda = nan;  ///< max |lambda| of the s - 2 Dim density/stress eigenvalues (0 at rest, to rounding)
  double structure_residual = nan;  ///< max |zero blocks of the at-rest structure| / max |Jhat| (nan if not at rest)
};

/// Eigenvalues of Jhat(k) and the reduced acoustic problem. Throws std::invalid_argument for a non-finite k.
template <int Dim>
RateFormDispersion rate_form_dispersion(const RateFormSymbol<Dim>& symbol,
                                        const typename RateFormSymbol<Dim>::Wavevector& k);

}  // namespace sphstab
