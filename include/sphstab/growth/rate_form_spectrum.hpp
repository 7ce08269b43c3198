#pragma once
/// \file rate_form_spectrum.hpp
/// The full-state spectrum of the rate-form scheme (forms/rate_form.hpp) at a state at rest, through an exact
/// reduction of J = dF/dy (computed whole, by coloured complex step).
///
/// At rest (v = 0) every rate that multiplies a velocity difference has a zero derivative with respect to x, rho and
/// S, so with y = (x, v, q), q = (rho, S) of every particle that carries them,
///     J = [[0, X, 0], [Jvx, Jvv, Jvq], [0, Jqv, 0]],   X = d vhat / dv (the XSPH matrix, I without XSPH).
/// For lambda != 0, J (x, v, q) = lambda (x, v, q) gives x = X v / lambda, q = Jqv v / lambda and
///     lambda^2 v = lambda Jvv v + B v,   B = Jvx X + Jvq Jqv,
/// so the non-zero eigenvalues of J are lambda = +-sqrt(mu), mu in eig(B), when Jvv = 0, and the eigenvalues of the
/// companion matrix [[0, I], [B, Jvv]] otherwise (linear viscosity always on). Nothing is approximated: the zero
/// blocks are checked (structure_residual), and the tests compare with the dense spectrum of the whole J. The density
/// and stress add one zero eigenvalue per stored component (their perturbations are slaved to the motion), which
/// the reduction leaves out; a 21 x 21 block (4264 states) becomes an 882 x 882 problem.
///
/// **The predictor-corrector's one-step map, reduced the same way** (map_dt > 0). With a0 = p + Jvv v the
/// acceleration, p = Jvx x + Jvq q its elastic part and K = Jvq Jqv, the map M of integrate/linear_step_map.hpp
/// (GMS (6.14)-(6.18): x_p = x + dt X v + dt^2/2 a0, q_p = q + dt Jqv v, v_p = v + dt a0, corrector on v and q; x
/// not corrected, or by the trapezoid) acts on (v, p) as
///     v1 = v_p + dt/2 (a1 - a0),   a1 = p + dt B v + dt^2/2 Jvx a0 + Jvv v_p,
///     p1 = p + dt B v + dt^2/2 (Jvx C + K) a0,   C = I (Gms positions) or X (Trapezoid),
/// and leaves every direction with v = 0 and p = 0 fixed. p is confined to the range of [Jvx Jvq] (an orthonormal
/// basis of it, by column-pivoted QR, keeps the reduced map free of directions no state reaches), so
///     rho(M) = max(1, rho(M_red)),   M_red of size nv + rank([Jvx Jvq]),
/// exactly: the eigenvalue 1 is that of the fixed directions. 21 x 21 block: 882 + 882 instead of 4264 states.
/// **The staggered leap-frog's map** (map_integrator = Leapfrog, [Powell2012, algorithm 1.1]): at rest without
/// velocity-dependent rates (Jvv = 0) it is v^{n+3/2} - 2 v^{n+1/2} + v^{n-1/2} = dt^2 B v^{n+1/2}
/// (integrate/linear_step_map.hpp), so each eigenvalue mu of B gives the two roots of z^2 - (2 + dt^2 mu) z + 1 = 0 and
/// rho(M) = max(1, max |z|). With Powell's XSPH (map_leapfrog_xsph = eps > 0, RateFormRunOptions::leapfrog_xsph:
/// v^{n+1/2} <- P v^{n+1/2} before the drift, P = xsph_smoothing_matrix (x) I at the rest positions, integrate/xsph.hpp;
/// linear in v, so exact at rest) the step is w~ = P w_n, p_{n+1} = p_n + dt B w~, w_{n+1} = w~ + dt p_{n+1} (w_n =
/// v^{n+1/2}, p the elastic acceleration), i.e. w_{n+1} = (I + P + dt^2 B P) w_n - P w_{n-1}: the eigenvalues of that
/// companion matrix (2 nv, or 2 m in a class). With Jvv != 0 (a viscosity that acts at rest) it is not reduced: the map fields stay NaN
/// and `map_reason` says why (growth/stability_verdict.hpp then takes the dense map).
/// tests/growth/stability_verdict_test.cpp compares both with the dense maps of the whole J.
///
/// Non-smooth terms are linearised as their branch at rest: the viscosity's compression switch (v_ij . r_ij < 0) is
/// off (complex step takes the branch of the real part), the artificial stress keeps the tensile/compressive split of
/// the uniform stress (smooth unless a principal stress is 0, i.e. at xi = 1 with S = 0).
#include <Eigen/Core>
#include <complex>
#include <limits>
#include <string>

