#pragma once
/// \file stability_verdict.hpp
/// A stability verdict as a library result: for a semi-discrete system y' = F(y) at a state y*, an integrator and a
/// step dt, the two growth rates that decide what a run of length t_end shows, the detection floor of that run, and
/// the class that names which of them is responsible (docs/conventions.md §6-7; issue 31, part 1).
///
///   semi-discrete growth  gamma_J = max Re lambda(J), J = dF/dy at y* (growth/system_spectrum.hpp, or at rest the
///                         exact reduction of growth/rate_form_spectrum.hpp): the scheme's own instability, dt -> 0.
///   map growth            gamma_M = ln rho(M) / dt, M the integrator's one-step map linearised at y*
///                         (integrate/linear_step_map.hpp in closed form from J, or integrate/rate_form_step_matrix by
///                         central differences of the stepper): what the run at this dt actually amplifies.
///   detection floor       gamma_floor = ln(energy_ratio) / (2 t_end) (detection_floor): the slowest amplitude growth
///                         that raises the kinetic energy (~ amplitude^2, so 2 gamma) by energy_ratio within t_end.
///                         An input: the floor is a property of the run, not of the scheme.
///
/// **Classes** (classify_verdict), with gamma_res the rounding resolution of the rates (below):
///   semi      := gamma_J > gamma_floor
///   excess    := gamma_M - max(gamma_J, 0)       the growth the integrator adds to (or removes from) the scheme's
///   S (stable)        !semi and gamma_M <= gamma_floor
///   I (integrator)    !semi and gamma_M >  gamma_floor   J neutral within the floor, the map grows: the run's growth
///                                                         is the integrator's (e.g. the predictor-corrector's
///                                                         omega^4 dt^3 / 8 on an undamped spectrum)
///   U (semi-discrete) semi and excess <= gamma_floor     the run grows at the scheme's rate (to within the floor)
///   B (both)          semi and excess >  gamma_floor     the scheme grows, and the integrator adds growth the run can
///                                                         tell apart from it (excess above the floor)
/// Why B is not "gamma_M above the floor": a consistent integrator reproduces the scheme's growth (ln|R(dt lambda)|
/// / dt -> Re lambda as dt -> 0), so every U case has gamma_M ~ gamma_J > floor; only the excess is the integrator's.
/// A U whose map growth is below the floor (the integrator damps the scheme's instability at this dt, e.g. a
/// viscosity through the stepper) stays U and says so in `reason`: the class names the cause, both rates are given.
/// The comparisons are strict (a rate equal to the floor is not detected) and use no extra margin: the floor is the
/// caller's threshold. A floor at or below gamma_res cannot be resolved: status NumericalIssue with the reason.
///
/// **Resolution**: gamma_res = 1e-7 max(max |lambda(J)|, 1 / dt). The rates come from dense eigenvalues (LAPACK
/// dgeev) of matrices with Jordan blocks: J has the zero eigenvalue of the slaved density/stress and translations,
/// and M the eigenvalue 1 of the same modes, which rounding splits by ~sqrt(eps) ~ 1.5e-8 of the matrix scale; the
/// factor ~7 is margin. Measured (tests/growth/stability_verdict_test.cpp): a periodic 1D lattice's translation gives
/// the reduction's gamma_J = 7e-9 max|lambda| (lambda = sqrt(mu) of a rounded zero mu), the leap-frog's neutral map
/// gamma_M = 8e-16 / time unit.
#include <Eigen/Core>
#include <complex>
#include <limits>
#include <optional>
#include <string>

#include "sphstab/core/status.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/linear_step_map.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/particles/bravais_lattice.hpp"

