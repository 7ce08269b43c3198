#pragma once
/// \file state_stability.hpp
/// The linear stability of a particle state that any SPH code produced: positions, velocities, densities, deviatoric
/// stresses, masses, the smoothing length and which particles are fixed, as arrays. The rate-form scheme
/// (forms/rate_form.hpp) is built AT that state (the state is its reference configuration: neighbour list, kernel
/// sums and fixed positions are those of the given positions), and the verdict of growth/stability_verdict.hpp is
/// taken there: the semi-discrete growth gamma_J = max Re lambda(J) with its mode (where it lives, which wavevector),
/// the integrator's one-step map growth gamma_M at the given dt, the detection floor and the class S / U / I / B. At
/// rest (every velocity 0) the leap-frog and predictor-corrector step limits of growth/rate_form_time_step.hpp are
/// added (they need the at-rest reduction).
///
/// What the arrays mean, in the scheme's terms: particle i has mass m_i and density rho_i, so the scheme is built on a
/// particle set of volumes V_i = m_i / rho0 and the uniform reference density rho0 (m_i = rho0 V_i), and the state
/// carries rho_i and S_i. Fixed particles sit at their given positions at rest (a non-zero velocity is refused);
/// their density and stress evolve (RateFormOptions::evolve_fixed) unless the options say otherwise. Away from an
/// equilibrium (F(y) != 0) J is the linearisation about the state, frozen at that instant: `acceleration_max` reports
/// how far the state is from equilibrium, so that a reader can judge the frozen-coefficient reading.
///
/// \code{.cpp}
/// sphstab::ParticleState<2> s{.x = x, .v = v, .density = rho, .deviator = S, .mass = m, .h = 1.3};
/// auto r = sphstab::state_stability(s, {.kernel = sphstab::KernelType::CubicSpline,
///                                        .material = sphstab::ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8),
///                                        .dt = 0.05, .floor = 0.01});
/// if (r.verdict.verdict != sphstab::VerdictClass::Stable) { /* r.verdict.semi_discrete_mode.particle ... */ }
/// \endcode
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/growth/rate_form_time_step.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {

/// A particle state as arrays, one row per particle (N particles).
template <int Dim>
struct ParticleState {
  Eigen::MatrixXd x;         ///< N x Dim positions, finite
  Eigen::MatrixXd v;         ///< N x Dim velocities, finite (empty: at rest); 0 on fixed particles
  Eigen::VectorXd density;   ///< N densities rho_i, finite and > 0
  Eigen::MatrixXd deviator;  ///< N x kStress deviatoric stress (1D: S_xx; 2D: S_xx, S_yy, S_xy), finite; empty: 0
  Eigen::VectorXd mass;      ///< N masses m_i, finite and > 0
  std::vector<bool> fixed;   ///< N flags (empty: every particle free); at least one particle must be free
  double h = 0;              ///< smoothing length, finite and > 0 (kernel support = the kernel's factor times h)
  /// The initial particle spacing dp, > 0, needed only by the artificial stress (f = W / W(dp)) and by the 2D
  /// wavevector estimate of the modes (with the lattice below); 0: unknown.
  double spacing = 0;
};

/// How to read the state: the scheme, the run the verdict is for, and the floor.
struct StateStabilityOptions {
  KernelType kernel = KernelType::CubicSpline;
  ElasticMaterial material = ElasticMaterial::from_bulk_shear(1.0, 0.0, 1.0);  ///< rho0, K, mu (validated)
  RateFormOptions scheme;     ///< the terms (pair_loop is irrelevant: J is computed with the row loop)
  /// The integrator of the verdict (integrator, reuse_corrector_rate, positions, leapfrog_xsph); dt and t_end below.
  RateFormRunOptions run;
  double dt = 0;     ///< the run's step, > 0
  double floor = 0;  ///< the detection floor gamma_floor > 0 (detection_floor(t_end, energy_ratio) of the run)
  /// 2D: the lattice the particles were laid on, for the dominant wavevector of the modes (with spacing > 0). Empty:
  /// detect it from the positions (detect_bravais_lattice_2d) when spacing > 0, else not estimated.
  std::optional<LatticeType> lattice = std::nullopt;
};

/// The scheme built at a state, and the state vector y in its layout.
template <int Dim>
struct RateFormAtState {
  std::shared_ptr<const RateFormScheme<Dim>> scheme;
  Eigen::VectorXd y;
};

struct StateStability {
  StabilityVerdict verdict;
  /// At rest: the step limits (leap-frog 2 / max|Im lambda|, predictor-corrector, effective Courant number); away
  /// from rest: status NotComputed with the reason.
  RateFormTimeStep time_step;
  int particles = 0;               ///< N
  int free = 0;                    ///< free particles
  int states = 0;                  ///< size of y (and J)
  bool at_rest = false;            ///< every velocity is 0
  double acceleration_max = 0;     ///< max |dv_i/dt| over the free particles at the state (0 at an equilibrium)
  double rate_scale = 0;           ///< c_P / h: the scale against which growth rates and the floor read
};

/// Builds the rate-form scheme at the state. Throws std::invalid_argument("state: ...") naming the first problem:
/// arrays of the wrong shape, non-finite entries, h, a mass or a density that is not > 0, coincident particles (two
/// particles closer than 1e-9 h), a fixed particle with a velocity, no free particle, the artificial stress without
/// a spacing; and as RateFormScheme's constructor (materials, options).
template <int Dim>
RateFormAtState<Dim> rate_form_at_state(const ParticleState<Dim>& state, KernelType kernel,
                                        const ElasticMaterial& material, const RateFormOptions& options);

/// The verdict of the state (see the file comment). Throws as rate_form_at_state, std::invalid_argument for a dt or
/// floor that is not finite and > 0, and as stability_verdict (its memory check included).
template <int Dim>
StateStability state_stability(const ParticleState<Dim>& state, const StateStabilityOptions& options);

}  // namespace sphstab