#include "sphstab/core/status.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace sphstab {

struct RateFormSpectrumOptions {
  bool want_mode = false;
  /// Optional orthonormal columns Q (free velocity DOFs x m) spanning a subspace that B and Jvv leave invariant, e.g.
  /// a mirror class of a symmetric block (growth/mirror_symmetry.hpp): the spectrum of Q^T B Q (and Q^T Jvv Q) is
  /// then the part of J's spectrum whose modes lie in that class; invariance_residual says how well it holds.
  Eigen::MatrixXd basis = {};
  /// Eigenvalues of J to return the modes of (the nearest eigenvalue to each, in `modes`); empty: none. E.g. the
  /// lowest vibration modes of a structure, to identify the one a run excites.
  Eigen::VectorXcd mode_targets = {};
  /// > 0: also the predictor-corrector's one-step map (two rate evaluations per step) at this dt, reduced as above
  /// (in the class of `basis` when one is given). 0: not computed.
  double map_dt = 0;
  PositionUpdate map_positions = PositionUpdate::Gms;  ///< the corrector's position update (rate_form_run.hpp)
  /// The integrator of the map: the two-rate predictor-corrector or the staggered leap-frog (not PC1).
  RateFormIntegrator map_integrator = RateFormIntegrator::PredictorCorrector;
  /// Leap-frog map only: epsilon of Powell's XSPH (2.71) on v^{n+1/2} (RateFormRunOptions::leapfrog_xsph), >= 0.
  double map_leapfrog_xsph = 0;
};

struct RateFormSpectrum {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  double growth_rate = nan;      ///< max Re lambda over the non-zero eigenvalues of J (>= 0: +-pairs)
  std::complex<double> lambda;   ///< the eigenvalue attaining it
  Eigen::VectorXcd eigenvalues;  ///< the non-zero part of the spectrum of J (2 per velocity DOF)
  Eigen::VectorXd mode;          ///< real velocity shape of lambda's eigenvector, free DOFs interleaved (want_mode)
  Eigen::MatrixXd modes;         ///< one column per mode target: real velocity shape, as `mode`
  Eigen::VectorXcd mode_eigenvalues;  ///< the eigenvalue of J each column of `modes` belongs to
  int states = 0;                     ///< size of J
  int reduced = 0;                    ///< size of the reduced eigenproblem
  double structure_residual = nan;    ///< max |zero blocks| / max |J|: the reduction's precondition (~1e-16)
  double invariance_residual = nan;   ///< with a basis: ||B Q - Q Q^T B Q||_F / ||B||_F (~1e-16 for a true class)
  /// With map_dt > 0: rho(M) = max(1, rho(M_red)), its eigenvalue (1 when the fixed directions attain it), the growth
  /// ln rho / map_dt, the size of M_red, and the velocity shape of the dominant eigenvector (free DOFs interleaved;
  /// empty when rho = 1 is attained by the fixed directions).
  double map_spectral_radius = nan;
  std::complex<double> map_eigenvalue{nan, nan};
  double map_growth = nan;
  int map_reduced = 0;
  Eigen::VectorXd map_mode;
  std::string map_reason;  ///< why the map was not reduced (leap-frog with Jvv != 0); empty otherwise
  Status status = Status::NotComputed;
  std::string reason;
  Status info() const { return status; }
};

/// Spectrum of J at y (a state at rest: all velocities 0). Throws std::invalid_argument for a state of the wrong
/// size, with non-zero velocities or a basis of the wrong height; NumericalIssue (with a reason) when the zero blocks
/// are not zero to 1e-10 relative or LAPACK fails.
template <int Dim>
RateFormSpectrum rate_form_spectrum(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y,
                                    const RateFormSpectrumOptions& options = {});

}  // namespace sphstab