namespace sphstab {

enum class VerdictClass {
  Stable,        ///< S: both rates at or below the floor
  SemiDiscrete,  ///< U: the semi-discrete system grows above the floor; the integrator adds nothing detectable
  Integrator,    ///< I: J neutral within the floor, the one-step map grows above it
  Both           ///< B: the semi-discrete system grows and the map grows faster by more than the floor
};

/// "S", "U", "I", "B".
std::string verdict_letter(VerdictClass c);
/// "stable", "semi-discrete", "integrator", "both".
std::string verdict_name(VerdictClass c);

/// ln(energy_ratio) / (2 t_end): the amplitude growth rate that multiplies the kinetic energy by energy_ratio in
/// t_end. Throws std::invalid_argument("detection_floor: ...") unless t_end > 0 and energy_ratio > 1, both finite.
double detection_floor(double t_end, double energy_ratio);

/// The class of the rules above from the two rates and the floor (no resolution check). Throws
/// std::invalid_argument("classify_verdict: ...") for a NaN rate or a floor that is not finite and > 0.
VerdictClass classify_verdict(double semi_discrete_growth, double map_growth, double floor);

/// A mode of the verdict: its shape and where it lives.
struct VerdictMode {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd shape;        ///< real velocity shape, free DOFs interleaved (f Dim + a), unit norm; empty: none
  double kx_over_pi = nan;      ///< dominant wavevector k dx / pi (1D: dominant_wavenumber's projection; 2D:
  double ky_over_pi = nan;      ///< dominant_wavevector, when a lattice is given); NaN when not estimated
  int particle = -1;            ///< the particle (index in the particle set) with the largest |v| in the shape
  double particle_share = nan;  ///< that particle's share of the squared norm (1: one particle; 1/N: spread evenly)
  /// Polarisation in the lattice axes: the share of the squared norm in the x components (1 in 1D; 2D: 1 for motion
  /// along x, 0 along y). NaN without particles.
  double x_share = nan;
};

struct StabilityVerdict {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  VerdictClass verdict = VerdictClass::Stable;
  std::string integrator;  ///< rate_form_integrator_name
  double dt = nan;
  double floor = nan;                             ///< gamma_floor, the input
  double semi_discrete_growth = nan;              ///< gamma_J = max Re lambda(J)
  std::complex<double> lambda{nan, nan};          ///< the eigenvalue of J attaining it
  double lambda_max = nan;                        ///< max |lambda(J)|
  double map_spectral_radius = nan;               ///< rho(M)
  double map_growth = nan;                        ///< gamma_M = ln rho(M) / dt
  std::complex<double> map_eigenvalue{nan, nan};  ///< the eigenvalue of M attaining rho
  double integrator_excess = nan;                 ///< gamma_M - max(gamma_J, 0)
  double resolution = nan;                        ///< gamma_res
  int map_size = 0;                               ///< rows of M (the integrator's carried state)
  std::string map_route;                          ///< "closed-form" (from J) or "stepper" (central differences)
  /// The fastest mode of J (computed when gamma_J > floor; with a rest state: the velocity shape of the reduction).
  VerdictMode semi_discrete_mode;
  /// The velocity slots of M's dominant eigenvector (computed when gamma_M > floor): where the run's growth lives.
  VerdictMode map_mode;
  Status status = Status::NotComputed;
  std::string reason;
  Status info() const { return status; }
  std::string letter() const { return verdict_letter(verdict); }
};

struct StabilityVerdictOptions {
  /// gamma_floor > 0 (detection_floor(t_end, energy_ratio) of the run the verdict is for). Required.
  double floor = std::numeric_limits<double>::quiet_NaN();
  /// 2D: the lattice for the dominant wavevector of the modes (dominant_wavevector); empty: not estimated. 1D always
  /// estimates (dominant_wavenumber, periodic when the particle set is).
  std::optional<BravaisLattice2D> lattice = std::nullopt;
  /// Map by central differences of the stepper (rate_form_step_matrix) even where the closed form applies. The
  /// options that act outside F take the stepper: absorbing_half_step always, leapfrog_xsph away from rest (at rest
  /// its map is reduced exactly, growth/rate_form_spectrum.hpp).
  bool stepper_map = false;
  double delta = 1e-7;  ///< the stepper's central-difference increment
  /// Optional orthonormal columns (free velocity DOFs x m) spanning an invariant class of the motion, e.g. the mirror
  /// class a kick excites (growth/mirror_symmetry.hpp): both rates are then those of the modes in that class. Needs
  /// the reduced route (below).
  Eigen::MatrixXd basis = {};
};

/// The verdict of `scheme` at state y (size scheme.size(); F(y) ~ 0 for the linearisation to describe small
/// perturbations, as at the uniform_state of a complete lattice) for the integrator `run` selects (integrator,
/// reuse_corrector_rate, positions, leapfrog_xsph, absorbing_half_step) at dt = run.dt (pass the run's dt:
/// run_rate_form reduces it to t_end / ceil(t_end / dt)). Two routes (map_route):
///   "reduced"      at rest (all velocities 0) with the two-rate predictor-corrector (either position update), or
///                  the leap-frog (with or without Powell's XSPH) without velocity-dependent rates at rest, and no
///                  stepper-only option: both rates
///                  from the exact reduction of growth/rate_form_spectrum.hpp (PC: rho = max(1, rho(M_red)), M_red of
///                  size dofs + rank[Jvx Jvq]; leap-frog: from the eigenvalues of B); no dense J or M. A basis
///                  restricts both to its class. A 21 x 21 Swegle block: eigenproblems of ~900 and ~1800.
///   "closed-form" / "stepper"  otherwise: J by coloured complex step, gamma_J by the exact reduction at rest, else
///                  dense eigenvalues of J; M dense (see above), size(M) = size, 2 size (pc1) or size + 2 dofs
///                  (leap-frog): memory is checked first. A basis is refused here.
/// Throws std::invalid_argument("stability_verdict: ...") for a state of the wrong size, options run_rate_form
/// rejects, a yield stress or neighbour skin, a floor that is not finite and > 0, or a basis off the reduced route; a non-finite J or M, a failed
/// eigensolver, or a floor below the resolution is a status (NumericalIssue) with the reason.
template <int Dim>
StabilityVerdict stability_verdict(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y,
                                   const RateFormRunOptions& run, const StabilityVerdictOptions& options);

/// The same for a given linearisation: J (n x n, dense), the state's layout, the integrator `run` selects at
/// run.dt, and the floor. Semi-discrete growth from the dense eigenvalues of J. The modes' shapes are the velocity
/// slots of the eigenvectors (layout order); without particles, `particle` is the index of the largest entry of the
/// shape (a velocity DOF) and no wavevector is estimated. Throws std::invalid_argument as linear_step_map and for a
/// floor that is not finite and > 0.
StabilityVerdict stability_verdict(const Eigen::MatrixXd& J, const StateLayout& layout, const RateFormRunOptions& run,
                                   double floor);

}  // namespace sphstab
